# -*- coding: utf-8 -*-
"""Data health, a part of the supervisor (mixed into :class:`~.supervisor.Supervisor`).

It owns: ``waiting`` (the communications whose first readable data the start still waits
for: while any, nothing is performed), ``stale`` (communications unreadable for longer than
``data_timeout``: the events reading them are held), ``unreadable`` (unreadable messages
counted per communication) and when each communication's unreadable data began, and
``ignored`` / ``last_ignored`` (events that came and were not taken, counted, and why the
last one was not). Fail closed: unreadable data is not a value."""

from __future__ import absolute_import, annotations, print_function

from typing import Callable, Dict, FrozenSet, Optional, Tuple

from .tables import Event, Tables

DATA_TIMEOUT = 1.0  # seconds of unreadable data from a communication before the events reading it are held


class DataHealth(Tables):
    """Whether the data the supervisor reads can be read, and what came and was not taken."""

    def _init_health(self, wait_for_data: bool, data_timeout: float, clock: Callable[[], float]) -> None:
        self.wait_for_data = wait_for_data
        self.data_timeout = data_timeout
        self.clock = clock
        self.unreadable: Dict[str, int] = {}  # communication -> how many of its messages could not be read
        self.ignored: Dict[str, int] = {}  # uncontrollable event -> how many times it came and was not taken
        self.last_ignored = ""  # why the last one was not taken

    def _reset_health(self) -> None:
        # communications that have not delivered readable data yet: while any, nothing is performed
        self.waiting = set(self.WAITED) if self.wait_for_data else set()
        self._unreadable_since: Dict[str, float] = {}  # communication -> its first unreadable data since readable
        self.stale: FrozenSet[str] = frozenset()  # communications unreadable for longer than data_timeout

    @property
    def held(self) -> bool:
        """Whether every controllable event is held (the start has not seen all its data yet)."""
        return bool(self.waiting)

    def _watch(self) -> None:
        """Communications unreadable for longer than ``data_timeout`` hold the events reading them."""
        now = self.clock()
        stale = frozenset(c for c, since in self._unreadable_since.items() if now - since >= self.data_timeout)
        if stale != self.stale:
            for c in stale - self.stale:
                self.warn("%s: no readable data for %.1f s; holding what reads it" % (c, self.data_timeout))
            self.stale = stale
            self.health_changes += 1
            self._dirty = True

    def _filter(self, enabled: Tuple[Callable[..., Optional[str]], ...]) -> Tuple[Callable[..., Optional[str]], ...]:
        stale = self.stale
        by_method = self.BY_METHOD
        return tuple(p for p in enabled if not (by_method[p.__name__].reads & stale))

    def ignore(self, name: str, why: str) -> bool:
        """``name`` (an event, or a topic's message) came and is not taken: counted, reported."""
        self.ignored[name] = self.ignored.get(name, 0) + 1
        self.health_changes += 1
        self.last_ignored = why
        self.warn("ignored %s: %s" % (name, why), "ignored " + name)
        return False

    def _readable(self, communication: str) -> None:
        """``communication`` delivered data that could be read."""
        if communication in self.waiting:
            self.waiting.discard(communication)
            self.health_changes += 1
        if self._unreadable_since.pop(communication, None) is not None and communication in self.stale:
            self.stale = self.stale - {communication}
            self.health_changes += 1
            self.warn("%s: readable data again" % (communication,))

    def _unreadable(self, event: Event, error: BaseException) -> bool:
        """Data of ``event`` that cannot be read: not delivered, counted and reported."""
        communication = event.communication or event.name
        self.unreadable[communication] = self.unreadable.get(communication, 0) + 1
        self.health_changes += 1
        self._unreadable_since.setdefault(communication, self.clock())
        self.warn(
            "%s: unreadable data (%s: %s); not delivered, the state is kept"
            % (event.name, type(error).__name__, error),
            "unreadable " + communication,
        )
        return False
