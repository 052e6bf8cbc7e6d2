"""robosc's own LALR runner (robosc.language.lalr) against Lark itself: for the same grammar,
the same trees (shapes, tokens, every position), the same comments, the same first error
with the same expected and accepted tokens; and the tables in grammar_tables.py are those
Lark computes from grammar.lark today."""

from __future__ import annotations

import random
import sys
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from robosc.language import grammar_compile, lalr
from robosc.language.grammar_tables import PIECES
from robosc.language.parser import file_tables
from robosc.language.reparse import cut

lark = pytest.importorskip("lark")

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))
from mutate import SOURCES, mutate  # noqa: E402

GRAMMAR = grammar_compile.GRAMMAR.read_text(encoding="utf-8")
INSERTS = ["&&", "||", "==", '"', "/*", "'", "@", "{", "}", "(", "-", "1e5", "\x00", "é", "state", "^state", "\n"]


def lark_parser(start: str | list[str]) -> tuple[Any, list[Any]]:
    comments: list[Any] = []
    parser = lark.Lark(
        GRAMMAR,
        parser="lalr",
        lexer="basic",
        propagate_positions=True,
        maybe_placeholders=False,
        start=start,
        lexer_callbacks={"LINE_COMMENT": comments.append, "BLOCK_COMMENT": comments.append},
    )
    return parser, comments


LARK_FILE = lark_parser("start")
LARK_PIECES = lark_parser(["robot_def", "library_def"])


def shape(node: Any) -> Any:
    """A tree or token of either parser as plain tuples: names, texts and positions."""
    if isinstance(node, (lark.Tree, lalr.Tree)):
        meta = node.meta
        where = None if meta.empty else (meta.line, meta.column, meta.start_pos, meta.end_line, meta.end_column, meta.end_pos)
        return (str(node.data), where, [shape(c) for c in node.children])
    if node.type == "$END":  # borrows the last token's start (its end is not used)
        return (node.type, node.start_pos, node.line, node.column)
    return (node.type, str(node), node.start_pos, node.line, node.column, node.end_line, node.end_column, node.end_pos)


SOFT = set(grammar_compile.SOFT_KEYWORDS)


def lark_parse(parser: Any, text: str, start: str) -> Any:
    """Lark's parse, with the soft keywords read as the spec says: a word is the keyword only
    where the parser would not take a name (Lark's lexer would reserve it everywhere)."""
    interactive = parser.parse_interactive(text, start=start)
    state = interactive.parser_state
    token = None
    for token in interactive.lexer_thread.lex(state):
        if token.type in SOFT:
            accepted = interactive.accepts()
            keep = "NAME" not in accepted and token.type in accepted
            token = token if keep else lark.Token.new_borrow_pos("NAME", str(token), token)
        try:
            interactive.feed_token(token)
        except lark.UnexpectedToken as exc:
            exc.interactive_parser = interactive
            raise
    try:
        return interactive.feed_eof(token)
    except lark.UnexpectedToken as exc:
        exc.interactive_parser = interactive
        raise


def by_lark(text: str, start: str = "start") -> tuple[Any, ...]:
    parser, comments = LARK_FILE if start == "start" else LARK_PIECES
    comments.clear()
    try:
        tree = lark_parse(parser, text, start)
    except lark.UnexpectedToken as exc:
        return ("token", shape(exc.token), sorted(exc.expected), sorted(exc.interactive_parser.accepts()))
    except lark.UnexpectedCharacters as exc:
        return ("character", exc.pos_in_stream, exc.line, exc.column, sorted(exc.allowed))
    return ("tree", shape(tree), [shape(c) for c in comments], order(tree))


def order(tree: Any) -> list[tuple[str, int]]:
    """The order the syntax builder meets the subtrees in (the first problem found is reported)."""
    return [(str(t.data), -1 if t.meta.empty else t.meta.start_pos) for t in tree.iter_subtrees()]


def by_robosc(text: str, start: str = "start") -> tuple[Any, ...]:
    tables = file_tables() if start == "start" else lalr.Tables(PIECES)
    comments: list[lalr.Token] = []
    try:
        tree = lalr.parse(tables, text, start, comments)
    except lalr.UnexpectedToken as exc:
        return ("token", shape(exc.token), sorted(exc.expected), sorted(exc.accepts()))
    except lalr.UnexpectedCharacters as exc:
        return ("character", exc.pos_in_stream, exc.line, exc.column, sorted(exc.allowed))
    return ("tree", shape(tree), [shape(c) for c in comments], order(tree))


def edited(rng: random.Random) -> str:
    """An example mutated token-wise, cut short, or with something typed into it."""
    text = SOURCES[rng.choice(sorted(SOURCES))]
    kind = rng.random()
    if kind < 0.6:
        return mutate(text, rng, rng.randint(1, 4))
    if kind < 0.8:
        return text[: rng.randrange(len(text))]
    at = rng.randrange(len(text))
    return text[:at] + rng.choice(INSERTS) + text[at:]


def test_the_tables_are_those_of_the_grammar() -> None:
    """Fails when grammar.lark changed and ``python -m robosc.language.grammar_compile`` was not run."""
    assert grammar_compile.TABLES.read_text(encoding="utf-8") == grammar_compile.render(GRAMMAR)


@pytest.mark.parametrize("name", sorted(SOURCES))
def test_examples_parse_as_lark_parses_them(name: str) -> None:
    text = SOURCES[name] + "/* a block\n comment */ // and a line comment\n"
    expected = by_lark(text)
    assert expected[0] == "tree"
    assert by_robosc(text) == expected


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.randoms(use_true_random=False))
def test_edited_examples_parse_or_fail_as_lark(rng: random.Random) -> None:
    text = edited(rng)
    assert by_robosc(text) == by_lark(text)


@pytest.mark.parametrize(
    "text",
    [
        "",
        "   // only a comment\n",
        "robot",
        "robot R {",
        "robot R { } extra",
        "library L { }",
        'robot R { component C { outgoing message m with type: none } requirement m needs a && b }',
        "robot R { component C { behaviour { initial state s { transition goto s } } } }",
        'robot R { provide m with { a: 1, b: { c: "x" } } if !(a.b[0] => -1.5) }',
        "robot R { datatype enum E from integer to { 1 -> a default -> b } }",
        "robot R { requirement { } needs true }",
    ],
)
def test_corner_cases_parse_or_fail_as_lark(text: str) -> None:
    assert by_robosc(text) == by_lark(text)


def test_definitions_alone_parse_as_lark_parses_them() -> None:
    """The language server's tables (one definition at a time)."""
    count = 0
    rng = random.Random(7)
    for text in SOURCES.values():
        found = cut(text)
        assert found is not None
        end, starts = found
        for piece_start, piece_end in zip(starts, [*starts[1:], end], strict=True):
            piece = text[piece_start:piece_end]
            for version in (piece, mutate(piece, rng, 1)):
                assert by_robosc(version, "robot_def") == by_lark(version, "robot_def")
                count += 1
    assert count > 40


SMALL_GRAMMAR = r"""
start: pair+ tail?
pair: item NAME | NAME ":" item
?item: "kw" word | word | "(" item ")" | word "."
word: NAME
!tail: "end" _rest
_rest: NUMBER*
NAME: /[a-z]+/
NUMBER: /[0-9]+/
%ignore /[ \n]+/
"""


@pytest.mark.parametrize(
    "text",
    ["kw x y", "x y kw z w", "(kw x) y end", "x y end 1 2 3", "x y end 1 (", "kw kw", "", "x y\n kw\n z w end", "a : x ."],
)
def test_a_small_grammar_parses_as_lark_parses_it(text: str) -> None:
    """Shapes this project's grammar does not have today: the position of a ?rule's only child
    taken from the rule's first and last tokens, !rules keeping their tokens, _rules inlined (also
    when empty), keywords folded into a pattern terminal."""
    parser = lark.Lark(SMALL_GRAMMAR, parser="lalr", lexer="basic", propagate_positions=True, maybe_placeholders=False)
    tables = lalr.Tables(grammar_compile.compile_tables(SMALL_GRAMMAR, ["start"]))
    try:
        expected: Any = shape(parser.parse(text))
    except lark.UnexpectedToken as exc:
        expected = (shape(exc.token), sorted(exc.expected), sorted(exc.interactive_parser.accepts()))
    try:
        got: Any = shape(lalr.parse(tables, text, "start"))
    except lalr.UnexpectedToken as exc:
        got = (shape(exc.token), sorted(exc.expected), sorted(exc.accepts()))
    assert got == expected
