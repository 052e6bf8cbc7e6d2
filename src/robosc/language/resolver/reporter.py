"""Collects the diagnostics of a resolution run."""

from __future__ import annotations

from collections.abc import Iterable

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, did_you_mean, error
from robosc.language.source import Span


class Reporter:
    def __init__(self) -> None:
        self.diagnostics: list[Diagnostic] = []

    def error(self, span: Span, message: str, code: Code, hint: str | None = None) -> None:
        self.diagnostics.append(error(span, message, code, hint))

    def unknown(self, span: Span, what: str, name: str, candidates: Iterable[str], where: str = "") -> None:
        """Rule 14: an unknown name, with the closest known one as a hint."""
        self.error(span, f"unknown {what} '{name}'{where}", Code.UNKNOWN_NAME, did_you_mean(name, candidates))
