"""Rule 10: a variable that takes part in synthesis is a boolean, a ranged integer or an enum."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import (
    ArrayType,
    BasicKind,
    BasicType,
    EnumType,
    ErrorType,
    Model,
    ObjectType,
    synthesis_variables,
)


def check(model: Model) -> Iterator[Diagnostic]:
    for variable, use in synthesis_variables(model).items():
        t = variable.type
        if isinstance(t, (EnumType, ErrorType, ArrayType, ObjectType)):
            continue  # arrays and objects are refused for every variable: no-array, no-object-variable
        if isinstance(t, BasicType) and t.kind in (BasicKind.BOOLEAN, BasicKind.INTEGER):
            continue  # unranged integers: rule 9
        yield error(
            variable.span,
            f"variable '{variable.name}' of type {t} takes part in synthesis (used at {use.span}); "
            "only booleans, ranged integers and enums can",
            Code.SYNTHESIS_TYPES,
            "use an enum that turns the data into a few named values",
        )
