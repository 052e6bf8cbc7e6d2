"""World files: what they build, and every problem reported at its file, line and column."""

from __future__ import annotations

import math
import os
from pathlib import Path

import pytest

pytest.importorskip("irsim", reason="robosc sim needs IR-SIM (pip install '.[sim]')")

from robosc.sim.world import TOPIC_ROLES, WorldError, load_world

WORLDS = Path(__file__).resolve().parent.parent / "examples" / "worlds"

MINIMAL = """\
world: box
size: [4, 3]
starts:
  - [1, 1, 90]
goal: {x: [3, 4], y: [2, 3]}
"""


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "w.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def test_the_bundled_worlds_load() -> None:
    maze = load_world(WORLDS / "maze.yaml")
    assert maze.name == "maze" and maze.walls and maze.line is None
    assert maze.starts[0].heading == pytest.approx(math.pi / 2)
    line = load_world(WORLDS / "line.yaml")
    assert line.line is not None and len(line.boxes) == 1
    assert line.topics["line_correction"] == "/line/correction"


def test_defaults_of_a_minimal_world(tmp_path: Path) -> None:
    world = load_world(write(tmp_path, MINIMAL))
    assert world.size == (4.0, 3.0) and world.step == 0.05
    assert world.topics == TOPIC_ROLES and world.walls == () and world.presses == ()
    assert world.goal.contains(3.5, 2.5) and not world.goal.contains(2.9, 2.5)
    assert world.start(0) == world.start(5)  # robots share the starts there are


def test_emergency_stop_schedule_and_topics(tmp_path: Path) -> None:
    text = MINIMAL + "emergency_stop:\n  - [2, 4.5]\ntopics:\n  cmd_vel: /base/cmd_vel\n"
    world = load_world(write(tmp_path, text))
    assert world.presses == ((2.0, 4.5),)
    assert world.topics["cmd_vel"] == "/base/cmd_vel" and world.topics["scan"] == "/scan"


@pytest.mark.parametrize(
    ("text", "line", "column", "message"),
    [
        (MINIMAL.replace("size: [4, 3]", "size: [4, -3]"), 2, 11, "size must be greater than 0"),
        (MINIMAL.replace("size: [4, 3]", "size: [4, 3, 2]"), 2, 7, "size must have 2 items, not 3"),
        (MINIMAL.replace("size: [4, 3]", "size: [4, three]"), 2, 11, "size must be a number"),
        (MINIMAL.replace("size: [4, 3]", "size: [4, 1.0e+999]"), 2, 11, "size must be finite"),
        (MINIMAL.replace("  - [1, 1, 90]", "  - [9, 1, 90]"), 4, 5, "a start must lie inside the world"),
        (MINIMAL.replace("x: [3, 4]", "x: [4, 3]"), 5, 11, "goal x must be [low, high] with low < high"),
        (MINIMAL + "wals: []\n", 6, 1, "unknown key 'wals' in the world; did you mean 'walls'?"),
        (MINIMAL + "walls:\n  - [[0, 0]]\n", 7, 5, "a wall needs at least two points"),
        (MINIMAL + "step: 0.5\n", 6, 7, "step must be at most 0.2 s"),
        (MINIMAL + "topics:\n  scan: 3\n", 7, 9, "the topic of 'scan' must be a non-empty text"),
        (MINIMAL + "topics:\n  laser: /laser\n", 7, 3, "unknown key 'laser' in topics"),
        (MINIMAL + "robot:\n  lidar: {beams: 3.5}\n", 7, 18, "beams must be a whole number from 4 to 4096"),
        (MINIMAL + "line:\n  points: [[0, 0]]\n", 7, 11, "the line needs at least two points"),
        (MINIMAL + "emergency_stop:\n  - [5, 2]\n", 7, 5, "an emergency stop press [pressed, released] must be"),
        (MINIMAL + "size: [1, 1]\n", 6, 1, "'size' given twice in the world"),
        (MINIMAL.replace("world: box\n", ""), 1, 1, "the world needs 'world'"),
        ("world: [unclosed\n", 2, 1, "not valid YAML"),
        (MINIMAL + "walls: &w [[[0, 0], [1, 1]]]\nboxes: *w\n", 7, 8, "YAML aliases (*name) are not supported"),
        ("", 1, 1, "the world file is empty"),
        ("- 1\n", 1, 1, "the world must be a mapping"),
        (MINIMAL + "shared: maybe\n", 6, 9, "shared must be true or false"),
        (MINIMAL.replace("  - [1, 1, 90]", "  - [1, 1, 90]\n  - [1.1, 1, 0]") + "shared: true\n", 5, 5,
         "start 2 touches start 1: in a shared world robots are bodies"),
    ],
)
def test_errors_name_file_line_and_column(tmp_path: Path, text: str, line: int, column: int, message: str) -> None:
    path = write(tmp_path, text)
    with pytest.raises(WorldError) as caught:
        load_world(path)
    error = caught.value
    assert (error.line, error.column) == (line, column), str(error)
    assert message in error.message
    assert str(error).startswith(f"{path}:{line}:{column}: error: ")


def test_deep_nesting_and_special_files_are_refused(tmp_path: Path) -> None:
    deep = write(tmp_path, "world: box # it's [\nsize: " + "[" * 5000)
    with pytest.raises(WorldError, match=r"w.yaml:2:39: error: brackets nested more than 32 deep"):
        load_world(deep)
    quoted = write(tmp_path, MINIMAL.replace("world: box", "world: '" + "[" * 100 + "'"))
    assert load_world(quoted).name == "[" * 100
    long = write(tmp_path, MINIMAL + "walls: [" + "[[0, 0], [1, 1]], " * 1000 + "]\n")
    with pytest.raises(WorldError, match=r"w.yaml:6:10001: error: line longer than 10,000"):
        load_world(long)
    fifo = tmp_path / "fifo.yaml"
    os.mkfifo(fifo)
    with pytest.raises(WorldError, match="not a regular file"):
        load_world(fifo)
    with pytest.raises(WorldError, match="cannot read"):
        load_world(tmp_path / "missing.yaml")
    big = write(tmp_path, "#" * 1_000_001)
    with pytest.raises(WorldError, match="at most 1,000,000"):
        load_world(big)
