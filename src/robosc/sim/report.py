"""What a run of ``robosc sim`` found, for one robot and for a fleet alike (one :class:`Report`,
one :class:`RobotReport` per robot), and what is shown of it (:func:`columns`, :func:`verdict`).

A world with a goal (the maze, the line) says of each robot when it reached the goal; a fleet's
world (one with ``fleet``) says how many tasks each robot did, how long it stood waiting and how
often its way was blocked. Both say how far each robot drove, how close it came to walls, to
other robots and to the person, and whether it collided.
"""

from __future__ import annotations

import math

from robosc.record import field, record
from robosc.sim.simulation import Simulation, Status


@record
class RobotReport:
    name: str
    reached: float | None  # simulated seconds to the goal (a world with a goal)
    distance: float
    closest: float  # closest approach to a wall or a box
    collided_at: float | None
    commands: int
    refused: int
    closest_robot: float = math.inf  # in a shared world: closest approach to another robot's edge
    tasks: int = 0  # in a fleet's world: times it drove its whole task
    waiting: float = 0.0  # in a fleet's world: simulated seconds it stood still, idle or stopped
    stops: int = 0  # in a fleet's world: times it stopped because its way was blocked
    closest_person: float = math.inf


@record
class Report:
    """One run: whether it ended well and why, each robot's figures, the simulated and the real
    time it took, where its files are (``folder``), and what the animation draws (``status``,
    the person's trajectory, the door's states). ``tasks``: the tasks each robot of a fleet had to
    do (None: a world with a goal); ``collisions`` how many robots collided; ``ignored`` the answers
    the coordinator has no event for."""

    ok: bool
    why: str
    robots: tuple[RobotReport, ...]
    simulated: float  # seconds of simulated time
    wall: float  # seconds of real time, from the first step
    folder: str = ""  # where the packages, logs and recordings are
    status: tuple[Status, ...] = field(default=(), compare=False, repr=False)
    tasks: int | None = None
    collisions: int = 0
    ignored: int = 0
    person: bool = False  # the world has a person (each robot's closest_person is its closest approach)
    person_trajectory: tuple[tuple[float, float, float], ...] = field(default=(), compare=False, repr=False)
    door_states: tuple[tuple[float, str], ...] = field(default=(), compare=False, repr=False)  # (t, state)

    @property
    def fleet(self) -> bool:
        """Whether the run was a fleet's (robots doing tasks, not driving to a goal)."""
        return self.tasks is not None


@record
class FleetFigures:
    """What a fleet's world adds to a report: per robot the tasks it did (``done``), the seconds
    it waited and the times it stopped; the tasks each robot had to do, the answers the
    coordinator had no event for, and the door's states."""

    done: tuple[int, ...]
    waiting: tuple[float, ...]
    stops: tuple[int, ...]
    tasks: int
    ignored: int
    door_states: tuple[tuple[float, str], ...] = ()


def robot_names(count: int) -> list[str]:
    return [f"robot{i + 1}" for i in range(count)]


def report_of(
    sim: Simulation,
    ok: bool,
    why: str,
    wall: float,
    folder: str = "",
    names: list[str] | None = None,
    fleet: FleetFigures | None = None,
) -> Report:
    """The report of a run of ``sim`` (``names``: the robots', robot1, robot2, ... by default;
    ``fleet``: a fleet's figures, where the robots did tasks)."""
    names = names or robot_names(sim.robots)
    robots = tuple(
        RobotReport(
            name, s.reached if fleet is None else None, s.distance, s.closest, s.collided_at, s.commands, s.refused,
            s.closest_robot, fleet.done[i] if fleet else 0, fleet.waiting[i] if fleet else 0.0,
            fleet.stops[i] if fleet else 0, s.closest_person,
        )
        for i, (name, s) in enumerate(zip(names, sim.status, strict=True))
    )
    return Report(
        ok,
        why,
        robots,
        sim.time,
        wall,
        folder,
        tuple(sim.status),
        tasks=fleet.tasks if fleet else None,
        collisions=sum(1 for s in sim.status if s.collided_at is not None),
        ignored=fleet.ignored if fleet else 0,
        person=sim.walker is not None,
        person_trajectory=tuple(sim.person_trajectory),
        door_states=fleet.door_states if fleet else (),
    )


def columns(report: Report) -> tuple[tuple[str, ...], list[tuple[str, ...]]]:
    """The run's table, its headers and rows: per robot, for a world with a goal, when it got
    there, how far it drove, its closest approaches, the commands it was sent and refused; for a
    fleet, its tasks, waiting, distance, closest approaches (the person's too, where there is
    one), stops and collision."""
    if report.fleet:
        headers: tuple[str, ...] = ("robot", "tasks", "waiting", "distance", "closest robot", "stops", "collision")
    else:
        headers = ("robot", "time to goal", "distance", "closest approach", "commands", "refused")
    shared = report.fleet or any(math.isfinite(r.closest_robot) for r in report.robots)
    if shared and not report.fleet:  # the robots are bodies to each other
        headers = (*headers[:4], "closest robot", *headers[4:])
    if report.person and report.fleet:
        headers = (*headers[:5], "closest person", *headers[5:])
    rows = []
    for r in report.robots:
        cells = {
            "robot": r.name,
            "tasks": str(r.tasks),
            "waiting": f"{r.waiting:.0f} s",
            "time to goal": _goal(r),
            "closest approach": f"{r.closest:.2f} m",
            "closest robot": f"{r.closest_robot:.2f} m",
            "closest person": f"{r.closest_person:.2f} m",
            "commands": str(r.commands),
            "refused": str(r.refused),
            "stops": str(r.stops),
            "collision": "-" if r.collided_at is None else f"at {r.collided_at:.1f} s",
            "distance": f"{r.distance:.1f} m" if report.fleet else f"{r.distance:.2f} m",
        }
        rows.append(tuple(cells[h] for h in headers))
    return headers, rows


def _goal(robot: RobotReport) -> str:
    if robot.reached is not None:
        return f"{robot.reached:.1f} s"
    if robot.collided_at is not None:
        return f"hit at {robot.collided_at:.1f} s"
    return "not reached"


def verdict(report: Report) -> str:
    """The run's last line: ``ok: why (simulated and real time)`` or ``FAILED: ...``."""
    said = "ok" if report.ok else "FAILED"
    return f"{said}: {report.why} ({report.simulated:.1f} s simulated in {report.wall:.1f} s)"
