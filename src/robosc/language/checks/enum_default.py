"""Section 4: each enum has exactly one ``default`` rule."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Model


def check(model: Model) -> Iterator[Diagnostic]:
    for enum in model.enums:
        defaults = [rule for rule in enum.rules if rule.condition is None]
        if not defaults:
            yield error(
                enum.span,
                f"enum '{enum.name}' has no default rule",
                Code.ENUM_DEFAULT,
                "add 'default -> <value>' for data that no rule matches",
            )
        for extra in defaults[1:]:
            yield error(extra.span, f"enum '{enum.name}' has more than one default rule", Code.ENUM_DEFAULT)
