"""Rule 2: an automaton has exactly one initial state."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Model


def check(model: Model) -> Iterator[Diagnostic]:
    for component in model.components:
        for automaton in component.behaviours:
            initial = automaton.initial_states
            if not initial:
                yield error(
                    automaton.span,
                    f"the behaviour of '{component.name}' has no initial state",
                    Code.INITIAL_STATE,
                    "mark one state 'initial', as in 'initial marked state idle { ... }'",
                )
            for extra in initial[1:]:
                yield error(
                    extra.span,
                    f"'{component.name}' has more than one initial state ('{initial[0].name}' and '{extra.name}')",
                    Code.INITIAL_STATE,
                )
