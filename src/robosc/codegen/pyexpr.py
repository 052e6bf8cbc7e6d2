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
from robosc.plant.expressions import reads_data
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
    # where set: a count of fields that each hold one of the same values (``count(q in bot:
    # q.depot or q.lift)``) is read from a tally of those fields made once per evaluation of
    # the supervisor's conditions (see :func:`tallied`): the fields -> the tally's attribute
    tallies: dict[tuple[str, ...], str] | None = field(default=None, compare=False, repr=False)
    # a field of one robot of a group -> the fields of the same role of every robot of the
    # group, in order (the fields a tally counts)
    groups: Mapping[str, tuple[str, ...]] | None = field(default=None, compare=False, repr=False)
    # whether each expression written so far reads received data (see reads_data)
    reading: dict[int, tuple[m.Expr, bool]] = field(default_factory=dict, compare=False, repr=False)


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
    if reads_data(expr, names.reading):
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
        if expr.op == "or" and names.tallies is not None and owner == "self":
            found = tallied(expr, names)  # any(q in bot: q.corridor): whether the count is not 0
            if found is not None:
                return f"{_tally_count(found, owner)} > 0"
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
    if isinstance(expr, m.Count):
        found = tallied(expr, names) if owner == "self" else None
        if found is not None:  # one lookup per value, whatever the number of robots
            return _tally_count(found, owner)
        # booleans add up as 0 and 1
        return f"sum(({', '.join(_operand(t, names, owner) for t in expr.terms)},))"
    raise TypeError(f"cannot compile {type(expr).__name__}")


MISSING_AT_MOST = 2  # fields of a group a tallied count may leave out (the robot itself, one singled out)
TALLIED_FROM = 4  # robots in a group: in a smaller one, reading each field is quicker than a tally


def tallied(expr: m.Count | m.Binary, names: Names) -> tuple[str, tuple[str, ...], tuple[str, ...]] | None:
    """Where ``names.tallies`` is set and ``expr`` counts (a :class:`Count`), or asks whether
    any (a disjunction), among the robots of a group, those whose field holds one of the same
    values (a location, an enum value), each robot's field of the same role, all of the group's
    but at most MISSING_AT_MOST: the tally's attribute, the values (sorted) and the fields
    left out; the group's fields are added to ``names.tallies``. None for anything else."""
    if names.tallies is None or names.groups is None:
        return None
    found: dict[str, frozenset[str]] = {}
    place: dict[str, int] = {}  # a count's field -> its term's place (the robot's, in the group)
    if isinstance(expr, m.Count):
        for index, term in enumerate(expr.terms):
            if isinstance(term, m.Literal) and term.value is False:
                continue  # a robot left out (the robot itself, one singled out)
            holds = _holds(term, names)
            if holds is None or holds[0] in found:
                return None
            found[holds[0]] = holds[1]
            place[holds[0]] = index
    else:
        for leaf in _disjuncts(expr):
            holds = _holds(leaf, names)
            if holds is None:
                return None
            found[holds[0]] = found.get(holds[0], frozenset()) | holds[1]
    if len(found) < 2 or len(set(found.values())) != 1:
        return None
    group = names.groups.get(next(iter(found)))
    if group is None or len(group) < TALLIED_FROM or any(names.groups.get(f) != group for f in found):
        return None
    if isinstance(expr, m.Count) and (len(expr.terms) != len(group) or any(group[i] != f for f, i in place.items())):
        return None  # a count's terms not in the order of the group's robots
    missing = tuple(f for f in group if f not in found)
    if len(missing) > MISSING_AT_MOST:
        return None
    attribute = names.tallies.get(group)
    if attribute is None:
        attribute = names.tallies[group] = f"_t{len(names.tallies)}"
    return attribute, tuple(sorted(next(iter(found.values())))), missing


def _tally_count(found: tuple[str, tuple[str, ...], tuple[str, ...]], owner: str) -> str:
    """The code of a tallied count (see :func:`tallied`): a lookup per value, less the fields
    left out that hold one."""
    attribute, values, missing = found
    parts = [f"{owner}.{attribute}.get({v!r}, 0)" for v in values]
    inside = repr(values[0]) if len(values) == 1 else repr(values)
    test = "==" if len(values) == 1 else "in"
    parts += [f"({owner}.{f} {test} {inside})" for f in missing]
    text = " + ".join(parts[: len(values)])
    if missing:
        text += " - " + " - ".join(parts[len(values) :])
    return text if len(parts) == 1 else f"({text})"


def _disjuncts(expr: m.Expr) -> list[m.Expr]:
    """The operands of a chain of ``or``, flattened."""
    out, stack = [], [expr]
    while stack:
        e = stack.pop()
        if isinstance(e, m.Binary) and e.op == "or":
            stack += [e.right, e.left]
        else:
            out.append(e)
    return out


def _holds(term: m.Expr, names: Names) -> tuple[str, frozenset[str]] | None:
    """(field, values) where ``term`` is true exactly when the field holds one of the values
    (strings: locations, enum values); else None."""
    if isinstance(term, m.StateRef):
        field, location = names.locations[term.state]
        return field, frozenset((location,))
    if isinstance(term, m.Binary) and term.op == "=":
        for ref, value in ((term.left, term.right), (term.right, term.left)):
            if isinstance(ref, m.VariableRef) and not ref.steps and isinstance(value, m.EnumLiteral):
                return names.variables[ref.variable], frozenset((value.value.name,))
        return None
    if isinstance(term, m.Binary) and term.op == "or":
        left, right = _holds(term.left, names), _holds(term.right, names)
        if left is None or right is None or left[0] != right[0]:
            return None
        return left[0], left[1] | right[1]
    return None


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
