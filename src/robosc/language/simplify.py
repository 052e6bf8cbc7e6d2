"""Boolean constants folded out of model expressions, and balanced joins of many terms:
what expanding quantifiers over instances leaves (the resolver) and what reading conditions
through counters leaves (synthesis for fleets)."""

from __future__ import annotations

from collections.abc import Callable, Sequence

from robosc.language import model as m
from robosc.language.source import Span


def literal(value: bool, span: Span) -> m.Literal:
    return m.Literal(value, m.BOOLEAN, span)


def boolean_constant(e: m.Expr) -> bool | None:
    """True or False where ``e`` is that literal, else None."""
    return e.value if isinstance(e, m.Literal) and isinstance(e.value, bool) else None


def fold(e: m.Expr) -> m.Expr:
    """``e`` with the boolean constants that deciding ``q != r`` left folded away."""
    if isinstance(e, m.Unary) and e.op == "!":
        operand = fold(e.operand)
        return folded(e if operand is e.operand else m.Unary("!", operand, e.type, e.span))
    if isinstance(e, m.Binary) and e.op in ("and", "or", "=>"):
        left, right = fold(e.left), fold(e.right)
        return folded(e if left is e.left and right is e.right else m.Binary(e.op, left, right, e.type, e.span))
    return e


def folded(e: m.Expr) -> m.Expr:
    """:func:`fold` of ``e`` whose operands are folded already (only ``e`` itself is looked at)."""
    if isinstance(e, m.Unary) and e.op == "!":
        value = boolean_constant(e.operand)
        return e if value is None else literal(not value, e.span)
    if isinstance(e, m.Binary) and e.op in ("and", "or", "=>"):
        left, right = e.left, e.right
        a, b = boolean_constant(left), boolean_constant(right)
        if e.op == "and":
            if a is False or b is False:
                return literal(False, e.span)
            if a is True:
                return right
            if b is True:
                return left
        elif e.op == "or":
            if a is True or b is True:
                return literal(True, e.span)
            if a is False:
                return right
            if b is False:
                return left
        else:
            if a is False or b is True:
                return literal(True, e.span)
            if a is True:
                return right
            if b is False:
                return folded(m.Unary("!", left, m.BOOLEAN, e.span))
    return e


def join(op: str, terms: Sequence[m.Expr], span: Span) -> m.Expr:
    """The terms joined by ``and`` / ``or`` as a balanced tree (later stages recurse over
    expressions: a fleet's hundred terms nest 7 deep, not 100); constants folded away."""
    unit = op == "and"
    kept: list[m.Expr] = []
    for term in terms:
        value = boolean_constant(term)
        if value is None:
            kept.append(term)
        elif value is not unit:
            return literal(not unit, span)
    if not kept:
        return literal(unit, span)

    def build(parts: Sequence[m.Expr]) -> m.Expr:
        if len(parts) == 1:
            return parts[0]
        middle = len(parts) // 2
        return m.Binary(op, build(parts[:middle]), build(parts[middle:]), m.BOOLEAN, span)

    return build(kept)


def chain(e: m.Expr, n: int, op: str | None = None) -> tuple[m.Expr, ...]:
    """The ``n`` terms :func:`join` made ``e`` of with ``op`` (``e``'s own where None), split
    where it splits; () where ``e`` is not such a tree of ``n`` terms."""
    if n == 1:
        return (e,)
    if not isinstance(e, m.Binary) or e.op not in ("and", "or") or (op is not None and e.op != op):
        return ()
    middle = n // 2
    left, right = chain(e.left, middle, e.op), chain(e.right, n - middle, e.op)
    return left + right if left and right else ()


def replace(e: m.Expr, leaf: Callable[[m.Expr], m.Expr | None]) -> m.Expr:
    """``e`` with each node that ``leaf`` answers (not None) replaced by its answer, the
    operators around them rebuilt."""
    found = leaf(e)
    if found is not None:
        return found
    if isinstance(e, m.Unary):
        return m.Unary(e.op, replace(e.operand, leaf), e.type, e.span)
    if isinstance(e, m.Binary):
        return m.Binary(e.op, replace(e.left, leaf), replace(e.right, leaf), e.type, e.span)
    if isinstance(e, m.Count):
        return m.Count(e.group, tuple(replace(t, leaf) for t in e.terms), e.type, e.span)
    return e
