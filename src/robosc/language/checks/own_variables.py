"""Rule 7: a transition assigns only variables of its own automaton."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Model, result_transitions


def check(model: Model) -> Iterator[Diagnostic]:
    for component, transition in result_transitions(model):
        for assignment in transition.assignments:
            variable = assignment.variable
            if variable.owner != component.name and variable.name != "<invalid>":
                yield error(
                    assignment.span,
                    f"'{component.name}' cannot assign '{variable.owner}.{variable.name}': "
                    "a transition assigns only its own component's variables",
                    Code.OWN_VARIABLES,
                )
