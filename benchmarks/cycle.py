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

    python benchmarks/cycle.py [--samples 300] [--skip-ros] [--baseline REV] [--write docs/performance.md]

With ``--baseline REV`` (e.g. ``f1df180``, before the runtime was split out of the
generated code) the ticks of that revision's generated modules are measured in the
same run, alternating with today's.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
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
    """The generated module of an example (this robosc), loaded on this robosc's runtime."""
    from robosc.api import load_model, plan_supervisor, synthesize_model
    from robosc.debug.simulator import load_module

    return load_module(plan_supervisor(synthesize_model(load_model(ROOT / "examples" / f"{name}.rscd"))))


def load_baseline(revision: str, name: str, work: Path) -> Any:
    """The generated module of an example as robosc ``revision`` wrote it (before the runtime
    was split out, the module was stand-alone: it loads next to today's in one process)."""
    import importlib.util

    tree = work / f"robosc-{revision}"
    if not tree.exists():
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", revision, "src"], capture_output=True, check=True)
        tree.mkdir(parents=True)
        subprocess.run(["tar", "-x", "-C", str(tree)], input=archive.stdout, check=True)
    code = (
        "import sys; from robosc.api import load_model, supervisor_module, synthesize_model; "
        f"sys.stdout.write(supervisor_module(synthesize_model(load_model({str(ROOT / 'examples' / (name + '.rscd'))!r}))))"
    )
    text = subprocess.run(
        [sys.executable, "-c", code],
        env={**os.environ, "PYTHONPATH": str(tree / "src")},
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    onboard = tree / "src/robosc/runtime/onboard"
    if onboard.exists():  # after the split: the module runs on that revision's runtime, as a package of its own
        package = work / f"baseline_{revision}_{name}"
        if not package.exists():
            shutil.copytree(onboard, package / "onboard")
        (package / "__init__.py").write_text("")
        (package / "supervisor.py").write_text(text)
        sys.path.insert(0, str(work))
        return importlib.import_module(f"{package.name}.supervisor")
    path = work / f"baseline_{name}.py"
    path.write_text(text)
    spec = importlib.util.spec_from_file_location(f"baseline_{name}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class Flavour:
    """How a benchmark case drives one generation of the generated code."""

    def __init__(self, label: str, module: Any, old: bool) -> None:
        self.label, self.module, self.old = label, module, old

    def robot(self) -> Any:
        """A supervisor that has had its data (a robot's start waits for it since issue 21)."""
        from robosc.runtime.onboard.values import Data

        if self.old:
            return self.module.Supervisor(seed=1)
        sup = self.module.Robot(seed=1)
        clear = Data({"ranges": [5.0] * 360})
        for event in ("scan_front", "scan_right", "scan_diag_right", "scan"):
            if event in sup.EVENT:
                sup.deliver(event, clear)
        if "correction" in sup.EVENT:
            sup.deliver("correction", 0.0)
        return sup

    def deliver(self, sup: Any, event: str, value: Any = None) -> None:
        if self.old:
            getattr(sup, f"on_{event}")(value)
        else:
            sup.deliver(event, value)


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


def timed_ticks(sup: Any, before: Callable[[int], None] | None, ticks: int = 1000) -> list[int]:
    clock = time.perf_counter_ns
    tick = sup.tick
    samples: list[int] = []
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


def cases(f: Flavour, maze: Any, lf: Any) -> dict[str, tuple[Any, Callable[[int], None] | None]]:
    """Each case: a supervisor and what happens before each timed tick."""
    from robosc.runtime.onboard.values import Data

    out: dict[str, tuple[Any, Callable[[int], None] | None]] = {}
    m = Flavour(f.label, maze, f.old)
    sup = m.robot()
    out["maze_solver, steady"] = (sup, None)
    walls = [Data({"ranges": [0.3] + [5.0] * 359}), Data({"ranges": [5.0] * 360})]
    sup2 = m.robot()

    def maze_message(i: int) -> None:  # a scan that changes what is in front, and the turn finished
        m.deliver(sup2, "rotate_done")
        m.deliver(sup2, "scan_front", walls[i % 2])

    out["maze_solver, after a message"] = (sup2, maze_message)
    line = Flavour(f.label, lf, f.old)
    sup3 = line.robot()
    line.deliver(sup3, "correction", 10.0)
    line.deliver(sup3, "scan", Data({"ranges": [5.0] * 360}))
    out["line_follower, steady"] = (sup3, None)
    sup4 = line.robot()
    line.deliver(sup4, "scan", Data({"ranges": [5.0] * 360}))

    def lf_message(i: int) -> None:  # a new line correction every cycle
        line.deliver(sup4, "correction", float(i % 7))

    out["line_follower, after a message"] = (sup4, lf_message)
    sup5 = m.robot()
    lock = sup5.lock

    class Locked:
        def tick(self) -> None:
            with lock:
                sup5.tick()

    out["maze_solver, steady, with the ROS 1 node's lock"] = (Locked(), None)
    return out


def tick_benchmarks(baseline: str | None, work: Path) -> list[dict[str, Any]]:
    """Each case 3 x 1000 ticks per flavour; with a baseline, the two flavours alternate
    run by run, so that the machine's changing speed hits both alike."""
    flavours = [(Flavour("now", None, False), load("maze_solver"), load("line_follower"))]
    if baseline:
        split = subprocess.run(
            ["git", "-C", str(ROOT), "cat-file", "-e", f"{baseline}:src/robosc/runtime/onboard/supervisor.py"],
            capture_output=True,
        )
        old = Flavour(baseline, None, split.returncode != 0)
        flavours.append(
            (old, load_baseline(baseline, "maze_solver", work), load_baseline(baseline, "line_follower", work))
        )
    prepared = [(f, cases(f, maze, lf)) for f, maze, lf in flavours]
    samples: dict[tuple[str, str], list[int]] = {}
    for _ in range(3):
        for f, table in prepared:
            for case, (sup, before) in table.items():
                samples.setdefault((case, f.label), []).extend(timed_ticks(sup, before))
    rows = []
    for f, table in prepared:
        for case, (sup, before) in table.items():
            row = {"case": case, "version": f.label, **summary(samples[(case, f.label)])}
            if before is None and "lock" not in case:
                row["batch"] = batch_tick_us(sup)
            rows.append(row)
    return sorted(rows, key=lambda r: (list(prepared[0][1]).index(r["case"]), r["version"] != "now"))


# ---- message in, command out, on real ROS ---------------------------------------------------

# what makes a message a trigger and a command a response to it, per example
SCENARIOS = {
    "maze_solver": {
        "topic_in": "/scan",
        "topic_out": "/rotate_left",
        "is_trigger": "lambda m: len(m.ranges) > 0 and m.ranges[0] < 0.6",  # a wall in front
        "is_command": "lambda m: True",
        "setup": [],
        # the way is free, then the turn is reported done
        "reset": [("/scan", "LaserScan", [5.0] * 360), ("/rotate_done", "Empty", None)],
        "trigger": [("/scan", "LaserScan", [0.3] + [5.0] * 359)],
    },
    "line_follower": {
        "topic_in": "/scan",
        "topic_out": "/cmd_vel",
        "is_trigger": "lambda m: len(m.ranges) > 0 and m.ranges[0] > 0.4",  # safe again
        "is_command": "lambda m: m.linear.x > 0.1",  # move, not halt
        "setup": [("/line/correction", "Float32", 5.0)],
        "reset": [("/scan", "LaserScan", [0.2] + [5.0] * 359)],
        "trigger": [("/scan", "LaserScan", [5.0] * 360)],
    },
}

# Runs the generated node with the runtime's receive and publish wrapped: the time from a
# trigger message entering the node to the command's publish() returning.
NODE_DRIVER = """
import json, sys, time
sys.path.insert(0, {path!r})
{ros_setup}
from {package}.onboard import {adapter} as adapter
from {package}.{module} import Robot
scenario = json.loads({scenario!r})
is_command = eval(scenario["is_command"])
is_trigger = eval(scenario["is_trigger"])
latencies, pending = [], [None]
receive, publish = adapter.SupervisorNode.receive, adapter.SupervisorNode.publish

def timed_receive(self, topic, message):
    if topic.name == scenario["topic_in"] and is_trigger(message):
        pending[0] = time.perf_counter()
    receive(self, topic, message)

def timed_publish(self, topic, message):
    done = publish(self, topic, message)
    if pending[0] is not None and topic.name == scenario["topic_out"] and is_command(message):
        latencies.append(time.perf_counter() - pending[0])
        pending[0] = None
        if len(latencies) >= {samples}:
            with open({out!r}, "w") as handle:
                json.dump(latencies, handle)
            {stop}
    return done

adapter.SupervisorNode.receive = timed_receive
adapter.SupervisorNode.publish = timed_publish
{run}
"""

ROBOT_ROS1 = """
import json, sys, time
import rospy
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Empty, Float32
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
from std_msgs.msg import Empty, Float32
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


def _plan(example: str) -> Any:
    from robosc.api import load_model, plan_supervisor, synthesize_model

    return plan_supervisor(synthesize_model(load_model(ROOT / "examples" / f"{example}.rscd")))


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
            args = [
                "__name:=bench",
                f"_tick_on_message:={'true' if tick_on_message else 'false'}",
                "_rate:=10.0",
                "_seed:=1",
            ]
            path, adapter = package / "src", "ros1"
            setup = f"sys.argv[1:] = {args!r}"
            stop, run = 'import rospy; rospy.signal_shutdown("done")', 'adapter.main(Robot, "controller", "bench")'
            robot = ROBOT_ROS1.format(gap=gap)
        else:
            domain = 150 + (os.getpid() % 50)
            env = {**os.environ, "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST", "ROS_DOMAIN_ID": str(domain)}
            python = sys.executable
            params = [
                "--ros-args",
                "-p",
                f"tick_on_message:={'true' if tick_on_message else 'false'}",
                "-p",
                "rate:=10.0",
                "-p",
                "seed:=1",
            ]
            path, adapter, setup = package, "ros2", ""
            stop, run = "raise SystemExit(0)", f'adapter.main(Robot, "controller", ["bench", *{params!r}])'
            robot = ROBOT_ROS2.format(gap=gap)
        from robosc.codegen.module import module_name
        from robosc.codegen.ros import package_name

        plan = _plan(example)
        driver = NODE_DRIVER.format(
            path=str(path),
            ros_setup=setup,
            package=package_name(plan),
            module=module_name(plan),
            adapter=adapter,
            scenario=json.dumps(scenario),
            samples=samples,
            out=str(out),
            stop=stop,
            run=run,
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
        from ros_support import stop_all

        stop_all(processes)
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
        "| case | version | avg | min | max | std dev | median | batch |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in ticks:
        batch = fmt(r["batch"]) if "batch" in r else "-"
        lines.append(
            f"| {r['case']} | {r['version']} | {fmt(r['avg'])} | {fmt(r['min'])} | {fmt(r['max'])} | {fmt(r['std'])} | {fmt(r['median'])} | {batch} |"
        )
    medians = {(r["case"], r["version"]): r["median"] for r in ticks}
    versions = sorted({r["version"] for r in ticks} - {"now"})
    for version in versions:
        lines += ["", f"Median now / median {version}:"]
        for case in dict.fromkeys(r["case"] for r in ticks):
            if (case, version) in medians:
                lines.append(f"- {case}: {medians[(case, 'now')] / medians[(case, version)]:.2f}")
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
    parser.add_argument("--baseline", help="a git revision whose generated code runs side by side (e.g. f1df180)")
    args = parser.parse_args()
    overhead = timer_overhead()
    with tempfile.TemporaryDirectory() as tmp:
        ticks = tick_benchmarks(args.baseline, Path(tmp))
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
