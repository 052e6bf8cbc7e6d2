"""CIF export: every example becomes a CIF text whose references all resolve."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from conftest import EXAMPLES
from robosc.api import load_model
from robosc.cli.main import main
from robosc.codegen.cif import expression, to_cif
from robosc.language import model as m
from robosc.plant import build_network

ROBOTS = ["line_follower", "maze_solver", "pick_and_light"]


def declarations(text: str) -> tuple[set[str], set[str], set[str]]:
    """Declared events (Automaton.event), locations (Automaton.location) and variables."""
    events, locations, variables = set(), set(), set()
    automaton = ""
    for line in text.splitlines():
        line = line.strip()
        if found := re.match(r"plant automaton (\S+):", line):
            automaton = found.group(1)
        elif found := re.match(r"(?:un)?controllable (.+);", line):
            events |= {f"{automaton}.{e.strip()}" for e in found.group(1).split(",")}
        elif found := re.match(r"location (\S+):", line):
            locations.add(f"{automaton}.{found.group(1)}")
        elif found := re.match(r"disc \S+ (\S+) =", line):
            variables.add(f"{automaton}.{found.group(1)}")
        elif found := re.match(r"input \S+ (\S+);", line):
            variables.add(found.group(1))
    return events, locations, variables


@pytest.mark.parametrize("name", ROBOTS)
def test_cif_references_resolve(name: str):
    network = build_network(load_model(EXAMPLES / f"{name}.rscd"))
    text = to_cif(network)
    events, locations, variables = declarations(text)
    assert len(events) == len(network.events)
    automaton = ""
    for line in text.splitlines():
        line = line.strip()
        if found := re.match(r"plant automaton (\S+):", line):
            automaton = found.group(1)
        if found := re.match(r"edge (\S+?)( when| do| goto|;)", line):
            event = found.group(1)
            assert (event if "." in event else f"{automaton}.{event}") in events, line
        if found := re.search(r"goto (\S+);", line):
            assert f"{automaton}.{found.group(1)}" in locations, line
        if found := re.match(r"requirement (\S+) needs", line):
            assert found.group(1) in events, line
        for ref in re.findall(r"(?<![\w$.])([A-Za-z_$][\w$]*\.[A-Za-z_$][\w$]*)", line.split("//")[0]):
            if not line.startswith(("edge", "requirement")):
                continue
            assert ref in events or ref in locations or ref in variables, (ref, line)
    assert text.count("plant automaton") == len(network.automata)
    assert text.count("\nend\n") == len(network.automata)


def test_cif_content_of_the_line_follower():
    text = to_cif(build_network(load_model(EXAMPLES / "line_follower.rscd")))
    assert "enum Safety = unsafe, safe;" in text
    assert "input Safety Lidar_safety_received;" in text
    assert "edge scan.u_response do safety := Lidar_safety_received;" in text
    assert "plant automaton $continue:" in text  # a CIF keyword, escaped
    assert "requirement move.c_trigger needs (LineDetector.line_found and (Lidar.safety = safe));" in text


def test_cif_expressions_are_fully_parenthesised():
    a = m.Literal(1, m.INTEGER, None)  # type: ignore[arg-type]
    e = m.Binary("-", a, m.Binary("-", a, a, m.INTEGER, None), m.INTEGER, None)  # type: ignore[arg-type]
    assert expression(e) == "(1 - (1 - 1))"


def test_cli_cif(tmp_path: Path, capsys):
    out = tmp_path / "maze.cif"
    assert main(["cif", str(EXAMPLES / "maze_solver.rscd"), "-o", str(out)]) == 0
    assert "plant automaton Platform:" in out.read_text()
    assert main(["cif", str(EXAMPLES / "emergency_stop.rscd"), "-o", str(out)]) == 2
    assert "is a library" in capsys.readouterr().err
