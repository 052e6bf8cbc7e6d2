"""Event logs (JSON Lines, MCAP), sequence-of-events plots, automaton diagrams."""

from __future__ import annotations

import json
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from families import philosophers
from robosc.api import check_text, load_model, synthesize_model
from robosc.debug.diagram import diagrams, dot, svg
from robosc.debug.eventlog import CHANNEL, LogError, read_log

ROOT = Path(__file__).resolve().parent.parent


def run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "robosc", *args], capture_output=True, text=True, timeout=300, check=False
    )


@pytest.fixture(scope="module")
def big_log(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A 10,000-step random run of the maze solver, logged as JSON Lines."""
    path = tmp_path_factory.mktemp("logs") / "maze.jsonl"
    done = run(
        "simulate",
        str(ROOT / "examples/maze_solver.rscd"),
        "--random",
        "10000",
        "--seed",
        "5",
        "--quiet",
        "--log",
        str(path),
    )
    assert done.returncode == 0, done.stderr
    return path


def test_log_records_every_event_with_the_state_after_it(big_log: Path) -> None:
    records = read_log(big_log)
    assert len(records) > 7500  # every event taken (an answer no component waits for is not one)
    names = {r.event for r in records}
    assert {"scan_front", "rotate_done", "movement", "turn_left"} <= names
    assert all(
        r.controllable == (r.event in {"movement", "turn_left", "turn_right"} or "_data." in r.event) for r in records
    )
    turn = next(r for r in records if r.event == "turn_left")
    assert turn.data == 90 and turn.state["automata"]["Platform"] == "turning"
    assert [r.time for r in records] == sorted(r.time for r in records)


def test_mcap_log_opens_with_the_mcap_reader(tmp_path: Path, big_log: Path) -> None:
    from mcap.reader import make_reader

    direct = tmp_path / "direct.mcap"
    done = run(
        "simulate",
        str(ROOT / "examples/maze_solver.rscd"),
        "--random",
        "300",
        "--seed",
        "5",
        "--quiet",
        "--log",
        str(direct),
    )
    assert done.returncode == 0, done.stderr
    converted = tmp_path / "converted.mcap"
    assert run("log", str(big_log), "-o", str(converted)).returncode == 0
    for path, expected in ((direct, None), (converted, len(read_log(big_log)))):
        with path.open("rb") as handle:
            reader = make_reader(handle)
            summary = reader.get_summary()
            assert summary is not None
            assert [c.topic for c in summary.channels.values()] == [CHANNEL]
            assert [s.encoding for s in summary.schemas.values()] == ["jsonschema"]
            messages = list(reader.iter_messages())
        if expected is not None:
            assert len(messages) == expected
        first = json.loads(messages[0][2].data)
        assert {"time", "event", "controllable", "state"} <= set(first)
        assert len(read_log(path)) == len(messages)


def test_bad_logs_are_reported_with_file_and_line(tmp_path: Path) -> None:
    bad = tmp_path / "bad.jsonl"
    bad.write_text('{"time": 0, "event": "a", "controllable": true}\n{"time": 1, "event": \n')
    with pytest.raises(LogError, match=r"bad.jsonl:2:\d+: not JSON"):
        read_log(bad)
    done = run("plot", str(bad), "-o", str(tmp_path / "x.png"))
    assert done.returncode == 1 and "bad.jsonl:2:" in done.stderr and "Traceback" not in done.stderr
    bad.write_text('{"time": 0, "event": "a"}\n')
    with pytest.raises(LogError, match=r"bad\.jsonl:1:1: an event record needs time, event and controllable"):
        read_log(bad)
    assert run("plot", str(tmp_path / "missing.jsonl"), "-o", str(tmp_path / "x.png")).returncode == 1


def test_plot_of_ten_thousand_events(tmp_path: Path, big_log: Path) -> None:
    import matplotlib.image

    png = tmp_path / "maze.png"
    done = run("plot", str(big_log), "-o", str(png))
    assert done.returncode == 0, done.stderr
    image = matplotlib.image.imread(png)
    height, width = image.shape[:2]
    assert width >= 1200 and 300 <= height <= 2000
    pixels = (image[:, :, :3] * 255).round().astype(int).reshape(-1, 3).tolist()
    colors = {tuple(p) for p in pixels}
    assert (0xF2, 0x8E, 0x2B) in colors, "no controllable (orange) marks"
    assert (0x4E, 0x79, 0xA7) in colors, "no uncontrollable (blue) marks"
    svg_path = tmp_path / "maze.svg"
    assert run("plot", str(big_log), "-o", str(svg_path)).returncode == 0
    ET.parse(svg_path)  # well-formed
    assert svg_path.stat().st_size < 2_000_000  # the marks are rasterized: it stays small


def test_diagram_marks_what_synthesis_restricts() -> None:
    model = check_text(philosophers(3)).model
    assert model is not None
    result = synthesize_model(model)
    found = {d.name: d for d in diagrams(result)}
    p0 = found["P0"]
    restricted = [t for t in p0.transitions if t.restricted]
    assert [t.event for t in restricted] == ["take_left0"]
    assert restricted[0].added == "F1.free or P2.thinking"
    text = dot(p0)
    assert '[id="P0::e0", label="take_left0\\nadded: F1.free or P2.thinking", color="#d62728"' in text
    tree = ET.fromstring(svg(p0))
    ids = {e.get("id") for e in tree.iter() if e.get("id")}
    assert {"P0::thinking", "P0::has_left", "P0::eating", "P0::e0"} <= ids


def test_diagram_command_writes_every_automaton(tmp_path: Path) -> None:
    done = run("diagram", str(ROOT / "examples/pick_and_light.rscd"), "-o", str(tmp_path / "d"))
    assert done.returncode == 0, done.stderr
    model = load_model(ROOT / "examples/pick_and_light.rscd")
    expected = {c.name for c in model.components} | {f"plant_{c.name}" for c in model.communications}
    stems = {p.stem for p in (tmp_path / "d").glob("*.dot")}
    assert stems == expected
    assert {p.stem for p in (tmp_path / "d").glob("*.svg")} == expected
    arm = (tmp_path / "d" / "Arm.dot").read_text()
    assert 'label="pick.u_feedback\\ndo progress := value.sequence[0]"' in arm
    assert 'label="Arm.tau1_idle_to_full\\nif Arm.picks = 3"' in arm
    assert "needs: Camera.seen and Arm.picks < 3" in arm  # the user's requirement, orange


def test_diagram_escapes_model_strings() -> None:
    text = """
robot Q {
    component C {
        outgoing message hear with type: string
        behaviour {
            variable last: string = "a \\"quoted\\" \\\\ word"
            initial marked state s {
                on response from hear do last := "x\\"y <b>"
                on response from hear do last := "tab\\tnew\\nline\\rend"
            }
        }
    }
}
"""
    model = check_text(text).model
    assert model is not None
    result = synthesize_model(model)
    d = next(d for d in diagrams(result) if d.name == "C")
    tree = ET.fromstring(svg(d))  # Graphviz read the DOT, and its SVG is well-formed
    labels = ["".join(t.itertext()) for t in tree.iter() if t.tag.endswith("text")]
    assert 'do last := "x\\"y <b>"' in labels
    # a tab, newline or carriage return in a string is shown as the model writes it: one line
    assert 'do last := "tab\\tnew\\nline\\rend"' in labels


def test_diagrams_without_the_dot_program_use_graphviz_as_webassembly(monkeypatch: pytest.MonkeyPatch) -> None:
    import shutil

    from robosc.debug import layout

    real_which = shutil.which
    monkeypatch.setattr(layout.shutil, "which", lambda name: None if name == "dot" else real_which(name))
    assert layout.engine() == "wasm"
    result = synthesize_model(load_model(ROOT / "examples" / "maze_solver.rscd"))
    platform = next(d for d in diagrams(result) if d.name == "Platform")
    tree = ET.fromstring(svg(platform))
    texts = {t.text for t in tree.iter("{http://www.w3.org/2000/svg}text")}
    assert {"ready", "turning"} <= texts  # the states, laid out by the WebAssembly Graphviz


def test_failed_layout_leaves_no_partial_files(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from robosc.debug import diagram as diagram_module
    from robosc.debug.layout import LayoutError

    calls = []

    def failing(text: str) -> str:
        calls.append(text)
        if len(calls) == 3:
            raise LayoutError("no Graphviz")
        return "<svg/>"

    monkeypatch.setattr(diagram_module, "to_svg", failing)
    result = synthesize_model(load_model(ROOT / "examples" / "maze_solver.rscd"))
    with pytest.raises(LayoutError):
        diagram_module.write_diagrams(result, tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_nul_in_a_diagram_is_refused_before_graphviz() -> None:
    from robosc.debug.layout import LayoutError, to_svg

    with pytest.raises(LayoutError, match="NUL"):
        to_svg('digraph { a [label="x\0y"] }')


def test_plot_layout_is_bounded_whatever_the_log() -> None:
    """Thousands of different events, long names, a ``$`` (matplotlib's mathematics) and a
    long title: the rows, labels and marks the plot draws stay bounded."""
    from robosc.debug.eventlog import Record
    from robosc.debug.plot import COLUMNS, MAX_LABEL, MAX_ROWS, layout

    records = [Record(i / 10, f"e{i % 5000}", i % 3 == 0, None, {}) for i in range(20_000)]
    records += [Record(2000.0 + i, "frequent", False, None, {}) for i in range(100)]
    records.append(Record(3000.0, "$\\frac{" + "x" * 900, True, None, {}))
    shown = layout(records, title="t" * 10_000)
    assert len(shown.rows) == MAX_ROWS
    assert shown.rows[-1].label == "(4,943 other events)" and shown.rows[-1].controllable is None
    assert sum(row.events for row in shown.rows) == len(records)  # every event is on some row
    assert "frequent" in [row.label for row in shown.rows]  # the most frequent keep their rows
    assert len(shown.points) <= MAX_ROWS * (COLUMNS + 1) * 2
    assert all(len(row.label) <= MAX_LABEL + 1 for row in shown.rows)  # (+1: the backslash before $)
    assert len(shown.title) == 120
    few = layout(records[:50])
    assert [row.label for row in few.rows] == [f"e{i}" for i in range(50)]  # first occurrence, all shown
    assert sorted(row for _, row, _ in few.points) == list(range(50))
    assert all(abs(x - row / 10) <= 4.9 / COLUMNS for x, row, _ in few.points)  # within a column of the time


def test_jsonl_to_mcap_and_back_keeps_every_field(tmp_path: Path, big_log: Path) -> None:
    """Before: the simulator's 'step' (and any other field) was lost on the way."""
    original = [json.loads(line) for line in big_log.read_text().splitlines()]
    assert all("step" in r for r in original)
    assert run("log", str(big_log), "-o", str(tmp_path / "x.mcap")).returncode == 0
    assert run("log", str(tmp_path / "x.mcap"), "-o", str(tmp_path / "back.jsonl")).returncode == 0
    back = [json.loads(line) for line in (tmp_path / "back.jsonl").read_text().splitlines()]
    assert back == original


def test_the_robots_of_a_fleet_are_drawn_once_where_they_are_alike(tmp_path: Path) -> None:
    """The lift fleet's 4 robots (and their communications' plants) drawn once, conditions
    with r for the robot; a fleet whose first robot has a requirement of its own: each drawn."""
    from families import lift
    from robosc.debug.diagram import write_diagrams

    written = {p.name for p in write_diagrams(synthesize_model(check_text(lift(4)).model), tmp_path / "lift")}
    assert "bot.dot" in written and "plant_bot_go.svg" in written
    assert not any(name.startswith(("bot1", "bot2", "plant_bot1")) for name in written)
    text = (tmp_path / "lift" / "bot.dot").read_text()
    assert "drawn once for bot1 .. bot4" in text
    assert 'label="r.go\\nneeds: !any(q in bot: q.corridor or q.waiting or' in text
    assert "bot1" not in text.replace("bot1 .. bot4", "")
    apart = lift(4).replace("    for r in bot {", "    requirement bot1.go needs Lift.ground\n    for r in bot {", 1)
    written = {p.name for p in write_diagrams(synthesize_model(check_text(apart).model), tmp_path / "apart")}
    assert {"bot1.dot", "bot2.dot", "bot4.dot", "plant_bot1_go.dot", "plant_bot_call.dot"} <= written
    assert "bot.dot" not in written and "plant_bot_go.dot" not in written
