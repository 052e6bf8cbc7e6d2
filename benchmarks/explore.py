"""The explorations side by side (docs/synthesis-options.md): auto (the default), saturation and
chained, on the order benchmark's models and larger fleets. For each: synthesis time, peak live
BDD nodes, images and preimages, peak memory, controlled states (which must agree). Each run is a
process of its own with a time limit.

Run:  python benchmarks/explore.py [--timeout 300] [--models 'ring 24 (instances; counted)',...]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from orders import MODELS, rows

MODELS.update(
    {
        "ring 8 (copies; counted)": ("ring", 8, "counted"),
        "ring 24 (instances; counted)": ("ring_instances", 24, "counted"),
        "warehouse 16 (instances; counted)": ("warehouse_instances", 16, "counted"),
        "enum sensors 32": ("enum_sensors", 32, "monolithic"),
    }
)
EXPLORATIONS = ("auto", "saturation", "chained")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--timeout", type=float, default=300.0)
    parser.add_argument("--models", default=",".join(MODELS), help="names of MODELS, comma-separated")
    args = parser.parse_args()
    print(f"limit: {args.timeout:g} s per run\n")
    print("| model | exploration | synthesis s | peak live nodes | images | preimages | peak MB | controlled states |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for name in args.models.split(","):
        rows(
            name,
            [("interaction", explore) for explore in EXPLORATIONS],
            args.timeout,
            lambda f, _, explore: f"{explore} | {f['s']:.2f} | {f['peak_live_nodes']:,} | {f['images']:,} | "
            f"{f['preimages']:,} | {f['mb']:.0f}",
        )


if __name__ == "__main__":
    main()
