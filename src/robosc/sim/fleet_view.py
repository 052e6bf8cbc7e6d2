"""The fleet's live view fed by a simulation: the world's map for the page
(:func:`fleet_map`), and a feed that hands the page a frame of the world (where each robot and
the person are, the cells they hold) every few simulated tenths of a second, with the
coordinator's latest state, and each of the coordinator's events as it comes: from the
coordinator in this process, or read from the event log the coordinator package writes on ROS
(:class:`EventTail`)."""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

from robosc.sim.fleet import FleetWorld
from robosc.sim.world import World

FRAME_SECONDS = 0.2  # simulated seconds between two frames


def fleet_map(world: World, robots: int) -> dict[str, Any]:
    """What the page draws of a fleet's world: its size, walls and boxes, the cells (polygons),
    the waypoints, the door (its two ends), the charger, the robots' homes and the radii."""
    fleet = world.fleet
    assert fleet is not None
    person = fleet.person
    return {
        "size": list(world.size),
        "walls": [[list(p) for p in wall] for wall in world.walls],
        "boxes": [list(b) for b in world.boxes],
        "cells": {name: [list(p) for p in polygon] for name, polygon in fleet.cells},
        "waypoints": {name: list(p) for name, p in fleet.waypoints},
        "door": [list(fleet.door.a), list(fleet.door.b)] if fleet.door is not None else None,
        "charger": list(fleet.charger.at) if fleet.charger is not None else None,
        "homes": [[world.start(i).x, world.start(i).y] for i in range(robots)],
        "robot_radius": world.robot.radius,
        "person_radius": person.radius if person is not None else None,
    }


class FleetFeed:
    """Feeds ``publish`` (a LiveView's): the coordinator's events (:meth:`event`) and, at most
    every FRAME_SECONDS simulated, a frame of the world with the latest state (:meth:`step`)."""

    def __init__(self, publish: Callable[[dict[str, Any]], None], every: float = FRAME_SECONDS) -> None:
        self.publish = publish
        self.every = every
        self.state: dict[str, Any] | None = None  # the coordinator's latest state
        self.next = 0.0

    def event(self, record: dict[str, Any]) -> None:
        if isinstance(record.get("state"), dict):
            self.state = record["state"]
        self.publish(record)

    def step(self, world: FleetWorld) -> None:
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
