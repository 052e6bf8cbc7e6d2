"""A person walking a scripted path among the robots (a world's ``fleet.person``): the walk's
points in turn at the person's speed, standing at a point for its seconds. A person gives way:
one whose next step would bring them within GIVE_WAY metres of a robot's edge waits where they
are (people step aside for a robot that is already there; the robots keep out of the person's
way as their model says)."""

from __future__ import annotations

import math

from robosc.sim.world import Person, Pose

GIVE_WAY = 0.3  # metres between the person's edge and a robot's edge the person keeps
REACHED = 0.05  # metres from a point of the walk that count as there


class Walker:
    """Where the person goes next: ``velocity(now, x, y, robots)`` for each step."""

    def __init__(self, person: Person, robot_radius: float) -> None:
        self.person = person
        self.reach = person.radius + robot_radius + GIVE_WAY
        self.next = 1  # the point walked to
        self.standing_until = person.start + person.walk[0][2]

    @property
    def done(self) -> bool:
        return self.next >= len(self.person.walk)

    def velocity(self, now: float, dt: float, x: float, y: float, robots: list[Pose]) -> tuple[float, float]:
        """The person's velocity (vx, vy) for the step from ``now``."""
        if self.done or now + 1e-9 < self.standing_until:
            return 0.0, 0.0
        tx, ty, stand = self.person.walk[self.next]
        distance = math.hypot(tx - x, ty - y)
        if distance < REACHED:
            self.next += 1
            self.standing_until = now + stand
            return 0.0, 0.0
        speed = min(self.person.speed, distance / dt)
        vx, vy = speed * (tx - x) / distance, speed * (ty - y) / distance
        nx, ny = x + vx * dt, y + vy * dt
        for pose in robots:
            closer = math.hypot(nx - pose.x, ny - pose.y) < math.hypot(x - pose.x, y - pose.y)
            if closer and math.hypot(nx - pose.x, ny - pose.y) < self.reach:
                return 0.0, 0.0
        return vx, vy
