"""Model expressions as Python source text, for the generated supervisor module.

Locations and enum values are strings at run time, so a guard reads like the
model: ``(self.c_Platform == 'ready' and self.v_Distance_front == 'wall_front')``.
Every name and string from the model is written with :func:`repr`, never pasted.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass

from robosc.language import model as m

_OPERATORS = {
    "=": "==",
    "!=": "!=",
    "<": "<",
    "<=": "<=",
    ">": ">",
    ">=": ">=",
    "+": "+",
    "-": "-",
    "*": "*",
    "/": "/",
}


def identifier(*parts: str) -> str:
    """A Python identifier made of model names (which are ASCII letters, digits, '_')."""
    text = "_".join(parts)
    text = re.sub(r"\W", "_", text, flags=re.ASCII)
    return text if text and not text[0].isdigit() else f"_{text}"


def constant(value: object) -> str:
    """A Python literal for a model value (escaped by ``repr``)."""
    if isinstance(value, m.EnumValue):
        return repr(value.name)
    if isinstance(value, float) and not math.isfinite(value):
        return f"float({str(value)!r})"
    if isinstance(value, bool | int | float | str) or value is None:
        return repr(value)
    raise TypeError(f"no Python literal for {value!r}")


@dataclass(frozen=True)
class Names:
    """Where the generated code keeps each location and variable (``self.<field>``)."""

    locations: Mapping[m.State, tuple[str, str]]  # state -> (field, location name)
    variables: Mapping[m.Variable, str]  # variable -> field
    data: str = "value"  # the name the received data has inside a handler


def steps(steps: tuple[m.Step, ...]) -> str:
    out = []
    for step in steps:
        if isinstance(step, m.FieldStep):
            out.append("." + identifier(step.property.name))
        else:
            out.append(f"[{step.index}]")
    return "".join(out)


def python(expr: m.Expr, names: Names, owner: str = "self") -> str:
    """``expr`` as a Python expression; ``owner`` is how the code names the supervisor."""
    if isinstance(expr, m.Literal):
        return constant(expr.value)
    if isinstance(expr, m.EnumLiteral):
        return repr(expr.value.name)
    if isinstance(expr, m.StateRef):
        field, location = names.locations[expr.state]
        return f"{owner}.{field} == {location!r}"
    if isinstance(expr, m.VariableRef):
        return f"{owner}.{names.variables[expr.variable]}{steps(expr.steps)}"
    if isinstance(expr, m.DataRef):
        return f"{names.data}{steps(expr.steps)}"
    if isinstance(expr, m.Unary):
        inner = _operand(expr.operand, names, owner)
        return f"not {inner}" if expr.op == "!" else f"-{inner}"
    if isinstance(expr, m.Binary):
        left, right = _operand(expr.left, names, owner), _operand(expr.right, names, owner)
        if expr.op in ("and", "or"):
            return f"{left} {expr.op} {right}"
        if expr.op == "=>":
            return f"not {left} or {right}"
        return f"{left} {_OPERATORS[expr.op]} {right}"
    raise TypeError(f"cannot compile {type(expr).__name__}")


def _operand(expr: m.Expr, names: Names, owner: str) -> str:
    text = python(expr, names, owner)
    simple = isinstance(expr, m.Literal | m.EnumLiteral | m.VariableRef | m.DataRef)
    return text if simple else f"({text})"


def conjunction(parts: list[str]) -> str:
    """``a and b and c`` of already-compiled conditions (``True`` for none)."""
    kept = [p for p in parts if p != "True"]
    if not kept:
        return "True"
    if len(kept) == 1:
        return kept[0]
    return " and ".join(f"({p})" if " or " in p or p.startswith("not ") else p for p in kept)
