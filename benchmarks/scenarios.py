"""The conflicts fleet managers' users report, run in one world (issue 31, item 5): robosc's
supervisor against the obvious hand-written rule, K runs each with random speeds and start delays.

* **lane** (osrf/rmf_core#145): two robots cross a one-lane corridor from its two ends, at once.
* **swap** (open-rmf/rmf_ros2#503): the same two robots patrol the corridor end to end in
  opposite phase, swapping places again and again (``SWAPS`` tasks each).
* **crossing** (open-rmf/rmf#356): four robots cross one intersection, two along each street.

The hand-written rule is the model's requirements alone, each robot entering the next cell
when no other robot holds it ("enter a cell when it is free"), without what synthesis added.
The models (``examples/scenarios/*.rscd``) are written by ``model()`` from each robot's route
(``--write`` writes them again; the tests check they are what it writes).

    python benchmarks/scenarios.py [--runs 10] [--only lane] [--write]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))

from fleet_worlds import holding, move_name, state_name  # noqa: E402  (the routes' states, written once)

FOLDER = ROOT / "examples" / "scenarios"
SWAPS = 4  # tasks each robot of the swap scenario does

# each robot's route: the cells of positions 1 .. 7 (position 0 is its home bay, 4 the far bay:
# None, room for every robot); a robot drives position k -> k + 1 on each go
LANE = (
    ("l1", "l2", "l3", None, "l3", "l2", "l1"),  # bot1: from the west bay east and back
    ("l3", "l2", "l1", None, "l1", "l2", "l3"),  # bot2: from the east bay west and back
)
CROSSING = (
    ("w", "x", "e", None, "e", "x", "w"),  # bot1: west -> east and back
    ("e", "x", "w", None, "w", "x", "e"),  # bot2: east -> west and back
    ("n", "x", "s", None, "s", "x", "n"),  # bot3: north -> south and back
    ("s", "x", "n", None, "n", "x", "s"),  # bot4: south -> north and back
)
HEADERS = {
    "lane": (
        "// Two robots cross a one-lane corridor of three cells (l1, l2, l3, one robot each) from its\n"
        "// two ends and come back: bot1 from the west bay, bot2 from the east bay. Head-on in the lane\n"
        "// neither can go on (osrf/rmf_core#145). Written by benchmarks/scenarios.py from the routes."
    ),
    "crossing": (
        "// Four robots cross one intersection (x) and come back: bot1 west -> east, bot2 east -> west,\n"
        "// bot3 north -> south, bot4 south -> north, each street cell (w, e, n, s) and the crossing for\n"
        "// one robot. Robots waiting on each other around the crossing is a deadlock (open-rmf/rmf#356).\n"
        "// Written by benchmarks/scenarios.py from the routes."
    ),
}
ROUTES = {"lane": LANE, "crossing": CROSSING}


POSITIONS = 8  # a route's positions: home, then 1 .. 7


def _name(k: int) -> str:
    return state_name(k, POSITIONS)


def _to(k: int) -> str:
    return move_name(k, POSITIONS)


def model(name: str, routes: tuple[tuple[str | None, ...], ...]) -> str:
    """A fleet model for robots driving ``routes``: each ``go`` drives the next leg and the robot
    answers ``arrived`` (or ``stopped`` on its way); a robot starts a leg only into a cell no
    other robot holds."""
    lines = [HEADERS[name], f"robot {name.capitalize()} {{", f"    component bot[{len(routes)}] {{"]
    lines += [
        "        incoming message go with type: none // drive the route's next leg, or go on after a stop",
        "        outgoing message arrived with type: none // the leg is done",
        "        outgoing message stopped with type: none // stopped on the way: something is in front",
        "",
        "        behaviour {",
    ]
    for k in range(8):
        here, nxt = _name(k), k + 1
        initial = "initial marked " if k == 0 else ""
        lines.append(f"            {initial}state {here} {{ on request to go goto {_to(nxt)} }}")
        stop = f"stopped_{nxt}"
        lines.append(f"            state {_to(nxt)} {{")
        lines.append(f"                on response from arrived goto {_name(nxt)}")
        lines.append(f"                on response from stopped goto {stop}")
        lines.append("            }")
        lines.append(f"            state {stop} {{ on request to go goto {_to(nxt)} }}")
    lines += ["        }", "    }", ""]
    lines.append("    // a robot starts a leg only into a cell no other robot holds (is in, or on its way into")
    lines.append("    // or out of); its home bay and its far bay have room for every robot")
    for i, route in enumerate(routes, 1):
        for k in range(8):
            cell = route[k] if k < 7 else None
            if cell is None:
                continue
            others = [f"bot{j}.{s}" for j, other in enumerate(routes, 1) if j != i for s in holding(other, cell)]
            if others:
                lines.append(f"    requirement bot{i}.go needs bot{i}.{_name(k)} => !({' or '.join(others)})")
    lines.append("}")
    return "\n".join(lines) + "\n"


def write() -> list[Path]:
    written = []
    for name, routes in ROUTES.items():
        path = FOLDER / f"{name}.rscd"
        path.write_text(model(name, routes), encoding="utf-8")
        written.append(path)
    return written


# ---- the runs ---------------------------------------------------------------------------------
SCENARIOS = {  # name: (model, world, tasks)
    "lane": ("lane", "lane", 1),
    "swap": ("lane", "lane", SWAPS),
    "crossing": ("crossing", "crossing", 1),
}


def coordinators(model_name: str) -> dict[str, object]:
    """The generated coordinator module of robosc's supervisor and of the hand-written rule."""
    from robosc.api import plan_supervisor, synthesize_file
    from robosc.debug.simulator import load_module

    result = synthesize_file(FOLDER / f"{model_name}.rscd")
    assert result.ok, result.explanation
    assert result.added_guards, "synthesis added nothing: the rule would be the supervisor"
    return {"robosc": load_module(plan_supervisor(result)), "rule": load_module(plan_supervisor(rule(result)))}


def rule(result: Any) -> Any:
    """The hand-written rule as a synthesis result: the model's requirements alone, without what
    synthesis added."""
    from robosc.synthesis.result import EventGuard, SynthesisResult

    alone = tuple(EventGuard(g.event, g.required, None) for g in result.guards)
    return SynthesisResult(result.network, result.method, True, alone, result.reachable_states, result.seconds)


def run_once(module: object, world: object, tasks: int, seed: int) -> object:
    """One run with the robots' speeds and start delays drawn from ``seed``."""
    from robosc.sim.fleet import FleetRun, Jitter, instances
    from robosc.sim.run import drive

    robots = len(instances(module))  # type: ignore[arg-type]
    run = FleetRun(world, module, robots, seed=seed, jitter=Jitter(seed), tasks=tasks, stall=60.0)  # type: ignore[arg-type]
    return drive(run, timeout=300.0 * robots * tasks)


def table(runs: int, only: list[str] | None = None) -> Iterator[tuple[str, str, int, int, int, list[float]]]:
    """Per scenario and coordinator, as each is done: deadlocks, collisions, other failures and
    the completion times (simulated seconds) of the runs that did every task."""
    from robosc.sim.world import load_world

    for name, (model_name, world_name, tasks) in SCENARIOS.items():
        if only and name not in only:
            continue
        world = load_world(ROOT / "examples" / "worlds" / f"{world_name}.yaml")
        for who, module in coordinators(model_name).items():
            deadlocks = collisions = other = 0
            done: list[float] = []
            for seed in range(runs):
                report = run_once(module, world, tasks, seed)
                if report.ok:  # type: ignore[attr-defined]
                    done.append(report.simulated)  # type: ignore[attr-defined]
                elif report.why.startswith("deadlock"):  # type: ignore[attr-defined]
                    deadlocks += 1
                elif report.why.startswith("collision"):  # type: ignore[attr-defined]
                    collisions += 1
                else:
                    other += 1
            yield name, who, deadlocks, collisions, other, done


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=10)
    parser.add_argument("--only", nargs="*")
    parser.add_argument("--write", action="store_true", help="write the models again and stop")
    args = parser.parse_args(argv)
    if args.write:
        for path in write():
            print(f"wrote {path.relative_to(ROOT)}")
        return 0
    started = time.monotonic()
    print("| scenario | coordinator | runs | deadlocks | collisions | other failures | done | completion, s median (min .. max) |")
    print("|---|---|---:|---:|---:|---:|---:|---|")
    for name, who, deadlocks, collisions, other, done in table(args.runs, args.only):
        times = f"{statistics.median(done):.0f} ({min(done):.0f} .. {max(done):.0f})" if done else "-"
        print(f"| {name} | {who} | {args.runs} | {deadlocks} | {collisions} | {other} | {len(done)} | {times} |")
    print(f"({time.monotonic() - started:.0f} s)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
