"""A fleet in one world: the world's side (:class:`FleetWorld`: one physics environment where
the robots are bodies to each other, a driver per robot, the door, the person's detector) and
the generated coordinator (one supervisor for every robot, the module ``robosc generate``
writes) commanding it in this process (:class:`FleetRun`; on ROS: robosc.sim.fleet_ros). Both run through
robosc.sim.run, and report as a single robot does (robosc.sim.report).

What the world offers a fleet model, by the names of its communications (``bot1.go``: the
instance ``bot1``'s ``go``; instances in order are the world's robots 1, 2, ...):

* ``go`` (a command): drive the next leg of the robot's task (``fleet.task``, or its own in
  ``fleet.tasks``: waypoints in turn); the driver answers ``arrived`` at the leg's end, or
  ``stopped`` where its LiDAR sees its way blocked for half a second (it then waits; the next
  ``go`` goes on with the same leg). A ``go`` that comes while the robot is still driving is
  queued, as a driver queues goals.
* ``left`` (where the model has it): once in a leg, when the robot's body overlaps no cell but
  the one the leg ends in, having overlapped another (the cells behind it are free).
* ``dock``: drive to the charger, charge, drive home, then answer ``charged``.
* ``open_door`` / ``close_door``: the door opens or closes in its ``seconds`` and answers
  ``door_opened`` / ``door_closed``; a robot in the doorway while the door is not open is a
  collision.
* ``person_cell`` (an answer with data): the name of the cell the person is in ("" for none,
  and in a world without a person), at the first step and whenever it changes.

With a :class:`Jitter`, each robot drives at a share of the top speed and starts late, drawn
from a seed. The run ends when every task the world gave is done (its ``stops``, ``tasks`` per
robot, given to the coordinator's dispatcher; in a world without stops, when each robot has
driven its legs ``tasks`` times) (success), at the first
collision, when no robot has got on with its task (arrived at the end of a leg) for ``stall``
seconds while tasks remain (a deadlock, or robots stopping again and again: each robot's cell,
what its driver does and what it waits for are told), or at the time-out.
"""

from __future__ import annotations

import math
import random
import types
from collections.abc import Callable
from typing import Any

from robosc.record import record
from robosc.runtime.onboard.tasks import FAILED, Dispatcher
from robosc.sim.report import FleetFigures, Report, report_of
from robosc.sim.simulation import Simulation
from robosc.sim.world import Fleet, Pose, World, to_segment

REACHED = 0.06  # metres from a waypoint that count as there
BLOCKED_GAP = 0.25  # metres between the robot's edge and what its LiDAR sees ahead that block it
BLOCKED_FOR = 0.5  # seconds blocked before the driver stops and says so
AHEAD = math.radians(25)  # half the angle the driver looks ahead in
ROBOT_COMMANDS = ("go", "dock")
ROBOT_ANSWERS = ("arrived", "stopped", "charged", "left")  # what a driver says (Driver.answers)
DOOR_COMMANDS = {"open_door": "opening", "close_door": "closing"}
DOOR_ANSWERS = ("door_opened", "door_closed")  # what the door says (DoorSim.answers)
PERSON_DETECTOR = "person_cell"  # the answer that says which cell the person is in
# simulated seconds without a robot arriving at the end of a leg that end a run as a deadlock (the
# coordinator's random choices can keep robots waiting for a while: the door opened and closed
# again, robots docking, before the one that waits is chosen)
STALL = 60.0


class FleetMisfit(Exception):
    """The model's fleet cannot run in the world (its size, the world's robots)."""


def instances(module: types.ModuleType) -> list[str]:
    """The instances the coordinator commands with ``go``, in order (bot1, bot2, ..., bot10)."""
    found = {c.name.rsplit(".", 1)[0] for c in module.Robot.COMMUNICATIONS if c.name.endswith(".go")}

    def order(name: str) -> tuple[str, int]:
        base = name.rstrip("0123456789")
        return base, int(name[len(base) :] or 0)

    return sorted(found, key=order)


@record
class Jitter:
    """Robots that differ from run to run: each drives at a share of the world's top speed
    drawn from ``speed`` and starts after a delay drawn from ``delay`` (simulated seconds)."""

    seed: int
    speed: tuple[float, float] = (0.6, 1.0)
    delay: tuple[float, float] = (0.0, 5.0)

    def draw(self, robots: int) -> list[tuple[float, float]]:
        """(speed share, start delay) for each robot."""
        chance = random.Random(self.seed)
        return [(chance.uniform(*self.speed), chance.uniform(*self.delay)) for _ in range(robots)]


@record(frozen=False)
class FleetStatus:
    """What one robot did in the run."""

    name: str
    tasks: int = 0  # times it drove the whole task
    waiting: float = 0.0  # simulated seconds it stood still, idle or stopped (not charging), its tasks done or not
    stops: int = 0  # times it stopped because its way was blocked


class Driver:
    """One robot's driver: drives the legs of the task, docks, and answers as a fleet's robot
    does (see the module's description)."""

    def __init__(self, index: int, fleet: Fleet, home: Pose, speed: float = 1.0, wake: float = 0.0,
                 leaving: bool = False) -> None:
        self.index, self.fleet, self.home = index, fleet, home
        self.leaving = leaving  # whether it says ``left`` (the model has that answer)
        self.ending: str | None = None  # the cell the leg under way ends in ("": none) while ``left`` may come
        self.was_out = False  # whether its body has overlapped another cell in the leg under way
        self.task = fleet.task_of(index)
        self.speed = speed  # a share of the world's top speed this robot drives at
        self.wake = wake  # simulated seconds before it starts to move (commands wait till then)
        self.held: list[str] = []  # commands that came before it woke
        self.leg = 0  # the next leg of the task
        self.path: list[tuple[float, float]] = []  # points still to reach
        self.doing = "idle"  # idle, driving, stopped, docking, charging, undocking
        self.queued = 0  # gos that came while it was driving
        self.blocked_since: float | None = None
        self.charged_at = 0.0
        self.answers: list[str] = []

    def command(self, name: str, now: float) -> None:
        if now + 1e-9 < self.wake:
            self.held.append(name)
            return
        if name == "go":
            if self.doing == "stopped":
                self.doing = "driving"  # go on with the same leg
                self.blocked_since = None
            elif self.doing in ("driving", "docking", "charging", "undocking"):
                self.queued += 1
            else:
                self._start_leg()
        elif name == "dock" and self.doing == "idle" and self.fleet.charger is not None:
            self.path = [self._via(), self.fleet.charger.at]
            self.doing = "docking"

    def destination(self) -> tuple[float, float] | None:
        """Where the move under way ends (the robot holds its cell until it arrives), or None."""
        return self.path[-1] if self.doing in ("driving", "stopped") and self.path else None

    def _via(self) -> tuple[float, float]:
        """The point between this robot's home and the charger (home + the charger's via)."""
        assert self.fleet.charger is not None
        via = self.fleet.charger.via
        return self.home.x + via[0], self.home.y + via[1]

    def _start_leg(self) -> None:
        names = self.task[self.leg]
        self.path = [self.fleet.point(name, self.home) for name in names]
        self.doing = "driving"
        if self.leaving:
            self.ending, self.was_out = self.fleet.cell(*self.path[-1]), False

    def step(self, sim: Simulation, scan: list[float] | None, now: float, status: FleetStatus) -> None:
        """Drive toward the next point of the path; answer what happened."""
        if self.held and now + 1e-9 >= self.wake:
            held, self.held = self.held, []
            for name in held:
                self.command(name, now)
        if self.doing == "charging":
            if now >= self.charged_at:
                self.path = [self._via(), (self.home.x, self.home.y)]
                self.doing = "undocking"
            return
        if self.doing not in ("driving", "docking", "undocking") or not self.path:
            return
        pose = sim.bodies[self.index].pose
        if self.ending is not None and self.doing == "driving":
            self._left(pose, sim.world.robot.radius)
        if self.doing == "driving" and scan is not None and self._blocked(sim, scan):
            if self.blocked_since is None:
                self.blocked_since = now
            sim.command_velocity(self.index, 0.0, 0.0)
            if now - self.blocked_since >= BLOCKED_FOR:
                self.doing = "stopped"
                status.stops += 1
                self.answers.append("stopped")
            return
        self.blocked_since = None
        tx, ty = self.path[0]
        distance = math.hypot(tx - pose.x, ty - pose.y)
        if distance < REACHED:
            self.path.pop(0)
            if not self.path:
                sim.command_velocity(self.index, 0.0, 0.0)
                self._finished(now, status)
            return
        off = math.atan2(ty - pose.y, tx - pose.x) - pose.heading
        error = math.atan2(math.sin(off), math.cos(off))  # -pi .. pi
        limits = sim.world.robot
        angular = max(-limits.max_angular, min(limits.max_angular, 3.0 * error))
        linear = 0.0 if abs(error) > 0.35 else min(limits.max_linear * self.speed, 1.5 * distance)
        sim.command_velocity(self.index, linear, angular)

    def _left(self, pose: Pose, radius: float) -> None:
        """Say ``left`` (once a leg) when the body, which overlapped a cell other than the one
        the leg ends in, overlaps none but that one."""
        others = self.fleet.cells_under(pose.x, pose.y, radius) - {self.ending}
        if others:
            self.was_out = True
        elif self.was_out:
            self.answers.append("left")
            self.ending = None

    def _finished(self, now: float, status: FleetStatus) -> None:
        if self.doing == "docking":
            charger = self.fleet.charger
            assert charger is not None
            self.doing, self.charged_at = "charging", now + charger.seconds
            return
        if self.doing == "undocking":
            self.doing = "idle"
            self.answers.append("charged")
        else:
            self.doing = "idle"
            self.answers.append("arrived")
            self.leg += 1
            if self.leg == len(self.task):
                self.leg = 0
                status.tasks += 1
        if self.queued:
            self.queued -= 1
            self._start_leg()

    def _blocked(self, sim: Simulation, scan: list[float]) -> bool:
        """Whether something is closer than BLOCKED_GAP ahead of the robot, in the direction it drives."""
        beams = len(scan)
        reach = sim.world.robot.radius + BLOCKED_GAP
        pose = sim.bodies[self.index].pose
        tx, ty = self.path[0]
        heading = math.atan2(ty - pose.y, tx - pose.x) - pose.heading  # toward the next point
        step = 2 * math.pi / beams  # ranges[0] ahead, counter-clockwise
        centre, half = round(heading / step), int(AHEAD / step)
        return any(scan[(centre + k) % beams] < reach for k in range(-half, half + 1))


def door_in_scan(scan: list[float], pose: Pose, a: tuple[float, float], b: tuple[float, float]) -> list[float]:
    """``scan`` (ranges[0] ahead, counter-clockwise, from ``pose``) with the door, the segment
    ``a``-``b``, in it: each beam that meets the door sees it where it is nearer."""
    beams = len(scan)
    (ax, ay), (bx, by) = a, b
    ex, ey = bx - ax, by - ay
    out = list(scan)
    for k in range(beams):
        angle = pose.heading + 2 * math.pi * k / beams
        dx, dy = math.cos(angle), math.sin(angle)
        denominator = dx * ey - dy * ex
        if abs(denominator) < 1e-12:
            continue  # along the door
        wx, wy = ax - pose.x, ay - pose.y
        distance = (wx * ey - wy * ex) / denominator  # along the beam
        share = (wx * dy - wy * dx) / denominator  # along the door, 0 .. 1 on it
        if distance > 0.0 and 0.0 <= share <= 1.0 and distance < out[k]:
            out[k] = distance
    return out


class DoorSim:
    """The door: closed, opening, open or closing; it answers when it has opened or closed."""

    def __init__(self, seconds: float) -> None:
        self.state, self.seconds, self.until = "closed", seconds, 0.0
        self.answers: list[str] = []
        self.states: list[tuple[float, str]] = [(0.0, "closed")]  # (t, state) at each change, for pictures

    def command(self, name: str, now: float) -> None:
        moving = DOOR_COMMANDS[name]
        if (moving, self.state) in (("opening", "closed"), ("closing", "open")):
            self.state, self.until = moving, now + self.seconds
            self.states.append((now, moving))

    def step(self, now: float) -> None:
        if self.state in ("opening", "closing") and now >= self.until:
            self.state = "open" if self.state == "opening" else "closed"
            self.states.append((now, self.state))
            self.answers.append("door_opened" if self.state == "open" else "door_closed")


class FleetWorld:
    """The world's side of a fleet: the simulation, a driver per robot and the door. Commands
    come in by the coordinator's names (``bot1.go``, ``open_door``); each ``step()`` returns the
    answers the robots and the door gave (``bot1.arrived``, ``door_opened``). With ``leaving``
    (the model has the answer ``left``) the drivers say ``left`` too."""

    def __init__(self, world: World, names: list[str], jitter: Jitter | None = None, leaving: bool = False) -> None:
        if world.fleet is None:
            raise FleetMisfit(f"{world.path} is not a fleet's world (it has no 'fleet')")
        self.sim = Simulation(world, len(names))
        self.fleet = world.fleet
        self.names = names
        self.index = {name: i for i, name in enumerate(names)}
        draws = jitter.draw(len(names)) if jitter is not None else [(1.0, 0.0)] * len(names)
        self.drivers = [Driver(i, world.fleet, world.start(i), *draws[i], leaving=leaving) for i in range(len(names))]
        self.status = [FleetStatus(name) for name in names]
        self.door = DoorSim(world.fleet.door.seconds) if world.fleet.door is not None else None
        self.scans: list[list[float] | None] = [None] * len(names)
        self.progress = 0.0  # when a robot last arrived at the end of a leg of its task
        self.person_cell: str | None = None  # the cell the detector last said the person is in
        # the coordinator's task queue as last heard (robosc.runtime.onboard.node_tasks: tasks,
        # counts, waiting, t): from its dispatcher in this process, from its topic on ROS
        self.queue: dict[str, Any] = {}

    def command(self, name: str) -> None:
        """A command of the coordinator's (one it has no driver for does nothing)."""
        robot, _, what = name.rpartition(".")
        now = self.sim.time
        if robot in self.index and what in ROBOT_COMMANDS:
            self.drivers[self.index[robot]].command(what, now)
        elif name in DOOR_COMMANDS and self.door is not None:
            self.door.command(name, now)

    def step(self) -> list[tuple[str, Any]]:
        """One step; the answers given in it, (name, data): data is None but for the person's
        detector, which says the name of the cell the person is in ("" for none)."""
        sim = self.sim
        before = [(b.pose.x, b.pose.y) for b in sim.bodies]
        door = self.fleet.door if self.door is not None and self.door.state != "open" else None
        for message in sim.step():
            if message.role == "scan":  # a door not open is in the LiDAR's way
                scan = message.value
                if door is not None:
                    scan = door_in_scan(scan, sim.bodies[message.robot].pose, door.a, door.b)
                self.scans[message.robot] = scan
        now = sim.time
        answers: list[tuple[str, Any]] = []
        cell = self.fleet.cell(*sim.person) if sim.walker is not None else ""  # no person: nobody seen
        if cell != self.person_cell:
            self.person_cell = cell
            answers.append((PERSON_DETECTOR, cell))
        for i, (driver, status) in enumerate(zip(self.drivers, self.status, strict=True)):
            driver.step(sim, self.scans[i], now, status)
            pose = sim.bodies[i].pose
            if math.hypot(pose.x - before[i][0], pose.y - before[i][1]) <= 1e-4 and driver.doing in ("idle", "stopped"):
                status.waiting += sim.world.step
            if "arrived" in driver.answers:  # a leg of a task done (charging, the door, stopping again: none)
                self.progress = now
            answers += [(f"{self.names[i]}.{answer}", None) for answer in driver.answers]
            driver.answers.clear()
        if self.door is not None:
            self.door.step(now)
            answers += [(answer, None) for answer in self.door.answers]
            self.door.answers.clear()
            self._doorway()
        return answers

    def _doorway(self) -> None:
        door = self.fleet.door
        assert door is not None and self.door is not None
        if self.door.state == "open":
            return
        for i, body in enumerate(self.sim.bodies):
            if to_segment(body.pose.x, body.pose.y, door.a, door.b) < self.sim.world.robot.radius:
                status = self.sim.status[i]
                if status.collided_at is None:
                    status.collided_at, status.touched = self.sim.time, f"the door ({self.door.state})"

    def tally(self) -> tuple[dict[str, int], int]:
        """The coordinator's tasks per state as last heard (:attr:`queue`), and how many it holds."""
        counts = {state: int(n) for state, n in (self.queue.get("counts") or {}).items()}
        return counts, sum(counts.values())

    def verdict(self, tasks: int, timeout: float, stall: float, given: int = 0) -> tuple[bool, str] | None:
        """Why the run ends now, or None: with ``given`` tasks given, the run ends well when the
        coordinator's queue says that many are done; with none, when each robot has driven its
        legs ``tasks`` times."""
        sim = self.sim
        hit = [(self.names[i], s.touched) for i, s in enumerate(sim.status) if s.collided_at is not None]
        if hit:
            named = {f"robot{i + 1}": name for i, name in enumerate(self.names)}
            said = "; ".join(f"{name} touched {named.get(what, what)}" for name, what in hit)
            return False, f"collision: {said} at t = {sim.time:.1f} s"
        if given and self.tally()[0].get("done", 0) == given:
            return True, f"all {given} tasks given are done"
        if not given and all(s.tasks >= tasks for s in self.status):
            return True, f"every robot did its {tasks} task(s)"
        if sim.time - self.progress >= stall:
            where = "; ".join(self.whereabouts(i) for i in range(len(self.names)))
            return False, f"deadlock: no robot got on with its task for {stall:g} s: {where}"
        if sim.time >= timeout - 1e-9:
            return False, f"timeout: {timeout:g} s of simulated time; {self.summary()}"
        return None

    def summary(self) -> str:
        """The tasks done so far and where each robot is and what it waits for (for a run
        stopped before its end)."""
        counts, given = self.tally()
        done = f"{counts.get('done', 0)}/{given} tasks done" if given else f"{sum(s.tasks for s in self.status)} tasks done"
        tasks, waited = self.doing(), self.waited()
        where = []
        for i, name in enumerate(self.names):
            said = self.whereabouts(i)
            if name in tasks:
                said += f", on {tasks[name]}"
                if waited.get(name, 0.0) >= 1.0:
                    said += f", waiting {waited[name]:.0f} s"
            where.append(said)
        return f"{done}; " + "; ".join(where)

    def whereabouts(self, i: int) -> str:
        """Where robot ``i`` is and what it waits for: its cell, what its driver does, the cell
        its leg under way ends in and how far its next point is, or the point its next leg ends
        at (and that point's cell)."""
        pose, driver = self.sim.bodies[i].pose, self.drivers[i]
        here = self.fleet.cell(pose.x, pose.y) or "no cell"
        told = f"{self.names[i]} in {here} ({driver.doing}"
        if driver.path:
            x, y = driver.path[-1]
            told += f" into {self.fleet.cell(x, y) or 'no cell'}"
            x, y = driver.path[0]
            told += f", {math.hypot(x - pose.x, y - pose.y):.2f} m from ({x:g}, {y:g})"
        elif driver.doing == "idle":  # the point its next leg ends at, and that point's cell
            point = driver.task[driver.leg][-1]
            cell = self.fleet.cell(*self.fleet.point(point, driver.home)) or "no cell"
            told += f", its next move to {point}" + ("" if cell == point else f", in {cell}")
        return told + ")"

    def waited(self) -> dict[str, float]:
        """Each robot with a task: the simulated seconds since it last got on with it."""
        waiting = self.queue.get("waiting") or {}
        since = float(self.queue.get("t") or self.sim.time)
        return {name: max(0.0, float(w) + self.sim.time - since) for name, w in waiting.items()}

    def doing(self) -> dict[str, str]:
        """Each robot's task under way: its id and stops, the next one marked (``task2: shelf ->
        [depot]``)."""
        out = {}
        for task in self.queue.get("tasks") or []:
            if task.get("state") == "assigned" and task.get("by"):
                stops = [str(s) for s in task.get("stops") or []]
                reached = int(task.get("reached") or 0)
                out[str(task["by"])] = f"{task.get('id')}: " + " -> ".join(
                    f"[{stop}]" if k == reached else stop for k, stop in enumerate(stops)
                )
        return out

    def progress_line(self) -> str:
        """Where the run is, in one line: simulated time, tasks done and queued, who waits longest."""
        counts, given = self.tally()
        line = f"t = {self.sim.time:.0f} s: {counts.get('done', 0)}/{given} tasks done, {counts.get('assigned', 0)} under way, {counts.get('queued', 0)} queued"
        waited = self.waited()
        if waited:
            name = max(waited, key=lambda n: waited[n])
            line += f"; waiting longest: {name} ({waited[name]:.0f} s)"
        return line

    def frame(self) -> dict[str, Any]:
        """What the fleet's live view draws now: each robot's pose, what its driver does, the cell
        it is in and the cell it drives into (held from its ``go`` until it arrives), its tasks;
        the person (x, y) or None; the door's state or None."""
        robots: dict[str, Any] = {}
        tasks, waited = self.doing(), self.waited()
        for i, name in enumerate(self.names):
            pose, driver = self.sim.bodies[i].pose, self.drivers[i]
            end = driver.destination()
            into = self.fleet.cell(*end) if end is not None else ""
            robots[name] = {
                "x": round(pose.x, 3), "y": round(pose.y, 3), "heading": round(pose.heading, 3),
                "doing": driver.doing, "cell": self.fleet.cell(pose.x, pose.y), "into": into,
                "tasks": self.status[i].tasks, "collided": self.sim.status[i].collided_at is not None,
                "task": tasks.get(name, ""), "waited": round(waited[name], 1) if name in waited else None,
            }
        person = None
        if self.sim.walker is not None and math.isfinite(self.sim.person[0]):
            person = [round(self.sim.person[0], 3), round(self.sim.person[1], 3)]
        door = self.door.state if self.door is not None else None
        return {"t": round(self.sim.time, 3), "robots": robots, "person": person, "door": door,
                "queue": dict(self.queue.get("counts") or {})}

    def report(self, ended: tuple[bool, str], tasks: int, ignored: int, wall: float = 0.0, folder: str = "") -> Report:
        """The run's report (robosc.sim.report): ``tasks`` each robot had to do, ``ignored``
        answers the coordinator has no event for."""
        figures = FleetFigures(
            tuple(s.tasks for s in self.status), tuple(s.waiting for s in self.status),
            tuple(s.stops for s in self.status), tasks, ignored, tuple(self.door.states) if self.door is not None else (),
        )
        return report_of(self.sim, ended[0], ended[1], wall, folder, self.names, figures)


def check_size(names: list[str], robots: int) -> None:
    """The model's fleet (``names``, its instances that take ``go``) has ``robots`` robots, or
    FleetMisfit says so and how to run the model with that many without editing it."""
    if len(names) != robots:
        group = names[0].rstrip("0123456789") if names else "bot"
        raise FleetMisfit(
            f"the model's fleet has {len(names)} robots ({', '.join(names) or 'none'}) and {robots} were asked for; "
            f"--instances {group}={robots} makes the model's fleet {robots} robots without editing it"
        )


class FleetRun:
    """The generated coordinator (``module``) commanding ``world``'s fleet in this process (what
    robosc.sim.run.run_local steps for a fleet's world)."""

    def __init__(
        self, world: World, module: types.ModuleType, robots: int, seed: int = 0, rate: float = 10.0,
        jitter: Jitter | None = None, on_event: Callable[[dict[str, Any]], None] | None = None,
        on_step: Callable[[FleetWorld], None] | None = None, tasks: int = 1, stall: float = STALL,
        policy: str = "purpose",
    ) -> None:
        names = instances(module)
        check_size(names, robots)
        self.world = FleetWorld(world, names, jitter, leaving=any(e.endswith(".left") for e in module.Robot.EVENT))
        self.sim = self.world.sim
        self.rate = rate
        self.tasks, self.stall = tasks, stall  # the run ends well when every task given is done
        self.ignored = 0
        run = self

        class Coordinator(module.Robot):  # type: ignore[name-defined, misc]
            def send(self, name: str, data: Any) -> bool:
                run.world.command(name)
                return True

        # the simulated robots and the door start where the model starts them (a simulation's
        # trust_initial_state): nothing to confirm
        self.coordinator = Coordinator(seed=seed, warn=lambda text: None, clock=lambda: run.sim.time,
                                       wait_for_data=False, confirmed=True)
        if on_event is not None:  # each event as the event log has it: its time, data and the state after it
            def observe(event: str, controllable: bool, data: Any) -> None:
                on_event({"time": round(run.sim.time, 6), "event": event, "controllable": controllable,
                          "data": data, "state": run.coordinator.snapshot()})

            self.coordinator.observer = observe
        self.on_step = on_step  # called with the world's side after every step
        self._next_tick = 0.0
        # the world gives its tasks (fleet.stops, `tasks` per robot) through the coordinator's
        # run-time interface, as an operator would; a world without stops gives none, and the
        # coordinator then chooses at random (each robot drives its legs `tasks` times)
        self.dispatcher: Dispatcher | None = None
        stops = self.world.fleet.stops
        self.given = tasks * robots if stops else 0
        if stops:
            self.dispatcher = Dispatcher(self.coordinator, policy)
            self.coordinator.tasks = self.dispatcher
            for _ in range(self.given):
                task = self.dispatcher.submit(stops)
                if task.state == FAILED:
                    raise FleetMisfit(f"{world.path}: the world's task {list(stops)} is refused: {task.why}")

    def step(self) -> None:
        for name, data in self.world.step():
            if name in self.coordinator.EVENT:
                self.coordinator.deliver(name, data)
            else:
                self.ignored += 1  # the model has no such answer (a zero-time model has no arrived)
        if self.sim.time + 1e-9 >= self._next_tick:
            self._next_tick += 1.0 / self.rate
            self.coordinator.tick()
        if self.dispatcher is not None:
            d = self.dispatcher
            self.world.queue = {"counts": d.counts(), "waiting": d.waiting(), "t": self.sim.time,
                                "tasks": [t.as_dict() for t in d.doing.values()]}
        if self.on_step is not None:
            self.on_step(self.world)

    def ended(self, timeout: float) -> tuple[bool, str] | None:
        """Why the run ends now, or None (robosc.sim.run's loop asks after every step)."""
        return self.world.verdict(self.tasks, timeout, self.stall, self.given)

    def interrupted(self) -> tuple[bool, str]:
        """How the run ends when it is stopped (Ctrl-C): what was done, what each robot waits for."""
        return False, f"stopped at t = {self.sim.time:.1f} s (Ctrl-C); {self.world.summary()}"

    def report(self, ended: tuple[bool, str], wall: float, folder: str = "") -> Report:
        return self.world.report(ended, self.tasks, self.ignored, wall, folder)
