"""Collects the diagnostics of a resolution run."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, did_you_mean, error, warning
from robosc.language.source import Span


class Reporter:
    def __init__(self) -> None:
        self.diagnostics: list[Diagnostic] = []
        # each name that resolved, and what it names (a model object with a span): for editors
        self.references: list[tuple[Span, Any]] = []
        self.made = 0  # expression nodes resolved: quantifiers and 'for' blocks stop at a bound
        self.expansion_stopped = False  # the bound was passed (and said)

    def refer(self, span: Span, target: Any) -> None:
        self.references.append((span, target))

    def error(self, span: Span, message: str, code: Code, hint: str | None = None) -> None:
        self.diagnostics.append(error(span, message, code, hint))

    def warning(self, span: Span, message: str, code: Code, hint: str | None = None) -> None:
        self.diagnostics.append(warning(span, message, code, hint))

    def unknown(
        self,
        span: Span,
        what: str,
        name: str,
        candidates: Iterable[str],
        where: str = "",
        otherwise: Callable[[], str | None] | None = None,
    ) -> None:
        """Rule 14: an unknown name, with the closest known one as a hint (else the hint of
        ``otherwise``, e.g. a name in another component)."""
        hint = did_you_mean(name, candidates) or (otherwise() if otherwise else None)
        self.error(span, f"unknown {what} '{name}'{where}", Code.UNKNOWN_NAME, hint)
