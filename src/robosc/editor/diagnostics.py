"""``robosc check``'s diagnostics as LSP diagnostics, per file (a library's problems go to
the library's file), each with the fix its hint names, if any, in its ``data`` for the
quick fix: did-you-mean, a keyword's ``^`` escape, a missing integer range."""

from __future__ import annotations

import re
from typing import Any

from lsprotocol import types as lsp

from robosc.api import CheckResult
from robosc.editor.positions import to_range
from robosc.language.diagnostics import Diagnostic
from robosc.language.source import Span

SOURCE = "robosc"
DID_YOU_MEAN = re.compile(r"did you mean '([^']+)'\?")
ESCAPE = re.compile(r"write '(\^[A-Za-z_][A-Za-z0-9_]*)' to use it as a name")
RANGE = re.compile(r"as in '(?:[^':]*: )?integer(\(-?[0-9]+\.\.-?[0-9]+\))'")
BARE_INTEGER = re.compile(r"\binteger\b(?!\s*\()")


def fix_of(d: Diagnostic, text: str, lines: list[str]) -> dict[str, Any] | None:
    """The edit a diagnostic's hint names: {"title", "newText", "range" (LSP JSON)}."""
    hint = d.hint or ""
    whole = to_range(d.span, lines)
    found = DID_YOU_MEAN.search(hint)
    if found:
        return _fix(f"Change to '{found.group(1)}'", found.group(1), whole)
    found = ESCAPE.search(hint)
    if found:
        return _fix(f"Escape the keyword: '{found.group(1)}'", found.group(1), whole)
    found = RANGE.search(hint)
    if found:
        # after the one 'integer' without a range in the declaration
        bare = list(BARE_INTEGER.finditer(text, d.span.start, d.span.end))
        if len(bare) != 1:
            return None
        at = Span.of(d.span.path, text, bare[0].end())
        return _fix(f"Add the range {found.group(1)}", found.group(1), to_range(at, lines))
    return None


def _fix(title: str, new_text: str, where: lsp.Range) -> dict[str, Any]:
    start, end = where.start, where.end
    return {
        "title": title,
        "newText": new_text,
        "range": {
            "start": {"line": start.line, "character": start.character},
            "end": {"line": end.line, "character": end.character},
        },
    }


def code_actions(uri: str, diagnostics: list[lsp.Diagnostic]) -> list[lsp.CodeAction]:
    """A quick fix for each of robosc's diagnostics that carries one."""
    actions = []
    for d in diagnostics:
        data = d.data if isinstance(d.data, dict) else {}
        title, new_text, where = data.get("title"), data.get("newText"), data.get("range")
        if d.source != SOURCE or not isinstance(title, str) or not isinstance(new_text, str):
            continue
        try:
            start, end = where["start"], where["end"]  # type: ignore[index]
            edit_range = lsp.Range(
                start=lsp.Position(line=int(start["line"]), character=int(start["character"])),
                end=lsp.Position(line=int(end["line"]), character=int(end["character"])),
            )
        except (TypeError, KeyError, ValueError):
            continue  # not data of ours
        actions.append(
            lsp.CodeAction(
                title=title,
                kind=lsp.CodeActionKind.QuickFix,
                diagnostics=[d],
                edit=lsp.WorkspaceEdit(changes={uri: [lsp.TextEdit(range=edit_range, new_text=new_text)]}),
                is_preferred=True,
            )
        )
    return actions


def by_file(result: CheckResult) -> dict[str, list[lsp.Diagnostic]]:
    """path -> diagnostics; every file that was read has an entry (maybe empty)."""
    out: dict[str, list[lsp.Diagnostic]] = {path: [] for path in result.sources}
    texts = {path: source.text for path, source in result.sources.items()}
    lines = {path: text.splitlines() for path, text in texts.items()}
    for d in result.diagnostics:
        path = d.span.path
        message = d.message if d.hint is None else f"{d.message}\nhint: {d.hint}"
        out.setdefault(path, []).append(
            lsp.Diagnostic(
                range=to_range(d.span, lines.get(path, [])),
                message=message,
                severity=lsp.DiagnosticSeverity.Error if d.is_error else lsp.DiagnosticSeverity.Warning,
                code=str(d.code.value),
                source=SOURCE,
                data=fix_of(d, texts.get(path, ""), lines.get(path, [])),
            )
        )
    return out
