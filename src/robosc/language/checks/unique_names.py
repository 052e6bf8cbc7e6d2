"""Rule 1: names are unique per kind (components, communications, data types,
interfaces, object properties, states and variables within an automaton, enum
values), and enum values do not clash with state names."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import Protocol

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
        if item.name in first:
            earlier = first[item.name].span
            yield error(
                item.span,
                f"{kind} '{item.name}'{where} is defined more than once (first at {earlier})",
                "rule-1",
            )
        else:
            first[item.name] = item


def check(model: Model) -> Iterator[Diagnostic]:
    yield from duplicates("component", model.components)
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
    state_names = {state.name: state for state in states}
    for value in values:
        if value.name in state_names:
            state = state_names[value.name]
            yield error(
                value.span,
                f"enum value '{value.name}' has the name of state '{state.owner}.{state.name}' ({state.span})",
                "rule-1",
            )
