"""A world and the generated supervisors in one process, without middleware: the quickest
way to see a controller drive its robot (what ``robosc sim --ros none`` steps, through
robosc.sim.run, for a world with a goal; a fleet's world steps robosc.sim.fleet.FleetRun).

The supervisors are the very module ``robosc generate`` writes (loaded from the plan);
messages go to them and commands come from them by topic name, as they would over ROS.
"""

from __future__ import annotations

import math
import types
from collections.abc import Callable
from pathlib import Path
from typing import Any

from robosc.sim.report import Report, report_of, robot_names
from robosc.sim.simulation import Message, Simulation

# the roles of the simulator's topics that take commands, and what they do
COMMAND_ROLES = ("cmd_vel", "rotate_left", "rotate_right")


def number(value: Any) -> float:
    """A command's number; anything that is not one reads NaN (the robot then stops)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return math.nan
    return float(value)


def field_of(data: Any, *path: str) -> Any:
    """``data.linear.x`` of a Twist given as nested dicts or as message objects; absent: 0."""
    for name in path:
        if data is None:
            return 0.0
        data = data.get(name, 0.0) if isinstance(data, dict) else getattr(data, name, 0.0)
    return 0.0 if data is None else data


def apply_command(sim: Simulation, robot: int, role: str, data: Any) -> None:
    """A command published on the topic of ``role`` reaches robot ``robot``'s base."""
    if role == "cmd_vel":
        sim.command_velocity(robot, number(field_of(data, "linear", "x")), number(field_of(data, "angular", "z")))
    elif role == "rotate_left":
        sim.rotate(robot, number(data))
    elif role == "rotate_right":
        sim.rotate(robot, -number(data))


def scan_message(sim: Simulation, ranges: list[float]) -> dict[str, Any]:
    """A LaserScan's fields, as sensor_msgs/LaserScan names them."""
    lidar = sim.world.robot.lidar
    increment = 2 * math.pi / lidar.beams
    return {
        "angle_min": 0.0,
        "angle_max": increment * (lidar.beams - 1),
        "angle_increment": increment,
        "time_increment": 0.0,
        "scan_time": 1.0 / lidar.rate,
        "range_min": lidar.range_min,
        "range_max": lidar.range_max,
        "ranges": ranges,
    }


def named(record: dict[str, Any], robot: str) -> dict[str, Any]:
    """An event record of ``robot``'s controller with the event named for the robot
    (``robot2.e_forward``), as the live view lists a world's events; a state record as it is."""
    event = record.get("event")
    return {**record, "event": f"{robot}.{event}"} if event is not None else record


def robot_frame(sim: Simulation) -> dict[str, Any]:
    """What the live view draws of a world with a goal now (as a fleet's frame, robosc.sim.fleet:
    FleetWorld.frame): each robot's pose and whether it collided; no cells, tasks, person or door."""
    robots = {
        name: {
            "x": round(body.pose.x, 3), "y": round(body.pose.y, 3), "heading": round(body.pose.heading, 3),
            "doing": None, "cell": "", "into": "", "tasks": None, "collided": status.collided_at is not None,
        }
        for name, body, status in zip(robot_names(sim.robots), sim.bodies, sim.status, strict=True)
    }
    return {"t": round(sim.time, 3), "robots": robots, "person": None, "door": None}


class SimulationFrames:
    """A simulation seen by the live view's feed (robosc.sim.view.FleetFeed), as a fleet's
    world is: ``sim`` and ``frame()``."""

    def __init__(self, sim: Simulation) -> None:
        self.sim = sim

    def frame(self) -> dict[str, Any]:
        return robot_frame(self.sim)


class LocalRun:
    """``sim.robots`` instances of the generated ``Robot`` class driving the simulation.
    ``on_event(record)`` hears every robot's events, each named for its robot
    (``robot1.e_forward``); ``on_step(self)`` is called after each step."""

    def __init__(
        self,
        sim: Simulation,
        module: types.ModuleType,
        rate: float = 10.0,
        seed: int = 0,
        on_event: Callable[[dict[str, Any]], None] | None = None,
        on_step: Callable[[Any], None] | None = None,
    ) -> None:
        from robosc.runtime.onboard.values import Data

        self.sim = sim
        self.rate = rate
        self._data = Data
        topics = sim.world.topics
        role_of = {name.lstrip("/"): role for role, name in topics.items()}
        base = module.Robot
        self.listeners: dict[str, list[str]] = {}  # role -> communications that receive it
        self.commands: dict[str, str] = {}  # communication -> role
        for comm in base.COMMUNICATIONS:
            role = role_of.get(comm.ros_name.lstrip("/"))
            if role is None:
                continue
            if comm.kind == "outgoing":
                self.listeners.setdefault(role, []).append(comm.name)
            elif comm.kind == "incoming" and role in COMMAND_ROLES:
                self.commands[comm.name] = role
        run = self

        class Driven(base):  # type: ignore[valid-type, misc]
            index = 0

            def send(self, name: str, data: Any) -> bool:
                role = run.commands.get(name)
                if role is not None:
                    apply_command(run.sim, self.index, role, data)
                return True

        self.robots = []
        for i in range(sim.robots):
            robot = Driven(seed=seed + i, warn=lambda text: None, clock=lambda: run.sim.time)
            robot.index = i
            self.robots.append(robot)
        self._next_tick = 0.0
        self._logs: list[Any] = []
        self.on_event = on_event
        self.on_step = on_step
        if on_event is not None:
            self._observe([[] for _ in self.robots])

    def frame(self) -> dict[str, Any]:
        """What the live view draws now (:func:`robot_frame`)."""
        return robot_frame(self.sim)

    def record(self, paths: list[Path]) -> None:
        """Each robot's events to its event log (JSON Lines), stamped with simulated time."""
        from robosc.runtime.onboard.recording import EventLog

        logs = [EventLog(str(path)) for path in paths]
        self._logs += logs
        self._observe([[log] for log in logs])

    def _observe(self, sinks: list[list[Any]]) -> None:
        """Each robot's events to its ``sinks`` and to ``on_event``, stamped with simulated time."""
        from robosc.runtime.onboard.recording import Recorder

        for robot, name, mine in zip(self.robots, robot_names(len(self.robots)), sinks, strict=True):
            if self.on_event is not None:
                mine = [*mine, self._named(name)]
            robot.observer = Recorder(robot, mine, clock=lambda: self.sim.time)

    def _named(self, name: str) -> Callable[[dict[str, Any]], None]:
        on_event = self.on_event
        assert on_event is not None
        return lambda record: on_event(named(record, name))

    def close(self) -> None:
        for log in self._logs:
            log.close()
        self._logs.clear()

    def deliver(self, message: Message) -> None:
        robot = self.robots[message.robot]
        value = message.value
        if message.role == "scan":
            value = self._data(scan_message(self.sim, value))
        for name in self.listeners.get(message.role, ()):
            robot.deliver(name, value)

    def press(self, robot: int, pressed: bool) -> None:
        for message in self.sim.press(robot, pressed):
            self.deliver(message)

    def step(self) -> None:
        for message in self.sim.step():
            self.deliver(message)
        if self.sim.time + 1e-9 >= self._next_tick:
            self._next_tick += 1.0 / self.rate
            for robot in self.robots:
                robot.tick()
        if self.on_step is not None:
            self.on_step(self)

    def ended(self, timeout: float) -> tuple[bool, str] | None:
        """Why the run ends now (every robot reached the goal, one collided, ``timeout``
        simulated seconds passed), or None (robosc.sim.run's loop asks after every step)."""
        return self.sim.verdict(timeout)

    def interrupted(self) -> tuple[bool, str]:
        """How the run ends when it is stopped (Ctrl-C)."""
        return False, f"stopped at t = {self.sim.time:.1f} s (Ctrl-C)"

    def report(self, ended: tuple[bool, str], wall: float, folder: str = "") -> Report:
        return report_of(self.sim, ended[0], ended[1], wall, folder)
