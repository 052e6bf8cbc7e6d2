"""BDD variable orders side by side (docs/synthesis-options.md): for each model and each order
pipeline (``ORDER@EDGES`` also sets the edge order, e.g. ``interaction@reverse``), the total span of the order (Eclipse ESCET's measure: how far apart what interacts
is), synthesis time, peak live BDD nodes and peak memory. Each run is a process of its own
with a time limit; every order must give the same number of controlled states.

Run:  python benchmarks/orders.py [--timeout 120] [--orders interaction,interaction->force,...]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

HERE = Path(__file__).resolve().parent

MODELS = {
    "transfer line 32": ("transfer_line", 32, "monolithic"),
    "philosophers 14": ("philosophers", 14, "monolithic"),
    "ring 7 (copies; monolithic)": ("ring", 7, "monolithic"),
    "warehouse 5 (copies; monolithic)": ("warehouse", 5, "monolithic"),
    "ring 16 (instances; counted)": ("ring_instances", 16, "counted"),
}
ORDERS = (
    "interaction,model,interaction->force,interaction->force->slidwin,model->force->slidwin,sorted->force->slidwin,"
    "model->dcsh,model->dcsh->force,interaction->dcsh"
)

RUN = r"""
import json, resource, sys, time
sys.path.insert(0, sys.argv[1])
import families
from robosc.api import check_text, synthesize_model
from robosc.plant import build_network
from robosc.synthesis.options import SynthesisOptions
from robosc.synthesis.ordering import hyperedges, initial_order, total_span
family, n, fleet, spec = sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5]
explore = sys.argv[6] if len(sys.argv) > 6 else "auto"
order, _, edges = spec.partition("@")
model = check_text(getattr(families, family)(n)).model
network = build_network(model)
if fleet == "counted":  # the order is that of the network synthesis works on: the counted one
    from robosc.synthesis.counting.network import counted
    network = counted(network).network
start = time.perf_counter()
items = initial_order(network, order)
ordered = time.perf_counter() - start
span = total_span(list(range(len(items))), hyperedges(network, items))
options = SynthesisOptions(order=order, fleet=fleet, edges=edges or "model", explore=explore)
result = synthesize_model(model, options=options)
done = time.perf_counter() - start
print(json.dumps({"span": span, "order_s": ordered, "s": done, "states": result.reachable_states,
    "mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, **result.effort}))
"""


def run(name: str, order: str, timeout: float, explore: str = "auto") -> dict | None:  # type: ignore[type-arg]
    """Synthesis of MODELS[name] with ``order`` (``ORDER@EDGES``) in a process of its own: its
    figures, or None after printing a row that says why there are none."""
    family, n, fleet = MODELS[name]
    try:
        done = subprocess.run(
            [sys.executable, "-c", RUN, str(HERE), family, str(n), fleet, order, explore],
            capture_output=True, text=True, timeout=timeout, check=False,
        )
    except subprocess.TimeoutExpired:
        print(f"| {name} | `{order}` {explore} | | | over {timeout:g} s | | | |", flush=True)
        return None
    if done.returncode != 0:
        print(f"| {name} | `{order}` {explore} | | | failed: {done.stderr.strip().splitlines()[-1][:60]} | | | |", flush=True)
        return None
    return dict(json.loads(done.stdout.strip().splitlines()[-1]))


def rows(name: str, variants: list[tuple[str, str]], timeout: float, cells: Callable[[dict, str, str], str]) -> None:  # type: ignore[type-arg]
    """A table row for each run of MODELS[name] with an (order, exploration) of ``variants``:
    the model, ``cells(figures, order, exploration)``, the controlled states, which must agree."""
    states = set()
    for order, explore in variants:
        f = run(name, order, timeout, explore)
        if f is None:
            continue
        states.add(f["states"])
        print(f"| {name} | {cells(f, order, explore)} | {f['states']:,} |", flush=True)
    assert len(states) <= 1, f"{name}: the runs disagree on the controlled states: {states}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--timeout", type=float, default=120.0)
    parser.add_argument("--orders", default=ORDERS)
    parser.add_argument("--models", default=",".join(MODELS), help="names of MODELS, comma-separated")
    args = parser.parse_args()
    print(f"limit: {args.timeout:g} s per run\n")
    print("| model | order | total span | order s | synthesis s | peak live nodes | peak MB | controlled states |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for name in args.models.split(","):
        rows(
            name,
            [(order, "auto") for order in args.orders.split(",")],
            args.timeout,
            lambda f, order, _: f"`{order}` | {f['span']:,} | {f['order_s']:.2f} | {f['s']:.2f} | "
            f"{f['peak_live_nodes']:,} | {f['mb']:.0f}",
        )


if __name__ == "__main__":
    main()
