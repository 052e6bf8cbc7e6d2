"""Text to syntax nodes. Syntax errors become one diagnostic at the first place parsing fails."""

from __future__ import annotations

import gc
import re
from collections.abc import Iterator
from contextlib import contextmanager
from functools import lru_cache

from robosc.language import syntax as s
from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.lalr import Tables, Token, UnexpectedCharacters, UnexpectedInput, UnexpectedToken, parse
from robosc.language.source import SourceFile, Span
from robosc.language.transformer import MAX_STRING, SyntaxBuilder, SyntaxProblem
from robosc.record import record

# What the user typed, for the terminals named by pattern.
_TERMINAL_TEXT = {
    "NAME": "a name",
    "INT": "an integer",
    "DOUBLE": "a number",
    "STRING": "a string",
    "$END": "the end of the file",
}
_OPERATORS = {"OR", "AND", "EQ", "NE", "GT", "GE", "LT", "LE", "IMPLIES", "PLUS", "MINUS", "TIMES", "DIVIDE"}
_EXPRESSION_STARTS = {"NAME", "INT", "DOUBLE", "STRING", "VALUE", "TRUE", "FALSE", "LPAR", "BANG", "MINUS"}


@record
class ParseResult:
    syntax: s.FileSyntax | None
    diagnostics: tuple[Diagnostic, ...]


@lru_cache(maxsize=1)
def file_tables() -> Tables:
    """The tables that parse a whole file (loaded on first use)."""
    from robosc.language.grammar_tables import FILE

    return Tables(FILE)


def _describe_terminal(name: str, tables: Tables) -> str:
    if name in _TERMINAL_TEXT:
        return _TERMINAL_TEXT[name]
    literal = tables.literals.get(name)
    return f"'{literal}'" if literal is not None else name.lower()


def _describe_expected(expected: set[str], tables: Tables) -> str:
    names = set(expected)
    parts: list[str] = []
    if names >= _EXPRESSION_STARTS:
        names -= _EXPRESSION_STARTS
        parts.append("an expression")
    if len(_OPERATORS & names) > 3:
        names -= _OPERATORS
        parts.append("an operator")
    parts += sorted(_describe_terminal(n, tables) for n in names)
    if len(parts) > 8:
        parts = [*parts[:8], "..."]
    return parts[0] if len(parts) == 1 else "one of " + ", ".join(parts)


def _point(path: str, text: str, line: int, column: int, pos: int, length: int = 1) -> Span:
    return Span(path, line, column, line, column + length, pos, pos + length)


_EXPONENT = re.compile(r"(?<![\w.])(\d+(?:\.\d*)?|\.\d+)[eE][+-]?\d+")
_SPELLINGS = (  # what people write out of habit from other languages, and RoboSC's spelling
    ("&&", "write 'and' for a logical and"),
    ("||", "write 'or' for a logical or"),
    ("&", "write 'and' for a logical and"),
    ("|", "write 'or' for a logical or"),
    ("<>", "write '!=' for 'not equal'"),
    ("=!", "write '!=' for 'not equal'"),
)


def spelling_hint(text: str, pos: int) -> str | None:
    """A hint for an operator or number spelled as in another language, at or just before ``pos``."""
    for written, hint in _SPELLINGS:
        if text.startswith(written, pos) or (pos > 0 and text.startswith(written, pos - 1)):
            return hint
    if text.startswith("==", pos) or (pos > 0 and text.startswith("==", pos - 1)):
        return "write '=' to compare: RoboSC's equality is a single '='"
    if re.search(r"(?<![\w^])not\s*$", text[max(0, pos - 20) : pos]):
        return "write '!' for a logical not, as in '!S.active'"
    line_start = text.rfind("\n", 0, pos) + 1
    for found in _EXPONENT.finditer(text, line_start, pos + 40):
        if found.start() <= pos <= found.end():
            from decimal import Decimal

            plain = format(Decimal(found.group()), "f")
            plain = plain if "." in plain else plain + ".0"
            return f"numbers have no exponent in RoboSC; write {plain}"
    return None


def _syntax_error(exc: UnexpectedInput, path: str, text: str, tables: Tables) -> Diagnostic:
    if isinstance(exc, UnexpectedToken) and exc.token.type == "$END":
        lines = text.splitlines() or [""]
        line, column = len(lines), len(lines[-1]) + 1
        expected = exc.accepts()
        message = "unexpected end of file"
        if expected:
            message += f", expected {_describe_expected(expected, tables)}"
        return error(_point(path, text, line, column, len(text), 0), message, Code.SYNTAX)
    if isinstance(exc, UnexpectedToken):
        token = exc.token
        shown = str(token).replace("\n", " ")
        if len(shown) > 30:
            shown = shown[:27] + "..."
        span = _point(path, text, exc.line, exc.column, token.start_pos, max(1, len(str(token))))
        if text.startswith("/*", token.start_pos):
            return error(span, "unterminated comment (missing '*/')", Code.SYNTAX)
        hint = None
        if token.type != "NAME" and shown.isidentifier() and "NAME" in exc.expected:
            hint = f"'{shown}' is a keyword; write '^{shown}' to use it as a name"
        hint = hint or spelling_hint(text, token.start_pos)
        return error(
            span, f"unexpected '{shown}', expected {_describe_expected(exc.accepts(), tables)}", Code.SYNTAX, hint
        )
    assert isinstance(exc, UnexpectedCharacters)
    pos = exc.pos_in_stream
    char = text[pos] if pos < len(text) else ""
    span = _point(path, text, exc.line, exc.column, pos)
    if char in "\"'":
        return error(span, "unterminated string", Code.SYNTAX)
    if text.startswith("/*", pos):
        return error(span, "unterminated comment (missing '*/')", Code.SYNTAX)
    shown = repr(char) if not char.isprintable() or char.isspace() else f"'{char}'"
    message = f"unexpected character {shown}"
    if exc.allowed:
        message += f", expected {_describe_expected(exc.allowed, tables)}"
    return error(span, message, Code.SYNTAX, spelling_hint(text, pos))


@contextmanager
def gc_paused() -> Iterator[None]:
    """Parsing and checking allocate many short-lived objects and no cycles: pausing the
    cyclic garbage collector meanwhile saves about a tenth of the time on large models."""
    paused = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if paused:
            gc.enable()


def parse_text(text: str, path: str = "<text>") -> ParseResult:
    """Parse one ``.rscd`` file's text into syntax nodes, or one diagnostic."""
    with gc_paused():
        return _parse(text, path)


_LONG_STRING = re.compile(f"\"[^\"\\n]{{{MAX_STRING + 1},}}|'[^'\\n]{{{MAX_STRING + 1},}}")


def _parse(text: str, path: str) -> ParseResult:
    long = _LONG_STRING.search(text)
    if long is not None:  # before the lexer, whose string pattern needs memory in proportion to the string
        span = Span.of(path, text, long.start(), long.start() + 1)
        return ParseResult(None, (error(span, f"string too long (more than {MAX_STRING} characters)", Code.LIMIT),))
    tables = file_tables()
    comment_tokens: list[Token] = []
    try:
        tree = parse(tables, text, "start", comment_tokens)
    except UnexpectedInput as exc:
        return ParseResult(None, (_syntax_error(exc, path, text, tables),))
    builder = SyntaxBuilder(path, ())
    comments = tuple(s.Comment(str(t), builder.token_span(t)) for t in comment_tokens)
    builder.comments = comments
    try:
        result = builder.build(tree)
    except SyntaxProblem as problem:
        return ParseResult(None, (error(problem.span, problem.message, problem.code, problem.hint),))
    return ParseResult(result, ())


def parse_source(source: SourceFile) -> ParseResult:
    return parse_text(source.text, source.path)
