"""benchmarks/oracle.py's worker, run on one revision's sources (PYTHONPATH): for each model of
the job, its default method's and its monolithic method's answers in the given states (named as
oracle.key names them). Uses only what every revision since instances has: check_text,
build_network, explicit synthesis (for the plant's states), synthesize_symbolic,
synthesize_monolithic and ``allows``."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

from robosc.api import check_text
from robosc.plant import build_network
from robosc.synthesis.explicit import synthesize_explicit
from robosc.synthesis.methods import synthesize_symbolic
from robosc.synthesis.symbolic import synthesize_monolithic


def key(network: Any, state: Any) -> str:
    parts = [f"{a.name}={loc.name}" for a, loc in zip(network.automata, state.locations, strict=True)]
    parts += [f"{v.owner}.{v.name}={value!r}" for v, value in zip(network.variables, state.values, strict=True)]
    return ",".join(parts)


def answer(result: Any, network: Any, states: dict[str, Any], wanted: list[str]) -> dict[str, Any]:
    found: dict[str, Any] = {"ok": result.ok, "method": result.method, "reachable_states": result.reachable_states}
    if result.ok:
        found["allowed"] = {
            name: sorted(e.name for e in network.events if result.allows(e, states[name])) for name in wanted
        }
    return found


def main() -> None:
    job = json.loads(Path(sys.argv[1]).read_text())
    out = []
    for item in job:
        network = build_network(check_text(item["text"]).model)
        plant = synthesize_explicit(network, 10**6).supervisor  # its states: the plant's
        states = {key(network, s): s for s in plant.states}
        row = {}
        for method, synthesize in (("default", synthesize_symbolic), ("monolithic", synthesize_monolithic)):
            try:
                row[method] = answer(synthesize(network), network, states, item["states"])
            except Exception as exc:  # a revision that crashes on a model gets it wrong
                row[method] = {"error": f"{type(exc).__name__}"}
        out.append(row)
    print(json.dumps(out))


if __name__ == "__main__":
    main()
