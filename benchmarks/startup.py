"""Start-up benchmark (issue target): ``robosc check`` on an example within 1.5x of
``python -c "import lark"`` end to end, and ``robosc synthesize`` within 1.5x of importing
lark and dd, measured side by side (interleaved runs, medians), plus ``robosc --version``.

Run: python benchmarks/startup.py [--repeat 15] [--example examples/line_follower.rscd]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ROBOSC = [sys.executable, "-m", "robosc"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=15)
    parser.add_argument("--example", default=str(ROOT / "examples" / "line_follower.rscd"))
    args = parser.parse_args()
    # as after an install: every module compiled to bytecode (a module edited since its last
    # compile would be compiled again on every start where writing bytecode is off)
    import compileall

    import robosc

    compileall.compile_dir(Path(robosc.__file__).parent, quiet=1)
    runs = {
        "python (nothing imported)": [sys.executable, "-c", "pass"],
        "import lark": [sys.executable, "-c", "import lark"],
        # the floor of any click command line that parses: what robosc's own code adds is above it
        "import lark, click": [sys.executable, "-c", "import lark, click"],
        "robosc check": [*ROBOSC, "check", args.example],
        # dd imports networkx when it can; robosc's command keeps it out (cli/main.py), so
        # the floor does too
        "import lark, dd.cudd": [
            sys.executable,
            "-c",
            "import sys; sys.modules['networkx'] = None; import lark, dd.cudd",
        ],
        "robosc synthesize": [*ROBOSC, "synthesize", args.example],
        "robosc --version": [*ROBOSC, "--version"],
    }
    times: dict[str, list[float]] = {name: [] for name in runs}
    for _ in range(args.repeat):  # interleaved, so that a noisy moment hits every command alike
        for name, command in runs.items():
            start = time.perf_counter()
            subprocess.run(command, cwd=ROOT, capture_output=True, check=True)
            times[name].append(time.perf_counter() - start)
    median = {name: statistics.median(values) for name, values in times.items()}
    for name, value in median.items():
        print(f"{name:<28} median {value * 1000:7.1f} ms   (min {min(times[name]) * 1000:.1f})")
    check = median["robosc check"] / median["import lark"]
    synthesize = median["robosc synthesize"] / median["import lark, dd.cudd"]
    print(f"check / import lark:            {check:.2f}x (target 1.5x)")
    print(f"synthesize / import lark, dd:   {synthesize:.2f}x (target 1.5x)")
    floor = median["import lark, click"] / median["import lark"]
    print(f"import lark, click / import lark: {floor:.2f}x (the command-line library alone)")


if __name__ == "__main__":
    main()
