"""The automata network that synthesis works on.

Locations are :class:`robosc.language.model.State` objects: a component's own
states, and states made for the communication and data plants (``owner`` is
the plant's name). So every guard -- written by the user, made by the plant
construction, or added by synthesis -- is an ordinary model expression.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from enum import Enum

from robosc.language import model as m
from robosc.record import field, record


class EventKind(str, Enum):
    MESSAGE = "message"  # the one event of a message
    TRIGGER = "trigger"  # c_trigger: send a service request / start an action
    RESPONSE = "response"  # u_response
    ERROR = "error"  # u_error
    FEEDBACK = "feedback"  # u_feedback
    RESET = "reset"  # c_reset: back to idle after a response or error
    CANCEL = "cancel"  # c_cancel
    TAU = "tau"  # a component's own `transition`
    PROVIDE = "provide"  # a data plant choosing the data to send


@record(eq=False)
class Event:
    name: str
    controllable: bool
    kind: EventKind
    communication: m.Communication | None = None
    transition: m.TauTransition | None = None  # for TAU events
    provide: m.Provide | None = None  # for PROVIDE events (None: the "no data" choice)

    def __repr__(self) -> str:
        return f"Event({self.name})"


@record(eq=False)
class Update:
    """``variable := value``; ``value`` None means any value of the variable's domain
    (the update depends on data received from the middleware)."""

    variable: m.Variable
    value: m.Expr | None


@record(eq=False)
class Edge:
    source: m.State
    target: m.State
    event: Event
    guard: m.Expr | None = None
    updates: tuple[Update, ...] = ()


class AutomatonKind(str, Enum):
    COMPONENT = "component"
    MESSAGE = "message"
    SERVICE = "service"
    ACTION = "action"
    DATA = "data"


@record(eq=False)
class Automaton:
    name: str
    kind: AutomatonKind
    locations: tuple[m.State, ...]
    initial: m.State
    edges: tuple[Edge, ...]
    alphabet: frozenset[Event]
    component: m.Component | None = None

    @property
    def marked(self) -> tuple[m.State, ...]:
        return tuple(loc for loc in self.locations if loc.marked)


class Later:
    """A text written the first time it is asked for, then kept."""

    __slots__ = ("make", "text")

    def __init__(self, make: Callable[[], str]) -> None:
        self.make = make
        self.text: str | None = None

    def __call__(self) -> str:
        if self.text is None:
            self.text = self.make()
        return self.text


@record(eq=False)
class Requirement:
    """A state-event exclusion: ``event`` may occur only where ``condition`` holds. ``said``: how
    to tell it, or how to write that when asked (a fleet's requirements name every robot, and
    writing each out took longer than synthesis: 35 s for a warehouse of 200 robots)."""

    event: Event
    condition: m.Expr
    said: str | Callable[[], str] = field(repr=False)
    origin: m.Requirement | None = None

    @property
    def description(self) -> str:
        """The requirement as robosc tells it."""
        return self.said if isinstance(self.said, str) else self.said()


@record(eq=False)
class Network:
    model: m.Model
    events: tuple[Event, ...]
    automata: tuple[Automaton, ...]
    variables: tuple[m.Variable, ...]
    domains: dict[m.Variable, Sequence[object]] = field(repr=False)
    initial_values: dict[m.Variable, object] = field(repr=False)
    requirements: tuple[Requirement, ...] = ()
    # marked states must also satisfy this (a counted fleet: no agent outside its marked states)
    marker: m.Expr | None = None
    # states outside these are not states of the system: each tuple of counters sums to its total
    totals: tuple[tuple[tuple[m.Variable, ...], int], ...] = ()

    @property
    def controllable(self) -> tuple[Event, ...]:
        return tuple(e for e in self.events if e.controllable)

    @property
    def uncontrollable(self) -> tuple[Event, ...]:
        return tuple(e for e in self.events if not e.controllable)

    def requirements_on(self, event: Event) -> Iterator[Requirement]:
        return (r for r in self.requirements if r.event is event)

    def event(self, name: str) -> Event:
        return next(e for e in self.events if e.name == name)

    def branching(self, event: Event) -> bool:
        """Whether ``event`` may have several outcomes from one state: some automaton has two
        of its edges from one location, or an edge sets a variable to any value. (Two edges
        whose guards never hold together count too: the answer is "may".)"""
        for automaton in self.automata:
            if event not in automaton.alphabet:
                continue
            sources = [e.source for e in automaton.edges if e.event is event]
            if len(sources) != len(set(sources)):
                return True
            if any(u.value is None for e in automaton.edges if e.event is event for u in e.updates):
                return True
        return False


def received_type(event: Event) -> m.DataType | None:
    """The type of the data the controller receives with an uncontrollable event
    (a message's, a response's or a feedback's); None for the other events."""
    c = event.communication
    if c is None or event.controllable:
        return None
    if isinstance(c, m.Message):
        return c.type
    if event.kind is EventKind.FEEDBACK and isinstance(c, m.Action):
        return c.feedback_type
    if event.kind is EventKind.RESPONSE:
        return c.response_type
    return None


def event_of(network: Network, transition: m.Transition) -> Event:
    """The network event a component transition synchronises with."""
    if isinstance(transition, m.TauTransition):
        return next(e for e in network.events if e.transition is transition)
    c = transition.communication
    for e in network.events:
        if e.communication is not c:
            continue
        if e.kind is EventKind.MESSAGE:
            if (transition.result is m.ResultKind.REQUEST) == e.controllable:
                return e
        elif e.kind.value == {"request": "trigger"}.get(transition.result.value, transition.result.value):
            return e
    raise KeyError(transition)
