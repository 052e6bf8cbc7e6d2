"""The robots' bodies and sensors, simulated by IR-SIM (``ir-sim`` on PyPI): differential
drive, a 2D LiDAR cast against the walls and boxes, and collision detection.

In a ``shared`` world all robots live in one IR-SIM environment: each LiDAR sees the other
robots and robots touch each other. Otherwise each robot runs in an environment of its own
built from the same world (N copies of one robot sent through one maze from one start), so
robots share the map but neither see nor touch each other. This module only turns a world
into IR-SIM's configuration and reads it back in the conventions of ROS: a LaserScan whose
``ranges[0]`` looks straight ahead and which goes round counter-clockwise (a TurtleBot's LDS),
distances in metres.
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path
from typing import Any

from robosc.sim.world import Line, Person, Pose, World


def irsim_config(world: World, start: Pose | list[Pose], person: Person | None = None) -> dict[str, Any]:
    """IR-SIM's world configuration for the robots of ``world`` starting at ``start`` (one
    pose, or one per robot, all in one environment); with a ``person``, a body the robots'
    LiDARs see and touch follows them (IR-SIM's omnidirectional robot, moved by the walk)."""
    starts = start if isinstance(start, list) else [start]
    lidar = world.robot.lidar
    turn = max(world.robot.max_angular, world.robot.turn_speed)
    obstacles: list[dict[str, Any]] = [
        {"shape": {"name": "linestring", "vertices": [list(p) for p in wall]}, "state": [0, 0, 0]}
        for wall in world.walls
    ]
    obstacles += [
        {"shape": {"name": "rectangle", "length": w, "width": h}, "state": [x, y, 0]} for x, y, w, h in world.boxes
    ]
    config: dict[str, Any] = {
        "world": {
            "width": world.size[0],
            "height": world.size[1],
            "step_time": world.step,
            "sample_time": world.step,
            "collision_mode": "stop",
        },
        "robot": [
            {
                "kinematics": {"name": "diff"},
                "shape": {"name": "circle", "radius": world.robot.radius},
                "state": [pose.x, pose.y, pose.heading],
                "vel_max": [world.robot.max_linear, turn],
                "vel_min": [-world.robot.max_linear, -turn],
                "sensors": [
                    {
                        "type": "lidar2d",
                        "range_min": lidar.range_min,
                        "range_max": lidar.range_max,
                        # -pi .. pi, both ends included: beams + 1 rays one increment apart
                        "angle_range": 2 * math.pi,
                        "number": lidar.beams + 1,
                    }
                ],
            }
            for pose in starts
        ],
    }
    if person is not None:
        x, y, _ = person.walk[0]
        config["robot"].append({
            "kinematics": {"name": "omni"},
            "shape": {"name": "circle", "radius": person.radius},
            "state": [x, y, 0],
            "vel_max": [person.speed, person.speed],
            "vel_min": [-person.speed, -person.speed],
        })
    if obstacles:
        config["obstacle"] = obstacles
    return config


def _import_irsim() -> Any:
    """IR-SIM, imported quietly: on import it tries matplotlib's window backends one by one
    and prints each failure (there is no window here: the simulation runs headless)."""
    import contextlib
    import io

    with contextlib.redirect_stdout(io.StringIO()):
        import irsim
    return irsim


class Bodies:
    """Robots in one IR-SIM environment (each LiDAR sees the others, they touch each other):
    ``bodies``, stepped together."""

    def __init__(self, world: World, starts: list[Pose], person: Person | None = None) -> None:
        import yaml

        irsim = _import_irsim()

        with tempfile.TemporaryDirectory(prefix="robosc-sim-") as folder:
            path = Path(folder) / "world.yaml"
            path.write_text(yaml.safe_dump(irsim_config(world, list(starts), person)), encoding="utf-8")
            self.env = irsim.make(str(path), display=False, headless=True, log_level="ERROR")
        robots = self.env.robot_list
        self.bodies = [Body(world, self.env, robot) for robot in robots[: len(starts)]]
        self.person = robots[len(starts)] if person is not None else None  # IR-SIM's body of the person

    def person_at(self) -> tuple[float, float]:
        assert self.person is not None
        x, y = (float(v) for v in self.person.state[:2, 0])
        return x, y

    def step(self, velocities: list[tuple[float, float]], person: tuple[float, float] = (0.0, 0.0)) -> None:
        """One step of every robot, each driven with its (linear, angular) velocity, and of the
        person (their velocity, x and y)."""
        actions = [[linear, angular] for linear, angular in velocities]
        if self.person is not None:
            actions.append(list(person))
        self.env.step(actions, action_id=0)


class Body:
    """One simulated robot: its pose, the velocity it is driven with, its LiDAR."""

    def __init__(self, world: World, env: Any, robot: Any) -> None:
        self.world = world
        self.env = env
        self.robot = robot
        beams = world.robot.lidar.beams
        # IR-SIM's ray k looks at -pi + k increments: ROS's beam j (j increments from ahead) is its ray j + beams / 2
        self._order = [round((2 * math.pi * j / beams + math.pi) / (2 * math.pi / beams)) % beams for j in range(beams)]
        from shapely import MultiLineString, Point, unary_union
        from shapely.geometry import box

        self._point = Point
        parts = [MultiLineString([list(w) for w in world.walls])] if world.walls else []
        parts += [box(x - w / 2, y - h / 2, x + w / 2, y + h / 2) for x, y, w, h in world.boxes]
        self._obstacles = unary_union(parts) if parts else None
        self._track = None
        if world.line is not None:
            from shapely import LineString

            self._track = LineString(world.line.points)

    @property
    def pose(self) -> Pose:
        x, y, heading = (float(v) for v in self.robot.state[:3, 0])
        return Pose(x, y, heading)

    @property
    def collided(self) -> bool:
        return bool(self.robot.collision) or self.clearance() <= 0.0

    def clearance(self) -> float:
        """Distance from the robot's edge to the nearest wall or box (negative: overlapping)."""
        if self._obstacles is None:
            return math.inf
        pose = self.pose
        return float(self._obstacles.distance(self._point(pose.x, pose.y))) - self.world.robot.radius

    def scan(self) -> list[float]:
        """The LiDAR's ranges, ``ranges[0]`` ahead, counter-clockwise; no return reads ``inf``
        (REP 117)."""
        import numpy

        data = self.robot.get_lidar_scan()
        order = self._order
        ranges = numpy.asarray(data["ranges"], dtype=float)[order]
        valid = data.get("valid")
        if valid is not None:
            ranges = numpy.where(numpy.asarray(valid, dtype=bool)[order], ranges, math.inf)
        return [float(v) for v in ranges.tolist()]

    def line_reading(self) -> float | None:
        """The line detector: the correction (``gain`` per metre the line lies to the right of
        the point ``look_ahead`` in front of the robot), or None when the line is not seen."""
        line = self.world.line
        if line is None or self._track is None:
            return None
        pose = self.pose
        px = pose.x + line.look_ahead * math.cos(pose.heading)
        py = pose.y + line.look_ahead * math.sin(pose.heading)
        return _line_offset(self._track, line, px, py, self._point)


def _line_offset(track: Any, line: Line, px: float, py: float, point: Any) -> float | None:
    p = point(px, py)
    if track.distance(p) > line.width:
        return None
    s = track.project(p)
    here = track.interpolate(s)
    ahead = track.interpolate(min(s + 0.01, track.length))
    behind = track.interpolate(max(s - 0.01, 0.0))
    tx, ty = ahead.x - behind.x, ahead.y - behind.y
    norm = math.hypot(tx, ty) or 1.0
    # positive when the point lies left of the track: the line is then on the robot's right
    offset = (tx * (py - here.y) - ty * (px - here.x)) / norm
    return float(line.gain * offset)
