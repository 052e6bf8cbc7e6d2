"""A person walking a scripted path among the robots (a world's ``fleet.person``): the walk's
points in turn at the person's speed, standing at a point for its seconds. A person gives way:
one whose next step would bring them within GIVE_WAY metres of a robot's edge waits where they
are (people step aside for a robot that is already there; the robots keep out of the person's
way as their model says), and after WAIT_AT_MOST seconds walks round the robot, stepping to a
side where no step brings them closer to one. A point of the walk that a robot stands on, for
WAIT_AT_MOST seconds of waiting, counts as reached: the person stands where they are instead
(a robot stopped on the person's spot would otherwise keep them walking round it for ever, and
the robot waits for the person to leave)."""

from __future__ import annotations

import math

from robosc.sim.world import Person, Pose

GIVE_WAY = 0.3  # metres between the person's edge and a robot's edge the person keeps
# seconds a person waits for a robot in their way before they walk round it (the robots keep out
# of the person's way, so a robot standing in it waits for the person: without this, both waited
# for ever, a robot between the person and their way out of the aisle)
WAIT_AT_MOST = 5.0
PAST = 1.0  # metres beyond a robot's reach at which a person walking round it is past it
REACHED = 0.05  # metres from a point of the walk that count as there


class Walker:
    """Where the person goes next: ``velocity(now, x, y, robots)`` for each step."""

    def __init__(self, person: Person, robot_radius: float) -> None:
        self.person = person
        self.reach = person.radius + robot_radius + GIVE_WAY
        self.next = 1  # the point walked to
        self.standing_until = person.start + person.walk[0][2]
        self.blocked_since: float | None = None  # when a robot came in the way (None: the way is free)

    @property
    def done(self) -> bool:
        return self.next >= len(self.person.walk)

    def velocity(self, now: float, dt: float, x: float, y: float, robots: list[Pose]) -> tuple[float, float]:
        """The person's velocity (vx, vy) for the step from ``now``."""
        if self.done or now + 1e-9 < self.standing_until:
            return 0.0, 0.0
        tx, ty, stand = self.person.walk[self.next]
        distance = math.hypot(tx - x, ty - y)
        taken = any(math.hypot(tx - p.x, ty - p.y) < self.reach for p in robots)
        if distance < REACHED or (taken and self.blocked_since is not None and now - self.blocked_since >= WAIT_AT_MOST):
            self.next += 1  # there, or as near as a robot standing on the point lets them come
            self.standing_until = now + stand
            self.blocked_since = None
            return 0.0, 0.0
        speed = min(self.person.speed, distance / dt)
        heading = math.atan2(ty - y, tx - x)
        if self.free(x, y, heading, speed, dt, robots):
            if all(math.hypot(x - p.x, y - p.y) >= self.reach + PAST for p in robots):
                self.blocked_since = None  # well past the robot: the next one is waited for again
            return speed * math.cos(heading), speed * math.sin(heading)
        if self.blocked_since is None:
            self.blocked_since = now
        if now - self.blocked_since < WAIT_AT_MOST:
            return 0.0, 0.0
        for turn in (45, -45, 90, -90, 135, -135):  # round the robot, nearest the way first
            aside = heading + math.radians(turn)
            if self.free(x, y, aside, speed, dt, robots):
                return speed * math.cos(aside), speed * math.sin(aside)
        return 0.0, 0.0

    def free(self, x: float, y: float, heading: float, speed: float, dt: float, robots: list[Pose]) -> bool:
        """Whether a step from (x, y) toward ``heading`` keeps out of every robot's reach (or at
        least comes no closer to the robots within it)."""
        nx, ny = x + speed * math.cos(heading) * dt, y + speed * math.sin(heading) * dt
        for pose in robots:
            closer = math.hypot(nx - pose.x, ny - pose.y) < math.hypot(x - pose.x, y - pose.y)
            if closer and math.hypot(nx - pose.x, ny - pose.y) < self.reach:
                return False
        return True
