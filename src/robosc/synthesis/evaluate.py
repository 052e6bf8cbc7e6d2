"""Evaluating model expressions in a concrete network state (explicit synthesis, simulator)."""

from __future__ import annotations

import operator
from collections.abc import Callable, Mapping
from typing import Any

from robosc.language import model as m

COMPARE: dict[str, Callable[[Any, Any], bool]] = {
    "=": operator.eq,
    "!=": operator.ne,
    "<": operator.lt,
    "<=": operator.le,
    ">": operator.gt,
    ">=": operator.ge,
}
ARITHMETIC: dict[str, Callable[[Any, Any], Any]] = {
    "+": operator.add,
    "-": operator.sub,
    "*": operator.mul,
    "/": operator.truediv,
}


class Undefined(Exception):
    """The expression has no value here (division by zero)."""


def evaluate(e: m.Expr, locations: frozenset[m.State] | set[m.State], values: Mapping[m.Variable, Any]) -> Any:
    if isinstance(e, m.Literal):
        return e.value
    if isinstance(e, m.EnumLiteral):
        return e.value
    if isinstance(e, m.StateRef):
        return e.state in locations
    if isinstance(e, m.VariableRef):
        return values[e.variable]
    if isinstance(e, m.Unary):
        inner = evaluate(e.operand, locations, values)
        return (not inner) if e.op == "!" else -inner
    if isinstance(e, m.Binary):
        if e.op == "and":
            return evaluate(e.left, locations, values) and evaluate(e.right, locations, values)
        if e.op == "or":
            return evaluate(e.left, locations, values) or evaluate(e.right, locations, values)
        if e.op == "=>":
            return (not evaluate(e.left, locations, values)) or evaluate(e.right, locations, values)
        left, right = evaluate(e.left, locations, values), evaluate(e.right, locations, values)
        if e.op == "/" and right == 0:
            raise Undefined("division by zero")
        return COMPARE[e.op](left, right) if e.op in COMPARE else ARITHMETIC[e.op](left, right)
    if isinstance(e, m.Count):
        return sum(1 for term in e.terms if evaluate(term, locations, values))
    raise Undefined(f"cannot evaluate {type(e).__name__}")
