"""Model expressions as Python source text, for the generated supervisor module.

Locations and enum values are strings at run time, so a guard reads like the
model: ``self.a8_Platform == 'ready' and self.v0_Distance_front == 'wall_front'``.
Every string from the model is written with :func:`repr`, never pasted, and a
property whose name is not a plain Python identifier (a keyword reached through
``^``) is read with ``getattr``.
"""

from __future__ import annotations

import ast
import keyword
import math
import re
from collections.abc import Mapping

from robosc.language import model as m
from robosc.record import field, record

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


class Identifiers:
    """The one scheme from model names to generated identifiers: a letter prefix, a number
    that no other identifier with that prefix has, then the model name for the reader
    (``a8_Platform``, ``v0_Distance_front``, ``e3_pick_c_trigger``). The number alone makes
    the mapping injective (``A.b_c`` and ``A_b.c`` get different numbers), the prefix keeps
    keywords and the runtime's own names (which carry no digit) out of reach."""

    def __init__(self) -> None:
        self.count: dict[str, int] = {}

    def new(self, prefix: str, *parts: str) -> str:
        n = self.count.get(prefix, 0)
        self.count[prefix] = n + 1
        text = re.sub(r"\W", "_", "_".join(parts), flags=re.ASCII)
        return f"{prefix}{n}_{text}" if text else f"{prefix}{n}"


GENERATED = re.compile(r"^[A-Za-z]+[0-9]+(_|$)")  # what :class:`Identifiers` makes


def attribute(base: str, name: str) -> str:
    """``base.name``, or ``getattr(base, 'name')`` where ``name`` cannot follow a dot."""
    if name.isidentifier() and not keyword.iskeyword(name) and name.isascii():
        return f"{base}.{name}"
    return f"getattr({base}, {name!r})"


def constant(value: object) -> str:
    """A Python literal for a model value (escaped by ``repr``)."""
    if isinstance(value, m.EnumValue):
        return repr(value.name)
    if isinstance(value, float) and not math.isfinite(value):
        return f"float({str(value)!r})"
    if isinstance(value, bool | int | float | str) or value is None:
        return repr(value)
    raise TypeError(f"no Python literal for {value!r}")


@record
class Names:
    """Where the generated code keeps each location and variable (``self.<field>``)."""

    locations: Mapping[m.State, tuple[str, str]]  # state -> (field, location name)
    variables: Mapping[m.Variable, str]  # variable -> field
    data: str = "value"  # the name the received data has inside a handler
    # received data is read through the runtime's checks (num, whole, flag, text), and a
    # computation on it must give a number: unreadable data raises instead of passing as a value
    checked: bool = False
    # where set: a long condition over the state (a count over a fleet, what `any` over it
    # expands to) is written once, as a method of the supervisor, and called where it is used:
    # its code -> the method's name (see :func:`python`); the module stays linear in the fleet
    shared: dict[str, str] | None = field(default=None, compare=False, repr=False)


_READERS = {
    m.BasicKind.DOUBLE: "num",
    m.BasicKind.INTEGER: "whole",
    m.BasicKind.BOOLEAN: "flag",
    m.BasicKind.STRING: "text",
}
_ARITHMETIC = frozenset("+-*/")


def access(base: str, steps: tuple[m.Step, ...]) -> str:
    """``base`` followed by property and index steps."""
    for step in steps:
        base = attribute(base, step.property.name) if isinstance(step, m.FieldStep) else f"{base}[{step.index}]"
    return base


def step_path(steps: tuple[m.Step, ...]) -> tuple[str | int, ...]:
    """Steps as plain data for the runtime: property names and indices."""
    return tuple(s.property.name if isinstance(s, m.FieldStep) else s.index for s in steps)


SHARED_FROM = 160  # characters: a condition this long over the state is a method of its own


def python(expr: m.Expr, names: Names, owner: str = "self") -> str:
    """``expr`` as a Python expression; ``owner`` is how the code names the supervisor. With
    ``names.shared``, a long condition over the state is a method call (``self._part3()``),
    evaluated where it stands, as the expression itself would be."""
    code = _python(expr, names, owner)
    shared = names.shared
    if shared is None or owner != "self" or len(code) < SHARED_FROM or not isinstance(expr, _SHAREABLE):
        return code
    if any(isinstance(n, m.DataRef) for n in m.walk(expr)):
        return code  # received data: a handler's local
    name = shared.get(code)
    if name is None:
        name = shared[code] = f"_part{len(shared)}"
    return f"self.{name}()"


_SHAREABLE = (m.Count, m.Binary, m.Unary)


def _python(expr: m.Expr, names: Names, owner: str) -> str:
    if isinstance(expr, m.Literal):
        return constant(expr.value)
    if isinstance(expr, m.EnumLiteral):
        return repr(expr.value.name)
    if isinstance(expr, m.StateRef):
        field, location = names.locations[expr.state]
        return f"{owner}.{field} == {location!r}"
    if isinstance(expr, m.VariableRef):
        return access(f"{owner}.{names.variables[expr.variable]}", expr.steps)
    if isinstance(expr, m.DataRef):
        read = access(names.data, expr.steps)
        reader = _READERS.get(expr.type.kind) if names.checked and isinstance(expr.type, m.BasicType) else None
        return f"{reader}({read})" if reader else read
    if isinstance(expr, m.Unary):
        inner = _operand(expr.operand, names, owner)
        return f"not {inner}" if expr.op == "!" else f"-{inner}"
    if isinstance(expr, m.Binary):
        left, right = _operand(expr.left, names, owner), _operand(expr.right, names, owner)
        if expr.op in ("and", "or"):
            return f"{left} {expr.op} {right}"
        if expr.op == "=>":
            return f"not {left} or {right}"
        text = f"{left} {_OPERATORS[expr.op]} {right}"
        numeric = isinstance(expr.type, m.BasicType) and expr.type.kind in (m.BasicKind.DOUBLE, m.BasicKind.INTEGER)
        if names.checked and numeric and expr.op in _ARITHMETIC and any(isinstance(n, m.DataRef) for n in m.walk(expr)):
            return f"num({text})"  # inf - inf: NaN is not a value
        return text
    if isinstance(expr, m.Count):  # booleans add up as 0 and 1
        return f"sum(({', '.join(_operand(t, names, owner) for t in expr.terms)},))"
    raise TypeError(f"cannot compile {type(expr).__name__}")


def _operand(expr: m.Expr, names: Names, owner: str) -> str:
    text = python(expr, names, owner)
    simple = isinstance(expr, m.EnumLiteral | m.VariableRef | m.DataRef) or (
        isinstance(expr, m.Literal) and not (isinstance(expr.value, int | float) and expr.value < 0)
    )
    return text if simple else f"({text})"


def conjunction(parts: list[str]) -> str:
    """``a and b and c`` of already-compiled conditions (``True`` for none), each conjunct
    once, without redundant parentheses."""
    conjuncts: list[ast.expr] = []
    seen: set[str] = set()
    for part in parts:
        for c in _conjuncts(ast.parse(part, mode="eval").body):
            key = ast.dump(c)
            if key not in seen and not (isinstance(c, ast.Constant) and c.value is True):
                seen.add(key)
                conjuncts.append(c)
    if not conjuncts:
        return "True"
    if len(conjuncts) == 1:
        return ast.unparse(conjuncts[0])
    return ast.unparse(ast.BoolOp(op=ast.And(), values=conjuncts))


def _conjuncts(e: ast.expr) -> list[ast.expr]:
    if isinstance(e, ast.BoolOp) and isinstance(e.op, ast.And):
        return [c for v in e.values for c in _conjuncts(v)]
    return [e]
