# -*- coding: utf-8 -*-
"""Events with several outcomes, a part of the supervisor (mixed into :class:`~.belief.Belief`):
the model's transitions from one place on one event to different places. Which one the robot
had is told by what it says next (a message, an answer) or its driver's report; until then the
field is unconfirmed among them. A simulation that stands for the robot says which (``outcome``).

Standard library only, Python 3.8 or newer (ROS Noetic).
"""

from __future__ import absolute_import, annotations

from typing import Any, Callable, Dict, Optional, Tuple

from .answers import Answers
from .reading import Unreadable
from .unknown import TooMany, distinct


class Outcomes(Answers):
    """``_fork`` (called by the generated effects), ``outcomes`` and the variants of a trial."""

    # a simulation standing for the robots says which outcome an event had: outcome(field label,
    # outcomes) -> the one (None, on a robot: the field is unconfirmed among them); set in __init__
    outcome: Optional[Callable[[str, Tuple[Any, ...]], Any]]
    # the belief's (belief.py): trying completions, and what an event tried forked
    _trying: bool
    _forked: list[Tuple[str, Tuple[Any, ...]]]
    unconfirm: Callable[[Dict[str, Optional[Tuple[Any, ...]]], str], None]
    _over: Callable[[Callable[[], Any]], list[Tuple[Dict[str, Any], Any]]]

    def _fork(self, field: str, outcomes: Tuple[Any, ...]) -> None:
        """An event with several outcomes puts ``field`` in one of ``outcomes`` (the model's
        transitions from one place on one event to different places): which one, the robot tells
        next (a message, an answer, or its driver's report). Until then the field is unconfirmed
        among them, and the component is ``doubted`` (a node asks its driver at once). While
        completions are tried (``_over``) the first is taken and all noted for the caller."""
        if self._trying:
            setattr(self, field, outcomes[0])
            self._forked.append((field, outcomes))
            return
        if self.outcome is not None:  # a simulation that stands for the robot says which
            setattr(self, field, self.outcome(self.LABELS[field], outcomes))
            return
        setattr(self, field, outcomes[0])
        component = self.COMPONENT_OF.get(field, self.LABELS[field])
        self.unconfirm({field: outcomes}, "%s may be %s (an event with several outcomes)" % (
            self.LABELS[field], " or ".join(map(str, distinct(list(outcomes))))))
        self.doubt(component)

    def outcomes(self, name: str, value: Any = None) -> Dict[str, Tuple[Any, ...]]:
        """Where the event ``name`` (with ``value``, its data as the event's method takes it) would
        have several outcomes now: {field label: its outcomes}. Nothing is changed or sent."""
        event = self.EVENT[name]
        send = self.__dict__.get("send")

        def run() -> list[Tuple[str, Tuple[Any, ...]]]:
            self._provide()
            self.send = lambda name, data: True  # type: ignore[method-assign]
            try:
                getattr(self, event.method)(value)
            finally:
                if send is None:
                    del self.send
                else:
                    self.send = send  # type: ignore[method-assign]
            return list(self._forked)

        try:
            tried = self._over(run)
        except (TooMany, Unreadable):
            return {}
        out: Dict[str, Tuple[Any, ...]] = {}
        for _, forks in tried:
            for field, outcomes in forks:
                out[self.LABELS[field]] = distinct(list(out.get(self.LABELS[field], ())) + list(outcomes))
        return out

    def _variants(self) -> list[list[Any]]:
        """Every field's value now, once per combination of the outcomes of the event just tried."""
        states = [[getattr(self, attribute) for attribute in self.ATTRIBUTES]]
        for field, outcomes in self._forked:
            index = self.INDEX[field]
            states = [[*state[:index], value, *state[index + 1 :]] for state in states for value in outcomes]
        return states
