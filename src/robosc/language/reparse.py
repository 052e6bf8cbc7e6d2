"""Parsing again after an edit (for the language server): the text is cut into the file's
definitions (a component, a requirement, ...), each parsed alone and its parse kept by its
text, so that an edit parses only the definitions it touched. The syntax is built anew each
time, at each definition's place in the file: the result is exactly what
:func:`robosc.language.parser.parse_source` gives, which is what it falls back to whenever
cutting or a piece's parse fails (syntax errors are reported as the whole file's parse
reports them)."""

from __future__ import annotations

import itertools
import re
from collections import OrderedDict
from functools import lru_cache
from typing import Any

from robosc.language import syntax as s
from robosc.language.lalr import Tables, Token, Tree, UnexpectedInput, parse
from robosc.language.parser import ParseResult, gc_paused, parse_source
from robosc.language.source import SourceFile
from robosc.language.transformer import SyntaxBuilder, SyntaxProblem

_STARTS = ("component", "requirement", "provide", "datatype", "interface")
# what matters for cutting: comments and strings (skipped), braces, and a line that starts
# with a definition's keyword
_SCANNER = re.compile(
    r"//[^\n]*|/\*.*?\*/|\"(?:[^\"\\]|\\.)*\"|'(?:[^'\\]|\\.)*'|[{}]|(?<=\n)[ \t]*(?:"
    + "|".join(_STARTS)
    + r")\b",
    re.DOTALL,
)
_BLANK = re.compile(r"[^\n]")
MIN_PIECES = 8  # below this, parsing the whole file is as quick


@lru_cache(maxsize=1)
def _piece_tables() -> Tables:
    from robosc.language.grammar_tables import PIECES

    return Tables(PIECES)


def cut(text: str) -> tuple[int, list[int]] | None:
    """Where the definitions of the file's body start (each at the start of its line), and
    where the body ends (its closing brace); None when the text does not cut cleanly."""
    depth = 0
    starts: list[int] = []
    for found in _SCANNER.finditer(text):
        token = found.group()
        if token == "{":
            depth += 1
        elif token == "}":
            depth -= 1
            if depth == 0:
                rest = _SCANNER.search(text, found.end())
                while rest is not None and rest.group().startswith(("//", "/*")):
                    rest = _SCANNER.search(text, rest.end())
                return (found.start(), starts) if rest is None and starts else None
            if depth < 0:
                return None
        elif depth == 1 and token.lstrip()[:1].isalpha():  # a definition's first line
            starts.append(found.start())
    return None


class Reparser:
    """Parses versions of one file, keeping the parse of each definition by its text."""

    def __init__(self, capacity: int = 20_000) -> None:
        self.capacity = capacity
        self._pieces: OrderedDict[tuple[str, str], tuple[Tree, tuple[Token, ...]]] = OrderedDict()
        # the syntax each piece was last built into, by (text, rule, path, line, offset): the
        # pieces before an edit keep their place and need not be built again
        self._built: dict[tuple[str, str, str, int, int], tuple[Any, list[s.Comment]]] = {}

    def parse(self, source: SourceFile) -> ParseResult:
        with gc_paused():
            return self._parse_or_whole(source)

    def _parse_or_whole(self, source: SourceFile) -> ParseResult:
        text = source.text
        found = cut(text)
        if found is None or len(found[1]) < MIN_PIECES:
            return parse_source(source)
        end, starts = found
        try:
            return self._parse(source, starts, end)
        except (UnexpectedInput, SyntaxProblem, _Whole):
            return parse_source(source)

    def _piece(self, text: str, start: str) -> tuple[Tree, tuple[Token, ...]]:
        key = (text, start)
        kept = self._pieces.get(key)
        if kept is not None:
            self._pieces.move_to_end(key)
            return kept
        comments: list[Token] = []
        tree = parse(_piece_tables(), text, start, comments)
        kept = (tree, tuple(comments))
        self._pieces[key] = kept
        if len(self._pieces) > self.capacity:
            self._pieces.popitem(last=False)
        return kept

    def _parse(self, source: SourceFile, starts: list[int], end: int) -> ParseResult:
        text, path = source.text, source.path
        # the file without its definitions (blanked, so that every position stays): its
        # header, closing brace and the comments around them
        first = starts[0]
        skeleton = text[:first] + _BLANK.sub(" ", text[first:end]) + text[end:]
        shell = parse_source(SourceFile(path, skeleton))
        if shell.syntax is None or shell.syntax.definitions:
            raise _Whole
        kind = shell.syntax.kind
        rule = "robot_def" if kind == "robot" else "library_def"
        definitions: list[Any] = []
        comments = list(shell.syntax.comments)
        bounds = [*starts, end]
        line = text.count("\n", 0, first) + 1
        built: dict[tuple[str, str, str, int, int], tuple[Any, list[s.Comment]]] = {}
        for piece_start, piece_end in itertools.pairwise(bounds):
            piece = text[piece_start:piece_end]
            key = (piece, rule, path, line, piece_start)
            done = self._built.get(key)
            if done is None:
                tree, tokens = self._piece(piece, rule)
                builder = SyntaxBuilder(path, (), line - 1, piece_start)
                done = (builder.build(tree), [s.Comment(str(t), builder.token_span(t)) for t in tokens])
            built[key] = done
            definitions.append(done[0])
            comments += done[1]
            line += piece.count("\n")
        self._built = built  # this version's pieces only
        comments.sort(key=lambda c: c.span.start)
        file = s.FileSyntax(kind, shell.syntax.name, tuple(definitions), tuple(comments), shell.syntax.span)
        return ParseResult(file, ())


class _Whole(Exception):
    """Parse the whole file instead."""
