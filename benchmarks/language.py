"""Language front-end benchmark (issue targets):

* loading and checking a generated 5,000-line model takes under 1 s;
* ``robosc check examples/maze_solver.rscd`` end to end (process start included) under 0.5 s.

Run: python benchmarks/language.py [--lines 5000] [--repeat 5]
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

from robosc.api import check_text

ROOT = Path(__file__).resolve().parent.parent


def component(i: int) -> str:
    return f"""
    datatype enum Level{i} from LaserScan to {{
        value.ranges[{i % 360}] < 0.5 -> near{i}
        value.ranges[{(i + 90) % 360}] < 1.0 or value.ranges[{(i + 180) % 360}] < 1.0 -> mid{i}
        default -> far{i}
    }}

    component Part{i} {{
        outgoing message scan{i} with identifier: "/part{i}/scan", type: Level{i} links laser_scan
        outgoing message done{i} with identifier: "/part{i}/done", type: none
        incoming message go{i} with identifier: "/part{i}/go", type: Twist links twist
        service reset{i} with identifier: "/part{i}/reset", request: none, response: boolean links trigger

        behaviour {{
            variable level: Level{i} = far{i}
            variable count: integer(0..5) = 0

            on response from scan{i} do level := value

            initial marked state idle{i} {{
                on request to go{i} goto busy{i}
                transition if count = 5 goto full{i}
            }}

            state busy{i} {{
                on response from done{i} do count := count + 1 goto idle{i}
            }}

            state full{i} {{
                on request to reset{i}
                on response from reset{i} do count := 0 goto idle{i}
                on error from reset{i} goto idle{i}
            }}
        }}
    }}

    requirement go{i} needs Part{i}.level = far{i} and Part{i}.count < 5 and (Part{max(i - 1, 0)}.idle{max(i - 1, 0)} or Part{i}.level != near{i})
    requirement Part{i}.busy{i} disables {{reset{i}}}
    provide go{i} with {{ linear: {{ x: 0.1 * {i % 7}.0 }}, angular: {{ z: 0.0 }} }} if Part{i}.level = far{i}
"""


HEADER = """robot Generated {
    datatype object Vector3 {
        x: double
        y: double
        z: double
    }

    datatype object Twist {
        linear: Vector3
        angular: Vector3
    }

    datatype object LaserScan {
        ranges: array(double)
    }

    interface twist use Twist from geometry_msgs
    interface laser_scan use LaserScan from sensor_msgs
    interface trigger use Trigger from std_srvs
"""


def generated_model(lines: int) -> str:
    parts = [HEADER]
    i = 0
    while sum(p.count("\n") for p in parts) < lines - 1:
        parts.append(component(i))
        i += 1
    return "".join(parts) + "}\n"


def time_in_process(text: str, repeat: int) -> list[float]:
    check_text(text, "generated.rscd")  # warm: grammar tables are built once per process
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        result = check_text(text, "generated.rscd")
        times.append(time.perf_counter() - start)
        assert result.ok, result.render()[:2000]
    return times


def time_cli(repeat: int) -> list[float]:
    robosc = shutil.which("robosc") or str(Path(sys.executable).with_name("robosc"))
    command = [robosc, "check", str(ROOT / "examples" / "maze_solver.rscd")]
    subprocess.run(command, check=True, capture_output=True)  # warm the OS file cache and Lark's cache
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True)
        times.append(time.perf_counter() - start)
    return times


def report(label: str, times: list[float], target: float) -> None:
    median = statistics.median(times)
    verdict = "meets" if median < target else "MISSES"
    print(
        f"{label}: median {median * 1000:.1f} ms, min {min(times) * 1000:.1f} ms, "
        f"max {max(times) * 1000:.1f} ms over {len(times)} runs ({verdict} the {target * 1000:.0f} ms target)"
    )


def parse_side_by_side(text: str, repeat: int) -> None:
    """Parsing alone: Lark (when installed) and robosc's runner of the tables Lark made."""
    import gc

    from robosc.language import lalr
    from robosc.language.grammar_compile import GRAMMAR
    from robosc.language.parser import file_tables

    try:
        import lark
    except ImportError:
        return
    keep = {"LINE_COMMENT": lambda t: t, "BLOCK_COMMENT": lambda t: t}
    by_lark = lark.Lark(
        GRAMMAR.read_text(), parser="lalr", lexer="basic", propagate_positions=True, maybe_placeholders=False, lexer_callbacks=keep
    )
    tables = file_tables()
    times: dict[str, list[float]] = {"Lark": [], "robosc.language.lalr": []}
    gc.disable()
    for _ in range(repeat):  # interleaved
        start = time.perf_counter()
        by_lark.parse(text)
        times["Lark"].append(time.perf_counter() - start)
        start = time.perf_counter()
        lalr.parse(tables, text, "start", [])
        times["robosc.language.lalr"].append(time.perf_counter() - start)
    gc.enable()
    shown = ", ".join(f"{name} {statistics.median(t) * 1000:.0f} ms" for name, t in times.items())
    print(f"parse alone, same text, medians of {repeat}: {shown}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lines", type=int, default=5000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    text = generated_model(args.lines)
    n_lines = text.count("\n")
    print(f"generated model: {n_lines} lines, {len(text)} characters")
    report(f"load + check, {n_lines}-line model (in process)", time_in_process(text, args.repeat), 1.0)
    report("robosc check examples/maze_solver.rscd (process start included)", time_cli(args.repeat), 0.5)
    parse_side_by_side(text, args.repeat)


if __name__ == "__main__":
    main()
