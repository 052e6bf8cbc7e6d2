"""An enum value is named by one rule only (the original makes each rule declare its
value, so a second rule naming the same value is a duplicate name)."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Model


def check(model: Model) -> Iterator[Diagnostic]:
    for enum in model.enums:
        first: dict[str, int] = {}
        for number, rule in enumerate(enum.rules):
            key = rule.value.name
            if key in first:
                earlier = enum.rules[first[key]]
                yield error(
                    rule.span,
                    f"enum '{enum.name}' names value '{rule.value.name}' in more than one rule "
                    f"(first at {earlier.span})",
                    Code.ENUM_VALUES,
                    "join the conditions with 'or' in one rule, or give this value its own name",
                )
            else:
                first[key] = number
