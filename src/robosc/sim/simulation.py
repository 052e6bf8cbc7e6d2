"""The simulation of a world with N robots, without any middleware: commands in, messages
out, one fixed step of simulated time at a time.

What each robot's base does with commands is what a real mobile base does: a velocity
(Twist) is obeyed for ``command_timeout`` seconds and the robot stops when no new one comes;
a rotate command turns the robot in place by that many degrees (positive counter-clockwise),
ignoring velocities meanwhile, and then says it is done. A command that is not a finite
number stops the robot (fail safe). Per robot the simulation keeps what the run report
needs: time to the goal, distance travelled, the closest approach to a wall, collisions.
"""

from __future__ import annotations

import math
from typing import Any

from robosc.record import field, record
from robosc.sim.person import Walker
from robosc.sim.physics import Bodies, Body
from robosc.sim.world import World

SCAN_KEPT_EVERY = 1.0  # seconds of simulated time between the scans a run keeps for its recording


@record
class Message:
    """A message the simulator publishes: ``role`` names the topic (world.topics)."""

    robot: int
    role: str
    value: Any = None  # scan: list of ranges; line_correction: float; the rest: nothing


@record(frozen=False)
class Status:
    """What happened to one robot so far."""

    reached: float | None = None  # simulated time at which it reached (and held) the goal
    distance: float = 0.0  # metres travelled
    closest: float = math.inf  # closest approach of its edge to a wall or box, metres
    closest_robot: float = math.inf  # in a shared world: to another robot's edge, metres
    closest_person: float = math.inf  # in a world with a person: to the person's edge, metres
    collided_at: float | None = None
    touched: str = ""  # what it touched: "a wall or box", another robot ("robot2") or "the person"
    commands: int = 0  # velocity and rotate commands received
    refused: int = 0  # commands the supervisor refused (the node's ``blocked`` reports)
    bad_commands: int = 0  # commands with a number that is not finite (the robot stopped)
    trajectory: list[tuple[float, float, float, float]] = field(default_factory=list)  # t, x, y, heading
    scans: list[tuple[float, tuple[float, ...]]] = field(default_factory=list)  # t, ranges: one scan a second


class _Drive:
    """One robot's base: the velocity it is driven with and a rotation in progress."""

    def __init__(self) -> None:
        self.linear = 0.0
        self.angular = 0.0
        self.commanded_at = -math.inf
        self.turn_left = 0.0  # radians still to turn (negative: clockwise)
        self.turning = False
        self.still_since = 0.0


class Simulation:
    """``robots`` robots in ``world``; ``step()`` advances all by ``world.step`` seconds."""

    def __init__(self, world: World, robots: int = 1, trajectory_every: int = 2) -> None:
        if robots < 1:
            raise ValueError("at least one robot")
        self.world = world
        why = world.room_for(robots)
        if why is not None:
            raise ValueError(why)
        person = world.fleet.person if world.fleet is not None else None
        self.walker = Walker(person, world.robot.radius) if person is not None and world.shared else None
        if world.shared:  # one environment: the robots are bodies to each other (and the person)
            self.groups = [Bodies(world, [world.start(i) for i in range(robots)], person if self.walker else None)]
        else:
            self.groups = [Bodies(world, [world.start(i)]) for i in range(robots)]
        self.bodies: list[Body] = [body for group in self.groups for body in group.bodies]
        self.drives = [_Drive() for _ in range(robots)]
        self.status = [Status() for _ in range(robots)]
        self.time = 0.0
        self.steps = 0
        self.person: tuple[float, float] = (math.nan, math.nan)  # where the person is (x, y), if any
        self.person_trajectory: list[tuple[float, float, float]] = []  # t, x, y
        if self.walker is not None:
            self.person = self.groups[0].person_at()
        self.pressed = [False] * robots
        self._trajectory_every = max(1, trajectory_every)
        self._next_scan = 0.0
        self._next_line = 0.0
        self._next_kept_scan = 0.0
        for i, body in enumerate(self.bodies):
            self._record(i, body)

    @property
    def robots(self) -> int:
        return len(self.bodies)

    # ---- commands -------------------------------------------------------------------------
    def command_velocity(self, robot: int, linear: float, angular: float) -> None:
        drive, status = self.drives[robot], self.status[robot]
        status.commands += 1
        if not (math.isfinite(linear) and math.isfinite(angular)):
            status.bad_commands += 1
            linear = angular = 0.0
        limits = self.world.robot
        drive.linear = max(-limits.max_linear, min(limits.max_linear, linear))
        drive.angular = max(-limits.max_angular, min(limits.max_angular, angular))
        drive.commanded_at = self.time

    def rotate(self, robot: int, degrees: float) -> None:
        """Turn in place by ``degrees`` (positive counter-clockwise); ``rotate_done`` follows."""
        drive, status = self.drives[robot], self.status[robot]
        status.commands += 1
        if not math.isfinite(degrees):
            status.bad_commands += 1
            degrees = 0.0
        drive.turn_left = math.radians(degrees)
        drive.turning = True

    def refused(self, robot: int) -> None:
        self.status[robot].refused += 1

    def press(self, robot: int, pressed: bool) -> list[Message]:
        """Press (or release) robot ``robot``'s emergency stop button: the stop node says so."""
        if self.pressed[robot] == pressed:
            return []
        self.pressed[robot] = pressed
        return [Message(robot, "stop" if pressed else "continue")]

    # ---- time -----------------------------------------------------------------------------
    def step(self) -> list[Message]:
        """One step of simulated time; returns the messages the robots' sensors publish."""
        dt = self.world.step
        out: list[Message] = []
        velocities = []
        for i, drive in enumerate(self.drives):
            linear, angular = self._velocity(drive, dt)
            velocities.append((linear, angular) if self.status[i].collided_at is None else (0.0, 0.0))
        before = [body.pose for body in self.bodies]
        walking = (0.0, 0.0)
        if self.walker is not None:
            x, y = self.groups[0].person_at()
            walking = self.walker.velocity(self.time, dt, x, y, before)
        first = 0
        for group in self.groups:
            group.step(velocities[first : first + len(group.bodies)], walking)
            first += len(group.bodies)
        for i, (body, drive) in enumerate(zip(self.bodies, self.drives, strict=True)):
            after = body.pose
            self.status[i].distance += math.hypot(after.x - before[i].x, after.y - before[i].y)
            if drive.turning and abs(drive.turn_left) < 1e-9:
                drive.turning = False
                out.append(Message(i, "rotate_done"))
        self.time = round(self.time + dt, 9)
        self.steps += 1
        if self.walker is not None:
            self.person = self.groups[0].person_at()
            if self.steps % self._trajectory_every == 0:
                self.person_trajectory.append((self.time, round(self.person[0], 4), round(self.person[1], 4)))
        for i, body in enumerate(self.bodies):
            self._observe(i, body)
        for t0, t1 in self.world.presses:
            if t0 <= self.time < t1 + dt / 2:
                for i in range(self.robots):
                    out += self.press(i, self.time < t1)
        if self.time + 1e-9 >= self._next_scan:
            self._next_scan += 1.0 / self.world.robot.lidar.rate
            scans = [body.scan() for body in self.bodies]
            out += [Message(i, "scan", ranges) for i, ranges in enumerate(scans)]
            if self.time + 1e-9 >= self._next_kept_scan:  # for the recording
                self._next_kept_scan += SCAN_KEPT_EVERY
                for status, ranges in zip(self.status, scans, strict=True):
                    status.scans.append((self.time, tuple(ranges)))
        line = self.world.line
        if line is not None and self.time + 1e-9 >= self._next_line:
            self._next_line += 1.0 / line.rate
            for i, body in enumerate(self.bodies):
                reading = body.line_reading()
                out.append(Message(i, "line_lost") if reading is None else Message(i, "line_correction", reading))
        return out

    def _velocity(self, drive: _Drive, dt: float) -> tuple[float, float]:
        if drive.turning:
            speed = self.world.robot.turn_speed
            turn = max(-speed * dt, min(speed * dt, drive.turn_left))
            drive.turn_left -= turn
            return 0.0, turn / dt
        if self.time - drive.commanded_at >= self.world.robot.command_timeout - 1e-9:
            return 0.0, 0.0  # obeyed for command_timeout seconds from the step it came in
        return drive.linear, drive.angular

    def _observe(self, i: int, body: Body) -> None:
        status, drive = self.status[i], self.drives[i]
        clearance = body.clearance()
        status.closest = min(status.closest, clearance)
        nearest, gap = "", math.inf
        if self.world.shared:  # the other robots' edges
            pose, reach = body.pose, 2 * self.world.robot.radius
            for k, other in enumerate(self.bodies):
                there = other.pose
                found = math.hypot(pose.x - there.x, pose.y - there.y) - reach
                if k != i and found < gap:
                    nearest, gap = f"robot{k + 1}", found
            status.closest_robot = min(status.closest_robot, gap)
        if self.walker is not None:  # the person's edge
            pose, (px, py) = body.pose, self.person
            found = math.hypot(pose.x - px, pose.y - py) - self.world.robot.radius - self.walker.person.radius
            status.closest_person = min(status.closest_person, found)
            if found < gap:
                nearest, gap = "the person", found
        # IR-SIM stops bodies at contact, so a gap of a hair is a touch too
        if status.collided_at is None and (clearance <= 0.0 or gap <= 1e-3 or body.robot.collision):
            status.collided_at = self.time
            status.touched = nearest if nearest and gap <= max(clearance, 1e-3) else "a wall or box"
        if self.steps % self._trajectory_every == 0:
            self._record(i, body)
        moving = drive.turning or (
            self.time - drive.commanded_at <= self.world.robot.command_timeout + 1e-9
            and (drive.linear != 0.0 or drive.angular != 0.0)
        )
        if moving:
            drive.still_since = self.time
        goal = self.world.goal
        pose = body.pose
        if status.reached is None and goal.contains(pose.x, pose.y):
            if self.time - drive.still_since + 1e-9 >= goal.stopped:
                status.reached = self.time
        elif status.reached is not None and not goal.contains(pose.x, pose.y):
            status.reached = None  # it left the goal again

    def _record(self, i: int, body: Body) -> None:
        pose = body.pose
        self.status[i].trajectory.append((self.time, round(pose.x, 4), round(pose.y, 4), round(pose.heading, 4)))

    # ---- the end --------------------------------------------------------------------------
    @property
    def all_reached(self) -> bool:
        return all(s.reached is not None for s in self.status)

    @property
    def any_collided(self) -> bool:
        return any(s.collided_at is not None for s in self.status)

    def verdict(self, timeout: float) -> tuple[bool, str] | None:
        """How the run ended, (success, why), or None while it goes on: every robot reached
        the goal, one touched a wall or box, or ``timeout`` seconds of simulated time passed."""
        if self.any_collided:
            hit = [(f"robot{i + 1}", s.touched) for i, s in enumerate(self.status) if s.collided_at is not None]
            if all(what == "a wall or box" for _, what in hit):
                return False, f"{', '.join(name for name, _ in hit)} touched a wall or box at t = {self.time:.1f} s"
            said = "; ".join(f"{name} touched {what}" for name, what in hit)
            return False, f"{said} at t = {self.time:.1f} s"
        if self.all_reached:
            return True, "every robot reached the goal"
        if self.time >= timeout - 1e-9:
            return False, f"timeout: {timeout:g} s of simulated time"
        return None
