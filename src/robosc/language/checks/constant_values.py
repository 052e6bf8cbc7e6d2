"""Constant parts of expressions must be computable: a division whose divisor is the
constant zero (``1.0 / 0.0``, ``value.x / (2 - 2)``) can never be computed, at synthesis
or at run time, so it is an error where it is written."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import (
    Binary,
    EnumType,
    Expr,
    Literal,
    Model,
    ObjectValue,
    ResultTransition,
    TauTransition,
    Unary,
    walk_all,
)


def value(expr: Expr) -> object:
    """The value of an expression made of number literals only, else None."""
    if isinstance(expr, Literal) and isinstance(expr.value, int | float) and not isinstance(expr.value, bool):
        return expr.value
    if isinstance(expr, Unary) and expr.op == "-":
        inner = value(expr.operand)
        return -inner if isinstance(inner, int | float) else None
    if isinstance(expr, Binary) and expr.op in ("+", "-", "*", "/"):
        left, right = value(expr.left), value(expr.right)
        if not isinstance(left, int | float) or not isinstance(right, int | float):
            return None
        try:
            if expr.op == "+":
                return left + right
            if expr.op == "-":
                return left - right
            if expr.op == "*":
                return left * right
            return left / right
        except (ZeroDivisionError, OverflowError):
            return None
    return None


def expressions(model: Model) -> Iterator[Expr]:
    """Every expression written in the model."""
    for t in model.data_types:
        if isinstance(t, EnumType):
            yield from (r.condition for r in t.rules if r.condition is not None)
    for component in model.components:
        for automaton in component.behaviours:
            yield from (v.initial for v in automaton.variables if v.initial is not None)
            for transition in automaton.transitions:
                if isinstance(transition, TauTransition) and transition.guard is not None:
                    yield transition.guard
                elif isinstance(transition, ResultTransition):
                    yield from (a.value for a in transition.assignments)
    yield from (r.condition for r in model.requirements)
    for provide in model.provides:
        if provide.condition is not None:
            yield provide.condition
        stack: list[Expr | ObjectValue] = [provide.data]
        while stack:
            data = stack.pop()
            if isinstance(data, ObjectValue):
                stack += [f.value for f in data.fields]
            else:
                yield data


def check(model: Model) -> Iterator[Diagnostic]:
    for node in walk_all(expressions(model)):  # a part several expressions share: once
        if isinstance(node, Binary) and node.op == "/" and value(node.right) == 0:
            yield error(
                node.span,
                "division by zero: this can never be computed",
                Code.CONSTANT,
                "divide by something that is not zero",
            )
