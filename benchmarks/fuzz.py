"""The large fuzz run (issue target: no crash): mutated examples through check, synthesize
and generate, each with a time limit, in a process with a memory limit. Prints the
outcomes, the crash count and one example per distinct crash.

Run: python benchmarks/fuzz.py [--count 10000] [--seed 1] [--seconds 20] [--memory-gb 4]
"""

from __future__ import annotations

import argparse
import collections
import random
import resource
import signal
import sys
import tempfile
import time
import traceback
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mutate import SOURCES, mutate, pipeline


class Timeout(Exception):
    pass


def _alarm(signum: int, frame: Any) -> None:
    raise Timeout


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=10000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--seconds", type=int, default=20, help="time limit per input")
    parser.add_argument("--memory-gb", type=float, default=4.0)
    args = parser.parse_args()
    limit = int(args.memory_gb * 2**30)
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    signal.signal(signal.SIGALRM, _alarm)
    rng = random.Random(args.seed)
    outcomes: collections.Counter[str] = collections.Counter()
    crashes: dict[str, tuple[int, str]] = {}
    names = sorted(SOURCES)
    start = time.monotonic()
    with tempfile.TemporaryDirectory() as work:
        for number in range(args.count):
            name = rng.choice(names)
            text = mutate(SOURCES[name], rng, rng.randint(1, 4))
            signal.alarm(args.seconds)
            try:
                outcomes[pipeline(text, name, Path(work))] += 1
            except Timeout:
                outcomes["timeout"] += 1
                crashes.setdefault("timeout", (number, text))
            except Exception as exc:  # a crash: remember one input per place it happened
                frame = traceback.extract_tb(exc.__traceback__)[-1]
                key = f"{type(exc).__name__} at {Path(frame.filename).name}:{frame.lineno}"
                outcomes["crash"] += 1
                crashes.setdefault(key, (number, text))
            finally:
                signal.alarm(0)
    seconds = time.monotonic() - start
    print(f"{args.count} mutated models in {seconds:.0f} s (seed {args.seed})")
    for outcome, count in outcomes.most_common():
        print(f"  {outcome:<16} {count}")
    print(f"crashes: {outcomes['crash']}, timeouts: {outcomes['timeout']}, distinct: {len(crashes)}")
    for key, (number, text) in crashes.items():
        print(f"--- {key} (input {number}):\n{text[:2000]}")


if __name__ == "__main__":
    main()
