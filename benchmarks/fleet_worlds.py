"""Streets one robot wide at any fleet size, for benchmarks/throughput.py: a world file and a
model written from each robot's route.

* **lane(n)**: a corridor one robot wide (cells l1, l2, l3) between two gates (gw, ge: a cell
  for one robot in front of each end), n robots homed on each side on an arc round their gate.
* **crossing(n)**: two such streets that cross (cells w, x, e and s, x, n), a gate at each of
  the four ends and n robots homed round each gate.

A task: through the near gate and the street, cell by cell, to the far gate's point, on to the
robot's own turning place beyond it (``at_6``), back the same way and home. Round each gate,
the homes of its robots and the turning places of the robots from the far end take turns, each
on a ray of its own from the gate, at least SLOT apart and clear of the gate's cell; a robot's
way between the gate and its place is along that ray, crossing no other's.

Each leg ends at rest just inside the far end of the cell it drives into (END before the next
cell), so that a robot waits for the next cell with its body clear of it. A robot starts a leg
only into a cell no other robot holds, and holds the cells it starts in until its driver says
``left`` (its body is out of them: robosc.sim.fleet), so that the next robot going the same way
follows one cell behind. The walls are the lane's sides; the crossing's robots keep to their
streets by their legs.

``move_name`` and ``holding`` are the states of the two- and four-robot scenarios' routes
(benchmarks/scenarios.py), where a robot holds a cell until it arrives in the next;
``state_name`` (a robot at rest at a position) serves both.
"""

from __future__ import annotations

import functools
import math
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

CELL = 2.0  # metres: each cell's length
WIDTH = 1.2  # metres: a lane's width
GATE = 0.45  # metres from a street's end to its gate's point (the gate's cell: twice that deep)
ACROSS = 0.8  # metres from a gate's point to its cell's sides (the cell: twice that wide)
END = 0.3  # metres: a robot stops this far before a cell's end (its body in the cell, clear of the next)
BEYOND = 0.5  # metres: a robot comes to its place round a gate from this far beyond it, to stand facing the gate
LANE_ARC = 210.0  # degrees the lane's arcs span at most (round beside the lane's walls; the crossing's: 180)
SLOT = 0.55  # metres at least between neighbouring places round a gate (robots 0.4 m wide pass between them)


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


@dataclass(frozen=True)
class Leg:
    """One leg of a robot's route, as the model sees it: the cells its body is in when it starts
    (other than the one it ends in), the cell it ends in (None: a place of the robot's own), and
    whether its driver says ``left`` on the way (its body leaves every cell but the end's)."""

    start: tuple[str, ...]
    end: str | None
    points: tuple[str, ...]  # the world's waypoints it drives through

    @property
    def leaves(self) -> bool:
        return bool(self.start)


@dataclass(frozen=True)
class Street:
    """A street one robot wide: ``cells`` in a row from gate ``gates[0]`` to gate ``gates[1]``,
    the first starting at ``start`` and the row going ``along`` (a unit vector)."""

    cells: tuple[str, ...]
    gates: tuple[str, str]
    start: tuple[float, float]
    along: tuple[float, float]
    kinds: tuple[str, str]  # the robots homed at each end

    def at(self, distance: float) -> tuple[float, float]:
        """The point ``distance`` metres along the street from its start (negative: before it)."""
        return (round(self.start[0] + distance * self.along[0], 3), round(self.start[1] + distance * self.along[1], 3))

    def points(self) -> dict[str, tuple[float, float]]:
        """Its waypoints: each gate's point (GATE beyond the street's end) and its mouth (just in
        front of the first cell), and each cell's two ends (``l2_ge``: the end of l2 toward ge)."""
        length = CELL * len(self.cells)
        a, b = self.gates
        points = {a: self.at(-GATE), b: self.at(length + GATE), f"{a}_in": self.at(-END), f"{b}_in": self.at(length + END)}
        for k, cell in enumerate(self.cells):
            points[f"{cell}_{b}"] = self.at(CELL * (k + 1) - END)
            points[f"{cell}_{a}"] = self.at(CELL * k + END)
        return points

    def route(self, side: int, turn: str, robot: int = 1) -> list[Leg]:
        """The legs of a robot homed at gate ``gates[side]``: to the mouth, cell by cell through
        the street (each leg ends at the far end of the next cell), to the far gate's point, to
        ``turn`` (its own place beyond the far gate), back the same way, home. It comes to its
        place and its home from beyond them (``t3_out``, ``h3_out`` for robot 3), so that it
        stands there facing the gate it leaves by next."""
        near, far = self.gates if side == 0 else self.gates[::-1]
        cells = self.cells if side == 0 else self.cells[::-1]
        legs = [Leg((), near, (f"{near}_in",))]
        before = near
        for cell in cells:
            legs.append(Leg((before,), cell, (f"{cell}_{far}",)))
            before = cell
        legs += [Leg((before,), far, (far,)), Leg((far,), None, (f"{turn}_out", turn)), Leg((), far, (f"{far}_in",))]
        before = far
        for cell in reversed(cells):
            legs.append(Leg((before,), cell, (f"{cell}_{near}",)))
            before = cell
        return [*legs, Leg((before,), near, (near,)), Leg((near,), None, (f"h{robot}_out", "home"))]


def _states(k: int, leg: Leg, positions: int) -> dict[str, list[str]]:
    """The states of a robot during leg ``k`` (1 ..) and at its end: ``to`` (the cells held: the
    start's and the end's), ``past`` (after ``left``: the end's alone) and ``at``."""
    past = [f"past_{k}", f"stopped_past_{k}"] if leg.leaves else []
    return {"to": [f"to_{k}", f"stopped_{k}"], "past": past, "at": [state_name(k, positions)]}


def street_model(name: str, kinds: dict[str, tuple[list[Leg], int]]) -> str:
    """The fleet's model: a component array per kind of robot (its route and how many), each
    ``go`` driving the next leg; the robot answers ``left`` once its body is out of the cells it
    started the leg in, ``arrived`` at the leg's end (or ``stopped``). A robot starts a leg only
    into a cell no other robot holds (is in, or is on its way into or out of), written once per
    kind with ``any`` over each kind (so that synthesis counts the robots of a kind)."""
    lines = [f"// {name}: {sum(n for _, n in kinds.values())} robots, written by benchmarks/fleet_worlds.py from their routes",
             f"robot {name.capitalize()} {{"]
    for kind, (legs, count) in kinds.items():
        positions = len(legs)
        lines += [f"    component {kind}[{count}] {{",
                  "        incoming message go with type: none",
                  "        outgoing message arrived with type: none",
                  "        outgoing message stopped with type: none",
                  "        outgoing message left with type: none",
                  "        behaviour {"]
        for k, leg in enumerate(legs, 1):
            states = _states(k, leg, positions)
            initial = "initial marked " if k == 1 else ""
            lines.append(f"            {initial}state {state_name(k - 1, positions)} {{ on request to go goto to_{k} }}")
            lines.append(f"            state to_{k} {{")
            lines.append(f"                on response from arrived goto {states['at'][0]}")
            lines.append(f"                on response from stopped goto stopped_{k}")
            if leg.leaves:
                lines.append(f"                on response from left goto past_{k}")
            lines.append("            }")
            lines.append(f"            state stopped_{k} {{ on request to go goto to_{k} }}")
            if leg.leaves:
                lines.append(f"            state past_{k} {{")
                lines.append(f"                on response from arrived goto {states['at'][0]}")
                lines.append(f"                on response from stopped goto stopped_past_{k}")
                lines.append("            }")
                lines.append(f"            state stopped_past_{k} {{ on request to go goto past_{k} }}")
        lines += ["        }", "    }"]
    holders: dict[tuple[str, str], list[str]] = {}  # (kind, cell): the states a robot of the kind holds the cell in
    for kind, (legs, _) in kinds.items():
        for k, leg in enumerate(legs, 1):
            states = _states(k, leg, len(legs))
            for cell in leg.start:
                holders.setdefault((kind, cell), []).extend(states["to"])
            if leg.end is not None:
                holders.setdefault((kind, leg.end), []).extend(states["to"] + states["past"] + states["at"])
    for kind, (legs, _) in kinds.items():
        lines.append(f"    for r in {kind} {{")
        for k, leg in enumerate(legs, 1):
            if leg.end is None or leg.end in leg.start:
                continue
            free = []
            for other in kinds:
                held = " or ".join(f"q.{state}" for state in holders.get((other, leg.end), []))
                if held:
                    free.append(f"!any(q in {other}: q != r and ({held}))" if other == kind else f"!any(q in {other}: {held})")
            lines.append(f"        requirement r.go needs r.{state_name(k - 1, len(legs))} => (" + " and ".join(free) + ")")
        lines.append("    }")
    lines.append("}")
    return "\n".join(lines) + "\n"


def _spread(count: int, widest: float) -> tuple[float, float]:
    """(degrees an arc of ``count`` places spans, radians between neighbours): 32 degrees
    apart, over ``widest`` at most."""
    spread = min(widest, 32.0 * (count - 1))
    return spread, math.radians(spread / (count - 1)) if count > 1 else math.pi


def _arc(gate: tuple[float, float], facing: float, count: int, widest: float) -> list[tuple[float, float, float]]:
    """``count`` places round ``gate`` away from ``facing`` (the direction, in degrees, from the
    gate into its street), each on its own ray from the gate, at least SLOT from its neighbours,
    as near the gate as its body can be while clear of the gate's cell (GATE each way along the
    street, ACROSS each way across) by 0.1 m, facing the gate: (x, y, heading)."""
    spread, gap = _spread(count, widest)
    least = SLOT / (2 * math.sin(gap / 2))
    places = []
    for k in range(count):
        off = spread * (k / (count - 1) - 0.5) if count > 1 else 0.0  # degrees from straight away
        a, c = -math.cos(math.radians(off)), math.sin(math.radians(off))  # along the street, across
        r = least
        while math.hypot(max(0.0, abs(r * a) - GATE), max(0.0, abs(r * c) - ACROSS)) < 0.3:
            r += 0.01
        angle = math.radians(facing + 180.0 + off)
        x, y = gate[0] + r * math.cos(angle), gate[1] + r * math.sin(angle)
        places.append((round(x, 3), round(y, 3), round((math.degrees(angle) + 180.0) % 360.0, 1)))
    return places


def _clear(count: int, widest: float) -> float:
    """The widest arc, up to ``widest`` degrees in steps of 5, whose ``count`` places round a
    gate are reached from the gate's point and left for the street's mouth along ways that keep
    a robot's body 0.15 m clear of the ends of the lane's walls (0.35 m from its centre)."""
    from robosc.sim.world import to_segment

    mouth = (GATE - END, 0.0)
    ends = [(GATE, WIDTH / 2), (GATE, -WIDTH / 2)]
    while widest > 90.0:
        places = _arc((0.0, 0.0), 0.0, count, widest)  # the street along +x from the gate
        ways = []
        for x, y, _ in places:
            r = math.hypot(x, y)
            out = (x * (r + BEYOND) / r, y * (r + BEYOND) / r)
            ways += [((x, y), mouth), ((0.0, 0.0), out)]
        if all(to_segment(ex, ey, a, b) >= 0.35 for ex, ey in ends for a, b in ways):
            return widest
        widest -= 5.0
    return widest


def _streets(name: str, streets: list[Street], per_end: int, size: tuple[float, float],
             walls: list[Any], cells: dict[str, list[list[float]]], widest: float) -> tuple[str, str]:
    """(world file text, model text): ``per_end`` robots homed round each gate of each street,
    in turn (the first street's first gate, its second gate, the next street's ...), each robot
    crossing its street, turning at its own place beyond the far gate and coming back. Round a
    gate its homes and the turning places of the robots from the other end take turns
    (:func:`_arc`)."""
    points: dict[str, tuple[float, float]] = {}
    for street in streets:
        points.update(street.points())
    arcs = {}
    for s, street in enumerate(streets):
        for side in (0, 1):
            gate = points[street.gates[side]]
            facing = math.degrees(math.atan2(street.along[1], street.along[0])) + (0.0 if side == 0 else 180.0)
            arcs[(s, side)] = _arc(gate, facing, 2 * per_end, widest)
    # the robots in the coordinator's order (robosc.sim.fleet.instances): kind by kind, by name
    kinds = sorted((street.kinds[side], s, side) for s, street in enumerate(streets) for side in (0, 1))
    homes, legs = [], []
    for _, s, side in kinds:
        for k in range(per_end):
            robot = len(homes) + 1
            homes.append(arcs[(s, side)][2 * k])
            turn = arcs[(s, 1 - side)][2 * k + 1]
            points[f"t{robot}"] = (turn[0], turn[1])
            for name, (x, y, heading) in ((f"t{robot}", turn), (f"h{robot}", homes[-1])):
                points[f"{name}_out"] = (round(x - BEYOND * math.cos(math.radians(heading)), 3),
                                         round(y - BEYOND * math.sin(math.radians(heading)), 3))
            legs.append([list(leg.points) for leg in streets[s].route(side, f"t{robot}", robot)])
    model = {kind: (streets[s].route(side, "t"), per_end) for kind, s, side in kinds}
    turn_at = len(next(iter(model.values()))[0]) // 2
    world = _yaml(f"{name}{len(homes)}", size, homes, walls, points, legs, cells, [f"at_{turn_at}", "home"])
    return world, street_model(name, model)


def _reach(count: int, widest: float) -> float:
    """Metres from a gate's point to the world's edge, to hold ``count`` places round it and
    the ways beyond them."""
    farthest = max(math.hypot(x, y) for x, y, _ in _arc((0.0, 0.0), 0.0, count, widest))
    return math.ceil(10 * farthest) / 10 + 1.0


def lane(per_side: int) -> tuple[str, str]:
    """(world file text, model text) of the lane with ``per_side`` robots homed at each end."""
    widest = _clear(2 * per_side, LANE_ARC)
    reach = _reach(2 * per_side, widest)
    x0 = reach + 1.0  # the corridor's west end
    y = reach
    size = (2 * x0 + 3 * CELL, 2 * reach)
    street = Street(("l1", "l2", "l3"), ("gw", "ge"), (x0, y), (1.0, 0.0), ("west", "east"))
    east = x0 + 3 * CELL
    cells = {"gw": _box(x0 - 2 * GATE, y - ACROSS, x0, y + ACROSS), "ge": _box(east, y - ACROSS, east + 2 * GATE, y + ACROSS)}
    for k, name in enumerate(street.cells):
        cells[name] = _box(x0 + CELL * k, y - WIDTH / 2, x0 + CELL * (k + 1), y + WIDTH / 2)
    half = WIDTH / 2
    walls = [[(0, 0), (size[0], 0), (size[0], size[1]), (0, size[1]), (0, 0)],
             [(x0, y - half), (east, y - half)], [(x0, y + half), (east, y + half)]]
    return _streets("lane", [street], per_side, size, walls, cells, widest)


def crossing(per_end: int) -> tuple[str, str]:
    """(world file text, model text) of the crossing with ``per_end`` robots homed round each of
    its four gates."""
    reach = _reach(2 * per_end, 180.0)
    centre = reach + 1.0 + 1.5 * CELL
    half = CELL / 2
    size = (2 * centre, 2 * centre)
    west_east = Street(("w", "x", "e"), ("gw", "ge"), (centre - 1.5 * CELL, centre), (1.0, 0.0), ("west", "east"))
    south_north = Street(("s", "x", "n"), ("gs", "gn"), (centre, centre - 1.5 * CELL), (0.0, 1.0), ("south", "north"))
    cells = {"x": _box(centre - half, centre - half, centre + half, centre + half)}
    gate = 1.5 * CELL + GATE  # from the centre to a gate's point
    for name, (dx, dy) in {"w": (-1, 0), "e": (1, 0), "s": (0, -1), "n": (0, 1)}.items():
        px, py = centre + dx * CELL, centre + dy * CELL
        cells[name] = _box(px - half, py - half, px + half, py + half)
        gx, gy = centre + dx * gate, centre + dy * gate
        along, across = (GATE, ACROSS) if dx else (ACROSS, GATE)
        cells["g" + name] = _box(gx - along, gy - across, gx + along, gy + across)
    walls = [[(0, 0), (size[0], 0), (size[0], size[1]), (0, size[1]), (0, 0)]]
    return _streets("crossing", [west_east, south_north], per_end, size, walls, cells, 180.0)

def load(text: str) -> Any:
    """A world from its file's text."""
    from robosc.sim.world import load_world

    with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as f:
        f.write(text)
    try:
        return load_world(f.name)
    finally:
        Path(f.name).unlink()


@functools.lru_cache(maxsize=4)
def synthesized(text: str) -> Any:
    from robosc.api import check_text, synthesize_model

    checked = check_text(text)
    assert checked.model is not None, checked.diagnostics
    return synthesize_model(checked.model)
