"""A requirement on a message the robot sends (an ``outgoing`` message) is a warning: the
supervisor cannot forbid what the robot reports, so synthesis can only keep the whole system
out of every state where the message could come while the condition is false (SEMANTICS
section 4; the original tool cannot express it at all). Usually the requirement was meant for
an event the controller sends, or for a transition of a component."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, warning
from robosc.language.model import Direction, Message, Model, RequirementKind
from robosc.language.render import render


def check(model: Model) -> Iterator[Diagnostic]:
    for requirement in model.requirements:
        for c in requirement.communications:
            if not isinstance(c, Message) or c.direction is not Direction.OUTGOING:
                continue
            condition = render(requirement.condition)
            when = condition if requirement.kind is RequirementKind.NEEDS else f"not ({condition})"
            yield warning(
                requirement.span,
                f"'{c.name}' is a message the robot sends (outgoing), which the supervisor cannot forbid: "
                f"synthesis will keep the robot out of every state where '{c.name}' could come while "
                f"{when} does not hold, and fail if it cannot",
                Code.UNCONTROLLABLE_REQUIREMENT,
                f"to react to '{c.name}', write 'on response from {c.name}' in a component; to restrict the "
                "controller, require something of an event it sends (an incoming message, a service or an action)",
            )
