"""``robosc sim``: a world and a model, end to end. The controller is generated (one package,
relative names), the simulator's node and one controller per robot start on a private ROS
graph, and the run ends when every robot reached the goal (success), one touched a wall,
or the timeout passed. ``ros=0`` runs the same supervisors in this process, without ROS.
"""

from __future__ import annotations

import math
import tempfile
import time
import types
from collections.abc import Callable
from pathlib import Path

from robosc.record import field, record
from robosc.sim.local import COMMAND_ROLES, LocalRun
from robosc.sim.simulation import Simulation, Status
from robosc.sim.world import World


@record
class RobotReport:
    name: str
    reached: float | None  # simulated seconds to the goal
    distance: float
    closest: float
    collided_at: float | None
    commands: int
    refused: int
    closest_robot: float = math.inf  # in a shared world: closest approach to another robot's edge


@record
class Report:
    ok: bool
    why: str
    robots: tuple[RobotReport, ...]
    simulated: float  # seconds of simulated time
    wall: float  # seconds of real time, from the first step
    folder: str = ""  # where the packages, logs and recordings are
    status: tuple[Status, ...] = field(default=(), compare=False, repr=False)


def roles(world: World, communications: tuple[object, ...]) -> list[str]:
    """The simulator's topics a model uses: a communication whose ROS name is a world topic."""
    by_name = {name.lstrip("/"): role for role, name in world.topics.items()}
    used = []
    for comm in communications:
        role = by_name.get(str(getattr(comm, "ros_name", "")).lstrip("/"))
        kind = getattr(comm, "kind", "")
        if role is None or role in used:
            continue
        if (kind == "incoming") == (role in COMMAND_ROLES):
            used.append(role)
    return used


class Misfit(Exception):
    """A model that cannot drive the world's robots: it sends none of the commands they obey."""


def fit(world: World, communications: tuple[object, ...]) -> list[str]:
    """Notes on the model's topics that the simulator does not have (never received, never
    obeyed); raises Misfit when the model sends none of the commands the robots obey."""
    if not set(roles(world, communications)) & set(COMMAND_ROLES):
        commands = ", ".join(world.topics[role] for role in COMMAND_ROLES)
        raise Misfit(f"sends none of the commands the robots of {world.path} obey ({commands}): nothing would move them")
    known = {name.lstrip("/") for name in world.topics.values()}
    return [
        f"the simulator has no {getattr(c, 'ros_name', '')} ({getattr(c, 'kind', '')} {getattr(c, 'name', '')})"
        for c in communications
        if str(getattr(c, "ros_name", "")).lstrip("/") not in known
    ]


def robot_names(count: int) -> list[str]:
    return [f"robot{i + 1}" for i in range(count)]


def report(sim: Simulation, ok: bool, why: str, wall: float, folder: str = "") -> Report:
    robots = tuple(
        RobotReport(name, s.reached, s.distance, s.closest, s.collided_at, s.commands, s.refused, s.closest_robot)
        for name, s in zip(robot_names(sim.robots), sim.status, strict=True)
    )
    return Report(ok, why, robots, sim.time, wall, folder, tuple(sim.status))


def event_logs(folder: Path, robots: int) -> list[Path]:
    """Where each robot's controller writes its events: ``folder/events/robotK.jsonl``."""
    events = folder / "events"
    events.mkdir(parents=True, exist_ok=True)
    return [events / f"{name}.jsonl" for name in robot_names(robots)]


def run_local(
    world: World,
    module: types.ModuleType,
    robots: int = 1,
    timeout: float = 300.0,
    rate: float = 10.0,
    seed: int = 0,
    folder: Path | None = None,
) -> Report:
    """The generated supervisors (``module``) driving ``robots`` robots in this process;
    with a ``folder``, each robot's events go to ``folder/events/robotK.jsonl``."""
    sim = Simulation(world, robots)
    local = LocalRun(sim, module, rate=rate, seed=seed)
    if folder is not None:
        local.record(event_logs(folder, robots))
    started = time.monotonic()
    try:
        ok, why = local.run(timeout)
    finally:
        local.close()
    return report(sim, ok, why, time.monotonic() - started, str(folder or ""))


def run_ros(
    world: World,
    plan: object,
    module: types.ModuleType,
    ros: int,
    robots: int = 1,
    timeout: float = 300.0,
    speed: float = 1.0,
    rate: float = 10.0,
    seed: int = 0,
    folder: Path | None = None,
    domain: int | None = None,
    on_step: Callable[[Simulation], None] | None = None,
    on_start: Callable[[object], None] | None = None,
    trace: Callable[[str, int, str, float], None] | None = None,
    params: dict[str, object] | None = None,
    page: str | None = None,
) -> Report:
    """The generated controller package on ROS ``ros`` (1 or 2), one node per robot.
    ``on_start(graph)`` runs once the nodes are started, ``on_step(sim)`` after each step,
    ``trace(direction, robot, role, seconds)`` at each message sent ("out") and command come
    ("in"), with its time.perf_counter();
    ``params`` are more parameters of the controller nodes; ``page`` is the live view's page
    the package carries (then ``robosc view`` can watch the robots)."""
    from robosc.codegen.ros import generate, package_name
    from robosc.sim import session
    from robosc.sim.graph import Graph

    if folder is None:
        folder = Path(tempfile.mkdtemp(prefix="robosc-sim-"))
    folder.mkdir(parents=True, exist_ok=True)
    package = folder / f"{package_name(plan)}_ros{ros}"  # type: ignore[arg-type]
    generate(plan, ros, "controller", package, page, relative=True)  # type: ignore[arg-type]
    used = roles(world, module.Robot.COMMUNICATIONS)
    names = robot_names(robots)
    sim = Simulation(world, robots)
    graph = Graph(ros, folder, domain)
    bridge = None
    try:
        bridge = graph.bridge()
        session.setup(sim, bridge, names, used)
        session.wait_for(bridge, lambda m: m.get("op") == "ready", 60, "the simulator's node")
        for i, (name, log) in enumerate(zip(names, event_logs(folder, robots), strict=True)):
            # the simulation makes each robot where the model starts it, as it starts its controller
            # (and never starts a controller again): the robots are where the model's initial state says
            given: dict[str, object] = {
                "rate": float(rate),
                "seed": seed + i,
                "event_log": log,
                "trust_initial_state": True,
                **(params or {}),
            }
            graph.controller(package, name, given)
        if on_start is not None:
            on_start(graph)
        session.wait_for(bridge, session.connected(used, robots), 60 + 2 * robots, "the controllers to connect")
        started = time.monotonic()
        ok, why = session.run(sim, bridge, timeout, speed, on_step, trace, graph.failed)
        wall = time.monotonic() - started
        died = graph.failed(sim) if ok else None  # at the very end
        if died is not None:
            ok, why = False, died
        return report(sim, ok, why, wall, str(folder))
    except session.SessionError as exc:
        raise session.SessionError(f"{exc}\n{graph.output()}") from None
    finally:
        if bridge is not None:
            bridge.close()
        graph.stop()
