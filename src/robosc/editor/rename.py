"""Rename: the edits of ``Index.rename`` as a workspace edit, refused when the renamed model
would have errors the model had not (a name that is taken, say)."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Sequence
from pathlib import Path

from lsprotocol import types as lsp
from pygls.uris import from_fs_path

from robosc.editor.navigation import Index, RenameError
from robosc.language.diagnostics import Diagnostic
from robosc.language.source import Span


def apply(text: str, edits: list[tuple[Span, str]]) -> str:
    """``text`` with each span replaced (spans do not overlap)."""
    for span, new in sorted(edits, key=lambda e: e[0].start, reverse=True):
        text = text[: span.start] + new + text[span.end :]
    return text


def error_codes(diagnostics: Iterable[Diagnostic]) -> Counter[str]:
    """How many errors of each code."""
    return Counter(d.code.value for d in diagnostics if d.is_error)


def renamed(index: Index, edits: dict[str, list[tuple[Span, str]]], search_paths: Sequence[Path]) -> lsp.WorkspaceEdit:
    if set(edits) == {index.path}:  # all in the open model: check what it becomes
        from robosc.api import check_text

        result = check_text(apply(index.texts[index.path], edits[index.path]), index.path, search_paths)
        after = error_codes(result.diagnostics)
        worse = next((d for d in result.diagnostics if d.is_error and after[d.code.value] > index.errors[d.code.value]), None)
        if worse is not None:
            raise RenameError(f"not renamed: the model would not check: {worse.message} (line {worse.span.line})")
    changes = {
        from_fs_path(path) or path: [lsp.TextEdit(range=index.location(span).range, new_text=new) for span, new in found]
        for path, found in edits.items()
    }
    return lsp.WorkspaceEdit(changes=changes)
