"""Rule 1: names are unique per kind (components, communications, data types,
interfaces, object properties, states and variables within an automaton, enum
values), and enum values do not clash with state names."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import Protocol

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Model, ObjectType, State
from robosc.language.source import Span


class Named(Protocol):
    @property
    def name(self) -> str: ...

    @property
    def span(self) -> Span: ...


def duplicates(kind: str, items: Iterable[Named], where: str = "") -> Iterator[Diagnostic]:
    first: dict[str, Named] = {}
    for item in items:
        key = item.name.lower()
        if key not in first:
            first[key] = item
            continue
        earlier = first[key]
        if earlier.name == item.name:
            yield error(
                item.span,
                f"{kind} '{item.name}'{where} is defined more than once (first at {earlier.span})",
                Code.UNIQUE_NAMES,
            )
        else:
            yield error(
                item.span,
                f"{kind} '{item.name}'{where} differs from '{earlier.name}' ({earlier.span}) only in case; "
                "names are compared without case (as in the original tool)",
                Code.UNIQUE_NAMES,
                "choose a name that differs in more than case",
            )


def check(model: Model) -> Iterator[Diagnostic]:
    yield from duplicates("component", [c for c in model.components if c.group is None])  # instances: their check
    yield from duplicates("communication", model.communications)
    yield from duplicates("data type", model.data_types)
    yield from duplicates("interface", model.interfaces)
    for data_type in model.data_types:
        if isinstance(data_type, ObjectType):
            yield from duplicates("property", data_type.properties, f" of {data_type.name}")
    states: list[State] = []
    for component in model.components:
        for automaton in component.behaviours:
            yield from duplicates("state", automaton.states, f" of '{component.name}'")
            yield from duplicates("variable", automaton.variables, f" of '{component.name}'")
            states += automaton.states
    values = [value for enum in model.enums for value in enum.values]
    yield from duplicates("enum value", values)
    state_names = {state.name.lower(): state for state in states}
    for value in values:
        if value.name.lower() in state_names:
            state = state_names[value.name.lower()]
            yield error(
                value.span,
                f"enum value '{value.name}' has the name of state '{state.owner}.{state.name}' ({state.span})",
                Code.UNIQUE_NAMES,
            )
