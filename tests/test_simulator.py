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
from robosc.debug.simulator import CommandError, Violation

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
    assert (
        "refused: movement is not allowed now: the requirement at line 76 needs Platform.ready and ((Distance.right"
        in result.stdout
    )
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
    before = sim.supervisor.snapshot()
    # possible in every state (responsiveness), but no component answers it here: not an event
    assert sim.run("rotate_done").messages == (
        "ignored: rotate_done: Platform does not expect it where it is (ready)",
    )
    assert sim.supervisor.snapshot() == before


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


def test_tick_n_numbers_each_cycle() -> None:
    sim = sim_of("maze_solver")
    outcome = sim.run("tick 3")
    moves = [(step, e) for step, e in zip(outcome.steps, outcome.events, strict=True) if e == "movement"]
    assert moves == [(1, "movement"), (2, "movement"), (3, "movement")]
    with pytest.raises(CommandError, match="tick takes a number of cycles"):
        sim.run("tick three")


def test_refusal_names_what_is_false() -> None:
    sim = sim_of("shelf_picker")
    # the plant: navigate is already running
    sim.run("navigate.c_trigger")
    [plant] = sim.run("navigate.c_trigger").messages
    assert plant == "refused: navigate.c_trigger cannot happen while navigate is in executing (the plant)"
    # a requirement: one conjunct of it is false
    sim = sim_of("shelf_picker")
    [required] = sim.run("pick.c_trigger").messages
    assert required == (
        "refused: pick.c_trigger is not allowed now: the requirement at line 101 needs Base.at_shelf (false now)"
    )
    # the condition synthesis added: two items in the tray
    for line in ["navigate.c_trigger", "navigate.u_response"] + [
        "pick.c_trigger",
        "pick.u_response",
        "drop.c_trigger",
        "drop.u_response",
        "drop.c_reset",
        "pick.c_reset",
    ] * 2:
        assert not sim.run(line).messages, line
    [added] = sim.run("pick.c_trigger").messages
    assert added == (
        "refused: pick.c_trigger is not allowed now: synthesis added Tray.empty or Tray.one, which is false here "
        "('robosc synthesize' explains why)"
    )


def test_commands_get_did_you_mean() -> None:
    sim = sim_of("maze_solver")
    with pytest.raises(CommandError, match="did you mean 'tick'"):
        sim.run("tik")
    with pytest.raises(CommandError, match="did you mean 'expect'"):
        sim.run("expct Platform ready")


def test_interactive_failed_expect_is_reported_and_the_session_goes_on() -> None:
    result = run(
        "simulate",
        str(ROOT / "examples/maze_solver.rscd"),
        stdin="expect Platform turning\ntick 2\nquit\n",
    )
    assert result.returncode == 0, result.stderr
    assert "failed: step 0: expect Platform turning: Platform is ready" in result.stdout
    assert "     1  movement\n     2  movement" in result.stdout  # the session went on


def test_a_communications_name_stands_for_its_one_event_that_can_happen_now() -> None:
    """Before: 'pick' answered "did you mean 'tick'?" although pick.c_trigger was allowed."""
    sim = sim_of("shelf_picker")
    assert sim.run("navigate").events == ("navigate.c_trigger",)
    with pytest.raises(CommandError) as ambiguous:
        sim.run("navigate")
    assert str(ambiguous.value) == (
        "'navigate' could be navigate.u_response or navigate.u_error or navigate.u_feedback now: say which"
    )
    assert sim.run("navigate.u_response").events == ("navigate.u_response",)
    assert sim.run("pick").events == ("pick.c_trigger",)
    with pytest.raises(CommandError, match="none of dock's events can happen now"):
        sim.run("dock")
    with pytest.raises(CommandError, match="unknown command or event 'pic'"):
        sim.run("pic")


def test_steps_are_numbered_without_gaps_when_a_tick_does_nothing() -> None:
    sim = sim_of("shelf_picker")
    first = sim.run("tick")  # navigate.c_trigger
    assert first.steps == (1,)
    assert sim.run("tick").events == ()  # nothing allowed: waiting for the robot
    assert sim.run("navigate.c_reset").events == ()  # refused
    assert sim.run("navigate.u_response").steps == (2,)  # before: 4
