"""Sizes synthesis cannot represent are refused up front, with the figure that is too big:
an integer that takes part in synthesis has at most 65,536 values (synthesis encodes each
value; 65,536 take a few seconds, a million take over a minute)."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import BasicType, Model, synthesis_variables

MAX_VALUES = 65536


def check(model: Model) -> Iterator[Diagnostic]:
    for variable, use in synthesis_variables(model).items():
        t = variable.type
        if not isinstance(t, BasicType) or t.low is None or t.high is None:
            continue
        values = t.high - t.low + 1
        if values > MAX_VALUES:
            yield error(
                variable.span,
                f"'{variable.name}: {t}' has {values} values and takes part in synthesis (used at {use.span}); "
                f"synthesis handles at most {MAX_VALUES} values per variable",
                Code.LIMIT,
                "narrow the range, or turn the data into a few named values with an enum",
            )
