"""Source files and positions inside them."""

from __future__ import annotations

from robosc.record import record


@record
class Span:
    """A region of a source file. Lines and columns start at 1; offsets at 0."""

    path: str
    line: int
    column: int
    end_line: int
    end_column: int
    start: int
    end: int

    def __str__(self) -> str:
        return f"{self.path}:{self.line}:{self.column}"


@record
class SourceFile:
    """The text of one model file, as read."""

    path: str
    text: str

    def line_text(self, line: int) -> str:
        lines = self.text.splitlines()
        return lines[line - 1] if 0 < line <= len(lines) else ""
