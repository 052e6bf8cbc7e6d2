"""The operator precedence of LANGUAGE.md section 2, kept exactly."""

from __future__ import annotations

from typing import Any

import pytest

from robosc.language import syntax as s
from robosc.language.formatter import expr as show
from robosc.language.parser import parse_text

LEVELS = ["or", "and", "=", "!=", ">", ">=", "<", "<=", "=>", "+", "-", "*", "/"]


def tree(text: str) -> str:
    """The expression fully parenthesised, to show how it grouped."""
    result = parse_text(f"robot R {{ requirement x needs {text} }}")
    assert result.syntax is not None, result.diagnostics

    def paren(e: s.Expr) -> str:
        if isinstance(e, s.Binary):
            return f"({paren(e.left)} {e.op} {paren(e.right)})"
        if isinstance(e, s.Unary):
            return f"({e.op}{paren(e.operand)})"
        if isinstance(e, s.Paren):
            return paren(e.inner)
        return show(e)

    return paren(result.syntax.definitions[0].condition)


@pytest.mark.parametrize(
    ("text", "grouped"),
    [
        ("a = b and c", "((a = b) and c)"),
        ("x > 1 = y", "((x > 1) = y)"),
        ("a or b and c", "(a or (b and c))"),
        ("a and b or c", "((a and b) or c)"),
        ("a != b = c", "((a != b) = c)"),
        ("a > b != c", "((a > b) != c)"),
        ("a >= b > c", "((a >= b) > c)"),
        ("a < b >= c", "((a < b) >= c)"),
        ("a <= b < c", "((a <= b) < c)"),
        ("a => b <= c", "((a => b) <= c)"),
        ("a + b => c", "((a + b) => c)"),
        ("a - b + c", "((a - b) + c)"),
        ("a + b - c", "(a + (b - c))"),
        ("a * b - c", "((a * b) - c)"),
        ("a / b * c", "((a / b) * c)"),
        ("a * b / c", "(a * (b / c))"),
        ("!a / b", "((!a) / b)"),
        ("!-a", "(!(-a))"),
        ("-a * b", "((-a) * b)"),
        ("!a = b", "((!a) = b)"),
        ("(a or b) and c", "((a or b) and c)"),
    ],
)
def test_grouping(text: str, grouped: str):
    assert tree(text) == grouped


@pytest.mark.parametrize("op", LEVELS)
def test_every_binary_level_is_left_associative(op: str):
    assert tree(f"a {op} b {op} c") == f"((a {op} b) {op} c)"


@pytest.mark.parametrize(("i", "j"), [(i, j) for i in range(len(LEVELS)) for j in range(i + 1, len(LEVELS))])
def test_each_level_binds_looser_than_every_later_one(i: int, j: int):
    loose, tight = LEVELS[i], LEVELS[j]
    assert tree(f"a {loose} b {tight} c") == f"(a {loose} (b {tight} c))"
    assert tree(f"a {tight} b {loose} c") == f"((a {tight} b) {loose} c)"


# ---- where the precedence surprises: '=>' beside and, or and the comparisons --------------------
SURPRISE = """robot R {{
    component A {{
        incoming message go with type: none
        behaviour {{
            variable n: integer(0..3) = 0
            initial marked state idle {{ on request to go goto busy }}
            marked state busy {{ on request to go goto idle }}
        }}
    }}
    requirement go needs {condition}
}}
"""


def diagnostics_of(condition: str) -> list[Any]:
    from robosc.api import check_text

    return list(check_text(SURPRISE.format(condition=condition)).diagnostics)


@pytest.mark.parametrize(
    ("condition", "read", "meant"),
    [
        ("A.busy => A.idle and A.n = 0", "(A.busy => A.idle) and A.n = 0", "A.busy => (A.idle and A.n = 0)"),
        ("A.idle or A.busy => A.idle", "A.idle or (A.busy => A.idle)", "(A.idle or A.busy) => A.idle"),
        ("A.busy => A.idle = true", "(A.busy => A.idle) = true", "A.busy => (A.idle = true)"),
    ],
)
def test_an_implication_beside_a_looser_operator_is_warned_with_its_grouping(condition: str, read: str, meant: str) -> None:
    found = diagnostics_of(condition)
    assert [(d.code, d.severity.value) for d in found] == [("precedence", "warning")], found
    assert f"this reads as {read}" in found[0].message
    assert found[0].hint.startswith(f"write the parentheses: {meant} if that is what you mean, or {read}")
    assert found[0].span.line == 10


@pytest.mark.parametrize(
    "condition", ["(A.busy => A.idle) and A.n = 0", "A.busy => (A.idle and A.n = 0)", "A.busy => A.idle", "A.n + 1 => A.idle"]
)
def test_parentheses_silence_it(condition: str) -> None:
    assert [d.code for d in diagnostics_of(condition)] in ([], ["types"])


def test_a_type_error_the_grouping_causes_says_how_it_grouped() -> None:
    found = diagnostics_of("A.busy => A.n < 2")
    assert [d.code for d in found] == ["types"], found
    assert found[0].hint == "'=>' binds tighter than '<': this reads as (A.busy => A.n) < 2 (as in the original tool); write the parentheses: A.busy => (A.n < 2)"


def test_requirements_are_shown_with_their_real_grouping() -> None:
    from robosc.api import check_text
    from robosc.plant import build_network

    model = check_text(SURPRISE.format(condition="A.busy => A.idle and A.n = 0")).model
    assert model is not None
    texts = [r.description for r in build_network(model).requirements]
    assert texts == ["requirement go needs (A.busy => A.idle) and A.n = 0"]
