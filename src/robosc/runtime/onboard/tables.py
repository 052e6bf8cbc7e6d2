# -*- coding: utf-8 -*-
"""What a generated robot declares, and the base every part of the supervisor reads.

:class:`Event` and :class:`Communication` describe the network's events and the robot's
communications; :func:`moves` and :func:`tally` make methods the generated class uses;
:class:`Tables` holds the class tables a generated module fills in (``FIELDS``, ``EVENTS``,
``COMMUNICATIONS``, ``ANSWERS``, ...), indexes them once (:meth:`Tables.prepare`), and declares
the hooks the generated class overrides (``_provide``, ``_allowed``, ``_expected``), what is sent
(``send``) and what is recorded (``_record``). :class:`Warnings` reports, each kind at most
once per interval. The supervisor's parts (the cycle, ``supervisor.py``; the belief,
``belief.py``; data health, ``health.py``; effects, ``effects.py``) build on it."""

from __future__ import absolute_import, annotations, print_function

import operator
import sys
import time
from collections import Counter
from typing import Any, Callable, ClassVar, Dict, FrozenSet, Optional, Tuple

from .unknown import enumerable

REFUSED = object()  # data that must not be sent (not finite, or not computable)
KEEP = object()  # an assignment whose value could not be computed keeps the old value
NO_DATA = "none"  # the location of a data plant where no provide statement holds
WARNING_INTERVAL = 5.0  # seconds between two reports of the same kind of warning


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


def stderr(message: str) -> None:
    print("[robosc] " + message, file=sys.stderr)


class _Computed(object):
    """Where an event's data is computed by the model: any finite value in range."""

    def __repr__(self) -> str:
        return "ANY"


ANY = _Computed()


def moves(method: str, name: str, controllable: bool, *changes: Tuple[str, Optional[str], Any]) -> Any:
    """The method performing an event whose effect is only location changes (a reset, a tau
    transition, a response that moves a component): ``changes`` are (field, from, to), tried
    in order; for each field the first whose ``from`` is its location (None: any) applies. A
    tuple ``to``: the event's outcomes there (``_fork``)."""

    def perform(self: Any, data: Any = None) -> Optional[str]:
        done = set()
        for field, source, target in changes:
            if field not in done and (source is None or getattr(self, field) == source):
                if type(target) is tuple:
                    self._fork(field, target)
                else:
                    setattr(self, field, target)
                done.add(field)
        if not controllable:
            return None
        self._dirty = True
        if self.observer is not None:
            self._record(name, True, data)
        return name

    perform.__name__ = method
    perform.__doc__ = "%s: %s" % (name, ", ".join("%s %s -> %s" % (f, a, b) for f, a, b in changes))
    return perform


def tally(*fields: str) -> Callable[[Any], Dict[Any, int]]:
    """The method counting the values of ``fields`` (one per robot of a fleet): value -> how
    many of them have it. A fleet's ``count(q in bot: q.depot)`` is then one lookup, whatever
    the number of robots; ``_allowed`` tallies once per evaluation, at C speed."""
    getter = operator.attrgetter(*fields)
    if len(fields) == 1:
        return lambda self: Counter((getter(self),))
    return lambda self: Counter(getter(self))


class Tables(object):
    """The class tables of a generated robot, indexed, and the hooks it overrides."""



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
    REPLIES: ClassVar[Tuple[str, ...]] = ()  # ANSWERS taken where a command leads: answers to commands
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
    # the answers to commands a robot publishes (REPLIES' messages; not a service's or action's
    # response, which the middleware pairs with its request): a second copy cannot be told apart
    REPEATABLE: ClassVar[FrozenSet[str]]
    STILL_METHODS: ClassVar[FrozenSet[str]]  # the methods of STILL: performed without noting what changed

    # set by the supervisor's __init__
    warn: Warnings
    observer: Optional[Callable[[str, bool, Any], Any]]
    _dirty: bool  # the state changed since the allowed events were last computed
    health_changes: int  # counts the changes of what health() shows
    _sent: Dict[str, Any]  # data computed since the allowed events were, per event

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super(Tables, cls).__init_subclass__(**kwargs)
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
        cls.REPEATABLE = frozenset(name for name in cls.REPLIES if cls.EVENT[name].kind == "message")
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

    def send(self, name: str, data: Any) -> bool:
        """The controllable event ``name`` is being performed with ``data`` (None: empty).
        Return False to refuse it (it is then not performed). The default sends nothing."""
        return True

    def _record(self, event: str, controllable: bool, data: Any) -> None:
        observer = self.observer
        if observer is not None:
            try:
                observer(event, controllable, data)
            except Exception as error:
                self.warn("observer failed on %s: %s: %s" % (event, type(error).__name__, error), "observer")

    def _provide(self) -> None:
        """Step 1: each data plant moves to the data its conditions choose."""

    def _allowed(self) -> Tuple[Callable[..., Optional[str]], ...]:
        """Step 2: the controllable events the plant and the supervisor allow now."""
        return ()

    def _expected(self) -> Tuple[bool, ...]:
        """For each uncontrollable event (in ``UNCONTROLLABLE`` order): can the plant take it now?"""
        return ()


Tables.prepare()
