"""One physics environment for the whole fleet against one per robot: simulated steps per
second of wall time with N robots driving, in one run (IR-SIM, no middleware).

A ``shared`` world (robots are bodies to each other: each LiDAR sees the others, contact is a
collision) puts every robot in one IR-SIM environment; otherwise each robot has an environment
of its own. Both are stepped here with every robot driving forward on a free floor (robots in a
row, 1 m apart, each with a 360-beam LiDAR read 10 times a simulated second).

    python benchmarks/sim_world.py [--sizes 2 4 8 16] [--steps 200]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))

from robosc.sim.simulation import Simulation  # noqa: E402
from robosc.sim.world import load_world  # noqa: E402


def world(n: int, shared: bool, folder: Path) -> Path:
    starts = "\n".join(f"  - [1.0, {1.0 + i}, 0]" for i in range(n))
    path = folder / f"row_{n}_{shared}.yaml"
    path.write_text(
        f"world: row\nsize: [40, {n + 2}]\nshared: {str(shared).lower()}\n"
        "robot: {radius: 0.2, max_linear: 0.3, command_timeout: 0.3}\n"
        f"starts:\n{starts}\ngoal: {{x: [39, 40], y: [0, {n + 2}]}}\n",
        encoding="utf-8",
    )
    return path


def steps_per_second(n: int, shared: bool, steps: int, folder: Path) -> float:
    sim = Simulation(load_world(world(n, shared, folder)), robots=n)
    start = time.perf_counter()
    for _ in range(steps):
        for i in range(n):
            sim.command_velocity(i, 0.3, 0.0)
        sim.step()
    return steps / (time.perf_counter() - start)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[2, 4, 8, 16])
    parser.add_argument("--steps", type=int, default=200)
    args = parser.parse_args()
    print("| robots | one environment (shared), steps/s | one per robot, steps/s | shared / separate |")
    print("|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as folder:
        for n in args.sizes:
            shared, separate = (steps_per_second(n, s, args.steps, Path(folder)) for s in (True, False))
            print(f"| {n} | {shared:,.0f} | {separate:,.0f} | {shared / separate:.2f} |", flush=True)


if __name__ == "__main__":
    main()
