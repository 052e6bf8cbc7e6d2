# -*- coding: utf-8 -*-
"""The supervisor cycle (SEMANTICS.md section 6), the same for every robot.

A generated module subclasses :class:`Supervisor` with what is specific to its
robot: the state (``FIELDS``), the events (``EVENTS``), the communications
(``COMMUNICATIONS``), and the methods that hold the model's conditions and
effects: ``_provide`` (step 1: which data each communication sends),
``_allowed`` (step 2: the controllable events the plant and the supervisor allow,
as bound methods), ``_expected`` (which uncontrollable events the plant can take),
one method per controllable event (``e<N>_<name>``) and one per uncontrollable
event (``u<N>_<name>``). Generated names always carry a number after a letter
prefix, so they can never meet a name of this class (a test checks it).

    supervisor = Robot(seed=1)
    supervisor.deliver("scan", message)   # an uncontrollable event from the middleware
    supervisor.tick()                     # data events, then one allowed controllable event

Override :meth:`Supervisor.send` to put commands on the middleware.

Fail closed where the proof ends (the guarantee is about the state the supervisor
believes in, so that belief is kept honest):

* **Safe start.** Until every communication whose data a controllable event's condition
  or data reads (``Event.reads``: scans, corrections; not data-less events such as an
  emergency stop) has delivered readable data once, no controllable event is performed
  (``wait_for_data=False`` waives it).
* **Unreadable data is not a value.** Received data that a conversion or an assignment
  cannot read (a missing field or element, a wrong type, NaN, a computation that is not
  finite or leaves the variable's type) does not deliver its event: nothing changes, it
  is counted and reported. When a communication has delivered nothing readable for
  ``data_timeout`` seconds since its first unreadable message, every controllable event
  that reads it is held until readable data comes.
* **Unconfirmed is unknown.** A supervisor made with ``confirmed=False`` (what a node does
  at every start: nothing is taken from a file) does not know where the components are:
  their locations and variables are unconfirmed until the robots tell (an event whose
  effect is the same wherever the component is, a report :meth:`Supervisor.confirm`
  takes, fresh data). A controllable event is performed only where it is allowed in every
  state the robots may be in, and only when it sends the same data in each (see
  ``belief.py``); :meth:`Supervisor.unconfirm` makes a part unknown again (a command whose
  delivery is uncertain, an answer that did not come).
* **An answer the model cannot take now is not an event.** An uncontrollable event that a
  component answers in some locations (``ANSWERS``), arriving where none of them is, is
  ignored, counted and reported (the model's responsiveness self-loop would take it and
  change nothing); so is one stamped before the command it would answer (a late duplicate).
"""

from __future__ import absolute_import, annotations, print_function

import copy
import json
import random
import threading
import time
from typing import Any, Callable, Dict, Optional, Tuple

from .belief import Belief
from .effects import Effects
from .health import DATA_TIMEOUT
from .reading import Unreadable, flag, isfinite, num, text, unreadable_data, whole
from .tables import ANY, REFUSED, Communication, Event, Warnings, moves, stderr, tally
from .tasks import Dispatcher
from .unknown import TooMany, Unknown, distinct
from .values import finite, plain

# what a generated module reads from here (``rt.num``, ``rt.Supervisor``, ...)
__all__ = [
    "ANY",
    "DATA_TIMEOUT",
    "REFUSED",
    "Communication",
    "Event",
    "Supervisor",
    "Unreadable",
    "Warnings",
    "finite",
    "flag",
    "isfinite",
    "moves",
    "num",
    "tally",
    "text",
    "whole",
]


class Supervisor(Belief, Effects):
    """The state of a robot and its supervisor. Subclassed by the generated module.

    Not thread-safe by itself, so that a tick costs no lock where there is one
    thread (rclpy's single-threaded executor): where callbacks run on threads of
    their own (rospy), hold ``lock`` around every call, as the ROS 1 adapter does."""

    def __init__(
        self,
        seed: Optional[int] = None,
        warn: Optional[Callable[[str], Any]] = None,
        observer: Optional[Callable[[str, bool, Any], Any]] = None,
        wait_for_data: bool = True,
        data_timeout: float = DATA_TIMEOUT,
        clock: Callable[[], float] = time.monotonic,
        confirmed: bool = True,
    ) -> None:
        self.lock = threading.RLock()
        self._random = random.Random(seed).random
        self.warn = warn if isinstance(warn, Warnings) else Warnings(warn or stderr)
        self.observer = observer  # observer(event, controllable, data), called after every event
        self._init_health(wait_for_data, data_timeout, clock)
        self.health_changes = 0  # counts the changes of what health() shows
        self._init_answers()
        self.tasks: Optional[Dispatcher] = None  # a fleet's tasks and its choice with a purpose (tasks.py)
        self.outcome = None  # (belief.py: who says which outcome an event with several had)
        self.reset(confirmed)

    def reset(self, confirmed: bool = True) -> None:
        """Back to the initial state, waiting for data again (unless that is waived); with
        ``confirmed`` False, where every component is (its location and variables) is
        unconfirmed: the robots have not said yet."""
        for attribute, _label, _group, start, _domain in self.FIELDS:
            setattr(self, attribute, copy.deepcopy(start))
        self._reset_belief(confirmed)
        self._dirty = True  # the state changed since the allowed events were last computed
        self._enabled: Tuple[Callable[..., Optional[str]], ...] = ()
        self._sent = {}  # data computed since then, per event
        self._reset_health()
        self.health_changes += 1

    def holds(self, name: str) -> Optional[str]:
        """Why the controllable event ``name`` is held now, or None."""
        if self.waiting:
            return "held: waiting for the first readable data on %s" % ", ".join(sorted(self.waiting))
        reads = self.EVENT[name].reads & self.stale if name in self.EVENT else frozenset()
        if reads:
            return "held: no readable data on %s for %.1f s" % (", ".join(sorted(reads)), self.data_timeout)
        if self.unconfirmed:
            return "held: it may not be allowed where %s may be (unconfirmed)" % ", ".join(self.unsure())
        return None

    def health(self) -> Dict[str, Any]:
        """What keeps the supervisor from acting, as JSON-ready data: the communications it waits
        for, those held for unreadable data, the unreadable messages counted per communication,
        the components whose state is unconfirmed (with the values they may have, and why) and
        the events that came and were not taken (ignored), counted."""
        return {
            "held": bool(self.waiting),
            "waiting_for": sorted(self.waiting),
            "stale": sorted(self.stale),
            "unreadable": dict(self.unreadable),
            "unconfirmed": self.unsure(),
            "ignored": dict(self.ignored),
        }

    def tick(self) -> Optional[str]:
        """One cycle: perform the enabled data events, then one controllable event the
        supervisor allows. Taking the events in a shuffled order and performing the first
        allowed one picks each allowed event with equal chance; so does this, drawing once.
        The allowed events are computed again only after the state changed.
        Nothing is performed while the start waits for data.
        Returns the name of the event performed, or None."""
        if self.waiting:
            return None
        if self._unreadable_since:
            self._watch()
        if self._dirty:
            self._enabled = self._current()
            self._sent = {}
            self._dirty = False
        enabled = self._enabled
        tasks = self.tasks
        if tasks is not None:
            tasks.observe()
        n = len(enabled)
        if n == 0:
            return None
        if tasks is not None and tasks.policy != "random":
            chosen = tasks.choose(enabled)
            if chosen is None:
                return None
            perform = chosen
        else:
            perform = enabled[0] if n == 1 else enabled[int(self._random() * n)]
        if self.watching and perform.__name__ not in self.STILL_METHODS:
            return self._watched(perform, None)
        return perform()

    def _permitted(self) -> Tuple[Callable[..., Optional[str]], ...]:
        """The controllable events allowed now, after data events, with what is held taken out."""
        if self.waiting:
            return ()
        if self._unreadable_since:
            self._watch()
        self._dirty = True
        return self._current()

    def _current(self) -> Tuple[Callable[..., Optional[str]], ...]:
        """The controllable events allowed in this state, with the provided data computed and
        the events reading unreadable data taken out (the caller checked ``waiting``)."""
        if self.unconfirmed:
            return self._current_unsure()
        self._provide()
        allowed = self._allowed()
        return self._filter(allowed) if self.stale else allowed

    def settle(self, limit: int = 100) -> list[str]:
        """Supervision layer: after a callback, perform the enabled internal events (data
        choices, tau transitions, service / action resets and cancels) until none is left.
        Returns their names."""
        done: list[str] = []
        requests = self.REQUESTS
        for _ in range(limit):
            internal = [perform for perform in self._permitted() if perform.__name__ not in requests]
            if not internal:
                break
            name = self._watched(internal[0], None) if self.watching else internal[0]()
            if name is not None:
                done.append(name)
        self._dirty = True
        return done

    def allowed(self) -> list[str]:
        """The names of the controllable events the supervisor allows now (after data events),
        none of those held."""
        return [self.BY_METHOD[perform.__name__].name for perform in self._permitted()]

    def perform(self, name: str, data: Any = None) -> bool:
        """Perform the controllable event ``name`` if the supervisor allows it (True), else
        nothing (False). ``data`` replaces the provided data (a supervision layer forwards
        the controller's own message)."""
        event = self.EVENT.get(name)
        if event is None or not event.controllable:
            return False
        for perform in self._permitted():
            if perform.__name__ == event.method:
                done = self._watched(perform, data) if self.watching else perform(data)
                return done is not None
        return False

    def template(self, name: str) -> Any:
        """The data the controllable event ``name`` sends now, as a supervision layer compares a
        controller's message with it: the current provide statement's constants, ANY where the
        model computes a value; None when it sends no data (every field at its default)."""
        signature = self.EVENT[name].signature
        if signature is None:
            return None
        field, templates = signature
        if self.unconfirmed:
            try:
                outcomes = self._over(lambda: self._provide() or getattr(self, field))  # type: ignore[func-returns-value]
            except TooMany:
                return None
            locations = distinct([location for _, location in outcomes])
            return templates.get(locations[0]) if len(locations) == 1 else None
        self._provide()
        return templates.get(getattr(self, field))

    def deliver(self, name: str, value: Any = None, raw: bool = True, stamp: Optional[float] = None) -> bool:
        """Deliver the uncontrollable event ``name`` with its data; False (and nothing changes)
        when the plant cannot take it now, no component answers it where it is, it is stamped
        (``stamp``, seconds on the robot's wall clock) before the command it would answer, or
        its data cannot be read. With ``raw`` False, the data of an enum-typed event is already
        the enum value's name."""
        event = self.EVENT.get(name)
        if event is None or event.controllable:
            raise KeyError("no uncontrollable event %r" % (name,))
        if raw and event.convert is not None:
            try:
                value = event.convert[0](value)  # the enum's rules, as convert() applies them
            except Exception as error:
                return self._unreadable(event, unreadable_data(event.convert[1], error))
        if self.unconfirmed:
            return self._deliver_unsure(event, value, stamp)
        if name not in self.FREE:
            why = self._not_taken(name, stamp)
            if why is not None:
                return self.ignore(name, why)
        saved = self._apply(event, value)
        if saved is None:
            return False
        self._delivered(event, value, saved, stamp)
        if self.tasks is not None:
            self.tasks.observe()  # a stop passed between two ticks
        return True

    def _apply(self, event: Event, value: Any) -> Optional[Tuple[Any, ...]]:
        """Perform the uncontrollable ``event``'s effect with ``value``: every field's value before
        it, or None when the effect could not read the data (undone, as if it never came; reported)."""
        saved: Tuple[Any, ...] = type(self).GETTER(self)
        try:
            getattr(self, event.method)(value)
        except Unreadable as error:
            for attribute, before in zip(self.ATTRIBUTES, saved):
                setattr(self, attribute, before)
            self._unreadable(event, error)
            return None
        return saved

    def deliver_message(self, names: Tuple[str, ...], message: Any, stamp: Optional[float] = None) -> None:
        """Deliver the uncontrollable events ``names`` of one message, each with the message as its
        raw data, as :meth:`deliver` delivers them one by one. In the common case (each always
        taken, nothing unconfirmed, awaited, asked for, waited for, unreadable or recorded) without
        the bookkeeping those need: the cycle right after a message is what a robot waits for."""
        if (
            self.unconfirmed
            or self.commanded
            or self.asking
            or self.waiting
            or self._unreadable_since
            or self.observer is not None
            or not self.FREE.issuperset(names)
        ):
            for name in names:
                self.deliver(name, message, True, stamp)
            return
        events = self.EVENT
        answered = self.ANSWERED if stamp is not None and self.watching else ()
        when = stamp if stamp is not None else 0.0  # (read only with answered)
        for place in range(len(names)):
            event = events[names[place]]
            value = message
            if event.convert is not None:
                try:
                    value = event.convert[0](message)  # the enum's rules, as convert() applies them
                except Exception as error:
                    self._unreadable(event, unreadable_data(event.convert[1], error))
                    break
            saved = self._apply(event, value)
            if saved is None:
                break
            self._dirty = True
            for index, attribute in answered:
                if getattr(self, attribute) is not saved[index]:
                    self.heard[attribute] = max(when, self.heard.get(attribute, when))
        else:
            if self.tasks is not None:
                self.tasks.observe()
            return
        for name in names[place + 1 :]:  # after unreadable data: one by one, as deliver() takes them
            self.deliver(name, message, True, stamp)

    def expected(self) -> list[str]:
        """The uncontrollable events the plant can take now (a response only while waiting, ...)."""
        return [name for name, possible in zip(self.UNCONTROLLABLE, self._expected()) if possible]

    def convert(self, conversion: Tuple[Callable[[Any], str], str, str], value: Any) -> str:
        """An enum value from raw data by the enum's rules; Unreadable on data the rules cannot
        read (a missing field, a short array, a wrong type, NaN)."""
        rules, enum, _default = conversion
        try:
            return rules(value)
        except Exception as error:
            raise unreadable_data(enum, error) from None

    def snapshot(self) -> Dict[str, Dict[str, Any]]:
        """The whole state as JSON-ready data: {group: {label: value}}."""
        out: Dict[str, Dict[str, Any]] = {"automata": {}, "communications": {}, "data": {}, "variables": {}}
        for attribute, label, group, _start, _domain in self.FIELDS:
            value = getattr(self, attribute)
            if isinstance(value, Unknown):
                out[group][label] = None  # unconfirmed: see health()["unconfirmed"]
            else:
                out[group][label] = value if group != "variables" else plain(value)
        return out

    def to_json(self) -> str:
        return json.dumps(self.snapshot(), sort_keys=True)


Supervisor.prepare()
