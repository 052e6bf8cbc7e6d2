"""Instances (``component bot[4] ...``): their names, bot1 .. bot4, clash with no other
component's and no other group's, compared without case as rule 1 compares names."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Component, Model


def _what(component: Component) -> str:
    if component.group is None:
        return f"component '{component.name}' ({component.span})"
    return f"instance {component.index} of '{component.group}' ({component.span})"


def check(model: Model) -> Iterator[Diagnostic]:
    seen: dict[str, Component] = {}
    groups = model.groups
    for component in model.components:
        key = component.name.lower()
        earlier = seen.setdefault(key, component)
        if earlier is component or (component.group is None and earlier.group is None):
            continue  # plain components are rule 1's
        if component.group is not None and component.group == earlier.group:
            continue  # the same group declared twice: reported once, below
        yield error(
            component.span,
            f"'{component.name}' names both {_what(earlier)} and {_what(component)}",
            Code.INSTANCES,
            "rename the component or the group: instances are named by the group's name and a number",
        )
    declared: dict[str, Component] = {}
    for component in model.components:
        if component.group is None:
            continue
        first = declared.setdefault(component.group.lower(), groups[component.group][0])
        if first.span != component.span:
            yield error(
                component.span,
                f"group '{component.group}' is declared twice (first at {first.span})",
                Code.INSTANCES,
            )
    plain = {c.name.lower(): c for c in model.components if c.group is None}
    for name, instances in groups.items():
        clash = plain.get(name.lower())
        if clash is not None:
            yield error(
                instances[0].span,
                f"group '{name}' has the name of component '{clash.name}' ({clash.span})",
                Code.INSTANCES,
                f"'for r in {name}' and 'all(q in {name}: ...)' name the group: give the component another name",
            )
