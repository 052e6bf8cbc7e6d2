"""Spans (lines and columns from 1, in characters) as LSP ranges (from 0, in UTF-16 code
units, the protocol's default position encoding), and back."""

from __future__ import annotations

from lsprotocol import types as lsp

from robosc.language.source import Span


def _utf16(line: str, column: int) -> int:
    """UTF-16 units before character ``column`` (from 1) of ``line``."""
    prefix = line[: max(0, column - 1)]
    return len(prefix.encode("utf-16-le")) // 2


def to_range(span: Span, lines: list[str]) -> lsp.Range:
    def position(line: int, column: int) -> lsp.Position:
        text = lines[line - 1] if 0 < line <= len(lines) else ""
        return lsp.Position(line=max(0, line - 1), character=_utf16(text, column))

    return lsp.Range(start=position(span.line, span.column), end=position(span.end_line, span.end_column))


def to_offset(text: str, position: lsp.Position) -> int:
    """The character offset in ``text`` of an LSP position (past the end: the end)."""
    lines = text.splitlines(keepends=True)
    if position.line >= len(lines):
        return len(text)
    before = sum(len(line) for line in lines[: position.line])
    line = lines[position.line]
    units = 0
    for index, char in enumerate(line):
        if units >= position.character:
            return before + index
        units += 2 if ord(char) > 0xFFFF else 1
    return before + len(line.rstrip("\r\n"))
