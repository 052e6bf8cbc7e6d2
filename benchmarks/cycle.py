"""The paper's Table I measurement for the generated Python supervisor.

1. The controller tick without middleware: ``Supervisor.tick()`` of the generated
   module, 3 x 1000 ticks, each timed with ``time.perf_counter_ns``; average, min,
   max, standard deviation and median in microseconds. Two cases: a steady tick
   (no message since the last tick: the allowed events are known, one is chosen
   and sent) and a tick after a message changed the state (data events and every
   guard evaluated again). The timer's own cost per reading is printed too.
2. Message in to command out on real ROS 1 (rosmaster + rospy) and ROS 2 (rclpy,
   Fast DDS): inside the generated node, from the subscription callback being
   entered to the command's ``publish()`` returning; a second process plays the
   robot. Measured with ``tick_on_message`` (a cycle right after each message)
   and, for comparison, with the default 10 Hz timer only.

    python benchmarks/cycle.py [--samples 300] [--skip-ros] [--write docs/performance.md]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
ROS1_PYTHON = os.environ.get("ROBOSC_ROS1_PYTHON", "/usr/bin/python3")


def load(name: str) -> Any:
    from robosc.api import load_model, plan_supervisor, synthesize_model
    from robosc.runtime.simulator import load_module

    return load_module(plan_supervisor(synthesize_model(load_model(ROOT / "examples" / f"{name}.rscd"))))


def summary(samples_ns: list[int]) -> dict[str, float]:
    us = [s / 1000 for s in samples_ns]
    return {
        "avg": statistics.fmean(us),
        "min": min(us),
        "max": max(us),
        "std": statistics.pstdev(us),
        "median": statistics.median(us),
        "n": len(us),
    }


def timed_ticks(sup: Any, before: Callable[[int], None] | None, runs: int = 3, ticks: int = 1000) -> list[int]:
    clock = time.perf_counter_ns
    tick = sup.tick
    samples: list[int] = []
    for _ in range(runs):
        for i in range(ticks):
            if before is not None:
                before(i)
            start = clock()
            tick()
            samples.append(clock() - start)
    return samples


def timer_overhead() -> float:
    clock = time.perf_counter_ns
    gaps = []
    for _ in range(30000):
        a = clock()
        b = clock()
        gaps.append(b - a)
    return statistics.median(gaps) / 1000


def batch_tick_us(sup: Any, n: int = 200_000) -> float:
    tick = sup.tick
    start = time.perf_counter()
    for _ in range(n):
        tick()
    return (time.perf_counter() - start) / n * 1e6


def tick_benchmarks() -> list[dict[str, Any]]:
    rows = []
    maze = load("maze_solver")
    sup = maze.Supervisor(seed=1)
    rows.append(
        {"example": "maze_solver", "case": "steady", **summary(timed_ticks(sup, None)), "batch": batch_tick_us(sup)}
    )
    walls = [maze.Data({"ranges": [0.3] + [5.0] * 359}), maze.Data({"ranges": [5.0] * 360})]
    sup = maze.Supervisor(seed=1)

    def maze_message(i: int) -> None:  # a scan that changes what is in front, and the turn finished
        sup.on_rotate_done()
        sup.on_scan_front(walls[i % 2])

    rows.append({"example": "maze_solver", "case": "after a message", **summary(timed_ticks(sup, maze_message))})
    lf = load("line_follower")
    sup = lf.Supervisor(seed=1)
    sup.on_correction(10.0)
    sup.on_scan(lf.Data({"ranges": [5.0] * 360}))
    rows.append(
        {"example": "line_follower", "case": "steady", **summary(timed_ticks(sup, None)), "batch": batch_tick_us(sup)}
    )
    sup2 = lf.Supervisor(seed=1)
    sup2.on_scan(lf.Data({"ranges": [5.0] * 360}))

    def lf_message(i: int) -> None:  # a new line correction every cycle
        sup2.on_correction(float(i % 7))

    rows.append({"example": "line_follower", "case": "after a message", **summary(timed_ticks(sup2, lf_message))})
    # the ROS 1 node holds its lock around each tick (rospy runs callbacks on threads)
    sup3 = maze.Supervisor(seed=1)
    lock = sup3.lock

    class Locked:
        def tick(self) -> None:
            with lock:
                sup3.tick()

    rows.append(
        {"example": "maze_solver", "case": "steady, with the ROS 1 node's lock", **summary(timed_ticks(Locked(), None))}
    )
    return rows


# ---- message in, command out, on real ROS ---------------------------------------------------

# (example, topic in, receive method, publisher attribute, output check, robot script)
SCENARIOS = {
    "maze_solver": {
        "receive": "receive_scan",
        "publisher": "pub_rotate_left",
        "is_trigger": "lambda m: len(m.ranges) > 0 and m.ranges[0] < 0.6",  # a wall in front
        "is_command": "lambda m: True",
        "setup": [],
        # the way is free, then the turn is reported done
        "reset": [("/scan", "LaserScan", [5.0] * 360), ("/rotate_done", "Empty", None)],
        "trigger": [("/scan", "LaserScan", [0.3] + [5.0] * 359)],
    },
    "line_follower": {
        "receive": "receive_scan",
        "publisher": "pub_cmd_vel",
        "is_trigger": "lambda m: len(m.ranges) > 0 and m.ranges[0] > 0.4",  # safe again
        "is_command": "lambda m: m.linear.x > 0.1",  # move, not halt
        "setup": [("/line/correction", "Float64", 5.0)],
        "reset": [("/scan", "LaserScan", [0.2] + [5.0] * 359)],
        "trigger": [("/scan", "LaserScan", [5.0] * 360)],
    },
}

NODE_DRIVER = """
import json, sys, time
sys.path.insert(0, {path!r})
{ros_setup}
import {module} as generated
scenario = json.loads({scenario!r})
is_command = eval(scenario["is_command"])
is_trigger = eval(scenario["is_trigger"])
latencies, pending = [], [None]
original_receive = getattr(generated.Node, scenario["receive"])

def receive(self, message):
    if is_trigger(message):
        pending[0] = time.perf_counter()
    original_receive(self, message)

setattr(generated.Node, scenario["receive"], receive)
node = generated.Node({node_args})
publisher = getattr(node, scenario["publisher"])
original_publish = publisher.publish

def publish(message, *rest):
    original_publish(message, *rest)
    if pending[0] is not None and is_command(message):
        latencies.append(time.perf_counter() - pending[0])
        pending[0] = None
        if len(latencies) >= {samples}:
            with open({out!r}, "w") as handle:
                json.dump(latencies, handle)
            {stop}

publisher.publish = publish
{spin}
"""

ROBOT_ROS1 = """
import json, sys, time
import rospy
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Empty, Float64
scenario = json.loads(sys.argv[1])
rospy.init_node("robot", anonymous=True)
pubs = {{}}
def send(topic, kind, data):
    if topic not in pubs:
        pubs[topic] = rospy.Publisher(topic, globals()[kind], queue_size=10)
        time.sleep(0.5)
    if kind == "LaserScan":
        m = LaserScan(); m.ranges = data
    elif kind == "Empty":
        m = Empty()
    else:
        m = globals()[kind](data=data)
    pubs[topic].publish(m)
for step in scenario["setup"] + scenario["reset"] + scenario["trigger"]:
    send(*step)
time.sleep(1.0)
for s in scenario["setup"]:
    send(*s)
while not rospy.is_shutdown():
    for step in scenario["reset"]:
        send(*step)
        time.sleep(0.01)
    time.sleep({gap})
    for step in scenario["trigger"]:
        send(*step)
    time.sleep({gap})
"""

ROBOT_ROS2 = """
import json, sys, time
import rclpy
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Empty, Float64
scenario = json.loads(sys.argv[1])
rclpy.init()
node = rclpy.create_node("robot")
pubs = {{}}
def send(topic, kind, data):
    if topic not in pubs:
        pubs[topic] = node.create_publisher(globals()[kind], topic, 10)
    if kind == "LaserScan":
        m = LaserScan(); m.ranges = [float(x) for x in data]
    elif kind == "Empty":
        m = Empty()
    else:
        m = globals()[kind](data=data)
    pubs[topic].publish(m)
for step in scenario["setup"] + scenario["reset"] + scenario["trigger"]:
    send(*step)
end = time.time() + 2.0
while time.time() < end:
    rclpy.spin_once(node, timeout_sec=0.05)
for s in scenario["setup"]:
    send(*s)
while True:
    for step in scenario["reset"]:
        send(*step)
        time.sleep(0.01)
    rclpy.spin_once(node, timeout_sec={gap})
    for step in scenario["trigger"]:
        send(*step)
    rclpy.spin_once(node, timeout_sec={gap})
"""


def ros_latency(ros: int, example: str, samples: int, tick_on_message: bool, work: Path) -> dict[str, Any] | None:
    from ros_support import build_package, free_port, wait_until

    package = build_package(f"examples/{example}.rscd", ros, "controller", work)
    scenario = SCENARIOS[example]
    out = work / f"latency_{ros}_{example}_{tick_on_message}.json"
    out.unlink(missing_ok=True)
    gap = 0.05 if tick_on_message else 0.25
    processes: list[subprocess.Popen[bytes]] = []
    logs = open(work / "bench.log", "ab")  # noqa: SIM115
    try:
        if ros == 1:
            port = free_port()
            env = {
                **{k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "PYTHON"))},
                "ROS_MASTER_URI": f"http://127.0.0.1:{port}",
                "ROS_HOSTNAME": "127.0.0.1",
                "ROS_HOME": str(work / "ros_home"),
            }
            processes.append(
                subprocess.Popen(
                    [ROS1_PYTHON, "/usr/bin/rosmaster", "--core", "-p", str(port)], env=env, stdout=logs, stderr=logs
                )
            )
            time.sleep(1.5)
            python = ROS1_PYTHON
            scripts = package / "scripts"
            module = next(scripts.glob("*_node.py")).stem
            args = [
                "__name:=bench",
                f"_tick_on_message:={'true' if tick_on_message else 'false'}",
                "_rate:=10.0",
                "_seed:=1",
            ]
            path, setup = scripts, f"sys.argv[1:] = {args!r}\nimport rospy"
            stop, spin = 'rospy.signal_shutdown("done")', "rospy.spin()"
            robot = ROBOT_ROS1.format(gap=gap)
        else:
            domain = 150 + (os.getpid() % 50)
            env = {**os.environ, "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST", "ROS_DOMAIN_ID": str(domain)}
            python = sys.executable
            module = next(p.name for p in package.iterdir() if (p / "node.py").exists()) + ".node"
            params = [
                "--ros-args",
                "-p",
                f"tick_on_message:={'true' if tick_on_message else 'false'}",
                "-p",
                "rate:=10.0",
                "-p",
                "seed:=1",
            ]
            path, setup = package, f"import rclpy\nrclpy.init(args=['bench', *{params!r}])"
            stop, spin = "raise SystemExit(0)", "rclpy.spin(node.node)"
            robot = ROBOT_ROS2.format(gap=gap)
        driver = NODE_DRIVER.format(
            path=str(path),
            ros_setup=setup,
            module=module,
            scenario=json.dumps(scenario),
            node_args="",
            samples=samples,
            out=str(out),
            stop=stop,
            spin=spin,
        )
        processes.append(subprocess.Popen([python, "-c", driver], env=env, stdout=logs, stderr=logs))
        time.sleep(2.0)
        processes.append(
            subprocess.Popen([python, "-c", robot, json.dumps(scenario)], env=env, stdout=logs, stderr=logs)
        )
        limit = 30 + samples * gap * 3
        if not wait_until(out.exists, limit, 0.2):
            return None
        time.sleep(0.2)
        values = [int(v * 1e9) for v in json.loads(out.read_text())]
        return {
            "ros": ros,
            "example": example,
            "tick_on_message": tick_on_message,
            **summary(values),
            "p99": percentile(values, 99) / 1000,
        }
    finally:
        for p in reversed(processes):
            p.terminate()
        for p in processes:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
        logs.close()


def percentile(values: list[int], q: float) -> float:
    ordered = sorted(values)
    index = min(len(ordered) - 1, max(0, round(q / 100 * (len(ordered) - 1))))
    return float(ordered[index])


def fmt(x: float) -> str:
    return f"{x:.3f}" if x < 10 else f"{x:.1f}"


def report(ticks: list[dict[str, Any]], overhead: float, latencies: list[dict[str, Any]], samples: int) -> str:
    lines = [
        "### Controller tick without middleware (`benchmarks/cycle.py`)",
        "",
        f"3 x 1000 ticks per row, each timed with `perf_counter_ns` (one reading costs {overhead:.3f} µs, included in each sample); "
        "`batch`: 200,000 ticks timed together, per tick. Microseconds.",
        "",
        "| example | case | avg | min | max | std dev | median | batch |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in ticks:
        batch = fmt(r["batch"]) if "batch" in r else "-"
        lines.append(
            f"| {r['example']} | {r['case']} | {fmt(r['avg'])} | {fmt(r['min'])} | {fmt(r['max'])} | {fmt(r['std'])} | {fmt(r['median'])} | {batch} |"
        )
    lines += [
        "",
        "### Message in to command out on real ROS (`benchmarks/cycle.py`)",
        "",
        "Inside the generated node: from entering the subscription callback to `publish()` of the resulting command "
        f"returning; {samples} samples per row (fewer where noted), a second process plays the robot. Microseconds.",
        "",
        "| ROS | example | cycle | samples | median | p99 | avg | min | max |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in latencies:
        cycle = "tick on message" if r["tick_on_message"] else "10 Hz timer only"
        if "median" not in r:
            lines.append(f"| {r['ros']} | {r['example']} | {cycle} | 0 | (no result) | | | | |")
            continue
        lines.append(
            f"| {r['ros']} | {r['example']} | {cycle} | {r['n']} | {fmt(r['median'])} | {fmt(r['p99'])} | {fmt(r['avg'])} | {fmt(r['min'])} | {fmt(r['max'])} |"
        )
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--samples", type=int, default=300)
    parser.add_argument("--skip-ros", action="store_true")
    parser.add_argument("--write", type=Path, help="replace the cycle section of this markdown file")
    args = parser.parse_args()
    overhead = timer_overhead()
    ticks = tick_benchmarks()
    latencies: list[dict[str, Any]] = []
    if not args.skip_ros:
        with tempfile.TemporaryDirectory() as tmp:
            for ros in (1, 2):
                for example in ("maze_solver", "line_follower"):
                    for on_message, n in ((True, args.samples), (False, max(20, args.samples // 10))):
                        found = ros_latency(ros, example, n, on_message, Path(tmp))
                        latencies.append(found or {"ros": ros, "example": example, "tick_on_message": on_message})
    text = report(ticks, overhead, latencies, args.samples)
    print(text)
    if args.write:
        start, end = "<!-- cycle:begin -->", "<!-- cycle:end -->"
        doc = args.write.read_text() if args.write.exists() else ""
        block = f"{start}\n{text}{end}"
        if start in doc and end in doc:
            doc = doc[: doc.index(start)] + block + doc[doc.index(end) + len(end) :]
        else:
            doc = doc.rstrip() + "\n\n## Run time\n\n" + block + "\n"
        args.write.write_text(doc)


if __name__ == "__main__":
    main()
