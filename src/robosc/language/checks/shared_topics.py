"""Rule 13 (warning): two components publish to the same topic."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, warning
from robosc.language.model import Direction, Message, Model


def check(model: Model) -> Iterator[Diagnostic]:
    publishers: dict[str, Message] = {}
    for communication in model.communications:
        if not isinstance(communication, Message) or communication.direction is not Direction.OUTGOING:
            continue
        first = publishers.setdefault(communication.ros_name, communication)
        if first.owner != communication.owner:
            yield warning(
                communication.span,
                f"'{communication.owner}' and '{first.owner}' both publish to topic '{communication.ros_name}'",
                Code.SHARED_TOPICS,
            )
