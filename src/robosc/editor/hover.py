"""Hover: what a name under the cursor is (a communication, state or variable of the checked
model) and, for a communication, each controllable event's condition: the user's
requirement and the one synthesis added, with why."""

from __future__ import annotations

import re
from typing import Any

from robosc.language import model as m

WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def word_at(line: str, character: int) -> str | None:
    """The identifier that covers ``character`` in ``line`` (``^`` escapes dropped)."""
    for match in WORD.finditer(line):
        if match.start() <= character <= match.end():
            return match.group()
    return None


def used_at(uses: list[Any], uri: str, most: int = 12) -> str:
    """Where a name is used, as Markdown: lines of this file, ``file:line`` of others."""
    if not uses:
        return "\n\n_not used anywhere_"
    places = [
        str(u.range.start.line + 1) if u.uri == uri else f"{u.uri.rsplit('/', 1)[-1]}:{u.range.start.line + 1}"
        for u in uses[:most]
    ]
    more = f" and {len(uses) - most} more" if len(uses) > most else ""
    return f"\n\nused {len(uses)} time{'s' if len(uses) != 1 else ''}: line {', '.join(places)}{more}"


def _type_name(t: Any) -> str:
    return str(getattr(t, "name", None) or getattr(getattr(t, "kind", None), "value", None) or t)


def describe(model: m.Model, result: Any, name: str) -> str | None:
    """Markdown about every declaration called ``name``; None if there is none."""
    from robosc.language.render import render

    parts: list[str] = []
    for component in model.components:
        for comm in component.communications:
            if comm.name != name:
                continue
            kind = type(comm).__name__.lower()
            if isinstance(comm, m.Message):
                head = f"**{comm.direction.value} message `{comm.name}`** of `{component.name}`: `{_type_name(comm.type)}`"
            else:
                head = f"**{kind} `{comm.name}`** of `{component.name}`"
            parts.append(head + f", ROS name `{comm.ros_name}`")
            parts += _guards(result, comm, render)
        automaton = component.automaton
        if automaton is None:
            continue
        for state in automaton.states:
            if state.name == name:
                flags = [w for w, on in (("initial", state.initial), ("marked", state.marked)) if on]
                parts.append(f"**state `{component.name}.{state.name}`** {' '.join(flags)}".rstrip())
        for variable in automaton.variables:
            if variable.name == name:
                parts.append(f"**variable `{component.name}.{variable.name}`**: `{_type_name(variable.type)}`")
    return "\n\n".join(parts) if parts else None


def _guards(result: Any, comm: m.Communication, render: Any) -> list[str]:
    if result is None:
        return ["_synthesis is running…_"]
    if not result.ok:
        return ["_no supervisor exists: see `robosc synthesize`_"]
    from robosc.synthesis.warnings import why_lines

    out = []
    for guard in result.guards:
        if guard.event.communication is not comm or not guard.event.controllable:
            continue
        required = render(guard.required) if guard.required is not None else "true"
        line = f"- `{guard.event.name}` needs `{required}`"
        if guard.added is not None:
            line += f"; **synthesis added** `{render(guard.added)}`"
            restriction = result.why(guard.event)
            if restriction is not None:
                line += "\n\n```\n" + "\n".join(why_lines(restriction)) + "\n```"
        out.append(line)
    return out
