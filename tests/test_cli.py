"""``robosc check`` and ``robosc fmt`` exit codes and output."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import EXAMPLES, robot
from robosc.cli.main import main


def run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "robosc", *args], capture_output=True, text=True, timeout=60, check=False
    )


def test_check_examples_exit_zero():
    result = run("check", *(str(p) for p in sorted(EXAMPLES.glob("*.rscd"))))
    assert result.returncode == 0, result.stderr
    assert result.stdout.count(": ok") == 6


def test_check_model_with_errors_exits_one(tmp_path: Path):
    bad = tmp_path / "bad.rscd"
    bad.write_text(robot("requirement act needs S.idel"))
    result = run("check", str(bad))
    assert result.returncode == 1
    assert f"{bad}:12:25: error: unknown state or variable 'idel'" in result.stderr
    assert "Traceback" not in result.stderr


def test_check_json(tmp_path: Path):
    bad = tmp_path / "bad.rscd"
    bad.write_text(robot("requirement act needs S.idel"))
    result = run("check", "--format", "json", str(bad))
    assert result.returncode == 1
    assert json.loads(result.stdout)[0]["message"] == "unknown state or variable 'idel' in component 'S'"


def test_warnings_alone_exit_zero(tmp_path: Path, capsys):
    model = tmp_path / "w.rscd"
    model.write_text(
        robot(
            'component A { outgoing message a with identifier: "/t", type: none }',
            'component B { outgoing message b with identifier: "/t", type: none }',
        )
    )
    assert main(["check", str(model)]) == 0
    out = capsys.readouterr().out
    assert "warning: 'B' and 'A' both publish to topic '/t'" in out and "ok (1 warning)" in out


def test_include_option_finds_libraries(tmp_path: Path):
    model = tmp_path / "r.rscd"
    model.write_text(robot("component E from EmergencyStopLibrary import EmergencyStop"))
    assert main(["check", str(model)]) == 1
    assert main(["check", "-I", str(EXAMPLES), str(model)]) == 0


@pytest.mark.parametrize(
    ("setup", "message"),
    [
        (lambda d: str(d / "missing.rscd"), "no such file"),
        (lambda d: str(d), "is a directory"),
        (lambda d: (d / "x.rscd").write_bytes(b"robot R { \xff }") and str(d / "x.rscd"), "not UTF-8"),
    ],
)
def test_input_problems_exit_two(tmp_path: Path, capsys, setup, message: str):
    path = setup(tmp_path)
    assert main(["check", path]) == 2
    assert message in capsys.readouterr().err


def test_usage_errors_exit_two(capsys):
    assert main(["check"]) == 2
    assert main(["frobnicate"]) == 2


def test_fmt_prints_canonical_layout(tmp_path: Path, capsys):
    model = tmp_path / "m.rscd"
    model.write_text("robot   R{component C{outgoing message m with type:none}requirement m needs true}")
    assert main(["fmt", str(model)]) == 0
    assert capsys.readouterr().out == (
        "robot R {\n"
        "    component C {\n"
        "        outgoing message m with type: none\n"
        "    }\n\n"
        "    requirement m needs true\n"
        "}\n"
    )
    assert main(["fmt", "--check", str(model)]) == 1
    assert main(["fmt", "--write", str(model)]) == 0
    assert main(["fmt", "--check", str(model)]) == 0


def test_fmt_syntax_error_exits_one(tmp_path: Path, capsys):
    model = tmp_path / "m.rscd"
    model.write_text("robot R {")
    assert main(["fmt", str(model)]) == 1
    assert "m.rscd:1:10: error: unexpected end of file" in capsys.readouterr().err


def test_synthesize_explains_added_conditions_and_warns(tmp_path: Path):
    from test_synthesis import GRAB

    model = tmp_path / "grab.rscd"
    model.write_text(GRAB)
    result = run("synthesize", str(model))
    assert result.returncode == 0, result.stderr
    assert "grab.c_trigger (never allowed):" in result.stdout
    assert "1. grab.u_error  ->  grab.error, Grabber.grabbing" in result.stdout
    assert f"{model}:5:9: warning: synthesis never allows 'grab.c_trigger'" in result.stderr
    assert "    hint: fix: add 'on error from grab' to state grabbing of Grabber" in result.stderr
    assert "      fix: add 'on error from grab' to state grabbing of Grabber" in result.stdout
    data = json.loads(run("synthesize", "--json", str(model)).stdout)
    grab = next(e for e in data["events"] if e["event"] == "grab.c_trigger")
    assert grab["added"] == "false" and grab["why"]["never"] is True
    assert [s["event"] for s in grab["why"]["consequence"]["path"]] == ["grab.u_error"]
    [fix] = grab["why"]["consequence"]["fixes"]
    assert fix["text"].startswith("add 'on error from grab'") and (fix["path"], fix["line"], fix["column"]) == (
        str(model),
        12,
        13,
    )
    assert {w["code"] for w in data["warnings"]} == {"never-allowed", "never-holds", "unreached-state"}
    assert all(w["severity"] == "warning" and w["line"] > 0 for w in data["warnings"])


def test_platform_claims_match_what_installs():
    """requires-python is no lower than what every dependency needs, and README says the same."""
    import re
    import tomllib
    from importlib.metadata import metadata

    root = Path(__file__).resolve().parent.parent
    project = tomllib.loads((root / "pyproject.toml").read_text())["project"]
    ours = project["requires-python"]
    lowest = tuple(int(x) for x in re.fullmatch(r">=(\d+)\.(\d+)", ours.strip()).groups())
    dependencies = [re.match(r"[A-Za-z0-9_.-]+", d).group() for d in project["dependencies"]]
    assert "dd" in dependencies and "click" in dependencies
    for dependency in dependencies:
        needed = metadata(dependency).get("Requires-Python") or ""
        found = re.search(r">=\s*(\d+)\.(\d+)", needed)
        if found:
            assert tuple(int(x) for x in found.groups()) <= lowest, (dependency, needed, ours)
    assert f"Python {lowest[0]}.{lowest[1]} or newer" in (root / "README.md").read_text()


def run_in(columns: str | None, *args: str) -> subprocess.CompletedProcess[str]:
    import os

    env = {k: v for k, v in os.environ.items() if k != "COLUMNS"}
    if columns is not None:
        env["COLUMNS"] = columns
    return subprocess.run(
        [sys.executable, "-m", "robosc", *args], capture_output=True, text=True, timeout=120, check=False, env=env
    )


@pytest.mark.parametrize("example", sorted(p.name for p in EXAMPLES.glob("*.rscd") if p.name != "emergency_stop.rscd"))
def test_synthesize_fits_the_width_columns_asks_for(example: str) -> None:
    """COLUMNS=100: no line of the table, the explanations or the warnings is wider (before:
    rows of 261 characters, warnings of over 600); piped without COLUMNS, each warning stays
    on one line, for programs that read it, and the table is kept to 160 columns (before: as
    wide as its longest condition, tens of thousands of characters for a fleet)."""
    narrow = run_in("100", "synthesize", str(EXAMPLES / example))
    assert narrow.returncode == 0, narrow.stderr
    lines = (narrow.stdout + narrow.stderr).splitlines()
    assert max(len(line) for line in lines) <= 100, max(lines, key=len)
    piped = run_in(None, "synthesize", str(EXAMPLES / example))
    assert len(piped.stdout.splitlines()) <= len(narrow.stdout.splitlines())
    table = [line for line in piped.stdout.splitlines() if line[:1] in "┏┃┡│└"]
    assert table and max(len(line) for line in table) <= 160, max(table, key=len)
    warnings = [line for line in piped.stderr.splitlines() if ": warning: " in line]
    assert len(warnings) == piped.stderr.count(": warning: ")  # one line each
    if example == "maze_solver.rscd":
        at = next(i for i, line in enumerate(table) if "│ movement " in line)
        cells = [line.split("│")[2].strip() for line in table[at:] if line.startswith("│")]
        end = next(i for i, cell in enumerate(cells) if cell.endswith("no_wall_diag_right))"))
        assert end > 0  # the condition wraps within its cell, all of it there
        assert " ".join(cells[: end + 1]).startswith("Platform.ready and ((Distance.right = wall_right")


def test_explicit_synthesis_says_it_is_a_cross_check_with_the_figures_it_compares() -> None:
    """Before: an empty table and '0 of 0 controllable events'."""
    done = run_in(None, "synthesize", "--explicit", str(EXAMPLES / "shelf_picker.rscd"))
    assert done.returncode == 0, done.stderr
    assert "explicit-state synthesis of ShelfPicker (a cross-check of the symbolic method" in done.stdout
    assert "controlled system: 1218 reachable states" in done.stdout
    assert "symbolic synthesis: 1218 reachable states, a condition added to 1 of 10 controllable events; they agree" in done.stdout
    assert "0 of 0" not in done.stdout
    data = json.loads(run_in(None, "synthesize", "--explicit", "--json", str(EXAMPLES / "maze_solver.rscd")).stdout)
    assert data["cross_check"] == {
        "method": "symbolic",
        "ok": True,
        "reachable_states": 128,
        "explicit_states_counted_so": 128,
        "agree": True,
        "differences": [],
    }


def test_synthesize_stats_prints_effort_that_does_not_depend_on_the_machine() -> None:
    """--stats: CUDD's peak live nodes and the image / preimage computations, the same on
    every run (wall time is not: the machine is shared)."""
    runs = [json.loads(run_in(None, "synthesize", "--stats", "--json", str(EXAMPLES / "shelf_picker.rscd")).stdout)
            for _ in range(2)]
    first, second = (r["effort"] for r in runs)
    assert first == second
    assert first["peak_live_nodes"] > 100 and first["images"] > 0 and first["preimages"] > 0
    assert first["variables"] > 0
    text = run_in(None, "synthesize", "--stats", str(EXAMPLES / "shelf_picker.rscd")).stdout
    assert f"effort: {first['peak_live_nodes']:,} peak live BDD nodes, {first['images']:,} images" in text
    assert "effort" not in json.loads(run_in(None, "synthesize", "--json", str(EXAMPLES / "shelf_picker.rscd")).stdout)


def test_a_counted_fleet_is_explained_once_for_its_robots_and_in_json() -> None:
    warehouse = str(Path(__file__).resolve().parent.parent / "examples/warehouse.rscd")
    result = run("synthesize", warehouse)
    assert result.returncode == 0, result.stderr
    assert result.stdout.count("(the same for every robot of bot (bot1 .. bot3))") == 1
    assert "      fix: requirement bot1.go needs bot1.out1 => " in result.stdout
    data = json.loads(run("synthesize", "--json", warehouse).stdout)
    why = {e["event"]: e["why"] for e in data["events"] if e["why"] is not None}
    assert sorted(why) == ["bot1.go", "bot2.go", "bot3.go"]
    assert all(w["note"].startswith("the same for every robot of bot") and len(w["path"]) == 10 for w in why.values())


def test_explicit_synthesis_compares_a_counted_fleet_orbit_by_orbit_and_says_they_agree() -> None:
    """Before: 'they DISAGREE' on every counted fleet (241 explicit states against 58 counted)."""
    done = run_in(None, "synthesize", "--explicit", str(EXAMPLES.parent / "docs/models/warehouse_zero_time.rscd"))
    assert done.returncode == 0, done.stderr
    assert "controlled system: 241 reachable states" in done.stdout
    assert "symmetric synthesis: 58 reachable states counted" in done.stdout
    assert "explicit: 58 counted so" in done.stdout
    assert "they agree in every controlled state and event" in done.stdout


def test_explicit_synthesis_of_a_model_too_large_for_it_says_so(monkeypatch: pytest.MonkeyPatch) -> None:
    """Before: 'internal error: TooManyStates'."""
    from click.testing import CliRunner

    from robosc.cli.main import cli
    from robosc.synthesis import explicit

    monkeypatch.setattr(explicit, "MAX_STATES", 1000)  # as over 200,000, sooner
    done = CliRunner().invoke(cli, ["synthesize", "--explicit", str(EXAMPLES / "warehouse.rscd")])
    assert done.exit_code == 2, done.output
    assert "explicit-state synthesis lists every state, and this model has more than 1000 states" in done.output


def test_looking_for_bad_states_only_where_the_requirements_reach_gives_the_same_conditions() -> None:
    """`--forward first` (the default on a counted fleet) and `--forward never` print the same
    conditions for the warehouse; the search differs (its preimages)."""
    from click.testing import CliRunner

    from robosc.cli.main import cli

    said = {}
    for forward in ("first", "never", "auto"):
        done = CliRunner().invoke(cli, ["synthesize", "--stats", "--forward", forward, str(EXAMPLES / "warehouse.rscd")])
        assert done.exit_code == 0, done.output
        lines = done.output.splitlines()
        conditions = [line for line in lines if "reachable states" not in line and not line.startswith("effort:")]
        preimages = re.search(r"([\d,]+) preimages", done.output)
        assert preimages is not None, done.output
        said[forward] = (conditions, preimages.group(1))
    assert said["first"][0] == said["never"][0] == said["auto"][0]
    assert said["first"][1] != said["never"][1] and said["auto"] == said["first"]


PRECEDENCE = """
robot Prec {
    component A {
        incoming message go with type: none
        behaviour {
            initial marked state idle { on request to go goto busy }
            marked state busy { on request to go goto idle }
        }
    }
    component B {
        incoming message run with type: none
        behaviour {
            initial marked state off { on request to run goto running }
            marked state running { on request to run goto off }
        }
    }
    requirement go needs B.running => A.idle and B.running
}
"""


def test_a_warning_check_gives_is_given_by_every_command_that_acts_on_the_model(tmp_path: Path) -> None:
    """`B.running => A.idle and B.running` reads as `(B.running => A.idle) and B.running`:
    check warned, and synthesize, build and generate (and synthesize's JSON) said nothing."""
    model = tmp_path / "prec.rscd"
    model.write_text(PRECEDENCE)
    said = f"{model}:17:26: warning: '=>' binds tighter than 'and'"
    for args in (("check",), ("synthesize",), ("build", "-o", str(tmp_path / "out")),
                 ("generate", "--ros", "2", "-o", str(tmp_path / "gen"))):
        result = run(*args, str(model))
        assert result.returncode == 0 and said in result.stdout + result.stderr, (args, result.stderr)
    data = json.loads(run("synthesize", "--json", str(model)).stdout)
    assert [w["code"] for w in data["warnings"]] == ["precedence"] and data["warnings"][0]["line"] == 17
