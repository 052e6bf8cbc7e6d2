"""Array data cannot reach synthesis (the original's NO_ARRAY_ALLOWED): received data
assigned to a variable that takes part in synthesis is not an array or an element of one.
(Variables of array type in synthesis are rule 10.) Turn array data into a few named
values with an enum instead: ``datatype enum E from LaserScan to { ... }``."""

from __future__ import annotations

import itertools
from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import ArrayType, FieldStep, IndexStep, Model, synthesis_inputs
from robosc.language.source import Span


def check(model: Model) -> Iterator[Diagnostic]:
    reported: set[Span] = set()
    for found in synthesis_inputs(model):
        steps = found.data.steps
        if not isinstance(found.data.type, ArrayType) and not any(isinstance(s, IndexStep) for s in steps):
            continue
        # the array is the data itself, or the property just before the first index
        where, what = found.communication.span, f"the data of '{found.communication.name}'"
        for before, step in itertools.pairwise(steps):
            if isinstance(step, IndexStep) and isinstance(before, FieldStep):
                where, what = before.property.span, f"property '{before.property.name}'"
                break
        else:
            if steps and isinstance(steps[-1], FieldStep) and isinstance(found.data.type, ArrayType):
                where, what = steps[-1].property.span, f"property '{steps[-1].property.name}'"
        if where in reported:
            continue
        reported.add(where)
        yield error(
            where,
            f"{what} is an array, and it reaches '{found.variable.name}', which takes part in synthesis "
            f"(at {found.data.span}); synthesis cannot read array data",
            Code.NO_ARRAY,
            "turn the array into a few named values with an enum, as in "
            "'datatype enum E from T to { value.ranges[0] < 0.5 -> near, default -> far }'",
        )
