"""A fleet in one world (robosc.sim.fleet): the warehouse's coordinator commanding drivers whose
robots take time to move and are bodies to each other, without middleware."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from robosc.api import check_text, plan_supervisor, synthesize_model
from robosc.cli.main import main
from robosc.cli.sim import report_table
from robosc.debug.simulator import load_module
from robosc.sim.fleet import FleetMisfit, FleetRun, FleetWorld, Jitter
from robosc.sim.run import drive
from robosc.sim.world import WorldError, load_world

pytest.importorskip("irsim")

ROOT = Path(__file__).resolve().parent.parent
WORLD = ROOT / "examples/worlds/warehouse.yaml"


def module_of(path: Path, robots: int = 3) -> object:
    text = path.read_text().replace("component bot[3]", f"component bot[{robots}]")
    return load_module(plan_supervisor(synthesize_model(check_text(text, path=str(path)).model)))


def test_the_warehouse_fleet_does_its_tasks_in_one_world_without_touching(capsys: pytest.CaptureFixture[str]) -> None:
    """robosc sim on the warehouse's world: three robots, each drives the whole task at least
    once through the door and the one-robot cells, none touches another robot, a wall or the
    door, and the table says so."""
    code = main(["sim", str(WORLD), str(ROOT / "examples/warehouse.rscd"), "--ros", "none"])
    out = capsys.readouterr().out
    assert code == 0, out
    assert "ok: all 3 tasks given are done" in out
    rows = re.findall(r"│ (bot\d) +│ +(\d+) │ +\d+ s │ +[\d.]+ m │ +([\d.]+) m │ +([\d.]+) m │ +\d+ │ +- │", out)
    assert [r[0] for r in rows] == ["bot1", "bot2", "bot3"], out
    assert all(int(tasks) >= 1 and float(robot) > 0.0 and float(person) > 0.0 for _, tasks, robot, person in rows), out


def test_the_zero_time_warehouse_collides_in_the_same_world() -> None:
    """The same world driven by the warehouse written as if moves took no time: its supervisor
    sends the next command before the robot is there, and the run fails with a collision (so
    the test above can fail). Any command the supervisor allows may be sent: the random choice
    sends the one that is unsafe (the door closed on a robot), which the purposeful one happens
    not to in this world."""
    run = FleetRun(
        load_world(WORLD), module_of(ROOT / "docs/models/warehouse_zero_time.rscd"), 3, tasks=1, policy="random"
    )
    report = drive(run, timeout=300)
    assert not report.ok and report.why.startswith("collision: "), report.why
    assert report.collisions >= 1


def test_a_fleet_of_another_size_than_the_model_is_refused(capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["sim", str(WORLD), str(ROOT / "examples/warehouse.rscd"), "--ros", "none", "--robots", "4"])
    assert code == 2
    assert "the model's fleet has 3 robots (bot1, bot2, bot3) and 4 were asked for" in capsys.readouterr().err
    with pytest.raises(FleetMisfit, match="has 3 robots"):
        FleetRun(load_world(WORLD), module_of(ROOT / "examples/warehouse.rscd"), 2)
    code = main(["sim", str(WORLD), str(ROOT / "examples/warehouse.rscd"), "--ros", "2", "--robots", "2"])
    assert code == 2  # before any ROS process starts
    assert "the model's fleet has 3 robots (bot1, bot2, bot3) and 2 were asked for" in capsys.readouterr().err


def test_a_robot_whose_way_is_blocked_stops_and_says_so(tmp_path: Path) -> None:
    """A box in the aisle's second cell: a robot drives into the first and, on its way on, sees
    the box, stops and says `stopped`; the coordinator has it between the two cells (holding
    both) and tells it to go on, it stops again, and no other robot is sent after it: the run
    ends as a deadlock naming where it is, with no collision."""
    text = WORLD.read_text().replace("walls:\n", "boxes:\n  - [6.4, 3.3, 0.3, 0.3]\nwalls:\n", 1)
    world = tmp_path / "blocked.yaml"
    world.write_text(text)
    run = FleetRun(load_world(world), module_of(ROOT / "examples/warehouse.rscd"), 3, seed=1, tasks=1, stall=20)
    report = drive(run, timeout=200)
    assert not report.ok and report.why.startswith("deadlock: "), report.why
    stopped = [s for s in report.robots if s.stops]
    assert len(stopped) == 1 and stopped[0].tasks == 0
    field = next(f[0] for f in run.coordinator.FIELDS if f[0].endswith("_" + stopped[0].name))
    assert getattr(run.coordinator, field) in ("stopped_out2", "to_out2")
    assert re.search(rf"{stopped[0].name} in c[12] \((stopped|driving) into c2, [\d.]+ m from \(6.4, 3.3\)\)", report.why), report.why
    assert stopped[0].stops >= 2
    assert report.collisions == 0


@pytest.mark.parametrize(("name", "homes"), [("warehouse", 8), ("warehouse_large", 16)])
def test_the_warehouse_worlds_have_a_home_per_robot_and_each_waypoint_in_its_cell(name: str, homes: int) -> None:
    world = load_world(ROOT / "examples" / "worlds" / f"{name}.yaml")
    assert world.room_for(homes) is None and f"it has {homes}, and {homes + 1} robots" in str(world.room_for(homes + 1))
    fleet = world.fleet
    assert fleet is not None
    assert {n: fleet.cell(*p) for n, p in fleet.waypoints} == {
        "wait_lane": "depot", "wait": "depot", "past": "depot", "past_lane": "depot",
        "c1": "c1", "c2": "c2", "c3": "c3", "shelf": "shelf"}
    for i in range(homes):  # every home and lane point in the depot, a robot's width apart
        start = world.start(i)
        assert fleet.cell(start.x, start.y) == "depot" and fleet.cell(*fleet.point("lane", start)) == "depot"
        if i:
            assert math.dist((start.x, start.y), (world.start(i - 1).x, world.start(i - 1).y)) > 2 * world.robot.radius + 0.2
    assert fleet.charger is not None and fleet.cell(*fleet.charger.at) == "depot"


def test_where_a_robot_is_says_the_point_its_next_leg_ends_at_and_what_it_drives_into() -> None:
    world = FleetWorld(load_world(WORLD), ["bot1", "bot2", "bot3"])
    assert world.whereabouts(0) == "bot1 in depot (idle, its next move to wait, in depot)"
    world.drivers[0].leg = 1
    assert world.whereabouts(0) == "bot1 in depot (idle, its next move to c1)"
    world.command("bot1.go")
    world.step()
    assert re.fullmatch(r"bot1 in depot \(driving into c1, [\d.]+ m from \(4\.4, 3\.3\)\)", world.whereabouts(0))


def _answers_of_a_leg(world: FleetWorld, robot: str) -> list[tuple[str, frozenset[str]]]:
    """Drive ``robot``'s next leg: each answer it gives and the cells its body is in then."""
    world.command(f"{robot}.go")
    said: list[tuple[str, frozenset[str]]] = []
    while not any(name == f"{robot}.arrived" for name, _ in said) and world.sim.time < 120:
        pose = world.sim.bodies[0].pose
        for name, _ in world.step():
            if name.startswith(robot + "."):
                pose = world.sim.bodies[0].pose
                said.append((name, world.fleet.cells_under(pose.x, pose.y, world.sim.world.robot.radius)))
    return said


def test_a_robot_says_left_once_its_body_is_out_of_the_cells_it_started_in() -> None:
    """With ``left`` in the model, a driver says it once in a leg, as soon as its body (not
    only its centre) overlaps no cell but the one the leg ends in, and before ``arrived``; in a
    leg that starts and ends in one cell it says nothing more than ``arrived``, and a model
    without ``left`` hears none."""
    world = FleetWorld(load_world(WORLD), ["bot1", "bot2", "bot3"], leaving=True)
    world.command("open_door")
    while world.door is not None and world.door.state != "open":
        world.step()
    said = _answers_of_a_leg(world, "bot1")  # to the place beside the doorway: depot to depot
    assert [name for name, _ in said] == ["bot1.arrived"], said
    said = _answers_of_a_leg(world, "bot1")  # into c1, out of the depot
    assert [name for name, _ in said] == ["bot1.left", "bot1.arrived"], said
    assert said[0][1] == {"c1"}, said  # out of the depot with its whole body
    # ... and not a step later than that: one step before, the body was still in the depot
    again = FleetWorld(load_world(WORLD), ["bot1", "bot2", "bot3"], leaving=True)
    again.command("open_door")
    while again.door is not None and again.door.state != "open":
        again.step()
    _answers_of_a_leg(again, "bot1")
    again.command("bot1.go")
    while True:
        pose = again.sim.bodies[0].pose
        under = again.fleet.cells_under(pose.x, pose.y, again.sim.world.robot.radius)
        if "bot1.left" in [name for name, _ in again.step()]:
            break
    assert "depot" in under
    quiet = FleetWorld(load_world(WORLD), ["bot1", "bot2", "bot3"])
    quiet.command("open_door")
    while quiet.door is not None and quiet.door.state != "open":
        quiet.step()
    _answers_of_a_leg(quiet, "bot1")
    assert [name for name, _ in _answers_of_a_leg(quiet, "bot1")] == ["bot1.arrived"]


def test_a_closed_door_is_in_the_lidars_way_a_robot_stops_before_it() -> None:
    """A robot told to go while the door is closed (no coordinator: the world alone) sees the
    door with its LiDAR, stops short of it and says `stopped`; once the door has opened and it is
    told to go on, it drives through and arrives, without touching it."""
    world = FleetWorld(load_world(WORLD), ["bot1", "bot2", "bot3"])
    world.command("bot1.go")  # to the place beside the doorway
    said: list[str] = []
    while not said and world.sim.time < 60:
        said = [name for name, _ in world.step() if name.startswith("bot1.")]
    assert said == ["bot1.arrived"], (said, world.sim.time)
    world.command("bot1.go")  # into the aisle, through the closed door
    said = []
    while not said and world.sim.time < 60:
        said = [name for name, _ in world.step() if name.startswith("bot1.")]
    assert said == ["bot1.stopped"], (said, world.sim.time)
    pose = world.sim.bodies[0].pose
    door_x = 3.4
    assert door_x - pose.x - world.sim.world.robot.radius > 0.1, pose  # short of the door
    assert world.sim.status[0].collided_at is None
    world.command("open_door")
    while "door_opened" not in [name for name, _ in world.step()]:
        pass
    world.command("bot1.go")
    while not (said := [name for name, _ in world.step() if name.startswith("bot1.")]):
        assert world.sim.time < 120
    assert said == ["bot1.arrived"] and world.fleet.cell(*(lambda p: (p.x, p.y))(world.sim.bodies[0].pose)) == "c1"
    assert all(s.collided_at is None for s in world.sim.status)


@pytest.mark.parametrize(
    ("change", "line", "message"),
    [
        (("shared: true", "shared: false"), 31, "a fleet's world is shared: add 'shared: true'"),
        (("    - [c2]\n", "    - [c9]\n"), 44, "unknown waypoint 'c9' (the waypoints, home, lane)"),
        (("    c1: [4.4, 3.3]\n", "    home: [4.4, 3.3]\n"), 37, "'home' is each robot's own: it cannot be a waypoint"),
        (("[6.4, 3.3, 20]", "[6.4, 3.3, 20, 1]"), 68, "a point of the walk is [x, y] or [x, y, seconds standing there]"),
        (("    speed: 0.6\n", "    speed: -1\n"), 63, "person speed"),
        (("  task:", "  tasks: [[[c1]]]\n  task:"), 31, "'task' (every robot's) or 'tasks' (one per robot), not both"),
        (("  task:", "  tasks:"), 42, "a leg of the task (a list of waypoints) must be a list"),
    ],
)
def test_a_fleet_world_is_checked_with_file_line_and_column(
    tmp_path: Path, change: tuple[str, str], line: int, message: str
) -> None:
    text = WORLD.read_text()
    assert change[0] in text
    path = tmp_path / "w.yaml"
    path.write_text(text.replace(change[0], change[1], 1))
    with pytest.raises(WorldError) as caught:
        load_world(path)
    assert caught.value.line == line and message in caught.value.message, str(caught.value)


def test_robots_keep_out_of_the_cells_at_and_next_to_a_person_standing_in_the_aisle(tmp_path: Path) -> None:
    """A person stands in the aisle's second cell from the start for 30 s, then leaves by the
    side way: the detector says so, no robot enters that cell or the cells next to it (the
    aisle's three) while the person is there, none touches the person, and every task is done
    afterwards; the table gives each robot's closest approach to the person."""
    text = WORLD.read_text()
    text = text[: text.index("  person:")] + (
        "  person:\n    walk:\n      - [6.4, 3.3, 30]\n      - [6.4, 4.8]\n      - [8.0, 5.6]\n"
    )
    world = tmp_path / "person.yaml"
    world.write_text(text)
    fleet = load_world(world).fleet
    assert fleet is not None
    run = FleetRun(load_world(world), module_of(ROOT / "examples/warehouse.rscd"), 3, tasks=1)
    report = drive(run, timeout=900)
    assert report.ok and report.collisions == 0, report.why
    left = next(t for t, x, y in run.sim.person_trajectory if fleet.cell(x, y) != "c2")
    assert left >= 30.0
    aisle = {"c1", "c2", "c3"}
    for status in run.sim.status:
        assert all(fleet.cell(x, y) not in aisle for t, x, y, _ in status.trajectory if t < left)
        assert any(fleet.cell(x, y) in aisle for t, x, y, _ in status.trajectory if t > left)
        assert status.closest_person > 0.5  # no robot came near: a cell between them
    out = report_table(report, "the person")
    rows = re.findall(r"│ (bot\d) +│ +\d+ │ +\d+ s │ +[\d.]+ m │ +[\d.]+ m │ +([\d.]+) m │ +\d+ │ +- │", out)
    assert [r[0] for r in rows] == ["bot1", "bot2", "bot3"] and all(float(r[1]) > 0.5 for r in rows), out


def test_jitter_makes_each_robot_start_late_and_drive_slower() -> None:
    """A robot told to go before its start delay is over stands still until then, and then
    drives no faster than its share of the top speed; the draws follow the seed."""
    draws = Jitter(5).draw(3)
    assert draws == Jitter(5).draw(3) and draws != Jitter(6).draw(3)
    assert all(0.6 <= share <= 1.0 and 0.0 <= delay <= 5.0 for share, delay in draws)
    world = FleetWorld(load_world(WORLD), ["bot1", "bot2", "bot3"], Jitter(5))
    share, delay = draws[0]
    start = world.sim.bodies[0].pose
    world.command("bot1.go")
    fastest = 0.0
    while world.sim.time < delay + 8.0:
        before = world.sim.bodies[0].pose
        world.step()
        after = world.sim.bodies[0].pose
        moved = math.hypot(after.x - before.x, after.y - before.y)
        if world.sim.time < delay - 1e-6:
            assert (after.x, after.y) == (start.x, start.y)
        fastest = max(fastest, moved / world.sim.world.step)
    assert 0.9 * share * 0.5 < fastest <= share * 0.5 + 1e-6  # it drove, at its share of 0.5 m/s


def test_the_detector_says_where_the_person_is_and_that_nobody_is_there_without_one(tmp_path: Path) -> None:
    """At the first step the detector reports the person's cell, then only changes; in a world
    without a person it reports no one ("") once, so a coordinator that waits for data on it
    does not wait for ever."""
    world = FleetWorld(load_world(WORLD), ["bot1", "bot2", "bot3"])
    assert ("person_cell", "") in world.step()  # the person starts outside every cell
    assert all(name != "person_cell" for name, _ in world.step())
    text = WORLD.read_text()
    alone = tmp_path / "alone.yaml"
    alone.write_text(text[: text.index("  person:")])
    empty = FleetWorld(load_world(alone), ["bot1", "bot2", "bot3"])
    assert ("person_cell", "") in empty.step()
    assert all(name != "person_cell" for name, _ in empty.step())


def test_a_person_walks_the_script_and_gives_way_to_a_robot_in_front() -> None:
    """The walk: standing at its first point until start + its seconds, then toward the next at
    the person's speed; a step that brings the person closer than 0.3 m to a robot's edge waits,
    and one that leads away from the robot does not."""
    from robosc.sim.person import Walker
    from robosc.sim.world import Person, Pose

    walker = Walker(Person(((0.0, 0.0, 2.0), (5.0, 0.0, 0.0)), radius=0.25, speed=0.5, start=1.0), robot_radius=0.2)
    assert walker.velocity(2.9, 0.1, 0.0, 0.0, []) == (0.0, 0.0)  # still standing: 1 s + 2 s
    assert walker.velocity(3.0, 0.1, 0.0, 0.0, []) == pytest.approx((0.5, 0.0))
    ahead = Pose(0.78, 0.0, 0.0)  # edges 0.33 m apart: one more step comes within 0.3 m
    assert walker.velocity(3.0, 0.1, 0.0, 0.0, [ahead]) == (0.0, 0.0)
    behind = Pose(-0.7, 0.0, 0.0)  # as close, but the step leads away from it
    assert walker.velocity(3.0, 0.1, 0.0, 0.0, [behind]) == pytest.approx((0.5, 0.0))
    assert walker.velocity(3.0, 0.1, 5.0, 0.0, []) == (0.0, 0.0) and walker.done  # there: the walk is over


def test_a_person_a_robot_keeps_standing_in_front_of_walks_round_it_after_a_while() -> None:
    """A robot that stays in the person's way (it waits for the person, as the robots keep out of
    the person's way): the person waits WAIT_AT_MOST seconds, then walks round it, never closer to
    its edge than 0.3 m once within that, and gets where they were going."""
    from robosc.sim.person import GIVE_WAY, WAIT_AT_MOST, Walker
    from robosc.sim.world import Person, Pose

    person = Person(((0.0, 0.0, 0.0), (3.0, 0.0, 0.0)), radius=0.25, speed=0.5, start=0.0)
    walker = Walker(person, robot_radius=0.2)
    robot = Pose(1.5, 0.0, 0.0)  # right on the way
    x, y, now, dt, closest, waited = 0.0, 0.0, 0.0, 0.1, math.inf, 0.0
    while not walker.done and now < 60:
        vx, vy = walker.velocity(now, dt, x, y, [robot])
        if (vx, vy) == (0.0, 0.0) and now > 0.0:
            waited += dt
        x, y, now = x + vx * dt, y + vy * dt, now + dt
        closest = min(closest, math.hypot(x - robot.x, y - robot.y) - 0.25 - 0.2)
    assert walker.done, (x, y, now)  # round the robot and there
    assert WAIT_AT_MOST - dt <= waited <= WAIT_AT_MOST + 2 * dt  # it waited for the robot first
    assert closest >= GIVE_WAY - 0.05 * dt, closest


def test_a_person_whose_spot_a_robot_stands_on_stands_where_they_are_and_walks_on() -> None:
    """The person's next point is where a robot has stopped (it waits for the person to leave the
    cell): after waiting WAIT_AT_MOST seconds the person takes the point as reached, stands where
    they are for its seconds and walks on (before, they walked round the robot for ever, and the
    warehouse of 16 robots on ROS 2 ended as a deadlock)."""
    from robosc.sim.person import WAIT_AT_MOST, Walker
    from robosc.sim.world import Person, Pose

    person = Person(((0.0, 0.0, 0.0), (2.0, 0.0, 3.0), (0.0, 2.0, 0.0)), radius=0.25, speed=0.5, start=0.0)
    walker = Walker(person, robot_radius=0.2)
    robot = Pose(2.0, 0.0, 0.0)  # on the point the person is to stand at
    x, y, now, dt, stood = 0.0, 0.0, 0.0, 0.1, 0.0
    while not walker.done and now < 60:
        vx, vy = walker.velocity(now, dt, x, y, [robot])
        if walker.next == 2 and (vx, vy) == (0.0, 0.0):
            stood += dt
        x, y, now = x + vx * dt, y + vy * dt, now + dt
    assert walker.done and math.hypot(x, y - 2.0) < 0.1, (x, y, now)  # on to the last point
    assert 3.0 - dt <= stood <= 3.0 + 2 * dt  # it stood its seconds where it was
    assert now > WAIT_AT_MOST
