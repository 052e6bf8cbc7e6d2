"""A variable cannot have an object type (as in the original): objects describe middleware
messages; keep the parts you need in variables of basic or enum types."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Model, ObjectType


def check(model: Model) -> Iterator[Diagnostic]:
    for variable in model.variables:
        if isinstance(variable.type, ObjectType):
            yield error(
                variable.span,
                f"variable '{variable.name}' has the object type {variable.type}; a variable cannot hold an object",
                Code.NO_OBJECT_VARIABLE,
                "keep the properties you need, as in 'variable x: double' with 'x := value.position.x'",
            )
