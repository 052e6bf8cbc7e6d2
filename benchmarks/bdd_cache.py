"""CUDD's initial computed-table size (``robosc.synthesis.encoding.CACHE_SLOTS``) side by
side with dd's default: the time to make a BDD manager and symbolic synthesis time on the
benchmark families, each run in its own process, interleaved, medians.

Run: python benchmarks/bdd_cache.py [--repeat 7]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CASES = [("transfer_line", 8), ("transfer_line", 24), ("philosophers", 8), ("philosophers", 14), ("enum_sensors", 32)]
SIZES = {"dd's default (2^18)": None, "2^16": 2**16}
PROGRAM = """
import sys, time
sys.path.insert(0, {benchmarks!r})
import dd.cudd
from families import enum_sensors, philosophers, transfer_line
from robosc.api import check_text, synthesize_model
from robosc.synthesis import encoding
size = None if sys.argv[3] == "None" else int(sys.argv[3])
start = time.perf_counter()
dd.cudd.BDD(initial_cache_size=size)
made = time.perf_counter() - start
encoding.CACHE_SLOTS = size
family = {{"transfer_line": transfer_line, "enum_sensors": enum_sensors, "philosophers": philosophers}}[sys.argv[1]]
model = check_text(family(int(sys.argv[2])), "/tmp/family.rscd").model
start = time.perf_counter()
synthesize_model(model)
print(made, time.perf_counter() - start)
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    program = PROGRAM.format(benchmarks=str(ROOT / "benchmarks"))
    times: dict[tuple[str, str], list[tuple[float, float]]] = {}
    for _ in range(args.repeat):
        for family, n in CASES:
            for label, size in SIZES.items():
                out = subprocess.run(
                    [sys.executable, "-c", program, family, str(n), str(size)],
                    capture_output=True,
                    text=True,
                    check=True,
                    cwd=ROOT,
                )
                made, took = (float(x) for x in out.stdout.split())
                times.setdefault((f"{family} {n}", label), []).append((made, took))
    for (case, label), values in times.items():
        made = statistics.median(v[0] for v in values) * 1000
        took = statistics.median(v[1] for v in values)
        print(f"{case:<18} {label:<20} manager {made:5.1f} ms   synthesis {took:7.3f} s")


if __name__ == "__main__":
    main()
