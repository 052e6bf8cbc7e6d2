"""Rule 6: no assignment on a transition that sends data to a node
(a ``request`` to an incoming message)."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Direction, Message, Model, ResultKind, ResultTransition


def check(model: Model) -> Iterator[Diagnostic]:
    for component in model.components:
        for automaton in component.behaviours:
            for transition in automaton.transitions:
                if (
                    isinstance(transition, ResultTransition)
                    and transition.assignments
                    and transition.result is ResultKind.REQUEST
                    and isinstance(transition.communication, Message)
                    and transition.communication.direction is Direction.INCOMING
                ):
                    yield error(
                        transition.assignments[0].span,
                        f"no assignment on a request to '{transition.communication.name}': "
                        "it sends data to the node and receives none",
                        "rule-6",
                    )
