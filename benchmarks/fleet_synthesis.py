"""Synthesis for fleets: how each method's cost grows with the number of robots.

Families (benchmarks/families.py): ``ring`` — N robots on a one-way ring of 2N zones, a zone
held by at most one robot; ``warehouse`` — a one-way loop of 2N+2 aisle zones with a door the
robots pass only while it is open and one charger for one robot. Each is written as the
original's users write fleets (a copied component per robot, a requirement per robot naming
every other robot) and, as ``ring_instances`` / ``warehouse_instances``, with instances.
``lift`` — robots sharing a corridor cell (one at a time) and a lift of capacity 2 with its
own automaton; ``ring_homes`` — the ring where each robot must be able to get back to a home
of its own (copies by hand that differ in their marked state); ``crossing`` — two kinds of
robots (two instance arrays, alike automata) on two one-way loops that share two crossing
cells, each for one robot of either kind; ``warehouse_example`` — the bundled
``examples/warehouse.rscd`` with N robots (moves that take time and may stop, a door, one
charger, the person's cell: 26 states per robot).

Methods (``SynthesisOptions.fleet``): ``counted`` (the default: robots that are copies counted
per state) and ``monolithic`` (the reference). Each run is a process of its own with a time
limit and an address-space limit, so that a method that blows up is cut off and the table
still prints; figures that do not depend on the machine (peak live BDD nodes, image and
preimage computations) are printed next to the wall time and the peak memory. Where both
finish, a third run asserts that they found the same supervisor (each event allowed in the
same states, over the states the monolithic supervisor reaches): the last column.

The largest condition synthesis added (as robosc prints it), the size of the generated
supervisor module and how long the module takes to tell what is allowed where the fleet starts
(``_allowed``, as a coordinator does after each event, median of 300) are printed too
(synthesis time includes none of them).

Run:  python benchmarks/fleet_synthesis.py [--families ring,warehouse] [--sizes 2,4,8,16,32]
          [--methods counted,monolithic] [--timeout 600] [--memory-gb 2] [--baseline REV]

With ``--baseline REV`` each method also runs from that revision's sources, in the same run
(the machine's speed varies), its row marked ``METHOD@REV``.

With ``--commands`` each row also gives what a user waits for: the whole ``robosc synthesize``
command (``--fleet METHOD``: warnings and explanations included), as text and ``--json``, and ``robosc build`` (the
default method, ROS 1 and ROS 2 packages) on the family's model written to a file, in seconds of
wall time, and their ratio (issue 48 asks for synthesize within 1.5 times build).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent

RUN = r"""
import json, resource, sys, time
sys.path.insert(0, sys.argv[1])
from families import FLEETS
from robosc.api import check_text, synthesize_model
from robosc.synthesis.options import SynthesisOptions
family, n, method = sys.argv[2], int(sys.argv[3]), sys.argv[4]
text = FLEETS[family](n)
start = time.perf_counter()
model = check_text(text).model
checked = time.perf_counter()
if method == "check":
    from robosc.plant import build_network
    from robosc.synthesis.symbolic import synthesize_monolithic
    from robosc.synthesis.counting.synthesis import synthesize_counted
    network = build_network(model)
    mono, fleet = synthesize_monolithic(network), synthesize_counted(network, least=2)
    if fleet.method != "symmetric":  # not counted: the same method twice, nothing to compare
        print(json.dumps({"same": "n/a (not counted: " + str(fleet.fleet)[:40] + ")"}))
        raise SystemExit(0)
    assert mono.ok == fleet.ok
    fp = mono.fixpoint
    enc = fp.enc
    for mine, theirs in zip(mono.guards, fleet.guards, strict=True):
        added = enc.boolean(theirs.added) if theirs.added is not None else enc.true
        # case by case: where the requirements allow it (their union can be exponential, as for
        # the last robots of a ring with homes), the counted method allows it exactly where the
        # monolithic one does
        event = mine.event
        counted_allows = fp.enabled[event] & added
        for part in fp.allowed.parts[event]:
            assert fp.reachable & part & ~counted_allows.equiv(fp.allowed.within[event]) == enc.false, event.name
    print(json.dumps({"same": True}))
    raise SystemExit(0)
result = synthesize_model(model, options=SynthesisOptions(fleet=method))
done = time.perf_counter()
effort = result.effort or {}
from robosc.language.render import render
condition = max((len(render(g.added)) for g in result.guards if g.added is not None), default=0)
module = allowed_us = None
if result.ok:
    import statistics
    from robosc.api import plan_supervisor, supervisor_module
    from robosc.debug.simulator import load_module
    module = len(supervisor_module(result).encode())
    Robot = load_module(plan_supervisor(result)).Robot
    try:
        robot = Robot(seed=0, wait_for_data=False, confirmed=True)
    except TypeError:  # a revision before the belief was confirmed
        robot = Robot(seed=0, wait_for_data=False)
    times = []
    for _ in range(300):  # what is allowed where the fleet starts, evaluated as the coordinator does
        begin = time.perf_counter()
        robot._allowed()
        times.append(time.perf_counter() - begin)
    allowed_us = statistics.median(times) * 1e6
print(json.dumps({
    "condition": condition, "module": module, "allowed_us": allowed_us,
    "lines": len(text.splitlines()), "check": checked - start, "synthesis": done - checked,
    "states": result.reachable_states, "ok": result.ok, "added": len(result.added_guards),
    "rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, **effort,
}))
"""


def checkout(revision: str, work: Path) -> Path:
    """The ``src`` folder of ``revision`` of this repository (git archive), to run it side by side."""
    target = work / revision
    target.mkdir(parents=True)
    archive = subprocess.run(
        ["git", "-C", str(HERE.parent), "archive", revision, "src"], capture_output=True, check=True
    )
    subprocess.run(["tar", "-x", "-C", str(target)], input=archive.stdout, check=True)
    return target / "src"


def measure(
    family: str, n: int, method: str, timeout: float, memory_gb: float, source: Path | None = None
) -> dict[str, object]:
    limit = int(memory_gb * (1 << 30))

    def cap() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

    start = time.perf_counter()
    try:
        env = {**os.environ, "PYTHONPATH": str(source)} if source is not None else None
        done = subprocess.run(
            [sys.executable, "-c", RUN, str(HERE), family, str(n), method],
            capture_output=True,
            text=True,
            timeout=timeout,
            preexec_fn=cap,
            check=False,
            env=env,
        )
    except subprocess.TimeoutExpired:
        return {"failed": f"over {timeout:g} s"}
    wall = time.perf_counter() - start
    if done.returncode != 0:
        last = (done.stderr.strip().splitlines() or ["?"])[-1]
        return {"failed": "out of memory" if "MemoryError" in done.stderr else last[:60], "wall": wall}
    figures: dict[str, object] = json.loads(done.stdout.strip().splitlines()[-1])
    figures["wall"] = wall
    return figures


def command_seconds(
    family: str, n: int, args: list[str], timeout: float, source: Path | None = None
) -> float | str:
    """Wall seconds of ``robosc ARGS FILE`` on the family's model (``source``: the revision's
    sources to run), or why it did not finish."""
    sys.path.insert(0, str(HERE))
    from families import FLEETS

    with tempfile.TemporaryDirectory() as folder:
        model = Path(folder) / f"{family}{n}.rscd"
        model.write_text(FLEETS[family](n))
        command = [sys.executable, "-m", "robosc", *[a.replace("{out}", folder + "/out") for a in args], str(model)]
        env = {**os.environ, "PYTHONPATH": str(source)} if source is not None else None
        start = time.perf_counter()
        try:
            done = subprocess.run(command, capture_output=True, text=True, timeout=timeout, check=False, env=env)
        except subprocess.TimeoutExpired:
            return f"over {timeout:g} s"
        if done.returncode not in (0, 1):
            return (done.stderr.strip().splitlines() or ["?"])[-1][:40]
        return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="2,4,8,16,32")
    parser.add_argument("--families", default="ring,warehouse")
    parser.add_argument("--methods", default="counted,monolithic")
    parser.add_argument("--timeout", type=float, default=600.0)
    parser.add_argument("--memory-gb", type=float, default=2.0)
    parser.add_argument("--commands", action="store_true", help="also time robosc synthesize and robosc build")
    parser.add_argument(
        "--baseline",
        help="a git revision run side by side, its methods marked @REV (e.g. 14910d1, before this session)",
    )
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as work:
        baseline = checkout(args.baseline, Path(work)) if args.baseline else None
        table(args, baseline)


def table(args: argparse.Namespace, baseline: Path | None) -> None:
    sizes = [int(s) for s in args.sizes.split(",")]
    print(f"limits: {args.timeout:g} s and {args.memory_gb:g} GB of address space per run\n")
    print(
        "| family | N | method | lines | wall s | synthesis s | peak MB | peak live nodes | images | preimages "
        "| controlled states | largest added condition, chars | module, KB | what is allowed, us | same supervisor |"
        + (" robosc synthesize s | synthesize --json s | robosc build s | synthesize / build |" if args.commands else "")
    )
    print("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|" + ("---:|---:|---:|---:|" if args.commands else ""))
    methods = args.methods.split(",")
    for family in args.families.split(","):
        for n in sizes:
            finished = 0
            runs = [(m, m, None) for m in methods]
            if baseline is not None:  # each method of this revision next to the baseline's
                runs = [r for m in methods for r in ((m, m, None), (f"{m}@{args.baseline}", m, baseline))]
            for label, method, source in runs:
                f = measure(family, n, method, args.timeout, args.memory_gb, source)
                if "failed" in f:
                    print(f"| {family} | {n} | {label} | | | {f['failed']} | | | | | | | | | |", flush=True)
                    continue
                same = ""
                finished += source is None  # the baseline's runs are not compared
                if source is None and finished == 2 and set(methods) >= {"counted", "monolithic"} and n >= 2:
                    check = measure(family, n, "check", args.timeout, args.memory_gb)
                    found = check.get("same")
                    same = found if isinstance(found, str) else "yes (asserted)" if found else f"NO: {check.get('failed')}"
                print(
                    f"| {family} | {n} | {label} | {f['lines']} | {f['wall']:.2f} | {f['synthesis']:.2f} | "
                    f"{f['rss_mb']:.0f} | {f.get('peak_live_nodes', '-'):,} | {f.get('images', '-')} | "
                    f"{f.get('preimages', '-')} | {f['states']:,} | {f['condition']:,} | "
                    f"{'-' if f['module'] is None else format(f['module'] / 1024, ',.0f')} | "
                    f"{'-' if f.get('allowed_us') is None else format(f['allowed_us'], ',.0f')} | {same} |"
                    + (commands(family, n, method, args.timeout, source) if args.commands else ""),
                    flush=True,
                )


def commands(family: str, n: int, method: str, timeout: float, source: Path | None) -> str:
    """The table's last four cells: ``robosc synthesize`` (text, then ``--json``), ``robosc
    build``, and the ratio of the slower synthesize to build."""
    text = command_seconds(family, n, ["synthesize", "--fleet", method], timeout, source)
    json_ = command_seconds(family, n, ["synthesize", "--json", "--fleet", method], timeout, source)
    build = command_seconds(family, n, ["build", "-o", "{out}"], timeout, source)
    ratio = "-"
    if isinstance(text, float) and isinstance(json_, float) and isinstance(build, float):
        ratio = f"{max(text, json_) / build:.1f}"

    def cell(x: float | str) -> str:
        return f"{x:.1f}" if isinstance(x, float) else x

    return f" {cell(text)} | {cell(json_)} | {cell(build)} | {ratio} |"


if __name__ == "__main__":
    main()
