"""``robosc check``'s diagnostics as LSP diagnostics, per file (a library's problems go to
the library's file)."""

from __future__ import annotations

from lsprotocol import types as lsp

from robosc.api import CheckResult
from robosc.editor.positions import to_range

SOURCE = "robosc"


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
            )
        )
    return out
