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
import math
import operator
import random
import sys
import threading
import time
from collections import Counter
from typing import Any, Callable, ClassVar, Dict, FrozenSet, Optional, Tuple

from .belief import TooMany, Unknown, completions, distinct, enumerable
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


def _unreadable_data(enum: str, error: Exception) -> Unreadable:
    """Why the rules of ``enum`` could not read the data: ``error``, said as Unreadable."""
    if isinstance(error, Unreadable):
        return Unreadable("%s: %s" % (enum, error))
    return Unreadable("%s: %s: %s" % (enum, type(error).__name__, error))


def _moved(new: Any, old: Any) -> bool:
    """Whether a field that is now ``new`` (another object than ``old``) changed: its value, or
    the values it may have (a new Unknown is made only when they change)."""
    return type(new) is not type(old) or type(new) is Unknown or new != old


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


def tally(*fields: str) -> Callable[[Any], Dict[Any, int]]:
    """The method counting the values of ``fields`` (one per robot of a fleet): value -> how
    many of them have it. A fleet's ``count(q in bot: q.depot)`` is then one lookup, whatever
    the number of robots; ``_allowed`` tallies once per evaluation, at C speed."""
    getter = operator.attrgetter(*fields)
    if len(fields) == 1:
        return lambda self: Counter((getter(self),))
    return lambda self: Counter(getter(self))


class Supervisor(object):
    """The state of a robot and its supervisor. Subclassed by the generated module.

    Not thread-safe by itself, so that a tick costs no lock where there is one
    thread (rclpy's single-threaded executor): where callbacks run on threads of
    their own (rospy), hold ``lock`` around every call, as the ROS 1 adapter does."""

    ROBOT: ClassVar[str] = ""
    PLAN: ClassVar[str] = ""  # a hash of the generated module: which supervisor this is
    # (attribute, label, group, start value, domain); group: automata, communications, data, variables
    FIELDS: ClassVar[Tuple[Tuple[Any, ...], ...]] = ()
    EVENTS: ClassVar[Tuple[Event, ...]] = ()  # in the network's order
    COMMUNICATIONS: ClassVar[Tuple[Communication, ...]] = ()
    # uncontrollable event -> ((component location field, the locations where the model answers it), ...):
    # only events some component answers in some locations but not in all
    ANSWERS: ClassVar[Dict[str, Tuple[Tuple[str, Tuple[str, ...]], ...]]] = {}
    ALWAYS: ClassVar[Tuple[str, ...]] = ()  # uncontrollable events the plant takes in every state
    STILL: ClassVar[Tuple[str, ...]] = ()  # controllable events whose effect changes no field
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
    COMPONENT_OF: ClassVar[Dict[str, str]]  # a component's field (location, variable) -> the component
    COMPONENTS: ClassVar[Dict[str, Tuple[str, ...]]]  # component -> its fields
    CANDIDATES: ClassVar[Dict[str, Optional[Tuple[Any, ...]]]]  # field -> the values to try (None: too many)
    INDEX: ClassVar[Dict[str, int]]  # field -> its place in ATTRIBUTES (and in values())
    TRACKED: ClassVar[Tuple[Tuple[int, str], ...]]  # (place, field) of the components' fields
    ANSWERED: ClassVar[Tuple[Tuple[int, str], ...]]  # (place, field) of the fields ANSWERS names
    GETTER: ClassVar[Callable[[Any], Any]]  # every field's value at once (C speed)
    FREE: ClassVar[FrozenSet[str]]  # ALWAYS but those ANSWERS names: always taken, without a look
    STILL_METHODS: ClassVar[FrozenSet[str]]  # the methods of STILL: performed without noting what changed

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
        cls.INDEX = dict((attribute, index) for index, attribute in enumerate(cls.ATTRIBUTES))
        getter = operator.attrgetter(*cls.ATTRIBUTES) if cls.ATTRIBUTES else (lambda _: ())
        cls.GETTER = getter if len(cls.ATTRIBUTES) != 1 else (lambda self: (getter(self),))
        answered = set(field for answers in cls.ANSWERS.values() for field, _ in answers)
        cls.ANSWERED = tuple((cls.INDEX[f], f) for f in cls.ATTRIBUTES if f in answered)
        cls.FREE = frozenset(cls.ALWAYS).difference(cls.ANSWERS)
        cls.STILL_METHODS = frozenset(e.method for e in cls.EVENTS if e.name in cls.STILL)
        cls.COMPONENT_OF = {}
        cls.COMPONENTS = {}
        cls.CANDIDATES = {}
        for attribute, label, group, _start, domain in cls.FIELDS:
            cls.CANDIDATES[attribute] = enumerable(domain)
            if group in ("automata", "variables"):
                component = label.split(".")[0]
                cls.COMPONENT_OF[attribute] = component
                cls.COMPONENTS[component] = (*cls.COMPONENTS.get(component, ()), attribute)
        cls.TRACKED = tuple((cls.INDEX[f], f) for f in cls.ATTRIBUTES if f in cls.COMPONENT_OF)

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
        self.warn = warn if isinstance(warn, Warnings) else Warnings(warn or _stderr)
        self.observer = observer  # observer(event, controllable, data), called after every event
        self.wait_for_data = wait_for_data
        self.data_timeout = data_timeout
        self.clock = clock
        self.unreadable: Dict[str, int] = {}  # communication -> how many of its messages could not be read
        self.ignored: Dict[str, int] = {}  # uncontrollable event -> how many times it came and was not taken
        self.last_ignored = ""  # why the last one was not taken
        self.health_changes = 0  # counts the changes of what health() shows
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
        self.reset(confirmed)

    def reset(self, confirmed: bool = True) -> None:
        """Back to the initial state, waiting for data again (unless that is waived); with
        ``confirmed`` False, where every component is (its location and variables) is
        unconfirmed: the robots have not said yet."""
        for attribute, _label, _group, start, _domain in self.FIELDS:
            setattr(self, attribute, copy.deepcopy(start))
        # unconfirmed field -> the values it may have (None: any); why, per component
        self.unconfirmed: Dict[str, Optional[Tuple[Any, ...]]] = {}
        self.why: Dict[str, str] = {}
        self.versions: Dict[str, int] = {}  # field -> how many times its candidates changed
        if not confirmed:
            self.unconfirm(
                dict((attribute, self.CANDIDATES[attribute]) for attribute in self.COMPONENT_OF),
                "not confirmed since the start",
            )
        self._dirty = True  # the state changed since the allowed events were last computed
        self._enabled: Tuple[Callable[..., Optional[str]], ...] = ()
        self._sent: Dict[str, Any] = {}  # data computed since then, per event
        # communications that have not delivered readable data yet: while any, nothing is performed
        self.waiting = set(self.WAITED) if self.wait_for_data else set()
        self.health_changes += 1
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
        if self.unconfirmed:
            return "held: it may not be allowed where %s may be (unconfirmed)" % ", ".join(self.unsure())
        return None

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

    # ---- what is known -------------------------------------------------------------------
    def unsure(self) -> Dict[str, Dict[str, Any]]:
        """The unconfirmed components: {component: {"why": ..., "may_be": {field label: [values]
        or "any"}}}."""
        out: Dict[str, Dict[str, Any]] = {}
        for attribute, values in self.unconfirmed.items():
            component = self.COMPONENT_OF.get(attribute, self.LABELS[attribute])
            entry = out.setdefault(component, {"why": self.why.get(component, "unconfirmed"), "may_be": {}})
            entry["may_be"][self.LABELS[attribute]] = "any" if values is None else [plain(v) for v in values]
        return out

    def unconfirm(self, fields: Dict[str, Optional[Tuple[Any, ...]]], why: str) -> None:
        """The ``fields`` (attribute -> the values each may have, None: any) are not known any
        more, for the reason ``why`` (said per component). A field with one value is known."""
        for attribute, values in fields.items():
            if values is not None:
                values = distinct(list(values))
            if values is not None and len(values) == 1:
                self.know(attribute, values[0])
                continue
            if attribute not in self.unconfirmed or self.unconfirmed[attribute] != values:
                self.versions[attribute] = self.versions.get(attribute, 0) + 1
            self.unconfirmed[attribute] = values
            self.health_changes += 1
            setattr(self, attribute, Unknown(attribute))
            component = self.COMPONENT_OF.get(attribute, self.LABELS[attribute])
            if self.why.get(component) != why:
                self.why[component] = why
                self.health_changes += 1
        self._dirty = True

    def know(self, attribute: str, value: Any) -> None:
        """The field ``attribute`` is confirmed to hold ``value``."""
        if attribute in self.unconfirmed:
            del self.unconfirmed[attribute]
            self.health_changes += 1
            self.versions[attribute] = self.versions.get(attribute, 0) + 1
            component = self.COMPONENT_OF.get(attribute, self.LABELS[attribute])
            if not any(self.COMPONENT_OF.get(a, self.LABELS[a]) == component for a in self.unconfirmed):
                self.why.pop(component, None)
        setattr(self, attribute, value)
        self._dirty = True

    def confirm(self, component: str, report: Any, since: Optional[float] = None) -> Optional[str]:
        """A report of where ``component`` is, from its driver: a location name, or an object
        with ``state`` (the location) and values of its variables by name. Taken (None) when
        every value is one the component may have now; else nothing changes, and why is
        returned. Variables it does not give stay as they are. ``since``: when (this wall clock)
        the driver was asked; an answer stamped later may not be in the report: it is taken."""
        fields = self.COMPONENTS.get(component)
        if fields is None:
            return "no component %s" % (component,)
        if isinstance(report, str) and report.lstrip().startswith("{"):
            try:
                report = json.loads(report)
            except ValueError as error:
                return "not a location or a JSON object (%s)" % (error,)
        if isinstance(report, str):
            report = {"state": report.strip()}
        if not isinstance(report, dict):
            return "not a location or a JSON object"
        values: Dict[str, Any] = {}
        by_label = dict((self.LABELS[a], a) for a in fields)
        for key, value in report.items():
            attribute = by_label.get(component if key == "state" else "%s.%s" % (component, key))
            if attribute is None:
                return "%s has no %s" % (component, "location" if key == "state" else "variable %s" % key)
            domain = next(f[4] for f in self.FIELDS if f[0] == attribute)
            if not _fits(domain, value):
                return "%s: %r is outside its domain" % (key, value)
            may = self.unconfirmed.get(attribute, ())
            if attribute in self.unconfirmed:
                if may is not None and not any(type(v) is type(value) and v == value for v in may):
                    return "%s: %r is not where it may be now (%s)" % (key, value, ", ".join(map(str, may)))
            elif not (type(getattr(self, attribute)) is type(value) and getattr(self, attribute) == value):
                return "%s: %r, but it is known to be %r" % (key, value, getattr(self, attribute))
            values[attribute] = value
        for attribute, value in values.items():
            self.know(attribute, Data.wrap(value) if isinstance(value, (dict, list)) else value)
            if self.watching and self.awaited(attribute):
                # as reported: waiting for its answer from when the driver was asked
                self.commanded[attribute] = since if since is not None else time.time()
            else:
                self.commanded.pop(attribute, None)
        return None

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

    def _answer_trial(self, method: str, attribute: str) -> Callable[[], Any]:
        def run() -> Any:
            getattr(self, method)(Unknown("value"))
            return getattr(self, attribute)

        return run

    def after_answers(self, attribute: str) -> Dict[str, Optional[Tuple[Any, ...]]]:
        """Where the component whose location is ``attribute`` may be when an answer it waits for
        may have come: where it is, or where any of them leads (every field of the component
        anywhere in its domain when an answer's effect reads its data)."""
        values = [getattr(self, attribute)]
        for name in self.awaited(attribute):
            try:
                outcomes = self._over(self._answer_trial(self.EVENT[name].method, attribute))
            except TooMany:
                component = self.COMPONENT_OF.get(attribute, attribute)
                return dict((a, self.CANDIDATES[a]) for a in self.COMPONENTS.get(component, (attribute,)))
            values.extend(value for _, value in outcomes)
        return {attribute: distinct(values)}

    def _over(self, run: Callable[[], Any]) -> list[Tuple[Dict[str, Any], Any]]:
        """``run()`` once per completion of the unconfirmed fields it reads (``belief.completions``),
        each from the state as it is now, which is put back afterwards; nothing is recorded
        meanwhile. Raises ``TooMany`` when the answer cannot be had by trying."""
        saved = [getattr(self, attribute) for attribute in self.ATTRIBUTES]
        mutable = [isinstance(value, (Data, list, dict)) for value in saved]
        dirty, sent, observer = self._dirty, self._sent, self.observer
        self.observer = None

        def assign(fixed: Dict[str, Any]) -> None:
            for attribute, value, copied in zip(self.ATTRIBUTES, saved, mutable):
                setattr(self, attribute, copy.deepcopy(value) if copied else value)
            for attribute, value in fixed.items():
                setattr(self, attribute, value)
            self._dirty = True
            self._sent = {}

        try:
            return completions(self.unconfirmed, assign, run)
        finally:
            for attribute, value in zip(self.ATTRIBUTES, saved):
                setattr(self, attribute, value)
            self._dirty, self._sent, self.observer = dirty, sent, observer

    def _settle_fields(self, states: list[list[Any]]) -> None:
        """After an event taken in several completions: each field known where it has one value
        in all of them, else unconfirmed with the values it has (its earlier candidates where a
        completion left it unknown)."""
        for index, attribute in enumerate(self.ATTRIBUTES):
            values = [state[index] for state in states]
            found: list[Any] = []
            anything = False
            for value in values:
                if isinstance(value, Unknown):
                    earlier = self.unconfirmed.get(attribute)
                    if earlier is None:
                        anything = True
                    else:
                        found.extend(earlier)
                else:
                    found.append(value)
            if anything:
                if self.unconfirmed.get(attribute, ()) is not None or attribute not in self.unconfirmed:
                    self.unconfirm({attribute: None}, self.why.get(self.COMPONENT_OF.get(attribute, ""), "unconfirmed"))
                continue
            found_values = distinct(found)
            if len(found_values) == 1:
                self.know(attribute, found_values[0])
            elif attribute not in self.unconfirmed or self.unconfirmed[attribute] != found_values:
                component = self.COMPONENT_OF.get(attribute, self.LABELS[attribute])
                self.unconfirm({attribute: found_values}, self.why.get(component, "unconfirmed"))

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
        if n == 0:
            return None
        perform = enabled[0] if n == 1 else enabled[int(self._random() * n)]
        if self.watching and perform.__name__ not in self.STILL_METHODS:
            return self._watched(perform, None)
        return perform()

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
            if new is not old and _moved(new, old):
                component = self.COMPONENT_OF[attribute]
                changes[component] = changes.get(component, 0) + 1

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

    def _current_unsure(self) -> Tuple[Callable[..., Optional[str]], ...]:
        """While part of the state is unconfirmed: the controllable events allowed wherever the
        robots may be (none when that cannot be told by trying)."""

        def run() -> Tuple[str, ...]:
            self._provide()
            allowed = self._allowed()
            return tuple(p.__name__ for p in (self._filter(allowed) if self.stale else allowed))

        try:
            outcomes = self._over(run)
        except TooMany as too_many:
            self.warn(
                "holding every command: too much is unconfirmed to tell what is allowed (%s)"
                % self.LABELS.get(too_many.field, too_many.field),
                "too many",
            )
            return ()
        if not outcomes:
            return ()
        first = outcomes[0][1]
        common = [name for name in first if all(name in names for _, names in outcomes[1:])]
        return tuple(self._unsure_event(name) for name in common)

    def _unsure_event(self, method: str) -> Callable[..., Optional[str]]:
        def perform(data: Any = None) -> Optional[str]:
            return self._perform_unsure(method, data)

        perform.__name__ = method
        return perform

    def _perform_unsure(self, method: str, data: Any) -> Optional[str]:
        """Perform a controllable event allowed wherever the robots may be: only when it sends the
        same data in every completion; then each field is where the event leaves it."""
        event = self.BY_METHOD[method]
        send = self.__dict__.get("send")

        def run() -> Tuple[Optional[str], list[Any], list[Any]]:
            self._provide()
            sent: list[Any] = []

            def stub(name: str, data: Any) -> bool:
                sent.append(data)
                return True

            self.send = stub  # type: ignore[method-assign]
            try:
                result = getattr(self, method)(data)
            finally:
                if send is None:
                    del self.send
                else:
                    self.send = send  # type: ignore[method-assign]
            return result, sent, [getattr(self, attribute) for attribute in self.ATTRIBUTES]

        try:
            outcomes = self._over(run)
        except TooMany:
            return None
        if not outcomes or any(result is None for _, (result, _, _) in outcomes):
            return None
        sent = outcomes[0][1][1]
        if any(plain(other[1][1]) != plain(sent) for other in outcomes[1:]):
            self.warn(
                "held: %s would send different data where the robots may be (unconfirmed)" % event.name,
                "differs " + event.name,
            )
            return None
        if sent and not self.send(event.name, sent[0]):
            return None
        self._settle_fields([states for _, (_, _, states) in outcomes])
        self._dirty = True
        if self.observer is not None:
            self._record(event.name, True, sent[0] if sent else data)
        return event.name

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
                return self._unreadable(event, _unreadable_data(event.convert[1], error))
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
                    self._unreadable(event, _unreadable_data(event.convert[1], error))
                    break
            saved = self._apply(event, value)
            if saved is None:
                break
            self._dirty = True
            for index, attribute in answered:
                if getattr(self, attribute) is not saved[index]:
                    self.heard[attribute] = max(when, self.heard.get(attribute, when))
        else:
            return
        for name in names[place + 1 :]:  # after unreadable data: one by one, as deliver() takes them
            self.deliver(name, message, True, stamp)

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
            if answers is not None and self.answered is not None:
                for field, locations in answers:
                    before, now = saved[index[field]], getattr(self, field)
                    if type(before) is str and type(now) is str and before in locations and now != before:
                        self.answered(field, locations)
        communication = event.communication
        if communication is not None and (self.waiting or self._unreadable_since):
            self._readable(communication)
        if self.observer is not None:
            self._record(event.name, False, value)

    def ignore(self, name: str, why: str) -> bool:
        """``name`` (an event, or a topic's message) came and is not taken: counted, reported."""
        self.ignored[name] = self.ignored.get(name, 0) + 1
        self.health_changes += 1
        self.last_ignored = why
        self.warn("ignored %s: %s" % (name, why), "ignored " + name)
        return False

    def _deliver_unsure(self, event: Event, value: Any, stamp: Optional[float]) -> bool:
        """An uncontrollable event while part of the state is unconfirmed: taken in each
        completion where it can be, ignored (nothing changes) in the others, which therefore
        stay possible: an answer may be spurious or a duplicate, so it tells where a component
        is only where every place it may be leads to the same one."""

        def run() -> Any:
            why = self._not_taken(event.name, stamp)
            state = [getattr(self, attribute) for attribute in self.ATTRIBUTES]
            if why is not None:
                return why, state
            try:
                getattr(self, event.method)(value)
            except Unreadable as error:
                return error
            return None, [getattr(self, attribute) for attribute in self.ATTRIBUTES]

        saved = type(self).GETTER(self)
        try:
            outcomes = self._over(run)
        except TooMany as too_many:  # it reads what cannot be tried: anything it may change is unknown
            self.unconfirm(
                dict((a, self.CANDIDATES[a]) for a in self.COMPONENT_OF),
                "%s came while too much was unconfirmed to follow it (%s)"
                % (event.name, self.LABELS.get(too_many.field, too_many.field)),
            )
            return self.ignore(event.name, "too much is unconfirmed to tell what it changes")
        unreadable = [result for _, result in outcomes if isinstance(result, Unreadable)]
        if unreadable:
            return self._unreadable(event, unreadable[0])
        if all(why is not None for _, (why, _) in outcomes):
            return self.ignore(event.name, outcomes[0][1][0] if outcomes else "not expected now")
        self._settle_fields([state for _, (_, state) in outcomes])
        self._delivered(event, value, saved, stamp)
        return True

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
            raise _unreadable_data(enum, error) from None

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
            if isinstance(value, Unknown):
                out[group][label] = None  # unconfirmed: see health()["unconfirmed"]
            else:
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

    @staticmethod
    def _outside(label: str, value: Any) -> Any:
        """Received data outside the type of the variable ``label`` (an enum read from the data
        as it came, which is not one of its names): Unreadable, the event is not delivered."""
        raise Unreadable("%s: %r is outside its type" % (label, plain(value)))

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
