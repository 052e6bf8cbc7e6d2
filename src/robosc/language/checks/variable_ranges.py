"""A constant given to a ranged integer variable (initially or by an assignment) lies in
its range. For a variable that takes part in synthesis that is an error (the plant could
not hold the value); for one that only carries data it is a warning, as the original
tool accepts it (its own language test assigns -5 to an ``integer(0..20)``)."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.checks.constant_values import value
from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error, warning
from robosc.language.model import BasicType, Expr, Model, ResultTransition, Variable, synthesis_variables


def _constants(model: Model) -> Iterator[tuple[Variable, Expr]]:
    for component in model.components:
        for automaton in component.behaviours:
            for variable in automaton.variables:
                if variable.initial is not None:
                    yield variable, variable.initial
            for transition in automaton.transitions:
                if isinstance(transition, ResultTransition):
                    for assignment in transition.assignments:
                        if not assignment.steps:
                            yield assignment.variable, assignment.value


def check(model: Model) -> Iterator[Diagnostic]:
    in_synthesis = synthesis_variables(model)
    for variable, expr in _constants(model):
        t = variable.type
        constant = value(expr)
        if not isinstance(t, BasicType) or not t.is_ranged_integer or not isinstance(constant, int):
            continue
        assert t.low is not None and t.high is not None
        if t.low <= constant <= t.high:
            continue
        message = f"{constant} is outside the range of '{variable.name}' ({t})"
        if variable in in_synthesis:
            yield error(expr.span, message, Code.RANGE, f"'{variable.name}' takes part in synthesis; widen its range")
        else:
            yield warning(
                expr.span,
                message + "; no guard or requirement reads it, so this is allowed, but the value will be out of range",
                Code.RANGE,
                f"widen the range of '{variable.name}'",
            )
