"""Under load and bad data, on real ROS 1 and ROS 2.

``layer``: the line follower's supervision layer while a controller floods
``robosc/controller/cmd_vel`` at about 1 kHz with a mix of halt (allowed), move (not
allowed: no line yet) and hostile commands (5.0, NaN, infinity). A probe counts what
reaches the robot (``/cmd_vel``) and what is reported (``/blocked``); every command must
be one or the other: dropped = sent - forwarded - reported.

``memory``: the line follower's ROS 1 controller node while scans arrive at about 1 kHz,
malformed ones (no ranges, NaN, wrong length) mixed with 100,000-range ones; the node's
resident memory every 10 s.

    python benchmarks/flood.py [--part layer|memory|all] [--seconds 10] [--memory-seconds 180]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
ROS1_PYTHON = os.environ.get("ROBOSC_ROS1_PYTHON", "/usr/bin/python3")

# the flooding controller and the counting robot, in one process
PROBE_ROS1 = """
import json, sys, threading, time
import rospy
from geometry_msgs.msg import Twist
from std_msgs.msg import String
seconds, rate = float(sys.argv[1]), float(sys.argv[2])
rospy.init_node("probe", anonymous=True)
counts = {"forwarded": 0, "reported": 0}
lock = threading.Lock()
def count(key):
    def callback(message):
        with lock:
            counts[key] += 1
    return callback
rospy.Subscriber("/cmd_vel", Twist, count("forwarded"), queue_size=100000)
rospy.Subscriber("/blocked", String, count("reported"), queue_size=100000)
out = rospy.Publisher("/robosc/controller/cmd_vel", Twist, queue_size=100000)
end = time.time() + 10
while out.get_num_connections() == 0 and time.time() < end:
    time.sleep(0.05)
time.sleep(1.0)
def twist(x, z):
    m = Twist(); m.linear.x, m.angular.z = x, z; return m
mix = [twist(0.0, 0.0), twist(0.15, 0.1), twist(5.0, 0.0), twist(float("nan"), 0.0), twist(0.0, float("inf"))]
sent, start = 0, time.time()
while time.time() - start < seconds:
    out.publish(mix[sent % len(mix)])
    sent += 1
    lag = start + sent / rate - time.time()
    if lag > 0:
        time.sleep(lag)
elapsed = time.time() - start
time.sleep(3.0)
with lock:
    print(json.dumps({"sent": sent, "seconds": elapsed, **counts}))
sys.stdout.flush()
rospy.signal_shutdown("done")
"""

PROBE_ROS2 = """
import json, sys, time
import rclpy
from geometry_msgs.msg import Twist
from std_msgs.msg import String
from rclpy.qos import QoSProfile, ReliabilityPolicy, HistoryPolicy
seconds, rate = float(sys.argv[1]), float(sys.argv[2])
rclpy.init()
node = rclpy.create_node("probe")
qos = QoSProfile(depth=100000, reliability=ReliabilityPolicy.RELIABLE, history=HistoryPolicy.KEEP_LAST)
counts = {"forwarded": 0, "reported": 0}
def count(key):
    def callback(message):
        counts[key] += 1
    return callback
node.create_subscription(Twist, "/cmd_vel", count("forwarded"), qos)
node.create_subscription(String, "/blocked", count("reported"), qos)
out = node.create_publisher(Twist, "/robosc/controller/cmd_vel", qos)
end = time.time() + 10
while out.get_subscription_count() == 0 and time.time() < end:
    rclpy.spin_once(node, timeout_sec=0.05)
end = time.time() + 1.0
while time.time() < end:
    rclpy.spin_once(node, timeout_sec=0.05)
def twist(x, z):
    m = Twist(); m.linear.x, m.angular.z = x, z; return m
mix = [twist(0.0, 0.0), twist(0.15, 0.1), twist(5.0, 0.0), twist(float("nan"), 0.0), twist(0.0, float("inf"))]
sent, start = 0, time.time()
while time.time() - start < seconds:
    out.publish(mix[sent % len(mix)])
    sent += 1
    rclpy.spin_once(node, timeout_sec=0)
    lag = start + sent / rate - time.time()
    if lag > 0:
        time.sleep(lag)
elapsed = time.time() - start
end = time.time() + 3.0
while time.time() < end:
    rclpy.spin_once(node, timeout_sec=0.01)
print(json.dumps({"sent": sent, "seconds": elapsed, **counts}))
"""

SCANS_ROS1 = """
import sys, time
import rospy
from sensor_msgs.msg import LaserScan
rospy.init_node("scanner", anonymous=True)
out = rospy.Publisher("/scan", LaserScan, queue_size=10)
rate, count_file = float(sys.argv[1]), sys.argv[2]
big = LaserScan(); big.ranges = [5.0] * 100000
kinds = [LaserScan(), big, LaserScan(ranges=[float("nan")] * 360), LaserScan(ranges=[0.1, 0.2]), big]
sent, start = 0, time.time()
while not rospy.is_shutdown():
    out.publish(kinds[sent % len(kinds)])
    sent += 1
    if sent % 200 == 0:
        with open(count_file, "w") as handle:
            handle.write("%d %f" % (sent, time.time() - start))
    lag = start + sent / rate - time.time()
    if lag > 0:
        time.sleep(lag)
"""


def env_ros1(port: int, home: Path) -> dict[str, str]:
    return {
        **{k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "PYTHON"))},
        "ROS_MASTER_URI": f"http://127.0.0.1:{port}",
        "ROS_HOSTNAME": "127.0.0.1",
        "ROS_HOME": str(home),
        "PYTHONUNBUFFERED": "1",
    }


def rss_mb(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return 0.0


def layer(ros: int, seconds: float, rate: float, work: Path) -> dict[str, float]:
    from ros_support import build_package, free_port

    package = build_package("examples/line_follower.rscd", ros, "supervisor", work)
    processes: list[subprocess.Popen[bytes]] = []
    logs = open(work / f"layer{ros}.log", "ab")  # noqa: SIM115
    try:
        if ros == 1:
            port = free_port()
            env = env_ros1(port, work / "home")
            processes.append(
                subprocess.Popen(
                    [ROS1_PYTHON, "/usr/bin/rosmaster", "--core", "-p", str(port)], env=env, stdout=logs, stderr=logs
                )
            )
            time.sleep(1.5)
            script = next((package / "scripts").glob("*_node"))
            processes.append(
                subprocess.Popen([ROS1_PYTHON, str(script), "_qos_depth:=1000"], env=env, stdout=logs, stderr=logs)
            )
            probe = [ROS1_PYTHON, "-c", PROBE_ROS1, str(seconds), str(rate)]
        else:
            env = {
                **os.environ,
                "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
                "ROS_DOMAIN_ID": str(120 + os.getpid() % 50),
                "PYTHONPATH": str(package),
            }
            module = next(p.name for p in package.iterdir() if (p / "node.py").exists())
            processes.append(
                subprocess.Popen(
                    [sys.executable, "-m", f"{module}.node", "--ros-args", "-p", "qos_depth:=1000"],
                    env=env,
                    stdout=logs,
                    stderr=logs,
                )
            )
            probe = [sys.executable, "-c", PROBE_ROS2, str(seconds), str(rate)]
        time.sleep(3.0)
        done = subprocess.run(probe, env=env, capture_output=True, text=True, timeout=seconds + 60)
        result: dict[str, float] = json.loads(done.stdout.strip().splitlines()[-1])
        result["dropped"] = result["sent"] - result["forwarded"] - result["reported"]
        return result
    finally:
        from ros_support import stop_all

        stop_all(processes)
        logs.close()


def baseline_package(revision: str, work: Path) -> Path:
    """The line follower's ROS 1 package as robosc ``revision`` generated it."""
    tree = work / f"robosc-{revision}"
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", revision, "src"], capture_output=True, check=True)
    tree.mkdir(parents=True, exist_ok=True)
    subprocess.run(["tar", "-x", "-C", str(tree)], input=archive.stdout, check=True)
    target = work / f"baseline-{revision}"
    code = (
        "from pathlib import Path; from robosc.api import load_model, plan_supervisor, synthesize_model; "
        "from robosc.codegen.ros import generate; "
        f"generate(plan_supervisor(synthesize_model(load_model({str(ROOT / 'examples/line_follower.rscd')!r}))), "
        f"1, 'controller', Path({str(target)!r}))"
    )
    subprocess.run([sys.executable, "-c", code], env={**os.environ, "PYTHONPATH": str(tree / "src")}, check=True)
    return target


def memory(
    seconds: float, rate: float, work: Path, baseline: str | None = None
) -> tuple[list[tuple[float, float]], float]:
    from ros_support import build_package, free_port

    if baseline:
        package = baseline_package(baseline, work)
    else:
        package = build_package("examples/line_follower.rscd", 1, "controller", work)
    port = free_port()
    env = env_ros1(port, work / "home")
    logs = open(work / "memory.log", "ab")  # noqa: SIM115
    processes = [
        subprocess.Popen(
            [ROS1_PYTHON, "/usr/bin/rosmaster", "--core", "-p", str(port)], env=env, stdout=logs, stderr=logs
        )
    ]
    try:
        time.sleep(1.5)
        script = next(p for p in (package / "scripts").iterdir() if p.name.split(".")[0].endswith("_node"))
        node = subprocess.Popen([ROS1_PYTHON, str(script), "_rate:=10.0"], env=env, stdout=logs, stderr=logs)
        processes.append(node)
        time.sleep(3.0)
        counted = work / "scans_sent"
        processes.append(
            subprocess.Popen(
                [ROS1_PYTHON, "-c", SCANS_ROS1, str(rate), str(counted)], env=env, stdout=logs, stderr=logs
            )
        )
        samples = []
        start = time.time()
        while time.time() - start <= seconds:
            samples.append((round(time.time() - start), rss_mb(node.pid)))
            time.sleep(10)
        sent, elapsed = counted.read_text().split()
        return samples, int(sent) / float(elapsed)
    finally:
        from ros_support import stop_all

        stop_all(processes)
        logs.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--part", choices=["layer", "memory", "all"], default="all")
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--memory-seconds", type=float, default=180.0)
    parser.add_argument("--baseline", help="memory: also run the node robosc REV generated (e.g. f1df180)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        if args.part in ("layer", "all"):
            print("| ROS | sent/s | forwarded/s | reported/s | dropped | seconds |")
            print("|---|---|---|---|---|---|")
            for ros in (1, 2):
                r = layer(ros, args.seconds, args.rate, Path(tmp))
                s = r["seconds"]
                print(
                    f"| {ros} | {r['sent'] / s:.0f} | {r['forwarded'] / s:.0f} | {r['reported'] / s:.0f} | {r['dropped']:.0f} | {s:.1f} |"
                )
        if args.part in ("memory", "all"):
            samples, achieved = memory(args.memory_seconds, args.rate, Path(tmp))
            print(
                f"\nROS 1 controller node, resident memory (MB) under malformed and 100,000-range scans ({achieved:.0f}/s):"
            )
            print(" ".join(f"{t}s:{mb:.1f}" for t, mb in samples))
            print(
                f"first {samples[0][1]:.1f} MB, last {samples[-1][1]:.1f} MB, most {max(mb for _, mb in samples):.1f} MB"
            )


if __name__ == "__main__":
    main()
