"""Diagnostics read ``path:line:col: error: message``, then the source line and a caret."""

from __future__ import annotations

import json

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
