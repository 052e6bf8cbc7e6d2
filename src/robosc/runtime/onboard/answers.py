# -*- coding: utf-8 -*-
"""Answers and commands, a part of the supervisor (mixed into :class:`~.supervisor.Supervisor`
through :class:`~.belief.Belief`): whether an answer (an uncontrollable event some component
answers in some locations) can be taken now, and, while a node watches (``watching``), when
each command changed a field and each answer did.

It owns ``watching``; ``commanded`` (field -> when, on this wall clock, a command last changed
it, until an answer does); ``heard`` (field -> the stamp of the last answer that changed it);
``skew`` (seconds a robot's clock may be behind this one); ``answered`` (told when an answer
moved a field from where its component answers it); ``changes`` (per component, how many
events changed it) and ``asking`` (the components whose driver is asked for a report). An
answer is not taken where no component waits for it, nor when it is stamped before the
command it would answer (a late duplicate).

Standard library only, Python 3.8 or newer (ROS Noetic).
"""

from __future__ import absolute_import, annotations

import time
from typing import Any, Callable, Dict, Optional, Tuple

from .health import DataHealth
from .tables import Event
from .unknown import Unknown


def moved(new: Any, old: Any) -> bool:
    """Whether a field that is now ``new`` (another object than ``old``) changed: its value, or
    the values it may have (a new Unknown is made only when they change)."""
    return type(new) is not type(old) or type(new) is Unknown or new != old


class Answers(DataHealth):
    """Which answers can be taken now, and when commands and answers changed each field."""

    def _init_answers(self) -> None:
        # while watching (a node sets it), per field: when (this wall clock) a command last changed it,
        # until an answer changes it (it waits for one); and the stamp (the robot's clock) of the last
        # answer that changed it; for telling a late answer from a new one and one that does not come
        self.watching = False
        self.commanded: Dict[str, float] = {}
        self.heard: Dict[str, float] = {}
        # told (while watching) when an answer moved a field from a location where its component
        # answers it: answered(field, those locations); the robot had the command that put it there
        self.answered: Optional[Callable[[str, Tuple[str, ...]], None]] = None
        self.skew = 0.0  # seconds a robot's clock may be behind this one
        # while watching, per component: how many events (commands, triggers, answers, data) changed
        # its fields; a driver's report asked for before one of them may tell where it was before
        self.changes: Dict[str, int] = {}
        # the components whose driver is being asked for a report (the node's, by when): changes
        # are counted only while any is (nothing to count them for otherwise)
        self.asking: Dict[str, float] = {}
        # an answer may be a second copy of an earlier one (a driver's retry, a bridge that sends
        # twice, a replay: a std_msgs/Empty carries nothing to tell them apart), so it leaves its
        # component where it was or where it leads until the driver's report tells (a node sets
        # it: parameter confirm_answers); ``doubted``: the components an answer left unconfirmed
        # since the node last looked (it asks their drivers at once)
        self.confirm_answers = False
        self.doubted: list[str] = []

    def awaited(self, attribute: str) -> list[str]:
        """The answers (uncontrollable events) the component whose location is ``attribute``
        waits for where it is now (none while it is unconfirmed)."""
        value = getattr(self, attribute)
        if isinstance(value, Unknown):
            return []
        return [
            name
            for name, answers in self.ANSWERS.items()
            if any(field == attribute and value in locations for field, locations in answers)
        ]

    def _watched(self, perform: Callable[..., Optional[str]], data: Any) -> Optional[str]:
        """``perform(data)`` noting when each field it changed changed (for late answers)."""
        before = type(self).GETTER(self)
        name = perform(data) if data is not None else perform()
        if name is not None:
            now = time.time()
            for index, attribute in self.TRACKED:
                if getattr(self, attribute) is not before[index]:
                    self.commanded[attribute] = now
            if self.asking:
                self._count(before)
        return name

    def _count(self, before: Any) -> None:
        """Count, per component, an event that changed it (``before``: every field's value before
        it): a driver's report asked for before may tell where it was before."""
        changes = self.changes
        for place, attribute in self.TRACKED:
            new, old = getattr(self, attribute), before[place]
            if new is not old and moved(new, old):
                component = self.COMPONENT_OF[attribute]
                changes[component] = changes.get(component, 0) + 1

    def _not_taken(self, name: str, stamp: Optional[float]) -> Optional[str]:
        """Why the uncontrollable event ``name`` (stamped ``stamp``) is not taken here, or None:
        the plant cannot take it, or no component that answers it waits for it."""
        if name in self.FREE:
            return None
        if not self._expected()[self.EXPECTED_AT[name]]:
            return "not expected now"
        answers = self.ANSWERS.get(name)
        return self._unanswered(answers, stamp) if answers is not None else None

    def _unanswered(self, answers: Tuple[Tuple[str, Tuple[str, ...]], ...], stamp: Optional[float]) -> Optional[str]:
        """Why no component takes an answer now (None: one does): none is where it answers it,
        or it is stamped before every command that put one there."""
        waiting = [field for field, locations in answers if getattr(self, field) in locations]
        if not waiting:
            return "%s does not expect it where it is (%s)" % (
                " or ".join(self.LABELS[f] for f, _ in answers),
                ", ".join(str(getattr(self, f)) for f, _ in answers),
            )
        if stamp is not None and all(self._before(stamp, f) for f in waiting):
            return "stamped before the command it would answer, or an answer taken since (a late duplicate)"
        return None

    def _before(self, stamp: float, field: str) -> bool:
        """Whether an answer stamped ``stamp`` was sent before the command that put ``field`` where it
        is, or before the last answer that changed it."""
        commanded = self.commanded.get(field)
        heard = self.heard.get(field)
        return (commanded is not None and stamp + self.skew < commanded) or (heard is not None and stamp < heard)

    def _delivered(self, event: Event, value: Any, saved: Any, stamp: Optional[float]) -> None:
        self._dirty = True
        if self.watching:
            index = self.INDEX
            if self.asking:
                self._count(saved)
            if self.commanded:
                for attribute in list(self.commanded):  # an answer came: no longer waiting for one
                    if getattr(self, attribute) is not saved[index[attribute]]:
                        del self.commanded[attribute]
            if stamp is not None:
                for place, attribute in self.ANSWERED:
                    if getattr(self, attribute) is not saved[place]:
                        self.heard[attribute] = max(stamp, self.heard.get(attribute, stamp))
            answers = self.ANSWERS.get(event.name)
            if (
                answers is not None
                and self.answered is not None
                and not self.may_repeat(event.name)  # a copy proves nothing
            ):
                for field, locations in answers:
                    before, now = saved[index[field]], getattr(self, field)
                    if type(before) is str and type(now) is str and before in locations and now != before:
                        self.answered(field, locations)
        if self.may_repeat(event.name):
            self._doubt(event.name, saved)
        communication = event.communication
        if communication is not None and (self.waiting or self._unreadable_since):
            self._readable(communication)
        if self.observer is not None:
            self._record(event.name, False, value)

    def may_repeat(self, name: str) -> bool:
        """Whether the event ``name`` may be a second copy of an earlier answer (confirm_answers)."""
        return self.confirm_answers and name in self.REPEATABLE

    def doubt(self, component: str) -> None:
        """``component`` was left unconfirmed by an answer or an event with several outcomes: the
        node asks its driver at once."""
        if component not in self.doubted:
            self.doubted.append(component)

    def _doubt(self, name: str, saved: Any) -> None:
        """The answer ``name`` moved fields from their values in ``saved`` and may have been a second
        copy of an earlier one: the belief's (:class:`~.belief.Belief`)."""
        raise NotImplementedError
