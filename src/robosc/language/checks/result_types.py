"""Rule 5: the result type of a transition fits its communication."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Action, Communication, Direction, Message, Model, ResultKind, result_transitions

R = ResultKind


def allowed(communication: Communication) -> tuple[frozenset[ResultKind], str]:
    if isinstance(communication, Message):
        if communication.direction is Direction.OUTGOING:
            return frozenset({R.RESPONSE}), "an outgoing message (the node publishes) only has 'response'"
        return frozenset({R.REQUEST}), "an incoming message (the controller publishes) only has 'request'"
    if isinstance(communication, Action):
        return frozenset(R), ""
    return frozenset({R.REQUEST, R.RESPONSE, R.ERROR}), "a service has 'request', 'response' and 'error'"


def check(model: Model) -> Iterator[Diagnostic]:
    for _, transition in result_transitions(model):
        kinds, explanation = allowed(transition.communication)
        if transition.result not in kinds:
            yield error(
                transition.span,
                f"'{transition.result.value}' does not fit '{transition.communication.name}': {explanation}",
                Code.RESULT_TYPES,
            )
