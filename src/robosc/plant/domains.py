"""The finite domains of the variables that take part in synthesis, and their start values."""

from __future__ import annotations

from collections.abc import Sequence

from robosc.language import model as m


def domain(variable: m.Variable) -> Sequence[object]:
    t = variable.type
    if isinstance(t, m.EnumType):
        return tuple(t.values)
    if isinstance(t, m.BasicType) and t.kind is m.BasicKind.BOOLEAN:
        return (False, True)
    if isinstance(t, m.BasicType) and t.is_ranged_integer:
        assert t.low is not None and t.high is not None
        return range(t.low, t.high + 1)
    raise ValueError(f"variable '{variable.name}' of type {t} has no finite domain")


def initial_value(variable: m.Variable) -> object:
    """The given initial value, or the type's default (SEMANTICS.md section 2): false;
    for an integer the value of its range closest to 0, as CIF does (``integer(-5..-2)``
    starts at -2); the enum's first declared value."""
    values = domain(variable)
    if variable.initial is not None:
        e = variable.initial
        if isinstance(e, m.EnumLiteral):
            return e.value
        if isinstance(e, m.Literal):
            return e.value
        if isinstance(e, m.Unary) and isinstance(e.operand, m.Literal) and isinstance(e.operand.value, int):
            return -e.operand.value
    t = variable.type
    if isinstance(t, m.BasicType) and t.low is not None and t.high is not None:
        return t.low if t.low > 0 else min(t.high, 0)
    return values[0]
