"""The operator precedence of LANGUAGE.md section 2, kept exactly."""

from __future__ import annotations

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
