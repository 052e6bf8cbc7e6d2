"""The random-model oracle's figures, for this revision and (``--baseline REV``) another, on the
same random fleets in one run: how many were compared, and how many each revision's methods
get wrong, per feature of the models.

The models are tests/fleet_models.py's, drawn with a fixed seed (the same every run). The
reference is this revision's explicit synthesis (checked against libFAUDES on every model);
each revision's default method and monolithic method run in a process of their own with that
revision's sources, and say, in every state the reference supervisor reaches, which events they
allow, and how many states they count (orbits for a counted fleet). A model is got wrong where
a method finds a supervisor where there is none (or none where there is one), allows a different
set of events in some reached state, or counts a different number of states.

Run:  python benchmarks/oracle.py [--models 1000] [--seed 28] [--baseline 5fa21e9] [--files F ...]
(needs the test extras: hypothesis, faudes)
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests"))

WORKER = HERE / "oracle_worker.py"
MAX_STATES = 2_000


def draw(count: int, seed: int) -> list[tuple[str, list[str]]]:
    """``count`` random fleets and their features, the same for the same seed."""
    from hypothesis import HealthCheck, given, settings
    from hypothesis import seed as fixed

    from fleet_models import fleets

    found: list[tuple[str, list[str]]] = []

    @fixed(seed)
    @settings(max_examples=count, deadline=None, database=None, suppress_health_check=list(HealthCheck))
    @given(fleets())
    def collect(model: tuple[str, frozenset[str]]) -> None:
        found.append((model[0], sorted(model[1])))

    collect()
    return found


def key(network: Any, state: Any) -> str:
    """A state, named the same in every process: its automata's locations and its values."""
    parts = [f"{a.name}={loc.name}" for a, loc in zip(network.automata, state.locations, strict=True)]
    parts += [f"{v.owner}.{v.name}={value!r}" for v, value in zip(network.variables, state.values, strict=True)]
    return ",".join(parts)


def orbit(network: Any, groups: list[Any], state: Any) -> tuple[Any, ...]:
    """A state up to permuting each group's robots (what a counted synthesis counts once)."""
    where = dict(zip(network.automata, state.locations, strict=True))
    values = dict(zip(network.variables, state.values, strict=True))
    mine: set[str] = set()
    parts: list[Any] = []
    for group in groups:
        local = []
        for agent in group.agents:
            rep = group.to_rep[id(agent)]
            local.append((repr([rep[where[a]].name for a in agent.automata]), repr([values[v] for v in agent.variables])))
            mine |= {a.name for a in agent.automata} | {f"{v.owner}.{v.name}" for v in agent.variables}
        parts.append(tuple(sorted(local)))
    parts.append(tuple(loc.name for a, loc in where.items() if a.name not in mine))
    parts.append(tuple(repr(value) for v, value in values.items() if f"{v.owner}.{v.name}" not in mine))
    return tuple(parts)


def reference(models: list[tuple[str, list[str]]], max_states: int) -> list[dict[str, Any] | None]:
    """This revision's explicit supervisor of each model (None: over ``max_states`` states)."""
    from faudes_oracle import libfaudes_supervisor, robosc_figures
    from robosc.api import check_text
    from robosc.plant import build_network
    from robosc.synthesis.counting.groups import groups
    from robosc.synthesis.explicit import TooManyStates, synthesize_explicit

    found: list[dict[str, Any] | None] = []
    for text, _ in models:
        network = build_network(check_text(text).model)
        try:
            explicit = synthesize_explicit(network, max_states=max_states)
        except TooManyStates:
            found.append(None)
            continue
        supervisor = explicit.supervisor
        reached = supervisor.controlled_states() if explicit.ok else []
        figures = robosc_figures(supervisor) if explicit.ok else (0, 0)
        assert figures == libfaudes_supervisor(explicit), text  # the reference is libFAUDES's too
        counted = [g for g in groups(network) if len(g.agents) >= 3]
        found.append(
            {
                "ok": explicit.ok,
                "states": {key(network, s): sorted(e.name for e in supervisor.allowed_events(s)) for s in reached},
                "orbits": len({orbit(network, counted, s) for s in reached}),
            }
        )
    return found


def run(source: Path, models: list[tuple[str, list[str]]], references: list[dict[str, Any] | None]) -> list[Any]:
    """The worker on ``source``'s robosc: each model's methods, as they decide in the reference's states."""
    with tempfile.TemporaryDirectory() as work:
        job = Path(work) / "job.json"
        job.write_text(json.dumps([{"text": t, "states": list(r["states"])} for (t, _), r in zip(models, references, strict=True) if r]))
        env = {**os.environ, "PYTHONPATH": str(source)}
        done = subprocess.run([sys.executable, str(WORKER), str(job)], capture_output=True, text=True, env=env, check=True)
    return json.loads(done.stdout)


def wrong(answer: dict[str, Any], expected: dict[str, Any]) -> str | None:
    if answer["ok"] != expected["ok"]:
        return "a supervisor or none"
    if not expected["ok"]:
        return None
    if answer["allowed"] != expected["states"]:
        return "allowed events"
    count = expected["orbits"] if answer["method"] == "symmetric" else len(expected["states"])
    if answer["reachable_states"] != count:
        return "state count"
    return None


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--models", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=28)
    parser.add_argument("--baseline", help="a git revision run side by side (e.g. 5fa21e9, before issue 28)")
    parser.add_argument("--files", nargs="*", help="these model files instead of random fleets, a row each")
    parser.add_argument("--max-states", type=int, default=MAX_STATES, help="larger models are left out")
    args = parser.parse_args()
    from fleet_models import FEATURES
    from fleet_synthesis import checkout

    if args.files:
        models = [(Path(f).read_text(), [Path(f).stem]) for f in args.files]
        features = [Path(f).stem for f in args.files]
    else:
        models, features = draw(args.models, args.seed), list(FEATURES)
    references = reference(models, args.max_states)
    kept = [(m, r) for m, r in zip(models, references, strict=True) if r is not None]
    revisions = [("this revision", HERE.parent / "src")]
    with tempfile.TemporaryDirectory() as work:
        if args.baseline:
            revisions.append((args.baseline, checkout(args.baseline, Path(work))))
        answers = {name: run(source, models, references) for name, source in revisions}
    drawn = f"{len(models)} models" if args.files else f"{len(models)} random fleets drawn (seed {args.seed})"
    print(f"{drawn}, {len(kept)} compared "
          f"({len(models) - len(kept)} over {args.max_states} states left out); reference: explicit synthesis, = libFAUDES on every one")
    columns = [f"{name}: {method}" for name, _ in revisions for method in ("default", "monolithic")]
    counts: dict[str, collections.Counter[str]] = {c: collections.Counter() for c in columns}
    reasons: dict[str, collections.Counter[str]] = {c: collections.Counter() for c in columns}
    having: collections.Counter[str] = collections.Counter()
    for index, ((_, has), expected) in enumerate(kept):
        having.update(has)
        having["all models"] += 1
        for name, _ in revisions:
            for method in ("default", "monolithic"):
                answer = answers[name][index][method]
                why = answer.get("error") or wrong(answer, expected)
                if why is not None:
                    column = f"{name}: {method}"
                    counts[column].update([*has, "all models"])
                    reasons[column][why] += 1
    rows = ["all models", *features]
    width = max(len(f"{r} ({having[r]})") for r in rows) + 2
    print("models got wrong (of the models with the feature)")
    print("feature".ljust(width) + "".join(c.rjust(28) for c in columns))
    for row in rows:
        print(f"{row} ({having[row]})".ljust(width) + "".join(str(counts[c][row]).rjust(28) for c in columns))
    for column in columns:
        if reasons[column]:
            print(f"{column}: " + ", ".join(f"{n} {why}" for why, n in reasons[column].most_common()))


if __name__ == "__main__":
    main()
