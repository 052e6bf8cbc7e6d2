"""Warning: a guard, requirement or provide condition reads an enum variable that has no
initial value. robosc starts it at the enum's first declared value (SEMANTICS.md section
2); the original tool's choice is unspecified (it writes CIF enums from an unordered set),
so before the first update the two may allow different events."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, warning
from robosc.language.model import EnumType, Model, synthesis_variables


def check(model: Model) -> Iterator[Diagnostic]:
    for variable, use in synthesis_variables(model).items():
        t = variable.type
        if not isinstance(t, EnumType) or variable.initial is not None or not t.values:
            continue
        first = t.values[0].name
        yield warning(
            variable.span,
            f"'{variable.name}' is read at {use.span} but has no initial value: it starts as '{first}', "
            f"the first value of {t.name} (the original tool's start value was unspecified)",
            Code.IMPLICIT_START,
            f"say where it starts, as in 'variable {variable.name}: {t.name} = {first}'",
        )
