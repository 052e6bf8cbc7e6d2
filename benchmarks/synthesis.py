"""Synthesis benchmark: symbolic (BDD) synthesis, explicit-state synthesis and libFAUDES
side by side on scaling families, each run in its own process with a time limit.

Targets (issue): every example end to end under 1 s (process start included);
2^20 reachable states in under 5 s symbolically; symbolic time polynomial in N
where the explicit methods grow exponentially; where libFAUDES stops finishing
within 60 s.

Run:  python benchmarks/synthesis.py [--limit 60] [--write docs/performance.md]
"""

from __future__ import annotations

import argparse
import multiprocessing
import re
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from families import FAMILIES

ROOT = Path(__file__).resolve().parent.parent
SIZES = {
    "transfer line (N machines, N-1 buffers)": [2, 3, 4, 5, 6, 8, 12, 16, 24, 32, 48, 64],
    "enum sensors (N components)": [2, 4, 8, 12, 14, 16, 20, 24, 32, 48, 64],
    "dining philosophers (N)": [2, 3, 4, 5, 6, 7, 8, 10, 12, 14, 16, 18, 20],
}


def _run(method: str, text: str, queue: multiprocessing.Queue) -> None:  # type: ignore[type-arg]
    from robosc.api import check_text
    from robosc.plant import build_network
    from robosc.synthesis.explicit import synthesize_explicit
    from robosc.synthesis.methods import synthesize_symbolic

    sys.path.insert(0, str(ROOT / "tests"))
    from test_synthesis_faudes import faudes_supervisor

    network = build_network(check_text(text).model)  # type: ignore[arg-type]
    start = time.perf_counter()  # everything is imported and the network built: time synthesis alone
    if method == "symbolic":
        result = synthesize_symbolic(network)
        queue.put((time.perf_counter() - start, result.reachable_states, result.ok))
    elif method == "explicit":
        result = synthesize_explicit(network, max_states=10**9)
        queue.put((time.perf_counter() - start, result.reachable_states, result.ok))
    else:
        states = faudes_supervisor(network)
        queue.put((time.perf_counter() - start, None if states is None else states[0], None))


def measure(method: str, text: str, limit: float) -> tuple[float, int | None] | str:
    queue: multiprocessing.Queue = multiprocessing.Queue()  # type: ignore[type-arg]
    process = multiprocessing.Process(target=_run, args=(method, text, queue))
    process.start()
    process.join(limit)
    if process.is_alive():
        process.kill()
        process.join()
        return "timeout"
    if queue.empty():
        return "failed"
    seconds, states, _ = queue.get()
    return seconds, states


def fmt(result: tuple[float, int | None] | str | None) -> str:
    if result is None:
        return "-"
    if isinstance(result, str):
        return result
    return f"{result[0]:.3f} s"


def ratio(slow: object, fast: object) -> str:
    if isinstance(slow, tuple) and isinstance(fast, tuple) and fast[0] > 0:
        return f"{slow[0] / fast[0]:.1f}x"
    return "-"


def examples_end_to_end(repeat: int = 5) -> list[str]:
    robosc = shutil.which("robosc") or str(Path(sys.executable).with_name("robosc"))
    rows = []
    for name in ["line_follower", "maze_solver", "pick_and_light"]:
        command = [robosc, "synthesize", str(ROOT / "examples" / f"{name}.rscd")]
        subprocess.run(command, check=True, capture_output=True)
        times = []
        for _ in range(repeat):
            start = time.perf_counter()
            out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
            times.append(time.perf_counter() - start)
        states = re.search(r"(\d+) reachable states", out)
        rows.append(
            f"| `robosc synthesize examples/{name}.rscd` | {states.group(1) if states else '?'} | "
            f"{statistics.median(times) * 1000:.0f} ms | {max(times) * 1000:.0f} ms |"
        )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--limit", type=float, default=60.0, help="seconds allowed per run")
    parser.add_argument("--write", type=Path, help="replace the synthesis section of this markdown file")
    args = parser.parse_args()
    out = ["## Synthesis (`benchmarks/synthesis.py`)", ""]
    out.append(
        f"Command: `.venv/bin/python benchmarks/synthesis.py --limit {args.limit:.0f}`. Each run in its own "
        f"process, stopped after {args.limit:.0f} s; times exclude parsing and plant construction."
    )
    out += ["", "### The examples end to end (process start included, median of 5)", ""]
    out += ["| command | reachable states | median | max |", "|---|---|---|---|"]
    out += examples_end_to_end()
    print("\n".join(out), flush=True)
    for family, build in FAMILIES.items():
        section = [
            "",
            f"### {family}",
            "",
            "| N | reachable states | symbolic | explicit | libFAUDES | explicit / symbolic | libFAUDES / symbolic |",
            "|---|---|---|---|---|---|---|",
        ]
        print("\n".join(section), flush=True)
        out += section
        stopped: set[str] = set()
        for n in SIZES[family]:
            text = build(n)
            results: dict[str, object] = {}
            for method in ["symbolic", "explicit", "faudes"]:
                if method in stopped:
                    results[method] = "skipped"
                    continue
                if method == "faudes" and family.startswith("enum"):
                    results[method] = "n/a (variables)"
                    continue
                result = measure(method, text, args.limit)
                results[method] = result
                if isinstance(result, str):
                    stopped.add(method)
            symbolic = results["symbolic"]
            states = symbolic[1] if isinstance(symbolic, tuple) else "?"
            row = (
                f"| {n} | {states} | {fmt(symbolic)} | {fmt(results['explicit'])} | "  # type: ignore[arg-type]
                f"{fmt(results['faudes'])} | {ratio(results['explicit'], symbolic)} | "  # type: ignore[arg-type]
                f"{ratio(results['faudes'], symbolic)} |"
            )
            print(row, flush=True)
            out.append(row)
            if "symbolic" in stopped:
                break
    if args.write:
        document = args.write.read_text() if args.write.exists() else "# Performance\n"
        section = "\n".join(out) + "\n"
        if "## Synthesis" in document:
            document = re.sub(r"## Synthesis.*?(?=\n## |\Z)", section, document, flags=re.S)
        else:
            document = document.rstrip("\n") + "\n\n" + section
        args.write.write_text(document)
        print(f"\nwrote {args.write}")


if __name__ == "__main__":
    main()
