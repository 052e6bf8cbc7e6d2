"""``robosc simulate``: scripted, random and interactive runs, each step checked."""

from __future__ import annotations

import json
import random
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from robosc.api import check_text, load_model, simulator, synthesize_model
from robosc.runtime.simulator import CommandError, Violation

ROOT = Path(__file__).resolve().parent.parent


def run(*args: str, stdin: str | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "robosc", *args], capture_output=True, text=True, timeout=120, input=stdin, check=False
    )


def sim_of(name: str, seed: int = 1) -> Any:
    return simulator(synthesize_model(load_model(ROOT / "examples" / f"{name}.rscd")), seed=seed)


def test_script_drives_the_maze_solver(tmp_path: Path) -> None:
    script = tmp_path / "maze.txt"
    script.write_text(
        "# a wall ahead makes it turn left\n"
        "tick\n"
        "expect Platform ready\n"
        'scan_front {"ranges": [0.3]}\n'
        "expect Distance.front wall_front\n"
        "tick\n"
        "expect Platform turning\n"
        "movement\n"
        "rotate_done\n"
        "scan_front no_wall_front\n"
        "tick\n"
        "expect Platform ready\n"
    )
    log = tmp_path / "events.jsonl"
    result = run(
        "simulate", str(ROOT / "examples/maze_solver.rscd"), "--script", str(script), "--seed", "1", "--log", str(log)
    )
    assert result.returncode == 0, result.stderr
    assert "turn_left" in result.stdout
    assert "refused: the supervisor does not allow movement now" in result.stdout
    events = [json.loads(line) for line in log.read_text().splitlines()]
    names = [e["event"] for e in events]
    assert names[names.index("scan_front") + 1] == "turn_left"
    turn = events[names.index("turn_left")]
    assert turn["controllable"] is True and turn["data"] == 90
    assert turn["state"]["automata"]["Platform"] == "turning"


def test_failed_expectation_stops_with_a_report(tmp_path: Path) -> None:
    script = tmp_path / "wrong.txt"
    script.write_text("tick\nexpect Platform turning\n")
    result = run("simulate", str(ROOT / "examples/maze_solver.rscd"), "--script", str(script))
    assert result.returncode == 1
    assert "violation at step 1: expect Platform turning: Platform is ready" in result.stderr
    assert "Traceback" not in result.stderr


def test_bad_script_line_gets_file_line_and_column(tmp_path: Path) -> None:
    script = tmp_path / "typo.txt"
    script.write_text("tick\n  scan_frnt {}\n")
    result = run("simulate", str(ROOT / "examples/maze_solver.rscd"), "--script", str(script))
    assert result.returncode == 2
    assert f"{script}:2:3: error: unknown command or event 'scan_frnt'; did you mean 'scan_front'?" in result.stderr
    script.write_text('scan_front {"ranges": [0.3}\n')
    result = run("simulate", str(ROOT / "examples/maze_solver.rscd"), "--script", str(script))
    assert result.returncode == 2
    assert "data for scan_front must be JSON (or one of wall_front, no_wall_front)" in result.stderr


@pytest.mark.parametrize("name", ["maze_solver", "line_follower", "pick_and_light"])
def test_random_runs_keep_every_requirement(name: str) -> None:
    sim = sim_of(name, seed=3)
    rng = random.Random(3)
    for _ in range(1500):
        sim.random_step(rng)
    assert len(sim.events) > 500
    controllable = {e.name for e in sim.network.controllable}
    assert controllable & set(sim.events), "the controller never acted"


def test_checks_catch_a_wrong_controller() -> None:
    """The checks are independent of the generated code: a tampered guard is caught."""
    sim = sim_of("maze_solver")
    sim.run("tick")
    broken = sim.supervisor
    allowed = broken._allowed
    broken._allowed = lambda: (*allowed(), broken.e1_turn_left)  # a broken controller: turns without a wall
    with pytest.raises(Violation) as caught:
        sim.perform("turn_left")
    assert "breaks 'requirement turn_left needs Platform.ready and Distance.front = wall_front'" in str(caught.value)


def test_blocking_is_caught() -> None:
    text = """
robot Stuck {
    component C {
        outgoing message go with type: none
        incoming message act with type: none
        incoming message back with type: none
        behaviour {
            initial marked state a {
                on request to act goto b
            }
            state b {
                on response from go goto c
            }
            state c {
                on request to back goto a
            }
        }
    }
    requirement back needs C.a
}
"""
    model = check_text(text).model
    assert model is not None
    result = synthesize_model(model)
    assert result.ok  # act is disabled: from b, go leads to c, where back is never allowed
    sim = simulator(result)
    assert sim.allowed() == []
    field = next(f.name for f in sim.plan.fields if f.label == "C")
    setattr(sim.supervisor, field, "b")  # force the plant where the supervisor would never let it go
    sim._before = sim.network_state()
    with pytest.raises(Violation, match="outside the controlled behaviour"):
        sim.deliver("go")


def test_unknown_event_and_data_errors() -> None:
    sim = sim_of("maze_solver")
    with pytest.raises(CommandError, match="did you mean 'rotate_done'"):
        sim.run("rotate_dne")
    with pytest.raises(CommandError, match="controllable"):
        sim.run("movement 3")
    assert sim.run("rotate_done").messages == ()  # possible in every state (responsiveness)


def test_interactive_session() -> None:
    result = run(
        "simulate",
        str(ROOT / "examples/maze_solver.rscd"),
        "--seed",
        "1",
        stdin='help\ntick\nscan_front {"ranges": [0.2]}\ntick\nstate\nbogus\nquit\n',
    )
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert "commands:" in out
    assert "turn_left" in out
    assert "error: unknown command or event 'bogus'" in out
    assert "allowed: movement" in out  # the first state shown


def test_random_cli_reports_and_library_is_refused(tmp_path: Path) -> None:
    result = run("simulate", str(ROOT / "examples/pick_and_light.rscd"), "--random", "500", "--seed", "2", "--quiet")
    assert result.returncode == 0, result.stderr
    assert "500 random steps" in result.stdout
    result = run("simulate", str(ROOT / "examples/emergency_stop.rscd"))
    assert result.returncode == 2
    assert "is a library" in result.stderr
