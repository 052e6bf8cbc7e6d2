"""The parser that reads models: a lexer and an LALR(1) driver running the tables Lark
computes from ``grammar.lark`` (``grammar_tables.py``, made by
:mod:`robosc.language.grammar_compile`).

Lark stays the grammar's compiler; running its tables here spares every command Lark's
import and grammar loading (most of ``robosc check``'s start-up). Trees, tokens, positions
and errors mean what Lark's mean with ``parser="lalr", lexer="basic",
propagate_positions=True``: the same tree shapes, the same first error and the same
expected tokens (checked against Lark by the tests). The tree building, the subtree order
and ``accepts`` follow Lark's code (MIT licence, lark-parser/lark).
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from typing import Any


class Token:
    """A terminal: its type, its text and where it is (lines and columns from 1, offsets from 0)."""

    __slots__ = ("column", "end_column", "end_line", "end_pos", "line", "start_pos", "type", "value")

    def __init__(
        self, type: str, value: str, start_pos: int, line: int, column: int, end_line: int, end_column: int, end_pos: int
    ) -> None:
        self.type = type
        self.value = value
        self.start_pos = start_pos
        self.line = line
        self.column = column
        self.end_line = end_line
        self.end_column = end_column
        self.end_pos = end_pos

    def __str__(self) -> str:
        return self.value

    def __repr__(self) -> str:
        return f"Token({self.type!r}, {self.value!r})"


class Meta:
    """Where a tree's text is: from its first token to its last (``empty`` when it has none).
    ``container_*`` is where the rule that produced it started and ended, which can be
    earlier than the tree itself for a ``?rule`` passing its only child on."""

    __slots__ = (
        "column",
        "container_column",
        "container_end_column",
        "container_end_line",
        "container_end_pos",
        "container_line",
        "container_start_pos",
        "empty",
        "end_column",
        "end_line",
        "end_pos",
        "line",
        "start_pos",
    )

    def __init__(self) -> None:
        self.empty = True  # no position yet (0 stands for none: lines count from 1)
        self.line = self.column = self.start_pos = self.end_line = self.end_column = self.end_pos = 0
        self.container_line = self.container_column = self.container_start_pos = 0
        self.container_end_line = self.container_end_column = self.container_end_pos = 0


class Tree:
    """A rule's node: the rule's (or its alias's) name and the children kept."""

    __slots__ = ("children", "data", "meta")

    def __init__(self, data: str, children: list[Any]) -> None:
        self.data = data
        self.children = children
        self.meta = Meta()

    def __repr__(self) -> str:
        return f"Tree({self.data!r}, {self.children!r})"

    def iter_subtrees(self) -> Iterator[Tree]:
        """Every subtree once, children before their parents (Lark's order)."""
        queue = [self]
        seen: dict[int, Tree] = {}
        for subtree in queue:
            seen[id(subtree)] = subtree
            queue += [c for c in reversed(subtree.children) if isinstance(c, Tree) and id(c) not in seen]
        return reversed(list(seen.values()))


class UnexpectedInput(Exception):
    """The text is not in the language: where parsing stopped."""

    line: int
    column: int
    pos_in_stream: int


class UnexpectedCharacters(UnexpectedInput):
    """No terminal matches the text at ``pos_in_stream``."""

    def __init__(self, pos: int, line: int, column: int, allowed: set[str]) -> None:
        super().__init__(f"no terminal matches at line {line} column {column}")
        self.pos_in_stream, self.line, self.column = pos, line, column
        self.allowed = allowed


class UnexpectedToken(UnexpectedInput):
    """The parser cannot take ``token`` here; ``expected`` are the terminals the state has an
    action on, :meth:`accepts` those it would really take."""

    def __init__(self, token: Token, expected: set[str], tables: Tables, stack: list[int], end: int) -> None:
        super().__init__(f"unexpected {token.type} at line {token.line} column {token.column}")
        self.token = token
        self.expected = expected
        self.pos_in_stream, self.line, self.column = token.start_pos, token.line, token.column
        self._tables = tables
        self._stack = stack
        self._end = end

    def accepts(self) -> set[str]:
        """The terminals after which parsing could go on, found by trying each (Lark's
        ``InteractiveParser.accepts``: reductions can fail where the state has an action)."""
        states = self._tables.states
        return {
            terminal
            for terminal in states[self._stack[-1]]
            if terminal.isupper() and takes(self._tables, self._stack, terminal, self._end)
        }


def takes(tables: Tables, stack: list[int], terminal: str, end: int = -1) -> bool:
    """Whether the parser in ``stack`` would take ``terminal`` (shift it, after the reductions
    it asks for; ``$END``: reach the ``end`` state), tried on a copy of the stack."""
    states, rules = tables.states, tables.rules
    stack = list(stack)
    while True:
        action = states[stack[-1]].get(terminal)
        if action is None:
            return False
        if action >= 0:
            return True
        origin, size = rules[~action][:2]
        if size:
            del stack[-size:]
        stack.append(states[stack[-1]][origin])
        if terminal == "$END" and stack[-1] == end:
            return True


class Tables:
    """One grammar's tables (a dictionary of ``grammar_tables.py``) made ready to run."""

    def __init__(self, data: dict[str, Any]) -> None:
        self.pattern = re.compile("|".join(f"(?P<{name}>{regexp})" for name, regexp in data["terminals"]))
        self.keywords: dict[str, dict[str, str]] = data["keywords"]
        self.soft: dict[str, str] = data["soft"]  # soft keywords: their text -> their terminal
        self.ignore = frozenset(data["ignore"])
        self.newline = frozenset(data["newline"])
        self.literals: dict[str, str] = data["literals"]
        self.allowed = frozenset(name for name, _ in data["terminals"]) - self.ignore
        self.rules: tuple[tuple[str, int, str, bool, tuple[int, ...] | None], ...] = data["rules"]
        self.states: tuple[dict[str, int], ...] = data["states"]
        self.start: dict[str, int] = data["start"]
        self.end: dict[str, int] = data["end"]


COMMENTS = frozenset({"LINE_COMMENT", "BLOCK_COMMENT"})  # ignored terminals that ``robosc fmt`` keeps


def tokens(tables: Tables, text: str, comments: list[Token] | None = None) -> Iterator[Token]:
    """The text's terminals, the ignored ones left out (:data:`COMMENTS` go to ``comments``)."""
    match = tables.pattern.match
    keywords, ignore, newline = tables.keywords, tables.ignore, tables.newline
    pos, line, line_start, end = 0, 1, 0, len(text)
    while pos < end:
        found = match(text, pos)
        if found is None:
            raise UnexpectedCharacters(pos, line, pos - line_start + 1, set(tables.allowed))
        value = found.group()
        kind: str = found.lastgroup  # type: ignore[assignment]  # every alternative is a named group
        start, start_line, column = pos, line, pos - line_start + 1
        if kind in newline:
            count = value.count("\n")
            if count:
                line += count
                line_start = pos + value.rindex("\n") + 1
        pos += len(value)
        if kind in ignore:
            if comments is not None and kind in COMMENTS:
                comments.append(Token(kind, value, start, start_line, column, line, pos - line_start + 1, pos))
            continue
        folded = keywords.get(kind)
        if folded is not None:
            kind = folded.get(value, kind)
        yield Token(kind, value, start, start_line, column, line, pos - line_start + 1, pos)


def parse(tables: Tables, text: str, start: str, comments: list[Token] | None = None) -> Tree:
    """Parse ``text`` from the rule ``start``; raises :class:`UnexpectedInput` at the first error."""
    states, rules = tables.states, tables.rules
    state_stack = [tables.start[start]]
    value_stack: list[Any] = []
    end_state = tables.end[start]

    soft = tables.soft

    def feed(token: Token, is_end: bool) -> Any:
        while True:
            actions = states[state_stack[-1]]
            action = actions.get(token.type)
            if action is None:
                expected = {name for name in actions if name.isupper()}
                raise UnexpectedToken(token, expected, tables, state_stack, end_state)
            if action >= 0:
                state_stack.append(action)
                value_stack.append(token)
                return None
            origin, size, name, expand1, include = rules[~action]
            if size:
                raw = value_stack[-size:]
                del state_stack[-size:]
                del value_stack[-size:]
            else:
                raw = []
            value_stack.append(_reduce(raw, name, expand1, include))
            state_stack.append(states[state_stack[-1]][origin])
            if is_end and state_stack[-1] == end_state:
                return value_stack[-1]

    last = None
    for last in tokens(tables, text, comments):
        if last.type == "NAME" and last.value in soft:
            keyword = soft[last.value]  # a soft keyword: the keyword where no name can stand
            if not takes(tables, state_stack, "NAME") and takes(tables, state_stack, keyword):
                last.type = keyword
        feed(last, False)
    if last is None:
        end = Token("$END", "", 0, 1, 1, 1, 1, 0)
    else:
        end = Token("$END", "", last.start_pos, last.line, last.column, last.end_line, last.end_column, last.end_pos)
    tree: Tree = feed(end, True)
    return tree


def _reduce(raw: list[Any], name: str, expand1: bool, include: tuple[int, ...] | None) -> Any:
    """The node a rule's reduction makes of its symbols (Lark's parse tree builder: tokens
    without a name dropped, ``_rule`` children inlined, a ``?rule`` with one child is that
    child; positions from the first and last symbol that has one)."""
    if include is None:
        children = raw
    else:
        children = []
        for i in include:
            if i >= 0:
                children.append(raw[i])
            else:
                children += raw[~i].children
    if expand1 and len(children) == 1:
        node = children[0]
        if not isinstance(node, Tree):
            return node
    else:
        node = Tree(name, children)
    meta = node.meta
    for child in raw:
        if isinstance(child, Tree):
            if child.meta.empty:
                continue
            first = child.meta
            line, column, start_pos = first.container_line, first.container_column, first.container_start_pos
        else:
            line, column, start_pos = child.line, child.column, child.start_pos
        if not meta.line:
            meta.line, meta.column, meta.start_pos = line, column, start_pos
            meta.empty = False
        meta.container_line, meta.container_column, meta.container_start_pos = line, column, start_pos
        break
    for child in reversed(raw):
        if isinstance(child, Tree):
            if child.meta.empty:
                continue
            last = child.meta
            line, column, end_pos = last.container_end_line, last.container_end_column, last.container_end_pos
        else:
            line, column, end_pos = child.end_line, child.end_column, child.end_pos
        if not meta.end_line:
            meta.end_line, meta.end_column, meta.end_pos = line, column, end_pos
            meta.empty = False
        meta.container_end_line, meta.container_end_column, meta.container_end_pos = line, column, end_pos
        break
    return node
