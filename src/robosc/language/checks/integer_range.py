"""Rule 9: an integer variable that takes part in synthesis needs a range."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import BasicKind, BasicType, Model, synthesis_variables


def check(model: Model) -> Iterator[Diagnostic]:
    for variable, use in synthesis_variables(model).items():
        t = variable.type
        if isinstance(t, BasicType) and t.kind is BasicKind.INTEGER and not t.is_ranged_integer:
            yield error(
                variable.span,
                f"integer variable '{variable.name}' takes part in synthesis (used at {use.span}) and needs a range",
                "rule-9",
                f"give it a range, as in '{variable.name}: integer(0..10)'",
            )
