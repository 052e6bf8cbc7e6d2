"""Go to definition and find references, from the names the resolver resolved
(``CheckResult.references``: each name's span and the model object it names)."""

from __future__ import annotations

from typing import Any

from lsprotocol import types as lsp
from pygls.uris import from_fs_path

from robosc.editor.positions import to_range
from robosc.language.source import SourceFile, Span


def _contains(span: Span, line: int, character: int) -> bool:
    """Whether a span holds an LSP position (lines from 0; characters as columns from 0)."""
    start, end = (span.line - 1, span.column - 1), (span.end_line - 1, span.end_column - 1)
    return start <= (line, character) <= end


class Index:
    """The references of one check of one file, and the texts of the files it read."""

    def __init__(self, path: str, references: tuple[tuple[Span, Any], ...], sources: dict[str, SourceFile]) -> None:
        self.path = path
        self.references = references
        self.lines = {p: source.text.splitlines() for p, source in sources.items()}

    def location(self, span: Span) -> lsp.Location:
        return lsp.Location(uri=from_fs_path(span.path) or span.path, range=to_range(span, self.lines.get(span.path, [])))

    def target_at(self, position: lsp.Position) -> Any:
        """The model object named at ``position``: a use of it, else its declaration."""
        line, character = position.line, position.character
        for span, target in self.references:
            if span.path == self.path and _contains(span, line, character):
                return target
        declared = [
            target
            for _, target in self.references
            if target.span.path == self.path and _contains(target.span, line, character)
        ]
        # the innermost declaration (a state inside a component's span, say)
        return min(declared, key=lambda t: (t.span.end - t.span.start), default=None)

    def definition(self, position: lsp.Position) -> lsp.Location | None:
        target = self.target_at(position)
        return self.location(target.span) if target is not None else None

    def uses(self, position: lsp.Position, declaration: bool) -> list[lsp.Location]:
        target = self.target_at(position)
        if target is None:
            return []
        found = [self.location(span) for span, t in self.references if t is target]
        if declaration:
            found.insert(0, self.location(target.span))
        return found
