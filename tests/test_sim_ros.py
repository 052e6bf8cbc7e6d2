"""The paper's robots driven by their generated controller nodes on real middleware: the
simulator's node publishes /clock, scans and line readings and obeys the commands; one
controller per robot runs in its namespace with use_sim_time (ROS 2: rclpy with Fast DDS in a
domain of its own; ROS 1: rospy with a rosmaster of its own on 127.0.0.1)."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest

from ros_support import new_domain, ros1_available, ros2_available, unavailable

pytest.importorskip("irsim", reason="robosc sim needs IR-SIM (pip install '.[sim]')")

from robosc.api import plan_supervisor, synthesize_file
from robosc.debug.simulator import load_module
from robosc.sim.report import Report
from robosc.sim.run import run_ros
from robosc.sim.simulation import Simulation
from robosc.sim.world import load_world

ROOT = Path(__file__).resolve().parent.parent
WORLDS = ROOT / "examples" / "worlds"


def need(ros: int) -> None:
    if ros == 2 and not ros2_available():
        unavailable("ROS 2 (pip install '.[ros2]')")
    if ros == 1 and not ros1_available():
        unavailable("ROS 1 (Debian's python3-rospy, python3-rosmaster)")


def run(model: Path, world: str, ros: int, folder: Path, **options: object) -> Report:
    result = synthesize_file(model)
    assert result.ok
    plan = plan_supervisor(result)
    options.setdefault("domain", new_domain())
    return run_ros(load_world(WORLDS / world), plan, load_module(plan), ros, folder=folder, **options)  # type: ignore[arg-type]


def sim_times(log: Path) -> list[float]:
    return [json.loads(line)["time"] for line in log.read_text().splitlines()]


@pytest.mark.parametrize("ros", [2, 1])
def test_the_maze_solver_leaves_the_maze_on_ros(tmp_path: Path, ros: int) -> None:
    need(ros)
    report = run(ROOT / "examples" / "maze_solver.rscd", "maze.yaml", ros, tmp_path, timeout=150, speed=8.0)
    robot = report.robots[0]
    assert report.ok, report.why + "\n" + _logs(tmp_path)
    assert robot.collided_at is None and robot.closest > 0.05
    assert 60 < robot.reached < 120
    assert robot.commands > 300  # the controller's Twists and rotations came over ROS
    assert report.wall < report.simulated / 3  # faster than real time: the nodes follow /clock
    # the controller ran on the simulation's clock: its event log is stamped in simulated seconds
    times = sim_times(tmp_path / "events" / "robot1.jsonl")
    assert 0 <= times[0] < 1.0 and report.simulated - 2.0 < times[-1] <= report.simulated + 0.5
    # ... and its timer too: 10 cycles per simulated second, not per wall second
    cycles = re.search(r"\[robosc\] stopped after (\d+) cycles", (tmp_path / "logs" / "robot1.log").read_text())
    assert cycles is not None
    assert abs(int(cycles.group(1)) - 10 * report.simulated) < 0.05 * 10 * report.simulated


def test_the_line_follower_stops_for_the_emergency_stop_button_and_before_the_box(ros2, tmp_path: Path) -> None:
    from std_srvs.srv import SetBool

    client = ros2.node.create_client(SetBool, "/robot1/emergency_stop_button")
    calls: list[tuple[float, bool, object]] = []  # (sim time, pressed, future)
    poses: dict[float, tuple[float, float]] = {}

    def on_step(sim: Simulation) -> None:
        t = round(sim.time, 2)
        if t in (10.0, 20.0):
            request = SetBool.Request()
            request.data = t == 10.0
            calls.append((t, request.data, client.call_async(request)))
        ros2.executor.spin_once(timeout_sec=0)
        pose = sim.bodies[0].pose
        poses[t] = (pose.x, pose.y)

    report = run(
        ROOT / "examples" / "line_follower.rscd", "line.yaml", 2, tmp_path, timeout=100, speed=4.0,
        domain=ros2.domain, on_step=on_step,
    )
    assert report.ok, report.why + "\n" + _logs(tmp_path)
    assert [(t, pressed, future.done()) for t, pressed, future in calls] == [(10.0, True, True), (20.0, False, True)]  # type: ignore[attr-defined]
    assert math.dist(poses[11.0], poses[20.0]) < 0.005  # stopped within a second of the press, until the release
    assert math.dist(poses[5.0], poses[10.0]) > 0.5 and math.dist(poses[21.0], poses[26.0]) > 0.5
    world = load_world(WORLDS / "line.yaml")
    box_x, _, box_w, _ = world.boxes[0]
    final = report.status[0].trajectory[-1]
    assert final[1] < box_x - box_w / 2 - world.robot.radius and report.robots[0].closest > 0.1
    events = [json.loads(line)["event"] for line in (tmp_path / "events" / "robot1.jsonl").read_text().splitlines()]
    assert "stop" in events and "continue" in events  # the button's messages reached the controller


def test_a_broken_line_follower_hits_the_box_on_ros(tmp_path: Path) -> None:
    need(1)
    text = (ROOT / "examples" / "line_follower.rscd").read_text()
    requirement = "    requirement move needs LineDetector.line_found and Lidar.safety = safe\n"
    assert requirement in text
    model = tmp_path / "model" / "line_follower.rscd"
    model.parent.mkdir()
    model.write_text(text.replace(requirement, ""))
    (model.parent / "emergency_stop.rscd").write_text((ROOT / "examples" / "emergency_stop.rscd").read_text())
    report = run(model, "line.yaml", 1, tmp_path / "run", timeout=80, speed=8.0)
    assert not report.ok and "robot1 touched a wall or box" in report.why
    assert report.robots[0].collided_at is not None


def test_a_fleet_of_maze_solvers_on_one_ros2_graph(tmp_path: Path) -> None:
    need(2)
    report = run(ROOT / "examples" / "maze_solver.rscd", "maze.yaml", 2, tmp_path, robots=3, timeout=150, speed=4.0)
    assert report.ok, report.why + "\n" + _logs(tmp_path)
    assert [r.name for r in report.robots] == ["robot1", "robot2", "robot3"]
    assert all(r.collided_at is None and 60 < (r.reached or 0) < 120 for r in report.robots)
    for name in ("robot1", "robot2", "robot3"):  # one controller node per robot, each in its namespace
        log = (tmp_path / "logs" / f"{name}.log").read_text()
        assert f"[{name}.maze_solver_robosc]" in log


def _logs(folder: Path) -> str:
    return "\n".join(f"--- {p.name}\n{p.read_text(errors='replace')[-2000:]}" for p in sorted((folder / "logs").glob("*.log")))


@pytest.mark.parametrize("ros", [2, 1])
def test_a_controller_that_dies_ends_the_run_with_who_and_when(tmp_path: Path, ros: int) -> None:
    """kill -9 of robot1's controller in the middle of a run: robosc sim says which robot, at
    what simulated time and how, and the run fails (before: it ran on until its timeout)."""
    import signal

    need(ros)
    graphs: list[object] = []

    def kill_at_five(sim: Simulation) -> None:
        if sim.time >= 5.0 and graphs:
            for name, process in graphs.pop().processes:  # type: ignore[attr-defined]
                if name == "robot1":
                    process.send_signal(signal.SIGKILL)

    report = run(
        ROOT / "examples" / "maze_solver.rscd",
        "maze.yaml",
        ros,
        tmp_path,
        timeout=150,
        speed=4.0,
        on_start=graphs.append,
        on_step=kill_at_five,
    )
    assert not report.ok
    assert re.fullmatch(r"the controller of robot1 died at 5\.\d s simulated \(killed by signal 9\)", report.why), report.why
    assert report.simulated < 7.0


@pytest.mark.parametrize(("ros", "sig"), [(2, "SIGTERM"), (1, "SIGTERM"), (2, "SIGHUP"), (1, "SIGKILL")])
def test_ending_robosc_sim_ends_every_process_it_started(tmp_path: Path, ros: int, sig: str) -> None:
    """``kill -TERM`` (or -HUP) of a running ``robosc sim`` ends its controllers, the
    simulator's node and the rosmaster within 5 s; ``kill -9`` too (they are asked to end when
    their parent dies). Before: they ran on with parent 1."""
    import os
    import signal
    import subprocess
    import sys
    import uuid

    import strays
    from robosc import children
    from ros_support import wait_until

    need(ros)
    mark, variable = uuid.uuid4().hex, "ROBOSC_SIM_PROBE"
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    env[variable] = mark
    args = ["sim", str(WORLDS / "maze.yaml"), str(ROOT / "examples" / "maze_solver.rscd"), "--ros", str(ros)]
    args += ["--robots", "2", "--speed", "1", "--timeout", "200", "--domain", str(new_domain())]
    log = tmp_path / "sim.log"
    with log.open("wb") as out:
        process = children.start([sys.executable, "-m", "robosc", *args], env=env, stdout=out, stderr=subprocess.STDOUT)
    try:
        assert wait_until(lambda: "the robots run on" in log.read_text(errors="replace"), 90), log.read_text()
        started = strays.marked(mark, variable)
        started.pop(process.pid, None)
        names = " ".join(started.values())
        assert names.count("__ns:=/robot") == 2, started  # the two controllers
        assert ("rosmaster" in names) == (ros == 1), started
        os.kill(process.pid, getattr(signal, sig))
        process.wait(timeout=30)
        assert process.returncode == (-9 if sig == "SIGKILL" else 128 + getattr(signal, sig)), log.read_text()
        left = strays.strays(mark, grace=5.0, variable=variable)
        assert not left, strays.report(left)
    finally:
        children.stop([process])
        strays.strays(mark, grace=0.0, variable=variable)
