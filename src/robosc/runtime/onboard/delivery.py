# -*- coding: utf-8 -*-
"""Commands on their way to the robots.

A command is performed when it is put on the wire, but the robot has it only once it
arrived. Until then what the command changed in the supervisor's state is unconfirmed:
the robot may be where it was or where the command sends it, and whatever is decided
meanwhile must be safe for both. On ROS 2 (reliable QoS) every matched subscriber
acknowledges a message it received: once they all did, the command is known delivered.
A subscriber that does not acknowledge within ``ack_timeout`` (a driver that died: DDS
keeps a dead subscriber matched until its lease ends, 20 s by default) leaves the robot
unconfirmed, and its driver is asked where it is. ROS 1 acknowledges nothing: a command
is taken as delivered, unless its topic loses its last subscriber within ``ack_timeout``
(TCPROS notices a driver that died at once).

Standard library only, Python 3.8 or newer (ROS Noetic).
"""

from __future__ import absolute_import, annotations

import time
from typing import Any, Dict, List, Optional, Set, Tuple

from .unknown import Unknown, distinct


class Pending(object):
    """A command whose delivery is not known yet."""

    __slots__ = ("after", "deadline", "either", "event", "topic", "versions")

    def __init__(
        self,
        event: str,
        topic: Any,
        deadline: float,
        after: Dict[str, Any],
        either: Dict[str, Optional[Tuple[Any, ...]]],
        versions: Dict[str, int],
    ) -> None:
        self.event = event
        self.topic = topic
        self.deadline = deadline
        self.after = after  # field -> its value once delivered (Unknown: it was unconfirmed anyway)
        self.either = either  # field -> the values it may have while the command is on its way
        self.versions = versions  # field -> its version once the command was sent


class Delivery(object):
    """The commands of one node (``NodeCore``) on their way."""

    def __init__(self, node: Any) -> None:
        self.node = node
        # since the last follow(): event, topic, the values before, the candidates of unconfirmed fields before
        self.sending: List[Tuple[str, Any, Any, Dict[str, Any], float]] = []
        self.pending: List[Pending] = []
        self.silent: Dict[str, float] = {}  # topic -> since when a subscriber has not acknowledged (ROS 2)

    def sent(self, event: str, topic: Any) -> None:
        """The node is putting ``event`` on ``topic`` (before the event's effect)."""
        supervisor = self.node.supervisor
        before = type(supervisor).GETTER(supervisor)
        unsure = dict(supervisor.unconfirmed) if supervisor.unconfirmed else {}
        self.sending.append((event, topic, before, unsure, time.monotonic()))

    def held(self, topic: Any) -> Optional[str]:
        """Why nothing more may be sent on ``topic`` now: a subscriber did not acknowledge what it
        was sent within ``ack_timeout`` (a driver that died, a link that is down), until it does;
        or (ROS 2) the last command on it that changed the state is not acknowledged yet: one at a
        time, so that no more than one goes into the void of a driver that has just died."""
        since = self.silent.get(topic.name)
        if since is not None:
            return "%s has not acknowledged a command for %.1f s" % (topic.name, time.monotonic() - since)
        if self.node.acknowledges and any(p.topic is topic for p in self.pending):
            return "the last command on %s is not acknowledged yet" % (topic.name,)
        return None

    def waiting(self) -> Set[str]:
        """The components that are unconfirmed only while a command to them is on its way."""
        supervisor = self.node.supervisor
        return set(supervisor.COMPONENT_OF.get(a, a) for p in self.pending for a in p.after)

    def follow(self) -> None:
        """What the commands sent since the last call changed becomes unconfirmed until they are
        acknowledged; acknowledged ones are known; late ones stay unconfirmed and are reported."""
        if self.sending:
            sending, self.sending = self.sending, []
            for event, topic, before, unsure, at in sending:
                self._track(event, topic, before, unsure, at)
        node = self.node
        for name in list(self.silent):
            topic = node.outputs.get(name)
            if topic is None or (node.listeners(topic) > 0 and node.acknowledged(topic)):
                del self.silent[name]
                node.log("info", "%s acknowledges again: its commands are no longer held" % name)
        if not self.pending:
            return
        now = time.monotonic()
        for pending in list(self.pending):
            listeners = node.listeners(pending.topic)
            if listeners == 0:
                self._lost(pending, "no subscriber left")
            elif node.acknowledges:
                if node.acknowledged(pending.topic):
                    self._delivered(pending)
                elif now >= pending.deadline:
                    self._lost(pending, "not acknowledged within %.1f s" % node.params["ack_timeout"])
            elif now >= pending.deadline:  # ROS 1: it kept its subscribers through the window
                self.pending.remove(pending)

    def _track(self, event: str, topic: Any, before: Any, unsure: Dict[str, Any], at: float) -> None:
        supervisor = self.node.supervisor
        changed: Dict[str, Optional[Tuple[Any, ...]]] = {}
        after: Dict[str, Any] = {}
        for index, attribute in supervisor.TRACKED:
            new, old = getattr(supervisor, attribute), before[index]
            if new is old:
                continue
            after[attribute] = new
            changed[attribute] = _either(unsure.get(attribute, (old,)), supervisor.unconfirmed.get(attribute, (new,)))
        if not after:
            return
        if self.node.acknowledges:  # ROS 2: unconfirmed until acknowledged
            supervisor.unconfirm(changed, "%s on its way" % (event,))
        versions = dict((attribute, supervisor.versions.get(attribute, 0)) for attribute in after)
        self.pending.append(Pending(event, topic, at + self.node.params["ack_timeout"], after, changed, versions))

    def arrived(self, field: str, locations: Tuple[str, ...]) -> None:
        """An answer moved ``field`` on from where it is answered (``locations``): a command on
        its way that put it there arrived, where the robot would not have answered from any other
        place the command left it (a driver answers what it did, once)."""
        for pending in list(self.pending):
            either = pending.either.get(field, ())
            if field not in pending.after or either is None:
                continue
            if all(value not in locations for value in either if value != pending.after[field]):
                del pending.after[field], pending.either[field]
                if not pending.after:
                    self.pending.remove(pending)

    def _delivered(self, pending: Pending) -> None:
        self.pending.remove(pending)
        supervisor = self.node.supervisor
        for attribute, value in pending.after.items():
            if isinstance(value, Unknown) or supervisor.versions.get(attribute, 0) != pending.versions[attribute]:
                continue  # unconfirmed for another reason too, or changed since: reports will tell
            supervisor.know(attribute, value)

    def _lost(self, pending: Pending, why: str) -> None:
        """Not acknowledged in time, or its topic lost its subscribers: what it changed is
        unconfirmed (where the robot may be, or anywhere once it changed since), said once."""
        self.pending.remove(pending)
        if self.node.acknowledges:
            self.silent.setdefault(pending.topic.name, time.monotonic())
        supervisor = self.node.supervisor
        components = sorted(set(supervisor.COMPONENT_OF[a] for a in pending.after))
        reason = "%s may not have arrived (%s)" % (pending.event, why)
        # where the robot may be: where the command may have left it, or where the supervisor has
        # it now (answers may have moved it on since)
        fields = dict(
            (a, _either(values, supervisor.unconfirmed.get(a, (getattr(supervisor, a),))))
            for a, values in pending.either.items()
        )
        supervisor.unconfirm(fields, reason)
        for component in components:
            supervisor.why[component] = reason
        supervisor.health_changes += 1
        self.node.log("warning", "%s: %s unconfirmed, held until its driver reports" % (reason, ", ".join(components)))


def _either(old: Optional[Tuple[Any, ...]], new: Optional[Tuple[Any, ...]]) -> Optional[Tuple[Any, ...]]:
    """The values a field may have when a command may or may not have moved it: where it may have
    been (``old``), or where it may be after (``new``); None (any value) where either is."""
    if old is None or new is None:
        return None
    return distinct(list(old) + list(new))
