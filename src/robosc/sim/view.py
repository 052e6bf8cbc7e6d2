"""The live view of a world (one robot's or a fleet's) fed by a simulation or by pose topics: the
world's map for the page (:func:`world_map`); a feed that hands the page a frame of the world
(where each robot and the person are, the cells they hold) every few simulated tenths of a
second, with the latest state, and each event as it comes: from the controllers in this
process, or read from the event logs the generated packages write on ROS (:class:`EventTail`);
and, for ``robosc view --world``, frames made from the poses the robots publish
(:class:`PoseFeed`)."""

from __future__ import annotations

import json
import math
import os
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from robosc.debug.world_view import robots_on, with_map
from robosc.sim.fleet_ros import pose_topics
from robosc.sim.world import World

FRAME_SECONDS = 0.2  # simulated seconds between two frames


def world_map(world: World) -> dict[str, Any]:
    """What the page draws of a world: its size, walls and boxes and the robots' radius; of a
    fleet's world the cells (polygons), the waypoints, the door (its two ends), the charger and
    the person's radius; of a world with a goal the goal (two corners) and the line, if any."""
    fleet = world.fleet
    drawn: dict[str, Any] = {
        "size": list(world.size),
        "walls": [[list(p) for p in wall] for wall in world.walls],
        "boxes": [list(b) for b in world.boxes],
        "cells": {},
        "waypoints": {},
        "door": None,
        "charger": None,
        "robot_radius": world.robot.radius,
        "person_radius": None,
    }
    if fleet is None:
        (x0, x1), (y0, y1) = world.goal.x, world.goal.y
        drawn["goal"] = [[x0, y0], [x1, y1]]
        drawn["line"] = [list(p) for p in world.line.points] if world.line is not None else None
        return drawn
    drawn["cells"] = {name: [list(p) for p in polygon] for name, polygon in fleet.cells}
    drawn["waypoints"] = {name: list(p) for name, p in fleet.waypoints}
    drawn["door"] = [list(fleet.door.a), list(fleet.door.b)] if fleet.door is not None else None
    drawn["charger"] = list(fleet.charger.at) if fleet.charger is not None else None
    drawn["person_radius"] = fleet.person.radius if fleet.person is not None else None
    return drawn


class WorldFeed:
    """Feeds ``publish`` (a LiveView's): the events (:meth:`event`) and, at most every
    FRAME_SECONDS simulated, a frame of the world with the latest state (:meth:`step`: ``world``
    has ``sim`` and ``frame()``, as robosc.sim.fleet.FleetWorld and robosc.sim.local.LocalRun do)."""

    def __init__(self, publish: Callable[[dict[str, Any]], None], every: float = FRAME_SECONDS) -> None:
        self.publish = publish
        self.every = every
        self.state: dict[str, Any] | None = None  # the coordinator's latest state
        self.next = 0.0

    def event(self, record: dict[str, Any]) -> None:
        if isinstance(record.get("state"), dict):
            self.state = record["state"]
        self.publish(record)

    def step(self, world: Any) -> None:
        now = world.sim.time
        if now + 1e-9 < self.next:
            return
        self.next = now + self.every
        self.publish({"time": round(now, 3), "frame": world.frame(), "state": self.state})


class EventTail:
    """The records a JSON Lines event log has gained since the last :meth:`read` (whole lines
    only; one that does not parse is skipped; a log that was rotated is read from its start)."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.offset = 0
        self.rest = b""

    def read(self) -> list[dict[str, Any]]:
        try:
            with open(self.path, "rb") as handle:
                if os.fstat(handle.fileno()).st_size < self.offset:  # rotated: a new file
                    self.offset, self.rest = 0, b""
                handle.seek(self.offset)
                chunk = handle.read()
        except OSError:
            return []
        self.offset += len(chunk)
        lines = (self.rest + chunk).split(b"\n")
        self.rest = lines.pop()
        found = []
        for raw in lines:
            try:
                record = json.loads(raw)
            except ValueError:
                continue
            if isinstance(record, dict):
                found.append(record)
        return found


PUBLISH_SECONDS = 0.1  # real seconds between two frames made from poses


class PoseFeed:
    """``robosc view --world``: a fleet coordinator's page with the world's map, and frames
    made from the poses the world publishes beside the coordinator (robosc.sim.fleet_ros's
    pose_topics: ``bot1/pose``, ``bot1/destination``, ``person/pose``, geometry_msgs/Pose2D).
    A robot is in a frame only when its pose came since the last one: one whose pose stops
    coming is marked stale on the page. Thread-safe (poses and events come on another thread)."""

    def __init__(self, world: World) -> None:
        if world.fleet is None:
            raise ValueError(f"{world.path} is not a fleet's world (it has no 'fleet')")
        self.world = world
        self.fleet = world.fleet
        self.names: list[str] = []
        self.publish: Callable[[dict[str, Any]], None] | None = None
        self.lock = threading.Lock()
        self.fresh: dict[str, dict[str, Any]] = {}  # robot -> its data, come since the last frame
        self.into: dict[str, str] = {}  # robot -> the cell its move ends in ("": none)
        self.person: list[float] | None = None
        self.state: dict[str, Any] | None = None
        self.time: float | None = None  # the coordinator's latest event's time
        self.sent = 0.0

    def page(self, html: str) -> str:
        self.names = robots_on(html)
        return with_map(html, world_map(self.world))

    def topics(self) -> list[list[str]]:
        return pose_topics(self.names, person=True, namespace="")  # the world side's, relative

    def attach(self, publish: Callable[[dict[str, Any]], None]) -> None:
        self.publish = publish

    def event(self, record: dict[str, Any]) -> None:
        with self.lock:
            if isinstance(record.get("state"), dict):
                self.state = record["state"]
            if isinstance(record.get("time"), (int, float)):
                self.time = float(record["time"])

    def pose(self, name: str, pose: list[float]) -> None:
        try:
            x, y, theta = (float(v) for v in pose)
        except (TypeError, ValueError):
            return
        robot, _, what = name.rpartition(".")
        seen = math.isfinite(x) and math.isfinite(y)
        with self.lock:
            if robot == "person" and what == "pose":
                self.person = [round(x, 3), round(y, 3)] if seen else None
            elif robot in self.names and what == "destination":
                self.into[robot] = self.fleet.cell(x, y) if seen else ""
            elif robot in self.names and what == "pose" and seen and math.isfinite(theta):
                self.fresh[robot] = {
                    "x": round(x, 3), "y": round(y, 3), "heading": round(theta, 3), "doing": None,
                    "cell": self.fleet.cell(x, y), "into": "", "tasks": None, "collided": False,
                }
            else:
                return
            if time.monotonic() - self.sent < PUBLISH_SECONDS or self.publish is None:
                return
            self.sent = time.monotonic()
            robots = {r: {**data, "into": self.into.get(r, "")} for r, data in self.fresh.items()}
            self.fresh = {}
            frame = {"t": self.time, "robots": robots, "person": self.person, "door": None}
            record = {"time": self.time, "frame": frame, "state": self.state}
        self.publish(record)
