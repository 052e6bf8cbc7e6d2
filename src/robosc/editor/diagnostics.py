"""``robosc check``'s diagnostics as LSP diagnostics, per file (a library's problems go to
the library's file)."""

from __future__ import annotations

import re

from lsprotocol import types as lsp

from robosc.api import CheckResult
from robosc.editor.positions import to_range

SOURCE = "robosc"
DID_YOU_MEAN = re.compile(r"did you mean '([^']+)'\?")


def fix_of(hint: str | None) -> dict[str, str] | None:
    """A hint that names the right text ("did you mean 'front'?"): the replacement, carried in
    the diagnostic's ``data`` for the code action."""
    found = DID_YOU_MEAN.search(hint or "")
    return {"replace": found.group(1)} if found else None


def code_actions(uri: str, diagnostics: list[lsp.Diagnostic]) -> list[lsp.CodeAction]:
    """A quick fix for each diagnostic that carries a replacement."""
    actions = []
    for d in diagnostics:
        data = d.data if isinstance(d.data, dict) else {}
        replacement = data.get("replace")
        if not isinstance(replacement, str) or d.source != SOURCE:
            continue
        # a qualified hint (Component.member) replaces the member only when the range is the member
        edit = lsp.TextEdit(range=d.range, new_text=replacement)
        actions.append(
            lsp.CodeAction(
                title=f"Change to '{replacement}'",
                kind=lsp.CodeActionKind.QuickFix,
                diagnostics=[d],
                edit=lsp.WorkspaceEdit(changes={uri: [edit]}),
                is_preferred=True,
            )
        )
    return actions


def by_file(result: CheckResult) -> dict[str, list[lsp.Diagnostic]]:
    """path -> diagnostics; every file that was read has an entry (maybe empty)."""
    out: dict[str, list[lsp.Diagnostic]] = {path: [] for path in result.sources}
    lines = {path: source.text.splitlines() for path, source in result.sources.items()}
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
                data=fix_of(d.hint),
            )
        )
    return out
