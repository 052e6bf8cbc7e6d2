"""Fleet benchmark (issue 11): N maze solvers in one world, each with its own namespaced
controller node (one generated package, N instances) on one ROS 2 graph, for N = 1, 2, 4, 8,
16. For each N, two runs of the same simulated time:

- timer-driven (the generated default, 10 cycles per simulated second): wall time, CPU seconds
  per controller process (from /proc), and missed cycles (the cycles each node says it ran at
  shutdown, against simulated time x rate);
- message-driven (``tick_on_message``, the timer at 0.01 Hz): latency from a LaserScan leaving
  the simulation to the first command of that robot coming back (bridge -> DDS -> controller
  -> DDS -> bridge), median and p99, in wall milliseconds; a scan that no command answers
  before the next scan (the robot is turning: nothing to command) is not counted.

Run: python benchmarks/fleet.py [--sizes 1 2 4 8 16] [--seconds 20] [--speed 2] [--ros 2]

With ``--world warehouse`` (issue 31): the warehouse's coordinator package
(``examples/warehouse.rscd`` with N robots, its default parameters) commanding N robots in the
warehouse's world (``examples/worlds/warehouse.yaml``, the person included; from 9 robots on
``warehouse_large.yaml``, the same with sixteen homes) on ROS 2 until each has done one task, as
``robosc sim`` runs it, for N = 2, 4, 8, 16 (``--speed``: at most that many simulated seconds
per real second; the physics of 16 robots runs at about 3):
simulated seconds per wall second, the coordinator's CPU (from /proc), decision latency (an
answer leaving the simulation -> the next command coming back: bridge -> DDS -> coordinator ->
DDS -> bridge, median and p99 in wall milliseconds; an answer no command follows before the next
answer is not counted), messages per wall second (answers and commands), tasks per simulated
hour, the time each robot stood waiting (mean), collisions and how the run ended.

Run: python benchmarks/fleet.py --world warehouse [--sizes 2 4 8 16] [--speed 4]

With ``--world throughput`` (issue 46): benchmarks/throughput.py, the tasks per simulated hour
of the coordinator's policy, of the random choice and of the reservation rule against the
world's physical bound, in the warehouse at 4, 8 and 16 robots and the lane, swap and crossing
scenarios (``--tasks K`` per robot).
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TICKS = os.sysconf("SC_CLK_TCK")


def cpu_seconds(pid: int) -> float | None:
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return None
    return (int(fields[11]) + int(fields[12])) / TICKS  # utime + stime


def one_run(plan, module, world, ros: int, robots: int, seconds: float, speed: float, message_driven: bool) -> dict:
    from robosc.sim.run import run_ros

    graph_box: list = []
    cpu: dict[str, float] = {}
    sent: list[float | None] = [None] * robots  # wall time of the last scan not yet answered
    latencies: list[float] = []

    def on_start(graph) -> None:
        graph_box.append(graph)

    def on_step(sim) -> None:
        if sim.steps % 20 == 0 and graph_box:  # every simulated second: the controllers' CPU so far
            for name, process in graph_box[0].processes:
                if name.startswith("robot"):
                    value = cpu_seconds(process.pid)
                    if value is not None:
                        cpu[name] = value

    def trace(direction: str, robot: int, role: str, now: float) -> None:
        if direction == "out" and role == "scan":
            sent[robot] = now  # a scan no command answered (the robot is turning) is not counted
        elif direction == "in" and sent[robot] is not None:
            latencies.append(now - sent[robot])
            sent[robot] = None

    params: dict[str, object] = {"tick_on_message": True} if message_driven else {}
    rate = 0.01 if message_driven else 10.0
    with tempfile.TemporaryDirectory(prefix="robosc-fleet-") as folder:
        report = run_ros(
            world, plan, module, ros, robots=robots, timeout=seconds, speed=speed, rate=rate,
            folder=Path(folder), domain=60 + robots, on_step=on_step, on_start=on_start, trace=trace, params=params,
        )
        cycles = []
        for name in (r.name for r in report.robots):
            found = re.search(r"stopped after (\d+) cycles", (Path(folder) / "logs" / f"{name}.log").read_text())
            cycles.append(int(found.group(1)) if found else 0)
    expected = int(report.simulated * rate + 1e-6)
    return {
        "wall": report.wall,
        "simulated": report.simulated,
        "collided": sum(r.collided_at is not None for r in report.robots),
        "cpu": statistics.mean(cpu.values()) if cpu else float("nan"),
        "missed": sum(max(0, expected - c) for c in cycles),
        "expected": expected * robots,
        "latencies": latencies,
    }


def warehouse_run(robots: int, speed: float, ros: int) -> dict:
    """One run of the warehouse's fleet with ``robots`` robots (see the module's description)."""
    from robosc.api import check_text, plan_supervisor, synthesize_model
    from robosc.debug.simulator import load_module
    from robosc.sim.fleet_ros import run_fleet_ros
    from robosc.sim.world import load_world

    path = ROOT / "examples" / "warehouse.rscd"
    text = path.read_text().replace("component bot[3]", f"component bot[{robots}]")
    plan = plan_supervisor(synthesize_model(check_text(text, path=str(path)).model))
    world = load_world(ROOT / "examples" / "worlds" / ("warehouse.yaml" if robots <= 8 else "warehouse_large.yaml"))
    cpu: list[float] = []
    events: list[tuple[str, float]] = []

    def on_end(graph) -> None:
        for name, process in graph.processes:
            if name == "coordinator":
                cpu.append(cpu_seconds(process.pid) or float("nan"))

    def trace(direction: str, name: str, now: float) -> None:
        events.append((direction, now))

    with tempfile.TemporaryDirectory(prefix="robosc-fleet-") as folder:
        report = run_fleet_ros(
            world, plan, load_module(plan), ros, robots, tasks=1, timeout=400.0 * robots, speed=speed,
            folder=Path(folder), domain=60 + robots, trace=trace, on_end=on_end,
        )
    latencies = []
    answered: float | None = None
    for direction, now in events:
        if direction == "out":
            answered = now  # an answer no command follows before the next one is not counted
        elif answered is not None:
            latencies.append(now - answered)
            answered = None
    return {"report": report, "cpu": cpu[0] if cpu else float("nan"), "latencies": latencies, "messages": len(events)}


def warehouse(sizes: list[int], speed: float, ros: int) -> None:
    print(f"the warehouse's fleet on ROS {ros}, one task per robot, {speed:g}x real time, "
          f"{os.cpu_count()} cores; Python {sys.version.split()[0]}")
    print("| N | simulated s | wall s | sim / wall | coordinator CPU % | decision ms median | p99 | samples "
          "| messages / s | tasks / sim h | waiting s / robot | collisions | ended |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for n in sizes:
        got = warehouse_run(n, speed, ros)
        report = got["report"]
        lat = sorted(1000 * x for x in got["latencies"])
        median = statistics.median(lat) if lat else float("nan")
        p99 = lat[min(len(lat) - 1, int(0.99 * len(lat)))] if lat else float("nan")
        tasks = sum(s.tasks for s in report.robots)
        waiting = statistics.mean(s.waiting for s in report.robots)
        print(f"| {n} | {report.simulated:.0f} | {report.wall:.0f} | {report.simulated / report.wall:.1f} "
              f"| {100 * got['cpu'] / report.wall:.1f} | {median:.1f} | {p99:.1f} | {len(lat)} "
              f"| {got['messages'] / report.wall:.1f} | {3600 * tasks / report.simulated:.0f} | {waiting:.0f} "
              f"| {report.collisions} | {report.why.split(':')[0]} |", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--world", choices=["maze", "warehouse", "throughput"], default="maze")
    parser.add_argument("--tasks", type=int, default=2, help="--world throughput: tasks per robot")
    parser.add_argument("--sizes", type=int, nargs="+")
    parser.add_argument("--seconds", type=float, default=20.0, help="simulated seconds per run")
    parser.add_argument("--speed", type=float, help="simulated seconds per wall second (2; the warehouse: 4)")
    parser.add_argument("--ros", type=int, choices=[1, 2], default=2)
    args = parser.parse_args()
    os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    if args.world == "warehouse":
        warehouse(args.sizes or [2, 4, 8, 16], args.speed or 4.0, args.ros)
        return
    if args.world == "throughput":  # benchmarks/throughput.py: the work done against the bound
        sys.path.insert(0, str(ROOT / "benchmarks"))
        from throughput import main as throughput

        throughput(["--sizes", *map(str, args.sizes or [4, 8, 16]), "--tasks", str(args.tasks)])
        return
    args.sizes = args.sizes or [1, 2, 4, 8, 16]
    args.speed = args.speed or 2.0

    from robosc.api import plan_supervisor, synthesize_file
    from robosc.debug.simulator import load_module
    from robosc.sim.world import load_world

    result = synthesize_file(ROOT / "examples" / "maze_solver.rscd")
    plan = plan_supervisor(result)
    module = load_module(plan)
    world = load_world(ROOT / "examples" / "worlds" / "maze.yaml")
    print(f"maze solvers on ROS {args.ros}, {args.seconds:g} s simulated per run at {args.speed:g}x real time, "
          f"{os.cpu_count()} cores; Python {sys.version.split()[0]}")
    print(f"{'N':>3} {'wall s':>7} {'CPU s/ctrl':>10} {'CPU %/ctrl':>10} {'missed cycles':>14} "
          f"{'latency ms median':>18} {'p99':>7} {'samples':>8} {'collided':>8}")
    for n in args.sizes:
        timer = one_run(plan, module, world, args.ros, n, args.seconds, args.speed, message_driven=False)
        driven = one_run(plan, module, world, args.ros, n, args.seconds, args.speed, message_driven=True)
        lat = sorted(1000 * x for x in driven["latencies"])
        median = statistics.median(lat) if lat else float("nan")
        p99 = lat[min(len(lat) - 1, int(0.99 * len(lat)))] if lat else float("nan")
        share = 100 * timer["cpu"] / timer["wall"] if timer["wall"] else float("nan")
        print(f"{n:>3} {timer['wall']:>7.1f} {timer['cpu']:>10.2f} {share:>10.1f} "
              f"{timer['missed']:>6} of {timer['expected']:<6} {median:>18.1f} {p99:>7.1f} {len(lat):>8} "
              f"{timer['collided'] + driven['collided']:>8}", flush=True)


if __name__ == "__main__":
    main()
