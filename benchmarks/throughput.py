"""Throughput of a fleet (issue 46, part 4): the work a fleet gets done, against the world's
physical bound and the rule other fleet managers use, in one run of this script.

Worlds: the warehouse (examples/worlds/warehouse.yaml, warehouse_large.yaml for 16 robots, the
person walking in) and, written for each size by benchmarks/fleet_worlds.py, the lane (a
corridor one robot wide, half the robots homed at each end, each crossing to the far end and
back), swap (the same, SWAPS times the tasks: the robots pass each other again and again) and
the crossing (two such streets that cross, a quarter of the robots at each end).

For each world and fleet size, K tasks per robot (the world's ``stops``, given at run time
through the coordinator's dispatcher, as ``robosc sim`` gives them), driven in this process by
the generated coordinator module (the same module and dispatcher the ROS node runs):

* **robosc**: the synthesized supervisor, the coordinator's policy ``purpose`` (the default);
* **random**: the same supervisor, the original tool's random choice among what it allows;
* **reservation**: no supervisor, the rule "enter the next cell only while no other robot holds
  it" (the model's requirements without what synthesis added), first come first served: the
  same policy, the robot waiting longest first (Open-RMF's reservations, openTCS's blocks);
* **bound**: the world's physical bound, from each robot driving its task alone (no other
  robot moving, no person, the door open). A cell fits one robot: no two robots' bodies are in
  one cell at once (a body is in every cell it overlaps). No run of K tasks per robot can end
  sooner than:

  - K times the longest lone task;
  - for each zone that takes one robot at a time (a cell or, in the warehouse, the whole aisle,
    a dead end one robot wide where robots cannot pass each other): the quickest way into it
    from a home, every task's lone time in it one after another, and the quickest way from it
    to a task's end; in the warehouse plus the time the person stands in the aisle (where the
    model lets nobody pass them) less twice the aisle's longest leg (what robots can still do
    meanwhile);
  - for each street one robot wide that robots homed at both of its ends cross both ways (the
    lane's, each of the crossing's): robots going opposite ways cannot be in it at once, so its
    crossings come in turns of one direction, at least 2K + 1 of them (each robot's crossings
    alternate in direction, starting from its own end). A turn takes at least one lone crossing
    (body in the street's first cell to out of its last), and each further robot in it comes
    out no sooner than its lone time in the street's last cell after the one before it;
    between two turns the robot coming out must get its body out of the gate's cell before the
    next one's comes in, and that one must get from the gate's cell into the street (lone
    times, the quickest). With M crossings in all and T turns: the way in from a home, T
    crossings, M - T times the time in the last cell, T - 1 changes at a gate, the way home.

  Tasks per hour <= 3600 N K / the longest of these. Every run must take at least that long
  whatever coordinates it.

Per run: tasks per simulated hour and its share of the bound, the wait per task (the time from
a task's assignment to its end beyond the same robot's lone time: what sharing cost it) mean and
longest, tasks per robot (min/max), door operations per task, collisions and how the run ended
(a deadlock: no robot got on for 60 s).

    python benchmarks/throughput.py [--worlds warehouse lane swap crossing] [--sizes 4 8 16] [--tasks 2]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from collections import Counter
from pathlib import Path
from typing import Any, NamedTuple

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))

AISLE = ("c1", "c2", "c3", "shelf")  # the warehouse's dead-end aisle: one robot in it at a time
# each world's streets one robot wide that its robots cross both ways: the gate's cell at one end,
# the street's cells in a row, the gate's cell at the other end
STREETS = {"lane": (("gw", "l1", "l2", "l3", "ge"),), "swap": (("gw", "l1", "l2", "l3", "ge"),),
           "crossing": (("gw", "w", "x", "e", "ge"), ("gs", "s", "x", "n", "gn"))}
STALL = 60.0
SWAPS = 3  # swap: the lane with this many times the tasks, the robots passing each other again and again


def replaced(record: Any, **changes: Any) -> Any:
    """A copy of a robosc record with some fields changed."""
    fields = {name: getattr(record, name) for name in record.__record_options__}
    fields.update(changes)
    return type(record)(**fields)


def worlds(name: str, robots: int) -> tuple[Any, Any] | None:
    """(world, synthesis result) of a world at a fleet size, or None where the world has no
    room for that many: the warehouse's world files (eight homes; sixteen in the large one); the
    lane (also for swap) and the crossing written for the size by benchmarks/fleet_worlds.py."""
    from robosc.api import synthesize_file
    from robosc.sim.world import load_world

    if name == "warehouse":
        world = load_world(ROOT / "examples/worlds" / ("warehouse.yaml" if robots <= 8 else "warehouse_large.yaml"))
        if robots > len(world.starts):
            return None
        return world, synthesize_file(ROOT / "examples/warehouse.rscd", sizes={"bot": robots})
    import fleet_worlds

    if name in ("lane", "swap") and robots % 2 == 0:
        world_text, model_text = fleet_worlds.lane(robots // 2)
    elif name == "crossing" and robots % 4 == 0:
        world_text, model_text = fleet_worlds.crossing(robots // 4)
    else:
        return None
    return fleet_worlds.load(world_text), fleet_worlds.synthesized(model_text)


def modules(result: Any) -> dict[str, Any]:
    """The coordinator module of the supervisor and of the reservation rule (its requirements alone)."""
    from robosc.api import plan_supervisor
    from robosc.debug.simulator import load_module
    from scenarios import rule

    supervised = load_module(plan_supervisor(result))
    return {"robosc": supervised, "random": supervised, "reservation": load_module(plan_supervisor(rule(result)))}


class Crossing(NamedTuple):
    """A robot's way through a street, alone: seconds from its body entering the street's cells
    to leaving them (``through``), in the cell it leaves them by (``by``), from entering the gate's
    cell it comes in by to entering the street (``gate_in``) and from leaving the street to
    leaving the gate's cell it goes out by (``gate_out``)."""

    through: float
    by: float
    gate_in: float
    gate_out: float


def crossings(spans: list[tuple[str, float, float]], street: tuple[str, ...]) -> list[Crossing]:
    """A robot's crossings of ``street`` (gate, cells ..., gate) from its cells' spans: each time
    its body is in the street's cells without a break, from one end to the other."""
    inner = set(street[1:-1])
    mine = sorted((span for span in spans if span[0] in inner), key=lambda span: span[1])
    out: list[Crossing] = []
    k = 0
    while k < len(mine):
        group = [mine[k]]
        end = mine[k][2]
        k += 1
        while k < len(mine) and mine[k][1] <= end + 1e-6:
            group.append(mine[k])
            end = max(end, mine[k][2])
            k += 1
        cells = {cell for cell, _, _ in group}
        if street[1] not in cells or street[-2] not in cells:
            continue  # only through a part of it (the crossing's other street)
        start = group[0][1]
        last = max(group, key=lambda span: span[2])
        came = street[0] if group[0][0] == street[1] else street[-1]
        went = street[-1] if came == street[0] else street[0]
        gate_in = min((start - a for cell, a, b in spans if cell == came and a <= start <= b + 1e-6), default=0.0)
        gate_out = min((b - end for cell, a, b in spans if cell == went and a - 1e-6 <= end <= b), default=0.0)
        out.append(Crossing(end - start, last[2] - last[1], gate_in, gate_out))
    return out


class Lone:
    """One robot's task driven alone (the others at home, no person, the door open)."""

    def __init__(self) -> None:
        self.time = 0.0  # the whole task
        self.inside: Counter[str] = Counter()  # seconds in each cell (and in the warehouse's aisle)
        self.first: dict[str, float] = {}  # seconds from the start until it first enters each zone
        self.after: dict[str, float] = {}  # seconds from last leaving each zone until the task ends
        self.legs_inside: dict[str, float] = {}  # each zone: its longest leg that ends in it
        self.spans: list[tuple[str, float, float]] = []  # (cell, from, to): its body in the cell, seconds from the start
        self.crossings: dict[tuple[str, ...], list[Crossing]] = {}  # each street it crosses: each crossing


def lone(world: Any, module: Any, robots: int, streets: tuple[tuple[str, ...], ...] = ()) -> list[Lone]:
    """Each robot driving its task alone: what :class:`Lone` holds. A robot is in a cell while
    its body overlaps it (a cell fits one robot: no two bodies in it at once)."""
    from robosc.sim.fleet import FleetWorld, instances

    quiet = replaced(world, fleet=replaced(world.fleet, person=None))
    names = instances(module)[:robots]
    radius = world.robot.radius
    out: list[Lone] = []
    for k, name in enumerate(names):
        fw = FleetWorld(quiet, names)
        if fw.door is not None:
            fw.command("open_door")
            while fw.door.state != "open":
                fw.step()
        start = fw.sim.time
        alone = Lone()
        last: dict[str, float] = {}
        open_spans: dict[str, float] = {}  # cell: since when its body is in it
        for _ in range(len(world.fleet.task_of(k))):
            began = fw.sim.time
            fw.command(f"{name}.go")
            while True:
                said = [answer for answer, _ in fw.step()]
                pose = fw.sim.bodies[k].pose
                cells = fw.fleet.cells_under(pose.x, pose.y, radius)
                zones = sorted(cells) + (["aisle"] if cells & set(AISLE) else [])
                for zone in zones:
                    alone.inside[zone] += fw.sim.world.step
                    alone.first.setdefault(zone, fw.sim.time - start)
                    last[zone] = fw.sim.time
                now = fw.sim.time - start
                for cell in cells - set(open_spans):
                    open_spans[cell] = now - fw.sim.world.step
                for cell in set(open_spans) - cells:
                    alone.spans.append((cell, open_spans.pop(cell), now - fw.sim.world.step))
                if f"{name}.arrived" in said:
                    break
                if f"{name}.stopped" in said:
                    fw.command(f"{name}.go")
                if fw.sim.time - start > 3600:
                    raise RuntimeError(f"{name} alone did not finish its task")
            for zone in zones:
                alone.legs_inside[zone] = max(alone.legs_inside.get(zone, 0.0), fw.sim.time - began)
        alone.time = fw.sim.time - start
        alone.spans += [(cell, since, alone.time) for cell, since in open_spans.items()]
        alone.crossings = {street: found for street in streets if (found := crossings(alone.spans, street))}
        alone.after = {zone: alone.time - (at - start) for zone, at in last.items()}
        out.append(alone)
    return out


def person_stay(world: Any, module: Any, robots: int) -> float:
    """Seconds the world's person spends in the warehouse's aisle cells c1 .. c3, where no robot
    may pass (the model keeps robots out of the person's cell and the cells next to it): the
    person walking their way alone, the robots at home."""
    from robosc.sim.fleet import FleetWorld, instances

    if world.fleet.person is None:
        return 0.0
    fw = FleetWorld(world, instances(module)[:robots])
    walker = fw.sim.walker
    stay = 0.0
    while not walker.done and fw.sim.time < 3600:
        fw.step()
        if fw.person_cell in AISLE[:3]:
            stay += fw.sim.world.step
    return stay


def streets(alone: list[Lone]) -> list[tuple[str, ...]]:
    """The streets crossed both ways by robots homed at both of their ends (each robot's first
    crossing starts at its home's end)."""
    out = []
    for street in sorted({street for a in alone for street in a.crossings}):
        used = [a for a in alone if street in a.crossings]
        if len({a.first.get(street[1], 0.0) < a.first.get(street[-2], 0.0) for a in used}) == 2:
            out.append(street)
    return out


def bound(world_name: str, tasks: int, alone: list[Lone], stay: float) -> tuple[float, str]:
    """Tasks per hour no coordinator can beat in a run of ``tasks`` tasks per robot, and what
    limits it: the run takes at least as long as

    * each robot's tasks one after another, alone (``tasks`` times its lone task), and
    * for each zone that takes one robot at a time (each cell, one robot each; in the warehouse
      the whole aisle, a dead end one robot wide where robots cannot pass each other): the
      quickest way into it from a home, then every task's lone time in it one after another,
      then the quickest way from it to the end of a task; in the warehouse, plus the time the
      person stands in the aisle (``stay``) less what robots can still do in it meanwhile (at
      most a leg under way and one leg into the shelf: twice its longest leg)."""
    robots = len(alone)
    limits = {"the longest lone task, one after another": tasks * max(a.time for a in alone)}
    cells = {cell for a in alone for cell in a.inside if cell not in ("aisle", "depot")}
    if world_name == "warehouse":
        cells = {"aisle"}
    for cell in cells:
        used = [a for a in alone if cell in a.inside]
        serial = tasks * sum(a.inside[cell] for a in used)
        ramps = min(a.first[cell] for a in used) + min(a.after[cell] for a in used)
        blocked = 0.0
        if world_name == "warehouse" and stay > 0:
            blocked = max(0.0, stay - 2 * max(a.legs_inside.get(cell, 0.0) for a in used))
        limits[f"{cell} (one robot at a time)"] = ramps + serial + blocked
    for street in streets(alone):
        used = [a for a in alone if street in a.crossings]
        ways = [c for a in used for c in a.crossings[street]]
        total = tasks * len(ways)
        phases = 2 * tasks + 1
        inner = street[1:-1]  # the street's own cells, between its gates
        ramps = min(min(a.first[c] for c in inner if c in a.first) for a in used) + \
            min(min(a.after[c] for c in inner if c in a.after) for a in used)
        switch = min(c.gate_out for c in ways) + min(c.gate_in for c in ways)
        limits[f"{'-'.join(inner)} ({phases} turns of one direction)"] = (
            ramps + phases * min(c.through for c in ways) + (total - phases) * min(c.by for c in ways)
            + (phases - 1) * switch)
    what = max(limits, key=lambda k: limits[k])
    return 3600.0 * robots * tasks / limits[what], what


def run(world: Any, module: Any, robots: int, tasks: int, policy: str, lone_time: float, seed: int = 0) -> dict[str, Any]:
    """One run; its time-out four times what the tasks take one after the other, each alone."""
    from robosc.sim.fleet import FleetRun
    from robosc.sim.run import drive

    doors: Counter[str] = Counter()

    def on_event(record: dict[str, Any]) -> None:
        if record["controllable"] and record["event"] in ("open_door", "close_door"):
            doors[record["event"]] += 1

    control = FleetRun(world, module, robots, seed=seed, tasks=tasks, stall=STALL, policy=policy, on_event=on_event)
    started = time.monotonic()
    report = drive(control, timeout=max(600.0, 4.0 * robots * tasks * lone_time))
    d = control.dispatcher
    assert d is not None
    done = [t for t in d.tasks.values() if t.state == "done"]
    return {"report": report, "done": done, "by": Counter(t.by for t in done), "doors": sum(doors.values()),
            "wall": time.monotonic() - started, "names": control.world.names}


def rows(names: list[str], sizes: list[int], tasks: int) -> Any:
    for name in names:
        for robots in sizes:
            made = worlds(name, robots)
            if made is None:
                continue
            world, result = made
            each = tasks * (SWAPS if name == "swap" else 1)
            built = modules(result)
            alone = lone(world, built["robosc"], robots, STREETS.get(name, ()))
            times = [a.time for a in alone]
            limit, what = bound(name, each, alone, person_stay(world, built["robosc"], robots) if name == "warehouse" else 0.0)
            yield name, robots, each, "bound", {"limit": limit, "what": what, "times": times}
            for who in ("robosc", "random", "reservation"):
                policy = "random" if who == "random" else "purpose"
                out = run(world, built[who], robots, each, policy, statistics.mean(times))
                out["times"] = times
                out["limit"] = limit
                yield name, robots, each, who, out


def line(name: str, robots: int, tasks: int, who: str, out: dict[str, Any]) -> str:
    if who == "bound":
        return (f"| {name} | {robots} | {tasks} | bound | {out['limit']:.0f} | 100 % | - | - | - | - | - | "
                f"{out['what']}; lone task {statistics.mean(out['times']):.0f} s |")
    report = out["report"]
    done = out["done"]
    hours = report.simulated / 3600.0
    rate = len(done) / hours if hours > 0 else 0.0
    index = {name: k for k, name in enumerate(out["names"])}
    waits = [max(0.0, (t.done_at - t.assigned_at) - out["times"][index[t.by]]) for t in done]
    per = [out["by"].get(name, 0) for name in out["names"]]
    ended = "ok" if report.ok else report.why.split(":")[0]
    wait = f"{statistics.mean(waits):.0f} / {max(waits):.0f}" if waits else "-"
    doors = f"{out['doors'] / len(done):.1f}" if done else "-"
    return (f"| {name} | {robots} | {tasks} | {who} | {rate:.0f} | {100 * rate / out['limit']:.0f} % | {wait} | "
            f"{min(per)}/{max(per)} | {doors} | {report.collisions} | {ended} | {len(done)} of {robots * tasks} tasks, "
            f"{report.simulated:.0f} s simulated in {out['wall']:.0f} s |")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--worlds", nargs="*", default=["warehouse", "lane", "swap", "crossing"])
    parser.add_argument("--sizes", nargs="*", type=int, default=[4, 8, 16])
    parser.add_argument("--tasks", type=int, default=2)
    args = parser.parse_args(argv)
    print("| world | robots | tasks each | coordinator | tasks per hour | of the bound | wait per task, s mean / longest "
          "| tasks per robot min/max | door operations per task | collisions | ended | |")
    print("|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---|---|")
    for name, robots, tasks, who, out in rows(args.worlds, args.sizes, args.tasks):
        print(line(name, robots, tasks, who, out), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
