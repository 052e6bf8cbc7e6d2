"""Model expressions back to RoboSC text, with the parentheses the precedence needs.

Used for everything robosc shows about a checked model: requirement texts,
synthesized guards, explanations.
"""

from __future__ import annotations

import re

from robosc.language import model as m
from robosc.language import simplify
from robosc.language.keywords import escape_name

# LANGUAGE.md section 2, loosest first.
LEVEL = {op: i for i, op in enumerate(["or", "and", "=", "!=", ">", ">=", "<", "<=", "=>", "+", "-", "*", "/"], 1)}
UNARY_LEVEL = {"!": 14, "-": 15}
ASSOCIATIVE = {"or", "and", "+", "*"}


def _level(e: m.Expr) -> int:
    if isinstance(e, m.Binary):
        return LEVEL[e.op]
    if isinstance(e, m.Unary):
        return UNARY_LEVEL[e.op]
    return 99


def _child(e: m.Expr, parent: str, right: bool) -> str:
    text, call = _shown(e)
    if call:  # any(q in bot: ...) reads as one operand
        return text
    level, parent_level = _level(e), LEVEL[parent]
    needs = level < parent_level or (
        right and level == parent_level and not (isinstance(e, m.Binary) and e.op == parent and parent in ASSOCIATIVE)
    )
    # "a and b or c" is legal but easy to misread: show and/or groups explicitly; and "=>", which
    # binds tighter than and, or and the comparisons, always in parentheses where it is an operand
    mixed_logic = isinstance(e, m.Binary) and e.op in ("and", "or") and parent in ("and", "or") and e.op != parent
    implication = isinstance(e, m.Binary) and e.op == "=>"
    return f"({text})" if needs or mixed_logic or implication else text


def steps(path: tuple[m.Step, ...]) -> str:
    return "".join(f"[{s.index}]" if isinstance(s, m.IndexStep) else f".{escape_name(s.property.name)}" for s in path)


_ESCAPED = {"\\": "\\\\", '"': '\\"', "\n": "\\n", "\t": "\\t", "\r": "\\r", "\b": "\\b", "\f": "\\f", "\0": "\\0"}


def literal(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value) if "." in repr(value) else f"{value:.1f}"
    if isinstance(value, str):  # the language's own escapes: one line, no control character
        return '"' + "".join(_ESCAPED.get(c, c) for c in value) + '"'
    if isinstance(value, m.EnumValue):
        return escape_name(value.name)
    return str(value)


def _shown(e: m.Expr) -> tuple[str, bool]:
    """``e`` as text, and whether that is an ``any`` / ``all`` over a group (read as a call)."""
    if not isinstance(e, m.Binary):
        return render(e), False
    nobody = _nobody(e)
    if nobody is not None:
        return nobody
    over = _over_group(e) if e.over is not None else None
    if over is not None:
        return over, True
    return f"{_child(e.left, e.op, False)} {e.op} {_child(e.right, e.op, True)}", False


def render(e: m.Expr) -> str:
    if isinstance(e, m.Binary):
        return _shown(e)[0]
    if isinstance(e, m.Unary):
        inner, call = _shown(e.operand)
        return f"{e.op}({inner})" if _level(e.operand) < UNARY_LEVEL[e.op] and not call else f"{e.op}{inner}"
    if isinstance(e, m.Literal):
        return literal(e.value)
    if isinstance(e, m.EnumLiteral):
        return escape_name(e.value.name)
    if isinstance(e, m.StateRef):
        return f"{escape_name(e.state.owner)}.{escape_name(e.state.name)}"
    if isinstance(e, m.VariableRef):
        return f"{escape_name(e.variable.owner)}.{escape_name(e.variable.name)}{steps(e.steps)}"
    if isinstance(e, m.DataRef):
        return "value" + steps(e.steps)
    if isinstance(e, m.Count):
        return _quantified(e) or f"count({', '.join(render(term) for term in e.terms)})"
    return "<invalid>"


def _over_group(e: m.Binary) -> str | None:
    """An ``any`` / ``all`` the resolver joined over a whole array, as it is written,
    ``any(q in bot: ...)``, where its terms are still the same condition of each instance."""
    assert e.over is not None
    group, size = e.over
    terms = simplify.chain(e, size)
    if not terms:
        return None
    body = _template(group, terms)
    if body is None:
        return None
    binder, template = body
    return f"{'any' if e.op == 'or' else 'all'}({binder} in {escape_name(group)}: {template})"


def _nobody(e: m.Binary) -> tuple[str, bool] | None:
    """A condition robosc made (synthesis: it has no place in a file; one a user wrote is shown
    as written) ``count(q in bot: X) = 0`` as ``!any(q in bot: X)`` (read as one operand) and
    ``count(q in bot: X) >= 1`` as ``any(q in bot: X)``; None for any other expression."""
    if e.span.line or not (isinstance(e.left, m.Count) and isinstance(e.right, m.Literal) and (e.op, e.right.value) in (("=", 0), (">=", 1))):
        return None
    over = _over(e.left)
    if over is None:
        return None
    return ("!any" if e.op == "=" else "any") + over, True


def _quantified(e: m.Count) -> str | None:
    """``e`` as it is written over an array, ``count(q in bot: ...)``, where it counts the same
    condition of each instance ``bot1``, ``bot2``, ... in order (a count written out, or of
    conditions that differ, is None: its terms are shown)."""
    over = _over(e)
    return None if over is None else "count" + over


def _over(e: m.Count) -> str | None:
    """What ``e`` counts over its array, ``(q in bot: ...)`` (see :func:`_quantified`)."""
    if not e.group or len(e.terms) < 2:
        return None
    body = _template(e.group, e.terms)
    if body is None:
        return None
    return f"({body[0]} in {escape_name(e.group)}: {body[1]})"


def _template(group: str, terms: tuple[m.Expr, ...]) -> tuple[str, str] | None:
    """(binder, the condition each of ``terms`` is of its instance ``group1``, ``group2``, ...
    in order, written with the binder), or None where they are not one condition."""
    texts = [render(term) for term in terms]
    binder = next((n for n in ("q", "p", "r", "s") if not any(re.search(rf"(?<![\w.]){n}\.", t) for t in texts)), None)
    if binder is None:
        return None
    template = None
    for index, text in enumerate(texts, 1):
        me = re.compile(r"(?<![\w.])" + re.escape(escape_name(f"{group}{index}")) + r"(?=\.)")
        if not me.search(text):
            return None
        body = me.sub(binder, text)
        if template is not None and body != template:
            return None
        template = body
    return None if template is None else (binder, template)
