# -*- coding: utf-8 -*-
"""Where events go besides the supervisor: the event log (JSON Lines, bounded in size)
and any other sink (the live view), each record with its time, data and the state."""

from __future__ import absolute_import, annotations

import contextlib
import json
import os
import time
from typing import Any, Callable, Iterable, Optional

from .values import plain


class Gated(object):
    """A sink that wants records only while ``wanted()`` says so (a topic with no subscriber):
    while no sink wants one, the record is not even made. What ``wanted()`` says is asked again
    at most every ``interval`` seconds (a node's cycle looks, not every event)."""

    def __init__(
        self, sink: Callable[[dict[str, Any]], Any], wanted: Callable[[], bool], interval: float = 0.1
    ) -> None:
        self.sink = sink
        self.asked = wanted
        self.interval = interval
        self.answer = False
        self.when = -1e18

    def wanted(self) -> bool:
        now = time.monotonic()
        if now - self.when >= self.interval:
            self.when = now
            self.answer = bool(self.asked())
        return self.answer

    def __call__(self, record: dict[str, Any]) -> Any:
        return self.sink(record)


class Recorder(object):
    """An observer for the supervisor: hands each event, with its time, data and the
    resulting state, to every sink that wants it. A failing sink is reported, never fatal.

    The state can also change without an event: a command's target is unconfirmed while the
    command is on its way (ROS 2) and known once it is acknowledged, a robot becomes
    unconfirmed when its driver goes silent or known when it reports. :meth:`settled` hands
    such a change on as a *state record*, one whose ``event`` is null, so that a log or a page
    never keeps showing a belief the node no longer holds."""

    def __init__(
        self, supervisor: Any, sinks: Iterable[Callable[[dict[str, Any]], Any]], clock: Callable[[], float] = time.time
    ) -> None:
        self.supervisor = supervisor
        self.sinks = list(sinks)
        self.clock = clock
        self.shown: Optional[dict[str, Any]] = None  # the state in the last record handed on

    def settled(self) -> None:
        """A state record, if the state differs from the last record's and any sink wants it."""
        sinks = self._wanting()
        if not sinks:
            return
        state = self.supervisor.snapshot()
        if state == self.shown:
            return
        self._hand(sinks, {"time": round(self.clock(), 6), "event": None, "controllable": False, "data": None, "state": state})

    def _wanting(self) -> list[Callable[[dict[str, Any]], Any]]:
        """The sinks that want records now."""
        return [s for s in self.sinks if not isinstance(s, Gated) or s.wanted()]

    def wanted(self) -> bool:
        """Whether any sink wants records now."""
        return bool(self._wanting())

    def __call__(self, event: str, controllable: bool, data: Any) -> None:
        sinks = self._wanting()
        if not sinks:
            return
        record = {
            "time": round(self.clock(), 6),
            "event": event,
            "controllable": controllable,
            "data": plain(data),
            "state": self.supervisor.snapshot(),
        }
        self._hand(sinks, record)

    def _hand(self, sinks: list[Callable[[dict[str, Any]], Any]], record: dict[str, Any]) -> None:
        self.shown = record["state"]
        for sink in sinks:
            try:
                sink(record)
            except Exception as error:  # a full disk or a closed page must not stop the node
                self.supervisor.warn("event not recorded: %s: %s" % (type(error).__name__, error), "record")


class EventLog(object):
    """Appends records to ``path`` as JSON lines. When the file would pass ``max_bytes``
    (0: no bound), it is renamed to ``path.1`` (replacing an older one) and a new file is
    started, so the log never takes more than about twice ``max_bytes``.

    Each line goes to the file in one unbuffered write. A write that fails (a full disk, a
    folder gone read-only) is said once through ``warn`` and the record is lost; the records
    after it are tried, and when one is written again that is said too, with how many were lost
    (a line torn by the failure is ended first). Closing never fails."""

    def __init__(self, path: str, max_bytes: int = 0, warn: Optional[Callable[[str], Any]] = None) -> None:
        self.path = path
        self.max_bytes = max_bytes
        self.warn = warn
        self.handle = open(path, "ab", buffering=0)  # noqa: SIM115 (kept open, closed by close())
        self.size = self.handle.tell()
        self.rotations = 0
        self.lost = 0  # records not written since the last one that was
        self.torn = False  # the last write may have left part of a line

    def __call__(self, record: dict[str, Any]) -> None:
        line = (json.dumps(record, sort_keys=True) + "\n").encode("utf-8")
        try:
            if self.handle.closed:  # a rotation that failed half-way
                self.handle = open(self.path, "ab", buffering=0)  # noqa: SIM115 (kept open)
                self.size = self.handle.tell()
            if self.max_bytes and self.size + len(line) > self.max_bytes and self.size > 0:
                self.rotate()
            if self.torn:
                self.size += self.handle.write(b"\n") or 0
                self.torn = False
            written = self.handle.write(line) or 0
            self.size += written
            if written < len(line):
                raise OSError("only %d of %d bytes written" % (written, len(line)))
        except (OSError, ValueError) as error:
            self.torn = True
            self.lost += 1
            if self.lost == 1 and self.warn is not None:
                self.warn("cannot write the event log %s (%s: %s): events are not logged until it can be"
                          % (self.path, type(error).__name__, error))
            return
        if self.lost:
            if self.warn is not None:
                self.warn("the event log %s is written again (%d events were not)" % (self.path, self.lost))
            self.lost = 0

    def rotate(self) -> None:
        self.handle.close()
        os.replace(self.path, self.path + ".1")
        self.handle = open(self.path, "ab", buffering=0)  # noqa: SIM115 (kept open)
        self.size = 0
        self.rotations += 1

    def close(self) -> None:
        with contextlib.suppress(OSError):  # unbuffered: nothing is lost
            self.handle.close()


def writable(path: str) -> Optional[str]:
    """None if ``path`` can be appended to, else why not."""
    try:
        with open(path, "a"):
            pass
    except (OSError, ValueError) as error:
        return "%s: %s" % (type(error).__name__, error)
    return None
