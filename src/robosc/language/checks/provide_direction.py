"""Rule 8: provide statements only for communication the controller sends
(incoming messages, service and action requests), never for outgoing messages."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Direction, Message, Model


def check(model: Model) -> Iterator[Diagnostic]:
    for provide in model.provides:
        communication = provide.communication
        if isinstance(communication, Message) and communication.direction is Direction.OUTGOING:
            yield error(
                provide.span,
                f"cannot provide data for '{communication.name}': it is an outgoing message, "
                "which the node publishes and the controller only receives",
                Code.PROVIDE_DIRECTION,
            )
