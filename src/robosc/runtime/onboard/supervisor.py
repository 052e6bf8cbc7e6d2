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
* **Resume.** :meth:`Supervisor.restore` takes back a persisted state (see
  ``persist.py``), each value checked against its field's domain.
"""

from __future__ import absolute_import, annotations, print_function

import copy
import json
import math
import random
import sys
import threading
import time
from typing import Any, Callable, ClassVar, Dict, FrozenSet, Optional, Tuple

from .values import Data, finite, plain

isfinite = math.isfinite  # for the generated data checks

REFUSED = object()  # data that must not be sent (not finite, or not computable)
KEEP = object()  # an assignment whose value could not be computed keeps the old value
NO_DATA = "none"  # the location of a data plant where no provide statement holds
WARNING_INTERVAL = 5.0  # seconds between two reports of the same kind of warning
DATA_TIMEOUT = 1.0  # seconds of unreadable data from a communication before the events reading it are held


class Unreadable(ValueError):
    """Received data that cannot be read as the model declares it."""


def num(value: Any) -> Any:
    """A number read from received data (a double or an integer of the model): not a
    boolean, string or NaN. Infinities pass: REP 117 gives them a meaning in a range
    (no return, too close), and they compare as such."""
    if type(value) is float:
        if value != value:
            raise Unreadable("NaN")
        return value
    if isinstance(value, (bool, str, bytes)) or value is None:
        raise Unreadable("%r is not a number" % (value,))
    try:
        number = float(value)
    except Exception:
        raise Unreadable("%r is not a number" % (value,)) from None
    if number != number:
        raise Unreadable("NaN")
    return value


def whole(value: Any) -> Any:
    """An integer read from received data."""
    if isinstance(value, bool) or not isinstance(value, int):
        try:
            import operator

            return operator.index(value)  # numpy integers
        except Exception:
            raise Unreadable("%r is not an integer" % (value,)) from None
    return value


def flag(value: Any) -> bool:
    """A boolean read from received data."""
    if isinstance(value, bool):
        return value
    if type(value).__name__ == "bool_":  # numpy
        return bool(value)
    raise Unreadable("%r is not a boolean" % (value,))


def text(value: Any) -> str:
    """A string read from received data."""
    if isinstance(value, str):
        return value
    raise Unreadable("%r is not a string" % (value,))


class Event(object):
    """One event of the network, as the runtime needs it."""

    __slots__ = ("communication", "controllable", "convert", "kind", "method", "name", "reads", "signature")

    def __init__(
        self,
        name: str,
        method: str,
        controllable: bool,
        kind: str,
        communication: Optional[str] = None,
        convert: Optional[Tuple[Callable[[Any], str], str, str]] = None,
        signature: Optional[Tuple[Any, ...]] = None,
        reads: Tuple[str, ...] = (),
    ) -> None:
        self.name = name
        self.method = method  # the generated method performing it
        self.controllable = controllable
        self.kind = kind  # message, trigger, response, error, feedback, cancel, reset, tau
        self.communication = communication  # the communication's name, or None
        self.convert = convert  # (rules function, enum name, default value) for enum data
        # alternatives of the data it sends: constants, ANY where the model computes a value
        self.signature = signature
        # controllable: the communications whose received data its condition or data reads
        self.reads = frozenset(reads)

    @property
    def is_request(self) -> bool:
        """Sent on the controller's behalf: what a supervision layer forwards or blocks."""
        return self.controllable and self.kind in ("message", "trigger")

    def __repr__(self) -> str:
        return "Event(%r)" % (self.name,)


class Communication(object):
    """A message, service or action, and where it is on ROS."""

    __slots__ = ("data", "interface", "kind", "name", "ros_name")

    def __init__(self, name: str, kind: str, ros_name: str, interface: Optional[str], data: str) -> None:
        self.name = name
        self.kind = kind  # outgoing, incoming, service, action
        self.ros_name = ros_name  # as the model gives it, e.g. "/scan"
        self.interface = interface  # "package/Type" of a linked interface, or None
        self.data = data  # messages: string, boolean, integer, double, none or object

    def __repr__(self) -> str:
        return "Communication(%r)" % (self.name,)


class Warnings(object):
    """Reports through ``sink``, each kind of warning at most once per ``interval`` seconds,
    with the number of repeats that were held back meanwhile."""

    def __init__(
        self,
        sink: Callable[[str], Any],
        interval: float = WARNING_INTERVAL,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.sink = sink
        self.interval = interval
        self.clock = clock
        self.last: Dict[str, Tuple[float, int]] = {}  # kind -> (time of the last report, repeats held back since)

    def __call__(self, message: str, kind: Optional[str] = None) -> bool:
        key = kind if kind is not None else message
        now = self.clock()
        seen = self.last.get(key)
        if seen is not None and now - seen[0] < self.interval:
            self.last[key] = (seen[0], seen[1] + 1)
            return False
        if len(self.last) > 1000:  # bounded: forget the oldest kinds
            for old in sorted(self.last, key=lambda k: self.last[k][0])[:500]:
                del self.last[old]
        repeats = seen[1] if seen is not None else 0
        self.last[key] = (now, 0)
        try:
            self.sink(message + (" (and %d more like it)" % repeats if repeats else ""))
        except Exception:  # a broken log must not stop the supervisor
            return False
        return True


def _stderr(message: str) -> None:
    print("[robosc] " + message, file=sys.stderr)


class _Computed(object):
    """Where an event's data is computed by the model: any finite value in range."""

    def __repr__(self) -> str:
        return "ANY"


ANY = _Computed()


def _fits(check: Any, value: Any) -> bool:
    """Whether ``value`` is inside a field's domain (``check`` as the generated code gives it:
    None for anything, a type name, ("integer", low, high), or the names an enum or a
    location takes)."""
    if check is None:
        return True
    if isinstance(check, tuple):  # the names of an enum or an automaton, or ("integer", low, high)
        if len(check) == 3 and check[0] == "integer" and type(check[1]) is int:
            return isinstance(value, int) and not isinstance(value, bool) and check[1] <= value <= check[2]
        return isinstance(value, str) and value in check
    if check == "boolean":
        return isinstance(value, bool)
    if check == "integer":
        return isinstance(value, int) and not isinstance(value, bool)
    if check == "double":
        return isinstance(value, (int, float)) and not isinstance(value, bool) and finite(float(value))
    if check == "string":
        return isinstance(value, str)
    return True


def _set_path(target: Any, steps: Tuple[Any, ...], value: Any) -> None:
    """``target.a.b[2] = value`` for steps ``("a", "b", 2)``."""
    for step in steps[:-1]:
        target = target[step] if isinstance(step, int) else getattr(target, step)
    last = steps[-1]
    if isinstance(last, int):
        target[last] = value
    else:
        setattr(target, last, value)


def moves(method: str, name: str, controllable: bool, *changes: Tuple[str, Optional[str], str]) -> Any:
    """The method performing an event whose effect is only location changes (a reset, a tau
    transition, a response that moves a component): ``changes`` are (field, from, to), tried
    in order; for each field the first whose ``from`` is its location (None: any) applies."""

    def perform(self: Supervisor, data: Any = None) -> Optional[str]:
        done = set()
        for field, source, target in changes:
            if field not in done and (source is None or getattr(self, field) == source):
                setattr(self, field, target)
                done.add(field)
        if not controllable:
            return None
        self._dirty = True
        if self.observer is not None:
            self._record(name, True, data)
        return name

    perform.__name__ = method
    perform.__doc__ = "%s: %s" % (name, ", ".join("%s %s -> %s" % change for change in changes))
    return perform


class Supervisor(object):
    """The state of a robot and its supervisor. Subclassed by the generated module.

    Not thread-safe by itself, so that a tick costs no lock where there is one
    thread (rclpy's single-threaded executor): where callbacks run on threads of
    their own (rospy), hold ``lock`` around every call, as the ROS 1 adapter does."""

    ROBOT: ClassVar[str] = ""
    PLAN: ClassVar[str] = ""  # a hash of the generated module: which supervisor a persisted state belongs to
    # (attribute, label, group, start value, domain); group: automata, communications, data, variables
    FIELDS: ClassVar[Tuple[Tuple[Any, ...], ...]] = ()
    EVENTS: ClassVar[Tuple[Event, ...]] = ()  # in the network's order
    COMMUNICATIONS: ClassVar[Tuple[Communication, ...]] = ()
    # indexes of the tables above, made by prepare()
    EVENT: ClassVar[Dict[str, Event]]
    CONTROLLABLE: ClassVar[Tuple[str, ...]]
    UNCONTROLLABLE: ClassVar[Tuple[str, ...]]
    EXPECTED_AT: ClassVar[Dict[str, int]]  # an uncontrollable event's place in _expected()
    BY_METHOD: ClassVar[Dict[str, Event]]
    REQUESTS: ClassVar[FrozenSet[str]]
    COMMUNICATION: ClassVar[Dict[str, Communication]]
    LABELS: ClassVar[Dict[str, str]]
    ATTRIBUTES: ClassVar[Tuple[str, ...]]
    WAITED: ClassVar[FrozenSet[str]]  # the communications whose data some controllable event reads

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super(Supervisor, cls).__init_subclass__(**kwargs)
        cls.prepare()

    @classmethod
    def prepare(cls) -> None:
        """Index the tables of a generated class (done once, when the class is made)."""
        cls.EVENT = dict((e.name, e) for e in cls.EVENTS)
        cls.CONTROLLABLE = tuple(e.name for e in cls.EVENTS if e.controllable)
        cls.UNCONTROLLABLE = tuple(e.name for e in cls.EVENTS if not e.controllable)
        cls.EXPECTED_AT = dict((name, index) for index, name in enumerate(cls.UNCONTROLLABLE))
        cls.BY_METHOD = dict((e.method, e) for e in cls.EVENTS)
        cls.REQUESTS = frozenset(e.method for e in cls.EVENTS if e.is_request)
        cls.COMMUNICATION = dict((c.name, c) for c in cls.COMMUNICATIONS)
        cls.LABELS = dict((f[0], f[1]) for f in cls.FIELDS)
        cls.ATTRIBUTES = tuple(f[0] for f in cls.FIELDS)
        cls.WAITED = frozenset(c for e in cls.EVENTS for c in e.reads)

    def __init__(
        self,
        seed: Optional[int] = None,
        warn: Optional[Callable[[str], Any]] = None,
        observer: Optional[Callable[[str, bool, Any], Any]] = None,
        wait_for_data: bool = True,
        data_timeout: float = DATA_TIMEOUT,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.lock = threading.RLock()
        self._random = random.Random(seed).random
        self.warn = warn if isinstance(warn, Warnings) else Warnings(warn or _stderr)
        self.observer = observer  # observer(event, controllable, data), called after every event
        self.wait_for_data = wait_for_data
        self.data_timeout = data_timeout
        self.clock = clock
        self.unreadable: Dict[str, int] = {}  # communication -> how many of its messages could not be read
        self.reset()

    def reset(self) -> None:
        """Back to the initial state, waiting for data again (unless that is waived)."""
        for attribute, _label, _group, start, _domain in self.FIELDS:
            setattr(self, attribute, copy.deepcopy(start))
        self._dirty = True  # the state changed since the allowed events were last computed
        self._enabled: Tuple[Callable[..., Optional[str]], ...] = ()
        self._sent: Dict[str, Any] = {}  # data computed since then, per event
        # communications that have not delivered readable data yet: while any, nothing is performed
        self.waiting = set(self.WAITED) if self.wait_for_data else set()
        self._unreadable_since: Dict[str, float] = {}  # communication -> its first unreadable data since readable
        self.stale: FrozenSet[str] = frozenset()  # communications unreadable for longer than data_timeout

    # ---- holding ---------------------------------------------------------------------------
    @property
    def held(self) -> bool:
        """Whether every controllable event is held (the start has not seen all its data yet)."""
        return bool(self.waiting)

    def holds(self, name: str) -> Optional[str]:
        """Why the controllable event ``name`` is held now, or None."""
        if self.waiting:
            return "held: waiting for the first readable data on %s" % ", ".join(sorted(self.waiting))
        reads = self.EVENT[name].reads & self.stale if name in self.EVENT else frozenset()
        if reads:
            return "held: no readable data on %s for %.1f s" % (", ".join(sorted(reads)), self.data_timeout)
        return None

    def _watch(self) -> None:
        """Communications unreadable for longer than ``data_timeout`` hold the events reading them."""
        now = self.clock()
        stale = frozenset(c for c, since in self._unreadable_since.items() if now - since >= self.data_timeout)
        if stale != self.stale:
            for c in stale - self.stale:
                self.warn("%s: no readable data for %.1f s; holding what reads it" % (c, self.data_timeout))
            self.stale = stale
            self._dirty = True

    def _filter(
        self, enabled: Tuple[Callable[..., Optional[str]], ...]
    ) -> Tuple[Callable[..., Optional[str]], ...]:
        stale = self.stale
        by_method = self.BY_METHOD
        return tuple(p for p in enabled if not (by_method[p.__name__].reads & stale))

    def health(self) -> Dict[str, Any]:
        """What keeps the supervisor from acting, as JSON-ready data: the communications it waits
        for, those held for unreadable data, and the unreadable messages counted per communication."""
        return {
            "held": bool(self.waiting),
            "waiting_for": sorted(self.waiting),
            "stale": sorted(self.stale),
            "unreadable": dict(self.unreadable),
        }

    # ---- the cycle ---------------------------------------------------------------------
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
        n = len(enabled)
        if n == 1:
            return enabled[0]()
        if n == 0:
            return None
        return enabled[int(self._random() * n)]()

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
            name = internal[0]()
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
                return perform(data) is not None
        return False

    def template(self, name: str) -> Any:
        """The data the controllable event ``name`` sends now, as a supervision layer compares a
        controller's message with it: the current provide statement's constants, ANY where the
        model computes a value; None when it sends no data (every field at its default)."""
        signature = self.EVENT[name].signature
        if signature is None:
            return None
        self._provide()
        field, templates = signature
        return templates.get(getattr(self, field))

    def deliver(self, name: str, value: Any = None, raw: bool = True) -> bool:
        """Deliver the uncontrollable event ``name`` with its data; False (and nothing changes)
        when the plant cannot take it now or its data cannot be read. With ``raw`` False, the
        data of an enum-typed event is already the enum value's name."""
        event = self.EVENT.get(name)
        if event is None or event.controllable:
            raise KeyError("no uncontrollable event %r" % (name,))
        if raw and event.convert is not None:
            try:
                value = self.convert(event.convert, value)
            except Unreadable as error:
                return self._unreadable(event, error)
        if not self._expected()[self.EXPECTED_AT[name]]:
            self.warn("ignored %s: not expected now" % (name,), "unexpected " + name)
            return False
        saved = [getattr(self, attribute) for attribute in self.ATTRIBUTES]
        try:
            getattr(self, event.method)(value)
        except Unreadable as error:  # the effect could not read the data: undone, as if it never came
            for attribute, before in zip(self.ATTRIBUTES, saved):
                setattr(self, attribute, before)
            return self._unreadable(event, error)
        self._dirty = True
        communication = event.communication
        if communication is not None and (self.waiting or self._unreadable_since):
            self._readable(communication)
        if self.observer is not None:
            self._record(name, False, value)
        return True

    def _readable(self, communication: str) -> None:
        """``communication`` delivered data that could be read."""
        if communication in self.waiting:
            self.waiting.discard(communication)
        if self._unreadable_since.pop(communication, None) is not None and communication in self.stale:
            self.stale = self.stale - {communication}
            self.warn("%s: readable data again" % (communication,))

    def _unreadable(self, event: Event, error: BaseException) -> bool:
        """Data of ``event`` that cannot be read: not delivered, counted and reported."""
        communication = event.communication or event.name
        self.unreadable[communication] = self.unreadable.get(communication, 0) + 1
        self._unreadable_since.setdefault(communication, self.clock())
        self.warn(
            "%s: unreadable data (%s: %s); not delivered, the state is kept"
            % (event.name, type(error).__name__, error),
            "unreadable " + communication,
        )
        return False

    def expected(self) -> list[str]:
        """The uncontrollable events the plant can take now (a response only while waiting, ...)."""
        return [name for name, possible in zip(self.UNCONTROLLABLE, self._expected()) if possible]

    def convert(self, conversion: Tuple[Callable[[Any], str], str, str], value: Any) -> str:
        """An enum value from raw data by the enum's rules; Unreadable on data the rules cannot
        read (a missing field, a short array, a wrong type, NaN)."""
        rules, enum, _default = conversion
        try:
            return rules(value)
        except Unreadable as error:
            raise Unreadable("%s: %s" % (enum, error)) from None
        except Exception as error:
            raise Unreadable("%s: %s: %s" % (enum, type(error).__name__, error)) from None

    # ---- persisted state -----------------------------------------------------------------
    def persistent(self) -> Dict[str, Any]:
        """The whole state by attribute, as JSON-ready data: what :meth:`restore` takes back."""
        return dict((attribute, plain(getattr(self, attribute))) for attribute in self.ATTRIBUTES)

    def restore(self, fields: Dict[str, Any]) -> None:
        """Take back a state made by :meth:`persistent` (of this very supervisor: the caller
        checks ``PLAN``). Every value is checked against its field's domain first; ValueError
        (and nothing changes) when one is missing or outside it."""
        if not isinstance(fields, dict):
            raise ValueError("the state is not an object")
        values = []
        for attribute, label, _group, _start, domain in self.FIELDS:
            if attribute not in fields:
                raise ValueError("no value for %s" % (label,))
            value = fields[attribute]
            if not _fits(domain, value):
                raise ValueError("%s: %r is outside its domain" % (label, value))
            values.append(Data.wrap(value) if isinstance(value, (dict, list)) else value)
        for attribute, value in zip(self.ATTRIBUTES, values):
            setattr(self, attribute, value)
        self._dirty = True
        self._sent = {}

    def calls_in_flight(self) -> list[str]:
        """The error events of services and actions that are waiting for an answer now."""
        expected = set(self.expected())
        return [e.name for e in self.EVENTS if e.kind == "error" and e.name in expected]

    # ---- output: override to put commands on the middleware ---------------------------
    def send(self, name: str, data: Any) -> bool:
        """The controllable event ``name`` is being performed with ``data`` (None: empty).
        Return False to refuse it (it is then not performed). The default sends nothing."""
        return True

    # ---- state -----------------------------------------------------------------------------
    def snapshot(self) -> Dict[str, Dict[str, Any]]:
        """The whole state as JSON-ready data: {group: {label: value}}."""
        out: Dict[str, Dict[str, Any]] = {"automata": {}, "communications": {}, "data": {}, "variables": {}}
        for attribute, label, group, _start, _domain in self.FIELDS:
            value = getattr(self, attribute)
            out[group][label] = value if group != "variables" else plain(value)
        return out

    def to_json(self) -> str:
        return json.dumps(self.snapshot(), sort_keys=True)

    # ---- used by the generated methods -----------------------------------------------------
    def _record(self, event: str, controllable: bool, data: Any) -> None:
        observer = self.observer
        if observer is not None:
            try:
                observer(event, controllable, data)
            except Exception as error:
                self.warn("observer failed on %s: %s: %s" % (event, type(error).__name__, error), "observer")

    def _choose(self, field: str, location: str) -> None:
        """A data plant moves to ``location`` (step 1 of the cycle)."""
        setattr(self, field, location)
        self._dirty = True
        if self.observer is not None:
            label = self.LABELS[field]
            self._record(label + (".provide_none" if location == NO_DATA else "." + location), True, None)

    def _refuse(self, communication: str, error: Optional[BaseException]) -> Any:
        """Computed data that must not be sent: it could not be computed (``error``), or a
        number in it is not finite. Reported; the event is then not performed."""
        if error is None:
            self.warn("%s: a number in the data is not finite; not sent" % (communication,), "finite " + communication)
        else:
            why = "%s: %s" % (type(error).__name__, error)
            self.warn("%s: cannot compute the data (%s); not sent" % (communication, why), "data " + communication)
        return REFUSED

    def _assign(self, *assignments: Tuple[str, Tuple[Any, ...], str, Callable[[], Any], Any]) -> None:
        """Assignments of one transition: each (field, steps, label, compute, check); every
        value is computed first, then stored. A value that cannot be computed, or is outside
        the variable's type, leaves the variable as it was (with a warning)."""
        values = []
        for _field, _steps, label, compute, _check in assignments:
            try:
                value = compute()
            except Exception as error:
                self.warn(
                    "%s: cannot compute the new value (%s: %s); kept" % (label, type(error).__name__, error),
                    "compute " + label,
                )
                value = KEEP
            values.append(value)
        for (field, steps, label, _compute, check), value in zip(assignments, values):
            if value is KEEP:
                continue
            if steps:
                try:
                    _set_path(getattr(self, field), steps, value)
                except Exception as error:
                    self.warn(
                        "%s: cannot store (%s: %s); kept" % (label, type(error).__name__, error), "store " + label
                    )
            elif _fits(check, value):
                setattr(self, field, value)
            else:
                self.warn("%s: %r is outside its type; kept" % (label, plain(value)), "outside " + label)

    def _receive(self, *assignments: Tuple[str, Tuple[Any, ...], str, Callable[[], Any], Any]) -> None:
        """Assignments of an uncontrollable event, which read received data: every value is
        computed and checked first, then stored. Unreadable when one cannot be computed or is
        outside its variable's type (the event is then not delivered)."""
        values = []
        for _field, _steps, label, compute, check in assignments:
            try:
                value = compute()
            except Unreadable as error:
                raise Unreadable("%s: %s" % (label, error)) from None
            except Exception as error:
                raise Unreadable("%s: %s: %s" % (label, type(error).__name__, error)) from None
            if not _fits(check, value):
                raise Unreadable("%s: %r is outside its type" % (label, plain(value)))
            values.append(value)
        for (field, steps, label, _compute, _check), value in zip(assignments, values):
            if steps:
                try:
                    _set_path(getattr(self, field), steps, value)
                except Exception as error:
                    raise Unreadable("%s: cannot store (%s: %s)" % (label, type(error).__name__, error)) from None
            else:
                setattr(self, field, value)

    def _unchanged(self, value: Any) -> None:
        """An uncontrollable event that changes nothing (a message no transition reads)."""

    # ---- generated per robot ---------------------------------------------------------------
    def _provide(self) -> None:
        """Step 1: each data plant moves to the data its conditions choose."""

    def _allowed(self) -> Tuple[Callable[..., Optional[str]], ...]:
        """Step 2: the controllable events the plant and the supervisor allow now."""
        return ()

    def _expected(self) -> Tuple[bool, ...]:
        """For each uncontrollable event (in ``UNCONTROLLABLE`` order): can the plant take it now?"""
        return ()


Supervisor.prepare()
