"""The 2D simulation (IR-SIM bodies): what a command does to a robot, what its sensors say,
and the paper's robots driven by their generated supervisors in this process."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

pytest.importorskip("irsim", reason="robosc sim needs IR-SIM (pip install '.[sim]')")

from robosc.api import plan_supervisor, synthesize_file
from robosc.cli.main import main
from robosc.debug.simulator import load_module
from robosc.sim.run import roles, run_local
from robosc.sim.simulation import Simulation
from robosc.sim.world import load_world

ROOT = Path(__file__).resolve().parent.parent
WORLDS = ROOT / "examples" / "worlds"

ROOM = """\
world: room
size: [6, 4]
robot: {radius: 0.1, max_linear: 0.3, max_angular: 2.0, turn_speed: 1.5, command_timeout: 0.3}
starts:
  - [2, 2, 0]
goal: {x: [5, 6], y: [0, 4], stopped: 1.0}
walls:
  - [[4, 0], [4, 1.5]]
"""


def world(tmp_path: Path, text: str = ROOM):
    path = tmp_path / "world.yaml"
    path.write_text(text, encoding="utf-8")
    return load_world(path)


def steps(sim: Simulation, seconds: float) -> list:
    out = []
    for _ in range(round(seconds / sim.world.step)):
        out += sim.step()
    return out


# ---- the bases -----------------------------------------------------------------------------


@pytest.mark.parametrize("degrees", [90, -90, 180])
def test_rotate_turns_in_place_by_the_angle_and_then_says_done(tmp_path: Path, degrees: int) -> None:
    sim = Simulation(world(tmp_path))
    sim.rotate(0, degrees)
    out = steps(sim, 3.0)
    pose = sim.bodies[0].pose
    turned = math.degrees(math.atan2(math.sin(pose.heading), math.cos(pose.heading)))
    assert turned == pytest.approx(degrees if degrees != 180 else math.copysign(180, turned), abs=0.5)
    assert (pose.x, pose.y) == pytest.approx((2.0, 2.0), abs=1e-6)  # in place
    assert [m.role for m in out if m.role == "rotate_done"] == ["rotate_done"]
    assert sim.status[0].commands == 1


def test_a_velocity_is_obeyed_for_the_command_timeout_only(tmp_path: Path) -> None:
    sim = Simulation(world(tmp_path))
    sim.command_velocity(0, 0.2, 0.0)
    steps(sim, 2.0)
    # 0.3 s at 0.2 m/s, then the base stops on its own
    assert sim.status[0].distance == pytest.approx(0.06, abs=1e-6)
    assert sim.bodies[0].pose.x == pytest.approx(2.06, abs=1e-6)


def test_velocities_are_limited_and_a_bad_number_stops_the_robot(tmp_path: Path) -> None:
    sim = Simulation(world(tmp_path))
    sim.command_velocity(0, 5.0, 0.0)  # above max_linear 0.3
    steps(sim, 0.2)
    assert sim.status[0].distance == pytest.approx(0.06, abs=1e-6)
    sim.command_velocity(0, math.nan, 0.0)
    before = sim.bodies[0].pose
    steps(sim, 0.2)
    assert sim.bodies[0].pose == before
    sim.rotate(0, math.inf)
    out = steps(sim, 0.2)
    assert sim.bodies[0].pose == before and [m.role for m in out if m.role == "rotate_done"] == ["rotate_done"]
    assert sim.status[0].bad_commands == 2 and sim.status[0].commands == 3


def test_the_scan_starts_ahead_and_goes_counter_clockwise(tmp_path: Path) -> None:
    text = ROOM.replace("walls:\n  - [[4, 0], [4, 1.5]]", "walls:\n  - [[3, 0], [3, 4]]\n  - [[0, 3], [6, 3]]")
    sim = Simulation(world(tmp_path, text))  # robot at (2, 2) facing +x: a wall 1 m ahead, 1 m to the left
    out = steps(sim, 0.05)
    scans = [m.value for m in out if m.role == "scan"]
    assert len(scans) == 1 and len(scans[0]) == 360
    ranges = scans[0]
    assert ranges[0] == pytest.approx(1.0, abs=0.03)  # ahead
    assert ranges[90] == pytest.approx(1.0, abs=0.03)  # left
    assert ranges[270] == math.inf or ranges[270] > 1.9  # right: nothing within 2 m
    assert ranges[45] == pytest.approx(math.sqrt(2), abs=0.05)
    sim.rotate(0, -90)  # now facing -y: the wall that was ahead is on the left
    steps(sim, 1.5)
    ranges = next(m.value for m in reversed(steps(sim, 0.2)) if m.role == "scan")
    assert ranges[90] == pytest.approx(1.0, abs=0.05)
    assert ranges[180] == pytest.approx(1.0, abs=0.05)  # behind: the wall at y = 3


def test_the_scan_rate_is_the_lidar_rate(tmp_path: Path) -> None:
    sim = Simulation(world(tmp_path))
    times = [round(sim.time, 2) for _ in range(40) for m in sim.step() if m.role == "scan"]
    assert times == [0.05] + [round(0.1 * k, 2) for k in range(1, 21)]  # 10 Hz from the first step


def test_touching_a_wall_is_a_collision(tmp_path: Path) -> None:
    sim = Simulation(world(tmp_path, ROOM.replace("[2, 2, 0]", "[3.5, 1, 0]")))
    for _ in range(60):
        sim.command_velocity(0, 0.3, 0.0)
        sim.step()
    status = sim.status[0]
    assert status.collided_at is not None and status.collided_at < 2.0
    assert status.closest <= 0.0 and sim.any_collided
    x = sim.bodies[0].pose.x
    sim.command_velocity(0, 0.3, 0.0)
    sim.step()
    assert sim.bodies[0].pose.x == x  # a robot that collided stays where it is


def test_the_goal_counts_after_standing_still_there(tmp_path: Path) -> None:
    sim = Simulation(world(tmp_path, ROOM.replace("[2, 2, 0]", "[4.8, 2, 0]")))
    for _ in range(20):  # 1 s at 0.3 m/s: into the goal at x >= 5
        sim.command_velocity(0, 0.3, 0.0)
        sim.step()
    assert sim.status[0].reached is None  # moving
    steps(sim, 0.9)
    assert sim.status[0].reached is None  # stopped for less than a second
    steps(sim, 0.5)
    assert sim.status[0].reached == pytest.approx(2.3, abs=0.11) and sim.all_reached


def test_the_line_detector_sign_and_gain(tmp_path: Path) -> None:
    line = "line:\n  points: [[0, 2.1], [6, 2.1]]\n  look_ahead: 0.15\n  width: 0.2\n  gain: 100\n"
    sim = Simulation(world(tmp_path, ROOM + line))  # the line is 0.1 m to the robot's left
    out = steps(sim, 0.05)
    readings = [m.value for m in out if m.role == "line_correction"]
    assert readings == [pytest.approx(-10.0, abs=1e-6)]  # negative: the line lies to the left
    sim2 = Simulation(world(tmp_path, ROOM + line.replace("2.1]", "1.95]")))
    assert [m.value for m in steps(sim2, 0.05) if m.role == "line_correction"] == [pytest.approx(5.0, abs=1e-6)]
    sim3 = Simulation(world(tmp_path, ROOM + line.replace("2.1]", "2.5]")))
    assert [m.role for m in steps(sim3, 0.05) if m.role.startswith("line")] == ["line_lost"]


def test_emergency_stop_presses_on_schedule_and_on_request(tmp_path: Path) -> None:
    sim = Simulation(world(tmp_path, ROOM + "emergency_stop:\n  - [1.0, 2.0]\n"), robots=2)
    out = [(round(sim.time, 2), m.robot, m.role) for _ in range(60) for m in sim.step() if m.role in ("stop", "continue")]
    assert out == [(1.0, 0, "stop"), (1.0, 1, "stop"), (2.0, 0, "continue"), (2.0, 1, "continue")]
    assert [m.role for m in sim.press(1, True)] == ["stop"]
    assert sim.press(1, True) == []  # already pressed
    assert sim.pressed == [False, True]


def test_robots_are_independent(tmp_path: Path) -> None:
    sim = Simulation(world(tmp_path), robots=3)
    sim.command_velocity(1, 0.2, 0.0)
    steps(sim, 1.0)
    assert [round(s.distance, 2) for s in sim.status] == [0.0, 0.06, 0.0]


# ---- the paper's robots, driven by their generated supervisors (no middleware) -------------


def supervisor(model: str | Path):
    result = synthesize_file(model)
    assert result.ok
    return load_module(plan_supervisor(result))


def test_the_models_use_the_worlds_topics() -> None:
    maze = load_world(WORLDS / "maze.yaml")
    line = load_world(WORLDS / "line.yaml")
    module = supervisor(ROOT / "examples" / "maze_solver.rscd")
    assert sorted(roles(maze, module.Robot.COMMUNICATIONS)) == [
        "cmd_vel",
        "rotate_done",
        "rotate_left",
        "rotate_right",
        "scan",
    ]
    module = supervisor(ROOT / "examples" / "line_follower.rscd")
    assert sorted(roles(line, module.Robot.COMMUNICATIONS)) == [
        "cmd_vel",
        "continue",
        "line_correction",
        "line_lost",
        "scan",
        "stop",
    ]


def test_the_maze_solver_leaves_the_maze_keeping_the_wall_on_its_right(tmp_path: Path) -> None:
    world_ = load_world(WORLDS / "maze.yaml")
    report = run_local(world_, supervisor(ROOT / "examples" / "maze_solver.rscd"), timeout=150, folder=tmp_path)
    robot = report.robots[0]
    assert report.ok, report.why
    assert robot.collided_at is None and robot.closest > 0.05
    assert 60 < robot.reached < 120 and robot.distance > 15  # the long way round, along the right-hand wall
    trajectory = report.status[0].trajectory
    # right-hand rule from the start (1.4, 1.2) facing north: up the west corridor first
    assert max(y for _, x, y, _ in trajectory if x < 1.9) > 3.5
    # the event log: the controller's commands and the robot's messages, in simulated time
    log = (tmp_path / "events" / "robot1.jsonl").read_text().splitlines()
    assert len(log) > 1000 and '"event": "turn_right"' in "".join(log)


def line_world(tmp_path: Path, extra: str = "") -> Path:
    text = (WORLDS / "line.yaml").read_text() + extra
    path = tmp_path / "line.yaml"
    path.write_text(text)
    return path


def test_the_line_follower_follows_the_line_and_stops_before_the_box(tmp_path: Path) -> None:
    world_ = load_world(WORLDS / "line.yaml")
    report = run_local(world_, supervisor(ROOT / "examples" / "line_follower.rscd"), timeout=80)
    assert report.ok, report.why
    trajectory = report.status[0].trajectory
    track = world_.line
    assert track is not None
    from shapely import LineString, Point

    line = LineString(track.points)
    assert max(line.distance(Point(x, y)) for _, x, y, _ in trajectory) < 0.12  # on the line all the way
    box_x, _, box_w, _ = world_.boxes[0]
    final = trajectory[-1]
    assert final[1] < box_x - box_w / 2 - world_.robot.radius  # stopped in front of the box
    assert report.robots[0].closest > 0.1


def test_the_line_follower_stands_still_while_the_emergency_stop_is_pressed(tmp_path: Path) -> None:
    world_ = load_world(line_world(tmp_path, "emergency_stop:\n  - [10, 20]\n"))
    report = run_local(world_, supervisor(ROOT / "examples" / "line_follower.rscd"), timeout=100)
    assert report.ok, report.why
    trajectory = report.status[0].trajectory
    at = {round(t, 1): (x, y) for t, x, y, _ in trajectory}
    assert at[11.0] == at[20.0]  # stopped within a second of the press, until the release
    assert math.dist(at[5.0], at[10.0]) > 0.5  # moving before
    assert math.dist(at[21.0], at[26.0]) > 0.5  # and after
    assert report.robots[0].reached > 50.0  # about 10 s later than without the stop


def broken_line_follower(tmp_path: Path) -> Path:
    """The line follower without the requirement that keeps it from driving into the box."""
    text = (ROOT / "examples" / "line_follower.rscd").read_text()
    requirement = "    requirement move needs LineDetector.line_found and Lidar.safety = safe\n"
    assert requirement in text
    (tmp_path / "emergency_stop.rscd").write_text((ROOT / "examples" / "emergency_stop.rscd").read_text())
    broken = tmp_path / "line_follower.rscd"
    broken.write_text(text.replace(requirement, ""))
    return broken


def test_without_its_requirement_the_line_follower_hits_the_box(tmp_path: Path) -> None:
    world_ = load_world(WORLDS / "line.yaml")
    report = run_local(world_, supervisor(broken_line_follower(tmp_path)), timeout=80)
    assert not report.ok
    assert report.robots[0].collided_at is not None and report.robots[0].reached is None


# ---- the command ---------------------------------------------------------------------------


def test_robosc_sim_without_middleware(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    record = tmp_path / "record"
    code = main(
        ["sim", str(WORLDS / "line.yaml"), str(ROOT / "examples" / "line_follower.rscd"), "--ros", "none",
         "--robots", "2", "--record", str(record)]
    )
    out = capsys.readouterr().out
    assert code == 0, out
    assert re.search(r"robot1 │ +4\d\.\d s │ +5\.\d\d m │ +0\.\d\d m │ +\d+ │ +0 │", out), out
    assert "robot2" in out and "ok: every robot reached the goal" in out
    for name in ("run.mcap", "run.gif", "robot1_events.png", "robot2_events.png", "events/robot2.jsonl"):
        assert (record / name).stat().st_size > 1000, name


def test_robosc_sim_fails_when_a_robot_hits_something(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["sim", str(WORLDS / "line.yaml"), str(broken_line_follower(tmp_path)), "--ros", "none"])
    out = capsys.readouterr().out
    assert code == 1
    assert re.search(r"robot1 │ +hit at 4\d\.\d s │", out), out
    assert re.search(r"FAILED: robot1 touched a wall or box at t = 4\d\.\d s", out), out


def test_robosc_sim_on_a_bad_world_names_the_place(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text("world: x\nsize: [4, 3]\nstarts: [[1, 1, 0]]\ngoal: {x: [3, 4], y: [2, 3]}\nwals: []\n")
    code = main(["sim", str(bad), str(ROOT / "examples" / "maze_solver.rscd"), "--ros", "none"])
    err = capsys.readouterr().err
    assert code == 2
    assert f"{bad}:5:1: unknown key 'wals' in the world; did you mean 'walls'?" in err
    assert "Traceback" not in err


def test_robosc_sim_refuses_a_model_that_moves_no_robot(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code = main(["sim", str(WORLDS / "maze.yaml"), str(ROOT / "examples" / "pick_and_light.rscd"), "--ros", "none"])
    err = capsys.readouterr().err
    assert code == 2
    assert "pick_and_light.rscd sends none of the commands the robots of" in err
    assert "(/cmd_vel, /rotate_left, /rotate_right): nothing would move them" in err


def test_robots_in_the_animation_are_told_apart_by_colour_and_name(tmp_path: Path) -> None:
    """Three maze solvers from one start drive the same way (they do not see each other):
    before, the GIF showed one robot; now each has its colour, its name (stacked when they
    share a spot) and a legend entry, and none hides another entirely."""
    import matplotlib.pyplot as plt

    from robosc.sim.recording import ROBOT_COLOURS, scene

    maze = load_world(WORLDS / "maze.yaml")
    report = run_local(maze, supervisor(ROOT / "examples" / "maze_solver.rscd"), robots=3, timeout=5)
    fig, draw, frames = scene(report, maze)
    try:
        artists = draw(frames - 1)
        ax = fig.axes[0]
        names = [t for t in ax.texts]
        assert [t.get_text() for t in names] == ["robot1", "robot2", "robot3"]
        assert [t.get_color() for t in names] == ROBOT_COLOURS[:3]
        positions = [t.get_position() for t in names]
        assert len(set(positions)) == 3  # on one spot, the names are stacked, not on top of each other
        assert [t.get_text() for t in ax.get_legend().get_texts()] == ["robot1", "robot2", "robot3"]
        bodies = [a for a in artists if a.__class__.__name__ == "Circle"]
        assert len({b.radius for b in bodies}) == 3  # the later ones smaller: all three show
    finally:
        plt.close(fig)


LANE = """\
world: lane
size: [6, 2]
shared: true
robot: {radius: 0.2, max_linear: 0.3, command_timeout: 0.3}
starts:
  - [1.0, 1.0, 0]
  - [3.0, 1.0, 180]
goal: {x: [5, 6], y: [0, 2]}
"""


@pytest.mark.parametrize("shared", [True, False])
def test_in_a_shared_world_robots_see_and_touch_each_other(tmp_path: Path, shared: bool) -> None:
    """Two robots 2 m apart, face to face, driving at each other: in a shared world (one IR-SIM
    environment) each LiDAR sees the other 1.8 m ahead (its near edge) and they collide, the run
    fails naming both; in a world that is not shared they are ghosts to each other."""
    sim = Simulation(world(tmp_path, LANE.replace("shared: true", f"shared: {str(shared).lower()}")), robots=2)
    scans = [m for m in sim.step() if m.role == "scan"]
    ahead = [scan.value[0] for scan in scans]
    if shared:
        assert ahead == [pytest.approx(1.8, abs=0.02), pytest.approx(1.8, abs=0.02)]
    else:
        assert ahead == [math.inf, math.inf]
    verdict = None
    for _ in range(200):
        sim.command_velocity(0, 0.3, 0.0)
        sim.command_velocity(1, 0.3, 0.0)
        sim.step()
        verdict = sim.verdict(1000.0)
        if verdict is not None:
            break
    if shared:
        assert verdict is not None and verdict[0] is False
        assert verdict[1].startswith("robot1 touched robot2; robot2 touched robot1 at t = ")
        assert [s.touched for s in sim.status] == ["robot2", "robot1"]
        assert all(s.closest_robot <= 1e-3 for s in sim.status)
    else:
        assert verdict is None or verdict[0] is not False or "touched" not in verdict[1]
        assert [s.collided_at for s in sim.status] == [None, None]


def test_a_shared_world_needs_a_start_for_each_robot(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    lane = world(tmp_path, LANE)
    with pytest.raises(ValueError, match=r"each needs a start of its own: it has 2, and 3 robots were asked for"):
        Simulation(lane, robots=3)
    code = main(["sim", str(tmp_path / "world.yaml"), str(ROOT / "examples/maze_solver.rscd"), "--robots", "3"])
    assert code == 2 and "it has 2, and 3 robots were asked for" in capsys.readouterr().err


def test_a_world_with_a_goal_and_a_fleets_world_run_through_one_entry_to_one_report() -> None:
    """robosc.api.run_world runs either kind of world in this process and returns the same
    report: robots with a goal say when they got there, a fleet's robots how many tasks they did;
    the time-out unless told is 300 s, and 300 s per robot and task in a fleet's world."""
    from robosc.api import run_world, synthesize_file
    from robosc.sim.report import Report
    from robosc.sim.run import default_timeout

    maze = run_world(ROOT / "examples/worlds/maze.yaml", synthesize_file(ROOT / "examples/maze_solver.rscd"), timeout=5)
    lane_world = load_world(ROOT / "examples/worlds/lane.yaml")
    lane = run_world(lane_world, synthesize_file(ROOT / "examples/scenarios/lane.rscd"), tasks=2)
    assert type(maze) is type(lane) is Report
    assert not maze.fleet and maze.tasks is None and [r.name for r in maze.robots] == ["robot1"]
    assert maze.simulated == pytest.approx(5.0, abs=0.11) and maze.why.startswith("timeout")
    assert lane.fleet and lane.tasks == 2 and lane.ok, lane.why
    assert len(lane.robots) == 2 and sum(r.tasks for r in lane.robots) == 4
    assert all(r.reached is None for r in lane.robots)
    assert lane.why == "all 4 tasks given are done"
    with pytest.raises(ValueError, match="at least 1 task"):
        run_world(lane_world, synthesize_file(ROOT / "examples/scenarios/lane.rscd"), tasks=0)
    assert default_timeout(lane_world, 4, 2) == 2400.0 and default_timeout(load_world(ROOT / "examples/worlds/maze.yaml"), 4) == 300.0
