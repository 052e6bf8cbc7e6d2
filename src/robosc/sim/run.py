"""``robosc sim``: a world and a model, end to end, for one robot or a fleet alike: one run in
this process (:func:`run_local`) and one over ROS (:func:`run_ros`), each giving one
:class:`~robosc.sim.report.Report`.

In a world with a goal (the maze, the line) each robot has a controller of its own and the run
ends when every robot reached the goal (success), one touched something, or the time is up. In
a fleet's world (one with ``fleet``) one coordinator commands every robot's driver, the door
and the rest, and the run ends when every task given is done, at a collision, a deadlock, or
the time-out. On ROS the controller is generated (one package, relative names) and runs with
the simulator's node on a private graph (robosc.sim.fleet_ros for a fleet).
"""

from __future__ import annotations

import tempfile
import time
import types
from collections.abc import Callable
from pathlib import Path
from typing import Any, Protocol

from robosc.codegen.plan import Plan
from robosc.codegen.ros import generate, package_name
from robosc.sim import session
from robosc.sim.fleet import FleetRun, Jitter, instances
from robosc.sim.fleet_ros import run_fleet_ros
from robosc.sim.graph import Graph
from robosc.sim.local import COMMAND_ROLES, LocalRun
from robosc.sim.report import Report, report_of, robot_names
from robosc.sim.simulation import Simulation
from robosc.sim.world import World


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


def event_logs(folder: Path, robots: int) -> list[Path]:
    """Where each robot's controller writes its events: ``folder/events/robotK.jsonl``."""
    events = folder / "events"
    events.mkdir(parents=True, exist_ok=True)
    return [events / f"{name}.jsonl" for name in robot_names(robots)]


FLEET_SECONDS = 300.0  # a fleet's default time-out: simulated seconds per robot and task
GOAL_SECONDS = 300.0  # a world with a goal's default time-out


def default_timeout(world: World, robots: int, tasks: int = 1) -> float:
    """Simulated seconds before a run counts as failed, unless told: 300 in a world with a goal,
    300 per robot and task in a fleet's."""
    return FLEET_SECONDS * robots * tasks if world.fleet is not None else GOAL_SECONDS


def robots_of(world: World, module: types.ModuleType, robots: int | None) -> int:
    """How many robots run: as asked, else one in a world with a goal and the model's fleet in
    a fleet's world (its instances that take ``go``)."""
    if robots is not None:
        return robots
    return len(instances(module)) if world.fleet is not None else 1


def check_tasks(tasks: int) -> None:
    """ValueError unless each robot of a fleet has at least one task to do."""
    if tasks < 1:
        raise ValueError(f"tasks: each robot has at least 1 task to do ({tasks} given)")


class Control(Protocol):
    """What commands the world's robots in this process: a controller per robot
    (robosc.sim.local.LocalRun) or a fleet's coordinator (robosc.sim.fleet.FleetRun)."""

    def step(self) -> None: ...

    def ended(self, timeout: float) -> tuple[bool, str] | None: ...

    def interrupted(self) -> tuple[bool, str]: ...

    def report(self, ended: tuple[bool, str], wall: float, folder: str = "") -> Report: ...


def run_local(
    world: World,
    module: types.ModuleType,
    robots: int | None = None,
    timeout: float | None = None,
    rate: float = 10.0,
    seed: int = 0,
    folder: Path | None = None,
    tasks: int = 1,
    jitter: Jitter | None = None,
    on_event: Callable[[dict[str, Any]], None] | None = None,
    on_step: Callable[[Any], None] | None = None,
    policy: str = "purpose",
) -> Report:
    """The generated supervisors (``module``) driving the world's robots in this process:
    ``robots`` robots (default :func:`robots_of`) for ``timeout`` simulated seconds at most
    (default :func:`default_timeout`). In a world with a goal each robot has a controller of its
    own, and with a ``folder`` each robot's events go to ``folder/events/robotK.jsonl``; in a
    fleet's world the coordinator commands them until the world's tasks are done (``tasks`` per
    robot, given at run time; ``policy``: how the coordinator chooses, robosc.runtime.onboard.tasks)
    and ``jitter`` draws the robots' speeds and start delays. ``on_event(record)`` hears every event (a
    robot's controller's named for its robot, ``robot1.e_forward``; the coordinator's as they
    are) and ``on_step(world)`` is called after each step with what the live view draws
    (``world.sim`` and ``world.frame()``: robosc.sim.local.LocalRun, robosc.sim.fleet.FleetWorld). Raises FleetMisfit when the model's fleet does not
    fit the world."""
    robots = robots_of(world, module, robots)
    timeout = timeout if timeout is not None else default_timeout(world, robots, tasks)
    check_tasks(tasks)
    control: Control
    local: LocalRun | None = None
    if world.fleet is not None:
        control = FleetRun(world, module, robots, seed, rate, jitter, on_event, on_step, tasks, policy=policy)
    else:
        control = local = LocalRun(Simulation(world, robots), module, rate, seed, on_event, on_step)
        if folder is not None:
            local.record(event_logs(folder, robots))
    try:
        return drive(control, timeout, str(folder or ""))
    finally:
        if local is not None:
            local.close()


def drive(control: Control, timeout: float, folder: str = "") -> Report:
    """Step ``control`` until the run ends (``timeout``: simulated seconds at most), and report
    (``folder``: where its files are): the loop of every run in this process."""
    started = time.monotonic()
    while True:
        try:
            control.step()
            ended = control.ended(timeout)
        except KeyboardInterrupt:  # stopped: the report says how far it got
            ended = control.interrupted()
        if ended is not None:
            return control.report(ended, time.monotonic() - started, folder)


def run_ros(
    world: World,
    plan: Plan,
    module: types.ModuleType,
    ros: int,
    robots: int | None = None,
    timeout: float | None = None,
    speed: float = 1.0,
    rate: float = 10.0,
    seed: int = 0,
    folder: Path | None = None,
    domain: int | None = None,
    on_step: Callable[[Any], None] | None = None,
    on_start: Callable[[object], None] | None = None,
    trace: Callable[..., None] | None = None,
    params: dict[str, object] | None = None,
    page: str | None = None,
    tasks: int = 1,
    jitter: Jitter | None = None,
    policy: str = "purpose",
) -> Report:
    """The generated controller package on ROS ``ros`` (1 or 2): in a world with a goal one node
    per robot, in a fleet's world one coordinator and a driver node per robot
    (robosc.sim.fleet_ros, where ``tasks`` and ``jitter`` are as in :func:`run_local`).
    ``on_start(graph)`` runs once the nodes are started, ``on_step`` after each step (with the
    simulation; a fleet's, with its robosc.sim.fleet.FleetWorld), ``trace`` at each message sent
    ("out") and command come ("in"), with its time.perf_counter(); ``params`` are more
    parameters of the controller nodes; ``page`` is the live view's page the package carries
    (then ``robosc view`` can watch the robots)."""
    robots = robots_of(world, module, robots)
    timeout = timeout if timeout is not None else default_timeout(world, robots, tasks)
    check_tasks(tasks)
    if world.fleet is not None:
        return run_fleet_ros(
            world, plan, module, ros, robots, tasks=tasks, timeout=timeout, speed=speed, rate=rate, seed=seed,
            folder=folder, domain=domain, on_start=on_start, trace=trace, jitter=jitter, on_step=on_step, page=page,
            settings=params, policy=policy,
        )
    if folder is None:
        folder = Path(tempfile.mkdtemp(prefix="robosc-sim-"))
    folder.mkdir(parents=True, exist_ok=True)
    package = folder / f"{package_name(plan)}_ros{ros}"
    generate(plan, ros, "controller", package, page, relative=True)
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
            # (and never starts a controller again): the robots are where the model's initial state
            # says; its side sends each answer once and offers no report to confirm one by
            given: dict[str, object] = {
                "rate": float(rate),
                "seed": seed + i,
                "event_log": log,
                "trust_initial_state": True,
                "confirm_answers": False,
                "claim": False,  # each robot's controller is started once, alone
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
        return report_of(sim, ok, why, wall, str(folder))
    except session.SessionError as exc:
        raise session.SessionError(f"{exc}\n{graph.output()}") from None
    finally:
        if bridge is not None:
            bridge.close()
        graph.stop()
