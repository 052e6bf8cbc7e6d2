"""Source files and positions inside them."""

from __future__ import annotations

from typing import NamedTuple

from robosc.record import record


class Span(NamedTuple):
    """A region of a source file. Lines and columns start at 1; offsets at 0. (A named tuple,
    not a record: a model has one per node, and a tuple is made several times faster.)"""

    path: str
    line: int
    column: int
    end_line: int
    end_column: int
    start: int
    end: int

    def __str__(self) -> str:
        return f"{self.path}:{self.line}:{self.column}"

    @classmethod
    def of(cls, path: str, text: str, start: int, end: int | None = None) -> Span:
        """The span of ``text[start:end]`` (empty without ``end``), lines and columns counted."""
        stop = start if end is None else end

        def line_column(offset: int) -> tuple[int, int]:
            return text.count("\n", 0, offset) + 1, offset - (text.rfind("\n", 0, offset) + 1) + 1

        (line, column), (end_line, end_column) = line_column(start), line_column(stop)
        return cls(path, line, column, end_line, end_column, start, stop)

    def __repr__(self) -> str:
        return (
            f"Span(path={self.path!r}, line={self.line}, column={self.column}, end_line={self.end_line}, "
            f"end_column={self.end_column}, start={self.start}, end={self.end})"
        )


@record
class SourceFile:
    """The text of one model file, as read."""

    path: str
    text: str

    def line_text(self, line: int) -> str:
        lines = self.text.splitlines()
        return lines[line - 1] if 0 < line <= len(lines) else ""
