"""Rule 4: a component has at most one behaviour."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Model


def check(model: Model) -> Iterator[Diagnostic]:
    for component in model.components:
        for extra in component.behaviours[1:]:
            yield error(
                extra.span,
                f"component '{component.name}' has more than one behaviour",
                Code.ONE_BEHAVIOUR,
                "put all states, variables and transitions in one 'behaviour { ... }'",
            )
