"""Building model expressions for guards and requirements that the plant construction makes."""

from __future__ import annotations

from collections.abc import Sequence

from robosc.language import model as m
from robosc.language.source import Span

NO_SPAN = Span("<robosc>", 0, 0, 0, 0, 0, 0)
TRUE = m.Literal(True, m.BOOLEAN, NO_SPAN)
FALSE = m.Literal(False, m.BOOLEAN, NO_SPAN)


def negate(e: m.Expr) -> m.Expr:
    if isinstance(e, m.Unary) and e.op == "!":
        return e.operand
    if isinstance(e, m.Literal) and isinstance(e.value, bool):
        return FALSE if e.value else TRUE
    return m.Unary("!", e, m.BOOLEAN, e.span)


def _join(op: str, parts: Sequence[m.Expr], empty: m.Expr) -> m.Expr:
    if not parts:
        return empty
    result = parts[0]
    for part in parts[1:]:
        result = m.Binary(op, result, part, m.BOOLEAN, part.span)
    return result


def any_of(parts: Sequence[m.Expr]) -> m.Expr:
    return _join("or", parts, FALSE)


def all_of(parts: Sequence[m.Expr]) -> m.Expr:
    return _join("and", parts, TRUE)


def variables_in(e: m.Expr) -> set[m.Variable]:
    return {n.variable for n in m.walk(e) if isinstance(n, m.VariableRef)}


def reads_data(e: m.Expr, known: dict[int, tuple[m.Expr, bool]] | None = None) -> bool:
    """Whether ``e`` reads received data. ``known``: the answers found so far, by id (the
    expression kept, so that its id stays its own), used and added to: each part is looked at
    once, however often it is asked about (the generated module asks at every level of a long
    condition, and walking each part again made writing a warehouse of 500 robots' take minutes)."""
    known = {} if known is None else known
    stack: list[tuple[m.Expr, bool]] = [(e, False)]
    while stack:
        node, seen = stack.pop()
        if id(node) in known:
            continue
        parts: tuple[m.Expr, ...] = ()
        if isinstance(node, m.Binary):
            parts = (node.left, node.right)
        elif isinstance(node, m.Unary):
            parts = (node.operand,)
        elif isinstance(node, m.Count):
            parts = node.terms
        if parts and not seen:
            stack.append((node, True))
            stack += [(part, False) for part in parts]
            continue
        known[id(node)] = (node, isinstance(node, m.DataRef) or any(known[id(part)][1] for part in parts))
    return known[id(e)][1]
