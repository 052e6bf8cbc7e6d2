"""Every robot sure to finish (robosc.synthesis.finish): the check names a robot that the
supervisor lets the others starve, with the run and the loop; enforcing it makes a supervisor
under which none can be; counted fleets are checked with one robot followed apart."""

from __future__ import annotations

import json

import pytest

from robosc.api import check_finish, check_text, enforce_finish, synthesize_model
from robosc.cli.main import main
from robosc.synthesis.options import SynthesisOptions

# robots share one cell; a lock, once turned, keeps out whom the requirements say: the fleet can
# still always get home (nonblocking), but the robots locked out can never get inside again
LOCK = """
robot Locks {
    component bot[N] {
        incoming message enter with type: none
        incoming message leave with type: none
        behaviour {
            initial marked state home { on request to enter goto inside }
            state inside { on request to leave goto home }
        }
    }
    component Lock {
        incoming message lock with type: none
        behaviour {
            initial marked state open { on request to lock goto locked }
            marked state locked { }
        }
    }
    LOCKED
    for r in bot {
        requirement r.enter needs !any(q in bot: q.inside)
    }
}
"""


def model(robots: int, locked: str) -> str:
    return LOCK.replace("N]", f"{robots}]").replace("LOCKED", locked)


def test_a_robot_the_others_can_starve_is_named_with_the_run_and_the_loop() -> None:
    result = synthesize_model(check_text(model(2, "requirement bot2.enter needs Lock.open")).model)
    assert result.ok and result.method == "symbolic"
    finish = check_finish(result)
    assert not finish.ok and finish.robots == ("bot1", "bot2")
    (starved,) = finish.starved
    assert (starved.robot, starved.location) == ("bot2", "inside")
    assert [s.event.name for s in starved.path] == ["lock"]
    assert {s.event.name for s in starved.loop} == {"bot1.enter", "bot1.leave"}
    assert starved.state == "bot1.home, bot2.home, Lock.locked"
    assert finish.places == ("home", "inside")


def test_a_fleet_where_nobody_is_locked_out_passes() -> None:
    finish = check_finish(synthesize_model(check_text(model(2, "")).model))
    assert finish.ok and finish.robots == ("bot1", "bot2") and finish.places == ("home", "inside")


def test_a_counted_fleet_is_checked_with_one_robot_followed_apart() -> None:
    text = model(4, "for r in bot { requirement r.enter needs Lock.open }")
    result = synthesize_model(check_text(text).model)
    assert result.method == "symmetric"
    finish = check_finish(result)
    assert finish.robots == ("bot1",) and finish.stands_for == ("bot1 .. bot4",)
    assert [(s.robot, s.location, [e.event.name for e in s.path]) for s in finish.starved] == [("bot1", "inside", ["lock"])]
    # the same answer as following every robot of the monolithic supervisor
    whole = check_finish(synthesize_model(check_text(text).model, options=SynthesisOptions(fleet="monolithic")))
    assert whole.robots == ("bot1", "bot2", "bot3", "bot4")
    assert [(s.robot, s.location) for s in whole.starved] == [(f"bot{i}", "inside") for i in range(1, 5)]
    assert check_finish(synthesize_model(check_text(model(4, "")).model)).ok


def test_enforcing_it_keeps_every_robot_able_to_finish() -> None:
    result = synthesize_model(check_text(model(2, "requirement bot2.enter needs Lock.open")).model)
    enforced = enforce_finish(result)
    assert enforced.ok and enforced is not result
    assert render_added(enforced) == {"lock": "false"}
    assert check_finish(enforced).ok
    assert enforce_finish(synthesize_model(check_text(model(2, "")).model)).guards  # nothing to enforce: same


def render_added(result: object) -> dict[str, str]:
    from robosc.language.render import render

    return {g.event.name: render(g.added) for g in result.guards if g.added is not None}  # type: ignore[attr-defined]


def test_robosc_synthesize_finish_says_who_can_be_starved_and_exits_1(
    tmp_path: object, capsys: pytest.CaptureFixture[str]
) -> None:
    from pathlib import Path

    path = Path(str(tmp_path)) / "locks.rscd"
    path.write_text(model(2, "requirement bot2.enter needs Lock.open"))
    assert main(["synthesize", str(path), "--finish", "check"]) == 1
    out = capsys.readouterr().out
    assert "bot2 can be starved: after lock it can never reach inside again; the others can go round" in out
    assert main(["synthesize", str(path), "--finish", "check", "--json"]) == 1
    data = json.loads(capsys.readouterr().out)["finish"]
    assert data["ok"] is False and data["starved"][0]["robot"] == "bot2" and data["starved"][0]["run"] == ["lock"]
    assert main(["synthesize", str(path), "--finish", "enforce"]) == 0
    out = capsys.readouterr().out
    assert "every robot can finish: bot1, bot2 can always get to each of home, inside again" in out
    assert "lock" in out and "a robot would be starved: from state [bot1.home, bot2.home, Lock.locked]" in out
