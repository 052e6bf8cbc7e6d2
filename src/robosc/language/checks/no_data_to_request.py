"""Rule 6: no assignment on a transition that sends data to a node
(a ``request`` to an incoming message)."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Direction, Message, Model, ResultKind, result_transitions


def check(model: Model) -> Iterator[Diagnostic]:
    for _, transition in result_transitions(model):
        communication = transition.communication
        if (
            transition.assignments
            and transition.result is ResultKind.REQUEST
            and isinstance(communication, Message)
            and communication.direction is Direction.INCOMING
        ):
            yield error(
                transition.assignments[0].span,
                f"no assignment on a request to '{communication.name}': it sends data to the node and receives none",
                Code.NO_DATA_TO_REQUEST,
            )
