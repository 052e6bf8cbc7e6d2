"""The generated node against a bare relay, on real ROS 2 (rclpy, Fast DDS) and ROS 1 (rosmaster,
rospy), in one run: message in -> command out.

The maze solver's node, with its default parameters but ``tick_on_message`` (a cycle right
after each message, as a relay does; the default waits for the 10 Hz timer), a bare relay
written for the same middleware (a scan in, a Twist out, nothing checked) and a maze solver
written by hand for it (the four ranges read, the platform's state kept, the model's three
rules), take turns behind
one robot process that sends a scan, waits for the command, and sends the next after a gap.
Printed side by side, in microseconds, median (p99):

* **inside the node**: from the subscription callback being entered to the command's
  ``publish()`` returning (measured in the node's process);
* **round trip**: from the robot's ``publish()`` to the command arriving in the robot.

The scans alternate between a wall on the right and none, so that the node's state changes
with every message (as a robot's does while it drives). Then, for each, what it does to the robot's storage in steady operation: the ``fsync`` /
``fdatasync`` / ``sync*`` / ``msync`` calls per message (counted with strace, in a run of its
own, where strace is installed) and the bytes it made the kernel write to storage
(``/proc/PID/io``), with the writes per hour of a line follower deciding 20 times a second; and
the bytes written in ``--steady`` seconds of steady operation (a scan every 50 ms, 20 decisions
a second, after 10 s to settle), per hour.

    python benchmarks/relay.py [--samples 400] [--ros 2 1] [--baseline 5fa21e9] [--rate 0.01] [--steady 60]

With ``--baseline REV`` that revision's generated node runs in the same rounds. Needs robosc,
rclpy (the ros2 extra) and, for ROS 1, Debian's rospy for /usr/bin/python3; not the test extras.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import shutil
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))
import revision as revisions  # noqa: E402

ROS1_PYTHON = os.environ.get("ROBOSC_ROS1_PYTHON", "/usr/bin/python3")
MODEL = ROOT / "examples" / "maze_solver.rscd"
SYNCS = "fsync,fdatasync,syncfs,sync,sync_file_range,msync"
# the node's cycles per second: its default; --rate 0.01 makes its timer so slow that it never
# sends a command of its own during a run (at 10 Hz the timer's own commands may reach the robot
# before the one its scan caused, and shorten the round trips measured)
RATE = [10.0]

# the generated node, its receive and publish timed (patched before the node is made)
NODE = """
import json, signal, sys, time
sys.path.insert(0, {path!r})
{setup}
from {package}.onboard import {adapter} as adapter
from {package}.{module} import Robot
inside, pending = [], [None]
receive, publish = adapter.SupervisorNode.receive, adapter.SupervisorNode.publish
def timed_receive(self, topic, message, *rest):
    if topic.name.endswith("scan"):
        pending[0] = time.perf_counter()
    return receive(self, topic, message, *rest)
def timed_publish(self, topic, message):
    done = publish(self, topic, message)
    if pending[0] is not None and topic.name.endswith("cmd_vel"):
        inside.append(time.perf_counter() - pending[0])
        pending[0] = None
    return done
adapter.SupervisorNode.receive = timed_receive
adapter.SupervisorNode.publish = timed_publish
def save(*_):
    with open({out!r}, "w") as handle:
        json.dump(inside, handle)
    sys.exit(0)
signal.signal(signal.SIGUSR1, save)
{run}
"""

# the relay itself, the same on both middlewares: a Twist out for each scan in, timed
RELAY = """inside = []
def relay(message):
    start = time.perf_counter()
    command = Twist()
    command.linear.x = 0.3
    out.publish(command)
    inside.append(time.perf_counter() - start)
"""

# a maze solver written by hand for the same middleware, the job robosc's node does: the four
# ranges the model reads, the platform's state (ready or turning) kept, the model's three rules
HAND = """inside = []
ready = [True]
def relay(message):
    start = time.perf_counter()
    ranges = message.ranges
    front = ranges[0] < 0.6
    right = ranges[270] < 0.7 or ranges[240] < 0.7
    diag_right = ranges[225] < 0.9
    if not ready[0]:
        return
    if not front and (right or not diag_right):
        command = Twist()
        command.linear.x = 0.3
        out.publish(command)
        inside.append(time.perf_counter() - start)
    elif front:
        ready[0] = False
        left.publish(Int16(data=90))
    elif not right and diag_right:
        ready[0] = False
        turn_right.publish(Int16(data=90))
def done(_):
    ready[0] = True
"""

RELAY_ROS2 = """
import json, signal, sys, time, rclpy
from rclpy.qos import QoSProfile, ReliabilityPolicy
from sensor_msgs.msg import LaserScan
from geometry_msgs.msg import Twist
rclpy.init()
node = rclpy.create_node("relay")
out = node.create_publisher(Twist, "/cmd_vel", QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE))
from std_msgs.msg import Empty, Int16
left = node.create_publisher(Int16, "/rotate_left", QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE))
turn_right = node.create_publisher(Int16, "/rotate_right", QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE))
{relay}node.create_subscription(LaserScan, "/scan", relay, QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT))
if "done" in globals():
    node.create_subscription(Empty, "/rotate_done", done, QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE))
def save(*_):
    with open(sys.argv[1], "w") as handle:
        json.dump(inside, handle)
    sys.exit(0)
signal.signal(signal.SIGUSR1, save)
node.create_timer(0.1, lambda: None)  # wakes the executor now and then, so that the signal is handled
from rclpy.executors import SingleThreadedExecutor  # spun as robosc's node is
executor = SingleThreadedExecutor()
executor.add_node(node)
executor.spin()
"""

RELAY_ROS1 = """
import json, signal, sys, time, rospy
from sensor_msgs.msg import LaserScan
from geometry_msgs.msg import Twist
rospy.init_node("relay", disable_signals=True)
out = rospy.Publisher("/cmd_vel", Twist, queue_size=10)
from std_msgs.msg import Empty, Int16
left = rospy.Publisher("/rotate_left", Int16, queue_size=10)
turn_right = rospy.Publisher("/rotate_right", Int16, queue_size=10)
{relay}rospy.Subscriber("/scan", LaserScan, relay, queue_size=10)
if "done" in globals():
    rospy.Subscriber("/rotate_done", Empty, done, queue_size=10)
def save(*_):
    with open(sys.argv[1], "w") as handle:
        json.dump(inside, handle)
    rospy.signal_shutdown("done")
signal.signal(signal.SIGUSR1, save)
rospy.spin()
"""

# the robot: a scan, then the command it causes, then the next scan after a gap
ROBOT_ROS2 = """
import json, sys, time, rclpy
from rclpy.qos import QoSProfile, ReliabilityPolicy
from sensor_msgs.msg import LaserScan
from geometry_msgs.msg import Twist
rclpy.init()
node = rclpy.create_node("robot")
scan = node.create_publisher(LaserScan, "/scan", QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT))
got = []
node.create_subscription(Twist, "/cmd_vel", got.append, QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE))
message = LaserScan(); message.ranges = [5.0] * 360
other = LaserScan(); other.ranges = [5.0] * 270 + [0.5] + [5.0] * 89  # a wall on the right: the state changes
trips, samples, gap = [], int(sys.argv[2]), float(sys.argv[3])
end = time.time() + 30
while scan.get_subscription_count() == 0 or node.count_publishers("/cmd_vel") == 0:
    rclpy.spin_once(node, timeout_sec=0.05)
    if time.time() > end: sys.exit(1)
while not got and time.time() < end:  # until the node has heard a scan (and got the reports)
    scan.publish(message); rclpy.spin_once(node, timeout_sec=0.1)
while len(trips) < samples:
    got.clear()
    message, other = other, message
    start = time.perf_counter()
    scan.publish(message)
    limit = time.perf_counter() + 1.0
    while not got and time.perf_counter() < limit:
        rclpy.spin_once(node, timeout_sec=0.001)
    if got:
        trips.append(time.perf_counter() - start)
    time.sleep(gap)
with open(sys.argv[1], "w") as handle:
    json.dump(trips, handle)
"""

ROBOT_ROS1 = """
import json, sys, threading, time, rospy
from sensor_msgs.msg import LaserScan
from geometry_msgs.msg import Twist
rospy.init_node("robot", disable_signals=True)
arrived = threading.Event()
rospy.Subscriber("/cmd_vel", Twist, lambda _: arrived.set(), queue_size=10)
scan = rospy.Publisher("/scan", LaserScan, queue_size=10)
message = LaserScan(); message.ranges = [5.0] * 360
other = LaserScan(); other.ranges = [5.0] * 270 + [0.5] + [5.0] * 89  # a wall on the right: the state changes
trips, samples, gap = [], int(sys.argv[2]), float(sys.argv[3])
end = time.time() + 30
while scan.get_num_connections() == 0 and time.time() < end:
    time.sleep(0.05)
while not arrived.is_set() and time.time() < end:
    scan.publish(message); time.sleep(0.1)
time.sleep(0.3)
while len(trips) < samples:
    arrived.clear()
    message, other = other, message
    start = time.perf_counter()
    scan.publish(message)
    if arrived.wait(1.0):
        trips.append(time.perf_counter() - start)
    time.sleep(gap)
with open(sys.argv[1], "w") as handle:
    json.dump(trips, handle)
"""

REPORTS_ROS2 = """
import rclpy
from std_srvs.srv import Trigger
rclpy.init()
node = rclpy.create_node("platform_driver")
def report(request, response):
    response.success, response.message = True, "ready"
    return response
node.create_service(Trigger, "/robosc/report/Platform", report)
rclpy.spin(node)
"""

REPORTS_ROS1 = """
import rospy
from std_srvs.srv import Trigger, TriggerResponse
rospy.init_node("platform_driver")
rospy.Service("/robosc/report/Platform", Trigger, lambda request: TriggerResponse(True, "ready"))
rospy.spin()
"""


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def generate(ros: int, out: Path, revision: str | None, work: Path) -> tuple[Path, str, str]:
    """The maze solver's package (this robosc, or ``revision``'s): (folder, package, module)."""
    revisions.generate(MODEL, ros, out, revision, work)
    package = next(p.name for p in (out / ("src" if ros == 1 else "")).iterdir() if (p / "onboard").is_dir())
    module = next(p.stem for p in (out / ("src" if ros == 1 else "") / package).glob("*_supervisor.py"))
    return out, package, module


class Middleware:
    """One ROS graph on this machine only: its environment and its processes."""

    def __init__(self, ros: int, work: Path) -> None:
        self.ros, self.work = ros, work
        self.log = open(work / f"ros{ros}.log", "ab")  # noqa: SIM115
        self.processes: list[subprocess.Popen[bytes]] = []
        if ros == 2:
            domain = 100 + os.getpid() % 100
            self.env = {**os.environ, "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST", "ROS_DOMAIN_ID": str(domain)}
            self.python = sys.executable
        else:
            port = free_port()
            self.env = {
                **{k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "PYTHON"))},
                "ROS_MASTER_URI": f"http://127.0.0.1:{port}",
                "ROS_HOSTNAME": "127.0.0.1",
                "ROS_HOME": str(work / "ros_home"),
            }
            self.python = ROS1_PYTHON
            self.start([ROS1_PYTHON, "/usr/bin/rosmaster", "--core", "-p", str(port)])
            time.sleep(1.5)
        self.start([self.python, "-c", REPORTS_ROS2 if ros == 2 else REPORTS_ROS1])

    def start(self, command: list[str], env: dict[str, str] | None = None) -> subprocess.Popen[bytes]:
        # a session of its own: ended with everything it started (strace's node too), whatever happens
        process = subprocess.Popen(
            command, env=env or self.env, stdout=self.log, stderr=self.log, start_new_session=True
        )
        self.processes.append(process)
        return process

    def stop(self) -> None:
        for process in reversed(self.processes):
            if process.poll() is None:
                process.send_signal(signal.SIGINT)
        for process in self.processes:
            with contextlib.suppress(subprocess.TimeoutExpired):
                process.wait(5)
            kill_group(process)
        self.log.close()


def kill_group(process: subprocess.Popen[bytes]) -> None:
    """End ``process`` and whatever it started (its session)."""
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(process.pid, signal.SIGKILL)
    with contextlib.suppress(subprocess.TimeoutExpired):
        process.wait(5)


def node_command(mw: Middleware, package: tuple[Path, str, str], out: Path) -> list[str]:
    folder, name, module = package
    if mw.ros == 2:
        params = ["--ros-args", "-p", "tick_on_message:=true", "-p", f"rate:={RATE[0]}"]
        run = f'adapter.main(Robot, "controller", ["bench", *{params!r}])'
        return [
            mw.python,
            "-c",
            NODE.format(path=str(folder), setup="", package=name, module=module, adapter="ros2", out=str(out), run=run),
        ]
    setup = f"sys.argv[1:] = ['__name:=bench', '_tick_on_message:=true', '_rate:={RATE[0]}']"
    run = 'adapter.main(Robot, "controller", "bench")'
    return [
        mw.python,
        "-c",
        NODE.format(
            path=str(folder / "src"), setup=setup, package=name, module=module, adapter="ros1", out=str(out), run=run
        ),
    ]


def relay_command(mw: Middleware, out: Path, profile: bool = False, hand: bool = False) -> list[str]:
    script = (RELAY_ROS2 if mw.ros == 2 else RELAY_ROS1).replace("{relay}", HAND if hand else RELAY)
    command = [mw.python, "-c", script, str(out)]
    if profile:  # the Fast DDS profile robosc's nodes load (onboard/fastdds.xml)
        xml = ROOT / "src/robosc/runtime/onboard/fastdds.xml"
        command = ["env", f"FASTRTPS_DEFAULT_PROFILES_FILE={xml}", *command]
    return command


def storage_writes(pid: int) -> int:
    """Bytes the process has made the kernel write to storage so far."""
    try:
        for line in Path(f"/proc/{pid}/io").read_text().splitlines():
            if line.startswith("write_bytes:"):
                return int(line.split()[1])
    except OSError:
        pass
    return -1


def round_of(mw: Middleware, build: Any, samples: int, gap: float, strace: bool) -> dict[str, Any]:
    """One node (``build(out)``: its command line, writing its inside times to ``out``) behind the
    robot: its inside and round-trip times, its syncs and storage writes."""
    tag = f"{time.monotonic_ns()}"
    inside_file, trips_file, strace_file = (mw.work / f"{tag}.{x}" for x in ("inside", "trips", "strace"))
    command = build(inside_file)
    if strace:
        command = ["strace", "-f", "-c", "-e", f"trace={SYNCS}", "-o", str(strace_file), *command[:1], *command[1:]]
    node = mw.start(command)
    robot_code = ROBOT_ROS2 if mw.ros == 2 else ROBOT_ROS1
    time.sleep(1.0)
    written = storage_writes(node.pid) if not strace else -1
    robot = mw.start([mw.python, "-c", robot_code, str(trips_file), str(samples), str(gap)])
    robot.wait(60 + samples * (gap + 0.05) * 3)
    written_after = storage_writes(node.pid) if not strace else -1
    target = node.pid
    if strace:  # the node is strace's child
        with contextlib.suppress(OSError, IndexError, ValueError):
            target = int(Path(f"/proc/{node.pid}/task/{node.pid}/children").read_text().split()[0])
    os.kill(target, signal.SIGUSR1)  # the node writes its inside times and ends
    with contextlib.suppress(subprocess.TimeoutExpired):
        node.wait(10)
    kill_group(node)
    kill_group(robot)
    mw.processes.remove(node)
    mw.processes.remove(robot)
    trips = json.loads(trips_file.read_text()) if trips_file.exists() else []
    inside = json.loads(inside_file.read_text()) if inside_file.exists() else []
    syncs = None
    if strace and strace_file.exists():
        syncs = 0
        for line in strace_file.read_text().splitlines():
            parts = line.split()
            if len(parts) >= 5 and parts[-1] in SYNCS.split(",") and parts[3].isdigit():
                syncs += int(parts[3])
    return {
        "inside": inside,
        "trips": trips,
        "syncs": syncs,
        "written": (written_after - written) if written >= 0 and written_after >= 0 else None,
    }


def us(values: list[float], q: float | None = None) -> float:
    if not values:
        return float("nan")
    if q is None:
        return statistics.median(values) * 1e6
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(q / 100 * (len(ordered) - 1)))] * 1e6


def steady_writes(mw: Middleware, build: Any, seconds: float) -> tuple[int, float]:
    """A node behind a robot sending a scan every 50 ms (20 Hz, each waiting for its command),
    for 10 s to settle and then ``seconds``: the bytes it made the kernel write to storage in
    those ``seconds``, and for how long that was."""
    command = build(mw.work / f"{time.monotonic_ns()}.inside")
    node = mw.start(command)
    robot_code = ROBOT_ROS2 if mw.ros == 2 else ROBOT_ROS1
    time.sleep(1.0)
    samples = int((10 + seconds) * 20 * 2)  # more than it can send: it is stopped
    robot = mw.start([mw.python, "-c", robot_code, str(mw.work / "steady.trips"), str(samples), "0.05"])
    time.sleep(10)
    start, before = time.monotonic(), storage_writes(node.pid)
    time.sleep(seconds)
    after, lasted = storage_writes(node.pid), time.monotonic() - start
    for process in (robot, node):
        kill_group(process)
        mw.processes.remove(process)
    return (after - before if before >= 0 and after >= 0 else -1), lasted


def measure(
    ros: int, samples: int, gap: float, rounds: int, baseline: str | None, work: Path, steady: float = 0.0
) -> list[dict[str, Any]]:
    mw = Middleware(ros, work)
    try:
        subjects: list[tuple[str, Any]] = []
        ours = generate(ros, work / f"ours_{ros}", None, work)
        subjects.append(("robosc, default parameters", lambda out: node_command(mw, ours, out)))
        if baseline is not None:
            theirs = generate(ros, work / f"base_{ros}", baseline, work)
            subjects.append((f"robosc {baseline}, default parameters", lambda out: node_command(mw, theirs, out)))
        subjects.append(("bare relay", lambda out: relay_command(mw, out)))
        subjects.append(("hand-written maze solver", lambda out: relay_command(mw, out, hand=True)))
        if ros == 2:
            subjects.append(("bare relay, robosc's DDS profile", lambda out: relay_command(mw, out, True)))
        results: dict[str, dict[str, Any]] = {}
        for _ in range(rounds):  # taking turns: the machine's noise falls on all alike
            for label, build in subjects:
                found = round_of(mw, build, samples // rounds, gap, strace=False)
                entry = results.setdefault(label, {"inside": [], "trips": [], "written": 0, "messages": 0})
                entry["inside"] += found["inside"]
                entry["trips"] += found["trips"]
                entry["written"] += found["written"] or 0
                entry["messages"] += len(found["trips"])
        for label, build in subjects:  # storage in steady operation: a scan every 50 ms for minutes
            if steady > 0:
                results[label]["steady"] = steady_writes(mw, build, steady)
        if shutil.which("strace"):
            for label, build in subjects:
                found = round_of(mw, build, min(100, samples), gap, strace=True)
                results[label]["syncs"] = found["syncs"]
                results[label]["sync_messages"] = len(found["trips"])
        return [dict(ros=ros, label=label, **entry) for label, entry in results.items()]
    finally:
        mw.stop()


def table(rows: list[dict[str, Any]]) -> str:
    steady_lines = [
        "",
        "In steady operation (a scan every 50 ms, after 10 s to settle):",
        "",
        "| ROS | node | measured for | bytes to storage | bytes to storage per hour |",
        "|---|---|---|---|---|",
    ]
    lines = [
        "| ROS | node | inside the node, us: median (p99) | round trip, us: median (p99) | syncs per message | bytes to storage per message | writes per hour at 20 Hz |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        syncs = r.get("syncs")
        if "steady" in r:
            written, lasted = r["steady"]
            per_hour = "n/a" if written < 0 else f"{written / lasted * 3600:,.0f}"
            steady_lines.append(f"| {r['ros']} | {r['label']} | {lasted:.0f} s | {written:,} | {per_hour} |")
        per = "n/a (no strace)" if syncs is None else f"{syncs / max(1, r.get('sync_messages', 1)):.2f}"
        written = r["written"] / max(1, r["messages"])
        hour = (
            "n/a"
            if syncs is None
            else f"{syncs / max(1, r.get('sync_messages', 1)) * 20 * 3600:,.0f} syncs, {written * 20 * 3600:,.0f} bytes"
        )
        lines.append(
            f"| {r['ros']} | {r['label']} | {us(r['inside']):,.0f} ({us(r['inside'], 99):,.0f}) "
            f"| {us(r['trips']):,.0f} ({us(r['trips'], 99):,.0f}) | {per} | {written:,.0f} | {hour} |"
        )
    return "\n".join(lines + (steady_lines if len(steady_lines) > 5 else []))


def ratios(rows: list[dict[str, Any]]) -> str:
    out = []
    for ros in sorted({r["ros"] for r in rows}, reverse=True):
        relay = next(r for r in rows if r["ros"] == ros and r["label"] == "bare relay")
        for r in rows:
            if r["ros"] == ros and r is not relay:
                out.append(
                    f"ROS {ros}, {r['label']}: {us(r['inside']) / us(relay['inside']):.2f}x the relay inside the node, "
                    f"{us(r['trips']) / us(relay['trips']):.3f}x its round trip (medians)"
                )
    return "\n".join(out)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=400)
    parser.add_argument("--rounds", type=int, default=4)
    parser.add_argument("--gap", type=float, default=0.02, help="seconds between a command and the next scan")
    parser.add_argument("--ros", type=int, nargs="+", default=[2, 1], choices=[1, 2])
    parser.add_argument("--baseline", default=None, help="also run this revision's generated node, in the same rounds")
    parser.add_argument("--keep", default=None, help="keep the packages and logs in this folder")
    parser.add_argument(
        "--rate", type=float, default=10.0, help="the node's rate (0.01: its timer sends nothing during a run)"
    )
    parser.add_argument(
        "--steady", type=float, default=60.0, help="seconds of steady operation to measure storage writes in (0: none)"
    )
    args = parser.parse_args()
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(1))  # so that the middleware's processes are ended
    RATE[0] = args.rate
    rows: list[dict[str, Any]] = []
    with tempfile.TemporaryDirectory(prefix="robosc-relay-") as folder:
        if args.keep:
            folder = args.keep
            Path(folder).mkdir(parents=True, exist_ok=True)
        for ros in args.ros:
            if ros == 1 and not Path(ROS1_PYTHON).exists():
                print("ROS 1: no", ROS1_PYTHON)
                continue
            rows += measure(ros, args.samples, args.gap, args.rounds, args.baseline, Path(folder), args.steady)
    print(table(rows))
    print()
    print(ratios(rows))


if __name__ == "__main__":
    main()
