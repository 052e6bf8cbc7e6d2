"""Rule 9: an integer whose value takes part in synthesis needs a range: a variable named
in a guard, requirement or provide condition, and (as the original decides) received
data, a message's or an object property's integer, assigned to such a variable."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import (
    BasicKind,
    BasicType,
    DataType,
    FieldStep,
    IndexStep,
    Literal,
    Model,
    Variable,
    synthesis_inputs,
    synthesis_variables,
)
from robosc.language.source import Span


def _unranged(t: DataType) -> bool:
    return isinstance(t, BasicType) and t.kind is BasicKind.INTEGER and not t.is_ranged_integer


def _suggested(variable: Variable) -> str:
    """A range to start from: 0..10, widened to hold the initial value."""
    initial = variable.initial.value if isinstance(variable.initial, Literal) else 0
    value = initial if isinstance(initial, int) and not isinstance(initial, bool) else 0
    return f"{min(0, value)}..{max(10, value)}"


def check(model: Model) -> Iterator[Diagnostic]:
    for variable, use in synthesis_variables(model).items():
        if _unranged(variable.type):
            yield error(
                variable.span,
                f"integer variable '{variable.name}' takes part in synthesis (used at {use.span}) and needs a range",
                Code.INTEGER_RANGE,
                f"give it a range, as in '{variable.name}: integer({_suggested(variable)})'",
            )
    reported: set[Span] = set()
    for found in synthesis_inputs(model):
        if not _unranged(found.data.type) or any(isinstance(s, IndexStep) for s in found.data.steps):
            continue  # array elements: no_array
        last = found.data.steps[-1] if found.data.steps else None
        where = last.property.span if isinstance(last, FieldStep) else found.communication.span
        what = (
            f"property '{last.property.name}'"
            if isinstance(last, FieldStep)
            else f"the data of '{found.communication.name}'"
        )
        if where in reported:
            continue
        reported.add(where)
        yield error(
            where,
            f"{what} is an integer without a range, and it reaches '{found.variable.name}', which takes part in "
            f"synthesis (at {found.data.span})",
            Code.INTEGER_RANGE,
            "give the integer a range, as in 'integer(0..100)'",
        )
