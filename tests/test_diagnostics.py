"""Diagnostics read ``path:line:col: error: message``, then the source line and a caret."""

from __future__ import annotations

import json

import pytest

from conftest import robot
from robosc.language.diagnostics import to_json


def test_text_rendering_with_caret_and_hint(check):
    result = check(robot("requirement act needs S.idel"))
    lines = result.render().splitlines()
    path = result.diagnostics[0].span.path
    assert lines[0] == f"{path}:12:25: error: unknown state or variable 'idel' in component 'S'"
    assert lines[1] == "    requirement act needs S.idel"
    assert lines[2] == "    " + " " * 24 + "^~~~"
    assert lines[3] == "    hint: did you mean 'idle'?"


def test_json_rendering(check):
    result = check(robot("requirement act needs S.idel"))
    data = json.loads(to_json(result.diagnostics))
    assert data[0]["line"] == 12 and data[0]["column"] == 25 and data[0]["code"] == "rule-14"
    assert data[0]["severity"] == "error" and data[0]["hint"] == "did you mean 'idle'?"


def test_diagnostics_are_sorted_by_position(check):
    result = check(robot("requirement zzz needs true", "requirement act needs S.q"))
    lines = [d.span.line for d in result.diagnostics]
    assert lines == sorted(lines) and len(lines) == 2


@pytest.mark.parametrize(
    ("condition", "hint"),
    [
        ("S.active && S.idle", "write 'and' for a logical and"),
        ("S.active & S.idle", "write 'and' for a logical and"),
        ("S.active || S.idle", "write 'or' for a logical or"),
        ("S.active == true", "write '=' to compare: RoboSC's equality is a single '='"),
        ("not S.active", "write '!' for a logical not, as in '!S.active'"),
        ("S.active <> false", "write '!=' for 'not equal'"),
        ("S.active and 1e-1 > 0.0", "numbers have no exponent in RoboSC; write 0.1"),
        ("S.active and 2.5E+3 > 1.0", "numbers have no exponent in RoboSC; write 2500.0"),
    ],
)
def test_habits_from_other_languages_get_a_hint(check, condition: str, hint: str):
    result = check(robot(f"requirement act needs {condition}"))
    [found] = result.diagnostics
    assert found.code == "syntax" and found.hint == hint


@pytest.mark.parametrize(
    ("condition", "hint"),
    [
        ("S.activ", "did you mean 'active'?"),  # a near spelling
        ("S.act", "did you mean 'active'?"),  # a prefix
        ("idel", "did you mean 'S.idle'?"),  # a member of a component, named bare
        ("C.idle", "did you mean 'S.idle'?"),  # the member is another component's
        ("S.zzz", None),  # nothing close: no hint
    ],
)
def test_did_you_mean_looks_at_every_name_in_reach(check, condition: str, hint: str | None):
    result = check(robot("component C { outgoing message o with type: none }", f"requirement act needs {condition}"))
    [found] = result.diagnostics
    assert found.code == "rule-14" and found.hint == hint
