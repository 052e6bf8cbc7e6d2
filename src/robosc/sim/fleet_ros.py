"""A fleet in one world on ROS, as it would be deployed: the generated coordinator package (one
node, in namespace ``/fleet``) on a private graph (robosc.sim.graph), a driver node per robot
(``/bot1_driver``: the robot's topics under that namespace, ``/fleet/bot1/go``,
``/fleet/bot1/arrived``, its pose) and the simulator's node (``/clock``, the door's topics, the
person's detector and pose): a topic per command obeyed and per answer given, std_msgs/Empty,
reliable, and each driver's report service (``/fleet/robosc/report/bot1``, std_srvs/Trigger),
which says where its robot (or the door) is. The coordinator trusts no initial state: it asks
them, as deployed. The simulation (robosc.sim.fleet.FleetWorld) runs in this process and owns simulated
time: ``/clock`` advances at every step, and the coordinator runs on it (``use_sim_time``).
"""

from __future__ import annotations

import ast
import json
import tempfile
import time
import types
from collections.abc import Callable
from pathlib import Path
from typing import Any

from robosc.codegen.plan import Plan
from robosc.codegen.ros import generate, package_name, ros_name
from robosc.runtime.onboard.node import REPORT_PREFIX
from robosc.runtime.onboard.node_tasks import TASK_TOPIC, TASKS_TOPIC
from robosc.sim import session
from robosc.sim.fleet import (
    DOOR_ANSWERS,
    DOOR_COMMANDS,
    PERSON_DETECTOR,
    ROBOT_ANSWERS,
    ROBOT_COMMANDS,
    STALL,
    FleetMisfit,
    FleetWorld,
    Jitter,
    check_size,
    instances,
)
from robosc.sim.graph import Graph
from robosc.sim.report import Report
from robosc.sim.world import World

NAMESPACE = "fleet"  # the coordinator's namespace on the simulation's graph
POSE_SECONDS = 0.2  # simulated seconds between two poses of a robot (and at most POSE_RATE a real second)
POSE_RATE = 10.0
TAKEN_WITHIN = 30.0  # simulated seconds within which the coordinator's queue holds every task given

# (direction, name, perf_counter seconds): an answer published ("out"), a command come ("in")
Trace = Callable[[str, str, float], None]


def wiring(plan: Plan, names: list[str], namespace: str = NAMESPACE) -> tuple[list[list[str]], list[list[str]]]:
    """The coordinator's topics the world's side has: ([[command, topic, kind]], [[answer,
    topic, kind]]), each a communication of the model's with the world's name for it; kind
    "none" (std_msgs/Empty) or, for the person's detector, "string" (std_msgs/String). Raises
    FleetMisfit for one of another type."""
    robots = set(names)
    commands: list[list[str]] = []
    answers: list[list[str]] = []
    for c in plan.communications:
        robot, _, what = c.name.rpartition(".")
        command = (robot in robots and what in ROBOT_COMMANDS) or c.name in DOOR_COMMANDS
        answer = (robot in robots and what in ROBOT_ANSWERS) or c.name in DOOR_ANSWERS
        detector = c.name == PERSON_DETECTOR
        if not (command or answer or detector):
            continue
        kind = "string" if detector else "none"
        if c.kind != ("incoming" if command else "outgoing") or c.data_kind != kind or c.interface is not None:
            way = "an incoming" if command else "an outgoing"
            typed = "a string or an enum from string" if detector else "none"
            raise FleetMisfit(
                f"{c.name} must be {way} message 'with type: {typed}' for the fleet's world "
                f"(it is {c.kind}, {c.data_kind})"
            )
        entry = [c.name, f"/{namespace}/{ros_name(c, True).lstrip('/')}", kind]
        (commands if command else answers).append(entry)
    return commands, answers


def reports(plan: Plan, commands: list[list[str]], answers: list[list[str]], namespace: str = NAMESPACE) -> dict[str, Any]:
    """What each driver of the world's side (a robot's, the door's) answers when the coordinator
    asks where its component is (the runtime's report service, ``/fleet/robosc/report/bot1``,
    std_srvs/Trigger): ``{component: {"service": name, "at": its initial location, "moves":
    {command or answer: [[from (None: any), to], ...]}}}``. A driver knows where it is as a real
    one does, from the commands it obeyed and the answers it gave: the world's side moves its
    component by the model's location changes as each goes by."""
    labels = {f.name: f.label for f in plan.fields if f.group == "automata"}
    initial = {f.label: ast.literal_eval(f.initial) for f in plan.fields if f.group == "automata"}
    wired = {entry[0] for entry in commands + answers}
    moves: dict[str, dict[str, list[list[str | None]]]] = {}  # component -> communication -> [from, to]s
    for event in plan.events:
        c = event.communication
        if c is None or c.name not in wired or not event.moves:
            continue
        for field, source, target in event.moves:
            if field in labels:
                moves.setdefault(labels[field], {}).setdefault(c.name, []).append([source, target])
    return {
        component: {"service": f"/{namespace}/{REPORT_PREFIX}{component}", "at": initial[component], "moves": mine}
        for component, mine in moves.items()
    }


def pose_topics(names: list[str], person: bool, namespace: str = NAMESPACE) -> list[list[str]]:
    """What the world's side publishes besides the coordinator's topics (geometry_msgs/Pose2D,
    as robots publish where they are): each robot's pose (``/fleet/bot1/pose``) and where its
    move ends (``/fleet/bot1/destination``, x NaN while it has none), and the person's position
    (``/fleet/person/pose``, x NaN while out of sight). The fleet's live view draws them.
    ``namespace`` "": the names relative to the coordinator's namespace (``bot1/pose``)."""
    prefix = f"/{namespace}/" if namespace else ""
    topics = [[f"{n}.{what}", f"{prefix}{n}/{what}"] for n in names for what in ("pose", "destination")]
    return topics + ([["person.pose", f"{prefix}person/pose"]] if person else [])


def poses_of(fleet: FleetWorld) -> dict[str, list[float]]:
    """The poses of :func:`pose_topics` now, by name."""
    nan = float("nan")
    out: dict[str, list[float]] = {}
    for i, name in enumerate(fleet.names):
        pose = fleet.sim.bodies[i].pose
        out[f"{name}.pose"] = [pose.x, pose.y, pose.heading]
        end = fleet.drivers[i].destination() or (nan, nan)
        out[f"{name}.destination"] = [end[0], end[1], 0.0]
    if fleet.sim.walker is not None:
        out["person.pose"] = [fleet.sim.person[0], fleet.sim.person[1], 0.0]
    return out


def run_fleet_ros(
    world: World,
    plan: Plan,
    module: types.ModuleType,
    ros: int,
    robots: int,
    tasks: int = 1,
    timeout: float = 600.0,
    stall: float = STALL,
    speed: float = 1.0,
    rate: float = 10.0,
    seed: int = 0,
    folder: Path | None = None,
    domain: int | None = None,
    on_start: Callable[[object], None] | None = None,
    trace: Trace | None = None,
    on_end: Callable[[object], None] | None = None,
    jitter: Jitter | None = None,
    on_step: Callable[[FleetWorld], None] | None = None,
    page: str | None = None,
    settings: dict[str, object] | None = None,
    policy: str = "purpose",
) -> Report:
    """The coordinator package on ROS ``ros`` (1 or 2) commanding ``world``'s fleet; the run
    ends as FleetRun's does (robosc.sim.fleet), or when the coordinator dies. ``on_start(graph)``
    runs once the nodes are started, ``on_end(graph)`` when the run is over, before they are
    stopped; ``trace`` sees every command come and answer sent; ``jitter`` draws the robots'
    speeds and start delays; ``on_step(world)`` runs after every step (the coordinator's event
    log is ``folder/events/coordinator.jsonl``); ``page``: the coordinator's live view page
    (robosc view finds it in /fleet); ``settings``: the coordinator's parameters besides the
    simulation's own (``answer_timeout``, ...)."""
    names = instances(module)
    check_size(names, robots)
    commands, answers = wiring(plan, names)
    fleet = FleetWorld(world, names, jitter, leaving=any(entry[0].endswith(".left") for entry in answers))
    if folder is None:
        folder = Path(tempfile.mkdtemp(prefix="robosc-fleet-"))
    folder.mkdir(parents=True, exist_ok=True)
    package = folder / f"{package_name(plan)}_ros{ros}"
    generate(plan, ros, "controller", package, page, relative=True)
    (folder / "events").mkdir(exist_ok=True)
    graph = Graph(ros, folder, domain)
    bridges: dict[str, session.Bridge] = {}  # "" the simulator's node, else a robot's driver
    try:
        poses = pose_topics(names, fleet.sim.walker is not None)
        stops = world.fleet.stops if world.fleet is not None else ()
        given = [f"/{NAMESPACE}/{TASK_TOPIC}", f"/{NAMESPACE}/{TASKS_TOPIC}"] if stops else []
        table = reports(plan, commands, answers)
        for owner in ["", *names]:  # the simulator's node (clock, door, detector), a driver per robot
            bridge = graph.bridge(*(("simulator", "robosc_sim") if not owner else (f"driver_{owner}", f"{owner}_driver")))
            bridges[owner] = bridge
            mine: dict[str, object] = {key: [e for e in entries if _owner(e[0], names) == owner]
                                       for key, entries in (("commands", commands), ("answers", answers), ("poses", poses))}
            mine["reports"] = {c: r for c, r in table.items() if _owner(c + ".", names) == owner}
            if not owner and given:  # the simulator's node gives the tasks, as an operator would
                mine["tasks"] = {"give": given[0], "queue": given[1]}
            bridge.send("setup", robots=[], topics={}, roles=[], scan={}, fleet=mine)
        for owner, bridge in bridges.items():
            session.wait_for(bridge, lambda m: m.get("op") == "ready", 60, _who(owner))
        params: dict[str, object] = {
            "rate": float(rate),
            "seed": seed,
            "event_log": folder / "events" / "coordinator.jsonl",
            "policy": policy,
            # as deployed: the coordinator trusts nothing it has not been told; the drivers
            # report where they are, the person's detector says where the person is
            **(settings or {}),
        }
        graph.controller(package, NAMESPACE, params, process="coordinator")
        if on_start is not None:
            on_start(graph)
        for owner, bridge in bridges.items():
            topics = [e[1] for e in commands + answers if _owner(e[0], names) == owner] + (given if not owner else [])
            session.wait_for(bridge, session.connected(topics, 1), 60 + 2 * robots, f"the coordinator to connect to {_who(owner)}")
        for _ in range(tasks * robots if stops else 0):  # the world's tasks, through the coordinator's topic
            bridges[""].send("task", text=json.dumps({"stops": list(stops)}))
        started = time.monotonic()
        try:
            ended, ignored = _run(
                fleet, bridges, graph, {entry[0] for entry in answers}, tasks, timeout, stall, speed, trace, on_step,
                tasks * robots if stops else 0,
            )
        except KeyboardInterrupt:  # stopped: the report says how far it got
            ended, ignored = (False, f"stopped at t = {fleet.sim.time:.1f} s (Ctrl-C); {fleet.summary()}"), 0
        wall = time.monotonic() - started
        if on_end is not None:
            on_end(graph)
        return fleet.report(ended, tasks, ignored, wall, str(folder))
    except session.SessionError as exc:
        raise session.SessionError(f"{exc}\n{graph.output()}") from None
    finally:
        for bridge in bridges.values():
            bridge.close()
        graph.stop()


def _owner(name: str, names: list[str]) -> str:
    """Whose node offers the topic of ``name`` (``bot1.go``, ``bot1.pose``): the robot's driver,
    or "" for the simulator's node (the door, the detector, the person)."""
    robot = name.rpartition(".")[0]
    return robot if robot in names else ""


def _who(owner: str) -> str:
    return f"{owner}'s driver" if owner else "the simulator's node"


def _run(
    fleet: FleetWorld,
    bridges: dict[str, session.Bridge],
    graph: Graph,
    answered: set[str],
    tasks: int,
    timeout: float,
    stall: float,
    speed: float,
    trace: Trace | None,
    on_step: Callable[[FleetWorld], None] | None = None,
    given: int = 0,
) -> tuple[tuple[bool, str], int]:
    """Steps the world at ``speed`` times real time, passing commands in and answers out (each
    through the node that offers its topic); with ``given`` tasks given, until the queue the
    coordinator publishes says they are done."""
    sim = fleet.sim
    ignored = 0
    started = time.monotonic()
    clock = bridges[""]
    clock.send("clock", t=sim.time)
    posed = (-1e9, -1e9)  # (simulated, real) time of the last poses
    while True:
        for owner, bridge in bridges.items():
            came = session.arrived(bridge)  # the commands that came since the last step
            if came is None:
                return (False, f"{_who(owner)} ended"), ignored
            for message in came:
                if message.get("op") == "queue":
                    queue = _queue(message.get("text"))
                    if queue.get("counts"):
                        fleet.queue = queue
                    refused = [t for t in queue.get("tasks", []) if t.get("state") == "failed"]
                    if refused:
                        return (False, f"task {refused[0].get('id')} refused: {refused[0].get('why')}"), ignored
                if message.get("op") == "order":
                    if trace is not None:  # when its line came from the node
                        trace("in", str(message.get("name")), float(message.get("received", time.perf_counter())))
                    fleet.command(str(message.get("name")))
        died = graph.failed(sim)
        if died is not None:
            return (False, died), ignored
        out = fleet.step()
        clock.send("clock", t=sim.time)
        for name, data in out:
            if name in answered:
                bridges[_owner(name, fleet.names)].send("answer", name=name, data=data)
                if trace is not None:
                    trace("out", name, time.perf_counter())
            else:
                ignored += 1  # the model has no such answer
        if sim.time - posed[0] >= POSE_SECONDS - 1e-9 and time.monotonic() - posed[1] >= 1.0 / POSE_RATE:
            posed = (sim.time, time.monotonic())
            mine: dict[str, dict[str, list[float]]] = {owner: {} for owner in bridges}
            for name, pose in poses_of(fleet).items():
                mine[_owner(name, fleet.names)][name] = pose
            for owner, bridge in bridges.items():
                bridge.send("poses", poses=mine[owner])
        if on_step is not None:
            on_step(fleet)
        taken = fleet.tally()[1]
        if given and taken < given and sim.time >= TAKEN_WITHIN:  # a task lost on its way is not done
            return (False, f"the coordinator has {taken} of the {given} tasks given after {TAKEN_WITHIN:g} s"), ignored
        ended = fleet.verdict(tasks, timeout, stall, given)
        if ended is not None:
            return ended, ignored
        session.pace(started, sim.time, speed)


def _queue(text: Any) -> dict[str, Any]:
    """The coordinator's task queue from its JSON ({} when it cannot be read)."""
    try:
        queue = json.loads(str(text))
    except ValueError:
        return {}
    return queue if isinstance(queue, dict) else {}
