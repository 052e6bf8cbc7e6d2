"""Diagnostics: what the language stage reports about a model, and how it is shown."""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from enum import Enum

from robosc.language.codes import Code
from robosc.language.source import SourceFile, Span
from robosc.record import record
from robosc.wrapping import fill


class Severity(str, Enum):
    ERROR = "error"
    WARNING = "warning"


@record
class Diagnostic:
    """One finding: where, how bad, what, and (optionally) a hint how to fix it.

    ``code`` names the rule (the registry is :class:`robosc.language.codes.Code`).
    """

    severity: Severity
    message: str
    span: Span
    code: Code
    hint: str | None = None

    @property
    def is_error(self) -> bool:
        return self.severity is Severity.ERROR


def error(span: Span, message: str, code: Code, hint: str | None = None) -> Diagnostic:
    return Diagnostic(Severity.ERROR, message, span, code, hint)


def warning(span: Span, message: str, code: Code, hint: str | None = None) -> Diagnostic:
    return Diagnostic(Severity.WARNING, message, span, code, hint)


def closest(name: str, candidates: Iterable[str]) -> str | None:
    """The known name closest to ``name``: a near spelling, else the shortest name that
    starts with it or contains it (``current`` -> ``current_correction``); None if none."""
    known = sorted(set(candidates))
    import difflib

    close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
    if close:
        return close[0]
    if len(name) < 3:
        return None
    lowered = name.lower()
    starting = [c for c in known if c.lower().startswith(lowered)]
    containing = [c for c in known if lowered in c.lower()]
    found = starting or containing
    return min(found, key=lambda c: (len(c), c)) if found else None


def did_you_mean(name: str, candidates: Iterable[str]) -> str | None:
    """A "did you mean ...?" hint for an unknown ``name``, or None when nothing is close."""
    found = closest(name, candidates)
    return f"did you mean '{found}'?" if found else None


def sort_key(diagnostic: Diagnostic) -> tuple[str, int, int]:
    return (diagnostic.span.path, diagnostic.span.line, diagnostic.span.column)


SHOWN = 120  # at most this much of a long source line is shown under a diagnostic


_CONTROL = re.compile("[\x00-\x1f\x7f-\x9f]")


def render_text(diagnostic: Diagnostic, sources: Mapping[str, SourceFile], columns: int | None = None) -> str:
    """``path:line:col: error: message``, then the source line and a caret under the span,
    then the hint; with ``columns``, the message and hint wrap to it and the source line is
    shown through a window that fits."""
    span = diagnostic.span
    lines = [fill(f"{span}: {diagnostic.severity.value}: {diagnostic.message}", columns)]
    source = sources.get(span.path)
    shown_at_most = SHOWN if columns is None else max(20, min(SHOWN, columns - 10))
    if source is not None and span.line > 0:
        text = _CONTROL.sub("?", source.line_text(span.line).expandtabs(1))  # shown, never sent to the terminal
        if text.strip():
            width = (span.end_column - span.column) if span.end_line == span.line else 1
            width = max(1, min(width, len(text) - span.column + 1))
            column = span.column
            if len(text) > shown_at_most:  # a window of the line around the span
                start = max(0, min(column - 1 - shown_at_most // 3, len(text) - shown_at_most))
                shown = text[start : start + shown_at_most]
                text = ("..." if start else "") + shown + ("..." if start + shown_at_most < len(text) else "")
                column = column - start + (3 if start else 0)
                width = max(1, min(width, shown_at_most - (column - 1)))
            lines.append(f"    {text}")
            lines.append("    " + " " * (column - 1) + "^" + "~" * (width - 1))
    if diagnostic.hint:
        lines.append(fill(f"    hint: {diagnostic.hint}", columns, "      "))
    return "\n".join(lines)


def to_json(diagnostics: Iterable[Diagnostic]) -> str:
    """The diagnostics as a JSON array (for editors and CI)."""
    import json

    return json.dumps(
        [
            {
                "path": d.span.path,
                "line": d.span.line,
                "column": d.span.column,
                "end_line": d.span.end_line,
                "end_column": d.span.end_column,
                "severity": d.severity.value,
                "code": d.code.value,
                "message": d.message,
                "hint": d.hint,
            }
            for d in diagnostics
        ],
        indent=2,
    )


def once_per_place(diagnostics: list[Diagnostic]) -> tuple[Diagnostic, ...]:
    """The diagnostics, each place and code reported once: a mistake in a component with
    instances, or in a 'for' block, is found once per instance, and said once."""
    seen = set()
    kept = []
    for diagnostic in diagnostics:
        key = (diagnostic.span, diagnostic.code, diagnostic.severity)
        if key not in seen:
            seen.add(key)
            kept.append(diagnostic)
    return tuple(kept)
