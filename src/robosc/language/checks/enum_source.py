"""Rule 11: an enum cannot be converted from another enum."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import EnumType, Model


def check(model: Model) -> Iterator[Diagnostic]:
    for enum in model.enums:
        if isinstance(enum.source, EnumType):
            yield error(
                enum.span,
                f"enum '{enum.name}' is converted from enum '{enum.source.name}'; convert from the raw data instead",
                Code.ENUM_SOURCE,
            )
