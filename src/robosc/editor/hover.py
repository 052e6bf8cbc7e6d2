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


def _owner(component: m.Component, model: m.Model) -> str:
    """How a hover names a declaration's component: ``Door``, or ``bot`` (bot1 .. bot4)."""
    if component.group is None:
        return f"`{component.name}`"
    instances = model.groups[component.group]
    return f"each of `{instances[0].name}` .. `{instances[-1].name}`" if len(instances) > 1 else f"`{component.name}`"


MOST_INSTANCES = 4  # a fleet's hover shows this many instances' conditions


def describe(model: m.Model, notes: dict[str, list[str]] | None, name: str) -> str | None:
    """Markdown about every declaration called ``name``; None if there is none. ``notes``:
    what synthesis found for each communication (:func:`guard_notes`), None while it runs.
    A declaration in a component with instances is described once, for all of them."""
    parts: list[str] = []
    shown: set[tuple[str, object]] = set()  # (kind, span) of what was described: once per declaration
    noted: dict[object, int] = {}  # a communication's span -> of how many instances the conditions are shown
    for component in model.components:
        owner = _owner(component, model)
        for comm in component.communications:
            local = comm.name.rsplit(".", 1)[-1]
            if name not in (comm.name, local):
                continue
            if ("comm", comm.span) in shown:  # another instance's: its conditions, for a few
                noted[comm.span] = noted.get(comm.span, 1) + 1
                if notes is not None and noted[comm.span] <= MOST_INSTANCES and not notes.get(NO_SUPERVISOR):
                    parts += notes.get(comm.name, [])
                continue
            shown.add(("comm", comm.span))
            kind = type(comm).__name__.lower()
            if isinstance(comm, m.Message):
                head = f"**{comm.direction.value} message `{local}`** of {owner}: `{_type_name(comm.type)}`"
            else:
                head = f"**{kind} `{local}`** of {owner}"
            parts.append(head + f", ROS name `{comm.ros_name}`" + (" (and so on)" if component.group else ""))
            if notes is None:
                parts.append("_synthesis is running…_")
            else:
                parts += notes.get(NO_SUPERVISOR, []) or notes.get(comm.name, [])
        automaton = component.automaton
        if automaton is None:
            continue
        for state in automaton.states:
            if state.name == name and ("state", state.span) not in shown:
                shown.add(("state", state.span))
                flags = [w for w, on in (("initial", state.initial), ("marked", state.marked)) if on]
                label = f"`{component.name}.{state.name}`" if component.group is None else f"`{state.name}` of {owner}"
                parts.append(f"**state {label}** {' '.join(flags)}".rstrip())
        for variable in automaton.variables:
            if variable.name == name and ("variable", variable.span) not in shown:
                shown.add(("variable", variable.span))
                label = f"`{component.name}.{variable.name}`" if component.group is None else f"`{variable.name}` of {owner}"
                parts.append(f"**variable {label}**: `{_type_name(variable.type)}`")
    groups = model.groups
    if name in groups:
        instances = groups[name]
        parts.append(
            f"**group `{name}`** of {len(instances)} instance{'s' if len(instances) != 1 else ''}: "
            + ", ".join(f"`{c.name}` in `{c.namespace}`" for c in instances[:MOST_INSTANCES])
            + (f" .. `{instances[-1].name}`" if len(instances) > MOST_INSTANCES else "")
        )
    return "\n\n".join(parts) if parts else None


NO_SUPERVISOR = ""  # the notes' key when synthesis found no supervisor


def guard_notes(result: Any) -> dict[str, list[str]]:
    """Communication name -> a Markdown line per controllable event: the user's condition and
    the one synthesis added, with why (plain data: made where synthesis ran, shown on hover)."""
    from robosc.language.render import render
    from robosc.synthesis.restrictions import restriction as why_restricted
    from robosc.synthesis.warnings import why_lines

    if not result.ok:
        return {NO_SUPERVISOR: ["_no supervisor exists: see `robosc synthesize`_"]}
    notes: dict[str, list[str]] = {}
    for guard in result.guards:
        if not guard.event.controllable:
            continue
        required = render(guard.required) if guard.required is not None else "true"
        line = f"- `{guard.event.name}` needs `{required}`"
        if guard.added is not None:
            line += f"; **synthesis added** `{render(guard.added)}`"
            restriction = why_restricted(result, guard.event)
            if restriction is not None:
                line += "\n\n```\n" + "\n".join(why_lines(restriction)) + "\n```"
        notes.setdefault(guard.event.communication.name, []).append(line)
    return notes
