"""The lane and the crossing of examples/scenarios at any fleet size, for benchmarks/throughput.py:
a world file and a model written from each robot's route, as benchmarks/scenarios.py writes the
two-robot and four-robot ones.

* **lane(n)**: a corridor one robot wide (cells l1, l2, l3) between two gates (gw, ge: cells
  for one robot at each end), n robots homed on each side on an arc round their gate. A task:
  through the gate and the corridor to the far gate, turn there (``at_5``), and back home.
* **crossing(n)**: two streets one robot wide that cross (cells w, x, e and n, x, s) with a
  gate at each of the four ends and n robots homed round each gate; a robot crosses to the
  far gate and comes back.

A robot starts a leg only into a cell no other robot holds (is in, on its way into or out of,
or stopped on the way); its home has room for it alone, and its way home from the gate (a ray
of the arc) crosses no other's. The walls are the lane's sides; the crossing's robots keep to
their streets by their legs.
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path
from typing import Any

CELL = 2.0  # metres: each cell's length
WIDTH = 1.2  # metres: a lane's width
ARC = 2.6  # metres from a gate's point to the homes round it
CHUNK = 60  # states named in one requirement at most (robosc check refuses 100 operands in a row)


def state_name(k: int, positions: int) -> str:
    """The state of a robot at position ``k`` of a route of ``positions`` (0: home)."""
    return "home" if k % positions == 0 else f"at_{k}"


def move_name(k: int, positions: int) -> str:
    """The state of a robot on its way into position ``k``."""
    return "to_home" if k % positions == 0 else f"to_{k}"


def holding(route: tuple[str | None, ...], cell: str) -> list[str]:
    """The states in which a robot on ``route`` (the cells of positions 1 .. P - 1) holds
    ``cell``: on its way into it, stopped on that way, in it, and on its way out of it."""
    positions = len(route) + 1
    states: list[str] = []
    for k in range(1, positions):
        if route[k - 1] == cell:
            out = k + 1
            for state in (move_name(k, positions), f"stopped_{k}", state_name(k, positions), move_name(out, positions), f"stopped_{out}"):
                if state not in states:
                    states.append(state)
    return states


def model(name: str, routes: list[tuple[str | None, ...]]) -> str:
    """The fleet's model: each ``go`` drives the next leg, the robot answers ``arrived`` (or
    ``stopped``), and a robot starts a leg only into a cell no other robot holds."""
    positions = len(routes[0]) + 1
    lines = [f"// {name}: {len(routes)} robots, written by benchmarks/fleet_worlds.py from their routes",
             f"robot {name.capitalize()} {{", f"    component bot[{len(routes)}] {{",
             "        incoming message go with type: none",
             "        outgoing message arrived with type: none",
             "        outgoing message stopped with type: none",
             "        behaviour {"]
    for k in range(positions):
        nxt = k + 1
        initial = "initial marked " if k == 0 else ""
        lines.append(f"            {initial}state {state_name(k, positions)} {{ on request to go goto {move_name(nxt, positions)} }}")
        lines.append(f"            state {move_name(nxt, positions)} {{")
        lines.append(f"                on response from arrived goto {state_name(nxt, positions)}")
        lines.append(f"                on response from stopped goto stopped_{nxt}")
        lines.append("            }")
        lines.append(f"            state stopped_{nxt} {{ on request to go goto {move_name(nxt, positions)} }}")
    lines += ["        }", "    }"]
    for i, route in enumerate(routes, 1):
        for k in range(positions):
            cell = route[k] if k < positions - 1 else None
            if cell is None:
                continue
            others = [f"bot{j}.{s}" for j, other in enumerate(routes, 1) if j != i for s in holding(other, cell)]
            for start in range(0, len(others), CHUNK):  # (a long condition split over requirements)
                part = " or ".join(others[start : start + CHUNK])
                lines.append(f"    requirement bot{i}.go needs bot{i}.{state_name(k, positions)} => !({part})")
    lines.append("}")
    return "\n".join(lines) + "\n"


def _fan(gate: tuple[float, float], facing: float, count: int) -> list[tuple[float, float, float]]:
    """``count`` homes on an arc round ``gate``, away from ``facing`` (the direction, in degrees,
    from the gate into its street), each facing the gate."""
    spread = min(150.0, 32.0 * (count - 1))
    homes = []
    for k in range(count):
        angle = facing + 180.0 + (spread * (k / (count - 1) - 0.5) if count > 1 else 0.0)
        x = gate[0] + ARC * math.cos(math.radians(angle))
        y = gate[1] + ARC * math.sin(math.radians(angle))
        homes.append((round(x, 3), round(y, 3), round((angle + 180.0) % 360.0, 1)))
    return homes


def _box(x0: float, y0: float, x1: float, y1: float) -> list[list[float]]:
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


def _yaml(name: str, size: tuple[float, float], homes: list[tuple[float, float, float]], walls: list[Any],
          points: dict[str, tuple[float, float]], legs: list[list[str]], cells: dict[str, list[list[float]]],
          stops: list[str]) -> str:
    def point(p: tuple[float, float]) -> str:
        return f"[{p[0]:g}, {p[1]:g}]"

    lines = [f"world: {name}", f"size: [{size[0]:g}, {size[1]:g}]", "step: 0.1", "shared: true",
             "robot: {radius: 0.2, max_linear: 0.5, max_angular: 2.0, command_timeout: 0.5,",
             "        lidar: {beams: 120, range_min: 0.12, range_max: 3.5, rate: 10}}",
             "starts:"]
    lines += [f"  - [{x:g}, {y:g}, {heading:g}]" for x, y, heading in homes]
    lines += [f"goal: {{x: [0, {size[0]:g}], y: [0, {size[1]:g}]}}", "walls:"]
    lines += ["  - [" + ", ".join(point(p) for p in wall) + "]" for wall in walls]
    lines += ["fleet:", "  waypoints:"]
    lines += [f"    {n}: {point(p)}" for n, p in points.items()]
    lines += ["  tasks:"]
    lines += ["    - [" + ", ".join("[" + ", ".join(leg) + "]" for leg in robot) + "]" for robot in legs]
    lines += ["  cells:"]
    lines += [f"    {n}: [" + ", ".join(point((c[0], c[1])) for c in corners) + "]" for n, corners in cells.items()]
    lines += [f"  stops: [{', '.join(stops)}]"]
    return "\n".join(lines) + "\n"


def lane(per_side: int) -> tuple[str, str]:
    """(world file text, model text) of the lane with ``per_side`` robots homed at each end."""
    margin = ARC + 1.0
    west = (margin, margin + 1.5)
    x0 = west[0] + 1.0  # the corridor's west end
    cells_x = [x0 + CELL * k for k in range(4)]
    east = (cells_x[-1] + 1.0, west[1])
    size = (east[0] + margin, west[1] + margin + 1.5)
    y = west[1]
    points = {"gw": west, "ge": east}
    cells = {"gw": _box(west[0] - 1.0, y - 1.0, x0, y + 1.0), "ge": _box(cells_x[-1], y - 1.0, east[0] + 1.0, y + 1.0)}
    for k, name in enumerate(("l1", "l2", "l3")):
        points[name] = ((cells_x[k] + cells_x[k + 1]) / 2, y)
        cells[name] = _box(cells_x[k], y - WIDTH / 2, cells_x[k + 1], y + WIDTH / 2)
    homes_w, homes_e = _fan(west, 0.0, per_side), _fan(east, 180.0, per_side)
    homes, legs, routes = [], [], []
    for k in range(per_side):  # alternately from the west and the east, so that any two robots meet
        homes += [homes_w[k], homes_e[k]]
        legs += [[["gw"], ["l1"], ["l2"], ["l3"], ["ge"], ["l3"], ["l2"], ["l1"], ["gw"], ["home"]],
                 [["ge"], ["l3"], ["l2"], ["l1"], ["gw"], ["l1"], ["l2"], ["l3"], ["ge"], ["home"]]]
        routes += [("gw", "l1", "l2", "l3", "ge", "l3", "l2", "l1", "gw"), ("ge", "l3", "l2", "l1", "gw", "l1", "l2", "l3", "ge")]
    half = WIDTH / 2
    walls = [[(0, 0), (size[0], 0), (size[0], size[1]), (0, size[1]), (0, 0)],
             [(x0, y - half), (cells_x[-1], y - half)], [(x0, y + half), (cells_x[-1], y + half)]]
    return (_yaml(f"lane{2 * per_side}", size, homes, walls, points, [[list(leg) for leg in r] for r in legs], cells,
                  ["at_5", "home"]), model("lane", routes))


def crossing(per_end: int) -> tuple[str, str]:
    """(world file text, model text) of the crossing with ``per_end`` robots homed at each of
    its four gates."""
    margin = ARC + 1.0
    centre = margin + 1.0 + 1.5 * CELL
    c = (centre, centre)
    half = CELL / 2
    size = (2 * centre, 2 * centre)
    gate = CELL * 1.5 + 1.0  # from the centre to a gate's point
    points = {"x": c, "w": (centre - CELL, centre), "e": (centre + CELL, centre),
              "s": (centre, centre - CELL), "n": (centre, centre + CELL),
              "gw": (centre - gate, centre), "ge": (centre + gate, centre),
              "gs": (centre, centre - gate), "gn": (centre, centre + gate)}
    cells = {"x": _box(centre - half, centre - half, centre + half, centre + half)}
    for name, (dx, dy) in {"w": (-1, 0), "e": (1, 0), "s": (0, -1), "n": (0, 1)}.items():
        px, py = centre + dx * CELL, centre + dy * CELL
        cells[name] = _box(px - half, py - half, px + half, py + half)
        gx, gy = centre + dx * gate, centre + dy * gate
        cells["g" + name] = _box(gx - 1.0, gy - 1.0, gx + 1.0, gy + 1.0)
    streets = {  # from: (its gate, the facing into the street, the cells out, the far gate)
        "w": ("gw", 0.0, ("w", "x", "e"), "ge"), "e": ("ge", 180.0, ("e", "x", "w"), "gw"),
        "s": ("gs", 90.0, ("s", "x", "n"), "gn"), "n": ("gn", 270.0, ("n", "x", "s"), "gs"),
    }
    fans = {end: _fan(points[g], facing, per_end) for end, (g, facing, _, _) in streets.items()}
    homes, legs, routes = [], [], []
    for k in range(per_end):
        for end, (g, _, out, far) in streets.items():
            homes.append(fans[end][k])
            route = (g, *out, far, *reversed(out), g)
            routes.append(route)
            legs.append([[cell] for cell in route] + [["home"]])
    walls = [[(0, 0), (size[0], 0), (size[0], size[1]), (0, size[1]), (0, 0)]]
    return (_yaml(f"crossing{4 * per_end}", size, homes, walls, points, legs, cells, ["at_5", "home"]),
            model("crossing", routes))


def load(text: str) -> Any:
    """A world from its file's text."""
    from robosc.sim.world import load_world

    with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as f:
        f.write(text)
    try:
        return load_world(f.name)
    finally:
        Path(f.name).unlink()


def synthesized(text: str) -> Any:
    from robosc.api import check_text, synthesize_model

    checked = check_text(text)
    assert checked.model is not None, checked.diagnostics
    return synthesize_model(checked.model)
