# -*- coding: utf-8 -*-
"""The supervision layer's side of a node (a part of :class:`~.node.NodeCore`): a command from
the existing controller is forwarded only as an event whose data it is exactly and that the
supervisor allows now; else it is blocked and reported on ``blocked``."""

from __future__ import absolute_import, annotations

import json
from typing import Any, List, Optional

from .messages import conforms
from .node_base import Call, NodeBase, Topic
from .values import finite, plain

BLOCKED_TOPIC = "blocked"


class SupervisionLayer(NodeBase):
    """Commands from the controller: forwarded, or blocked and reported."""

    def request(self, topic: Topic, message: Any) -> bool:
        """The controller published ``message`` on ``topic``: forwarded as the first event whose
        data it is exactly (see :func:`messages.conforms`) and that the supervisor allows now,
        else blocked and reported. Never forwarded as an event whose data it is not."""
        found = self.events_of(message, topic.events, topic.name)
        for event in found:
            if self.supervisor.perform(event.name, message):
                self.forwarded_count += 1
                self.supervisor.settle()
                self.checkpoint()
                return True
        self.refuse(found, topic.name, message)
        return False

    def admit(self, call: Call, request: Any) -> bool:
        """The controller calls a service or sends a goal: performed (True) only when the
        request is exactly the trigger's data and the supervisor allows it now, then what
        follows settled and persisted, as for a message; else reported."""
        found = self.events_of(request, [call.trigger], call.name)
        if found and self.supervisor.perform(call.trigger.name, request):
            self.supervisor.settle()
            self.checkpoint()
            return True
        self.refuse(found, call.name, request)
        return False

    def events_of(self, message: Any, events: List[Any], where: str) -> List[Any]:
        """The events among ``events`` whose data ``message`` is exactly, now (none when a number
        in it is not finite, or it cannot be compared)."""
        try:
            if not finite(message):
                return []
            return [e for e in events if conforms(message, self.supervisor.template(e.name))]
        except Exception as error:
            self.warnings("command on %s: %s: %s" % (where, type(error).__name__, error), "request " + where)
            return []

    def refuse(self, found: List[Any], where: str, message: Any) -> None:
        """Report a controller's command that is not forwarded: why, on ``blocked``."""
        if not found:
            why = "is the data of no event on it now" if finite(message) else "a number in it is not finite"
            self.blocked(None, where, why, message)
            return
        why = self.supervisor.holds(found[0].name) or self.refused or "the supervisor does not allow it now"
        self.refused = None  # read once: a later refusal (a message, a call, a goal) has its own reason
        self.blocked(found[0].name, where, why, message)

    def blocked(self, event: Optional[str], where: str, reason: str, data: Any = None) -> None:
        """Report a blocked request on ``blocked`` (JSON) and in the log (rate-limited)."""
        self.blocked_count += 1
        self.warnings("blocked %s on %s: %s" % (event or "a command", where, reason), "blocked %s %s" % (event, where))
        report = {
            "event": event,
            "topic": where,
            "reason": reason,
            "data": plain(data),
            "state": self.supervisor.snapshot(),
        }
        try:
            self.publish_text(BLOCKED_TOPIC, json.dumps(report, sort_keys=True))
        except Exception as error:
            self.warnings("cannot report a blocked command: %s" % (error,), "blocked report")
