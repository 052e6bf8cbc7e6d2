"""What synthesis gives: a guard per controllable event, or an explanation of why none exists."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Protocol

from robosc.language import model as m
from robosc.language.source import Span
from robosc.plant.network import Event, Network
from robosc.record import field, record
from robosc.synthesis.fixpoint import Fixpoint
from robosc.synthesis.state import NetworkState


@record
class EventGuard:
    """For one controllable event: what the user's model says, and what synthesis added.

    ``plant`` is where the plant (automata and their guards) allows the event;
    ``required`` the user's requirements on it (None when there are none);
    ``added`` the condition synthesis added (None when it added nothing).
    The event may happen exactly where ``plant``, ``required`` and ``added`` all hold.
    """

    event: Event
    required: m.Expr | None
    added: m.Expr | None


@record
class Step:
    event: Event
    state: str  # the state reached, described


@record
class Fix:
    """A small change to the model that removes the problem an explanation describes, in the
    model's own words, and where it goes (None: nowhere in particular)."""

    text: str
    span: Span | None = None
    kind: str = "missing"  # "missing" transition, "unmarked" dead end, or a shutting "requirement"

    def __str__(self) -> str:
        return f"{self.text} ({self.span})" if self.span is not None and self.span.line > 0 else self.text


@record
class Explanation:
    """Why synthesis failed: the reason, and a shortest sequence of uncontrollable
    events from the initial state to a state that must be avoided; ``fixes``: changes to
    the model that would remove the problem, where robosc can name them."""

    reason: str
    initial_state: str
    path: tuple[Step, ...]
    fixes: tuple[Fix, ...] = ()


@record
class Restriction:
    """Why synthesis added a condition to a controllable event.

    ``path``: a shortest run of the controlled system from the initial state to ``state``,
    where the plant and the requirements allow ``event`` but the supervisor does not;
    ``after``: the state ``event`` would lead to; ``consequence``: what goes wrong from
    there (its ``path`` starts at ``after``); ``never``: the supervisor never allows the
    event in any reachable state (its added condition is ``false``).
    """

    event: Event
    path: tuple[Step, ...]
    state: str
    after: str
    consequence: Explanation
    never: bool = False
    note: str = ""  # a counted fleet's: that its robots are restricted alike, and for which robot the run is told


class Supervisor(Protocol):
    """What the supervisor of every method answers about a state of the network it was
    synthesized for (:class:`~robosc.synthesis.fixpoint.Fixpoint` for the monolithic method,
    ``CountedSupervisor`` for a counted fleet, ``ExplicitSupervisor`` for the explicit one)."""

    def allows(self, event: Event, state: NetworkState) -> bool: ...

    def allowed_events(self, state: NetworkState) -> frozenset[Event]: ...

    def controlled(self, state: NetworkState) -> bool: ...


@record
class SynthesisResult:
    """What one synthesis found. ``method``: "symbolic" (monolithic BDDs), "symmetric" (a
    fleet's copies counted) or "explicit" (every state listed, a cross-check).

    ``supervisor`` answers for concrete states (:meth:`allows`, :meth:`allowed_events`,
    :meth:`controlled`); ``fixpoint`` holds the BDDs of a symbolic run (of the counted network
    where ``method`` is "symmetric"; None for the explicit method), from which explanations and
    warnings are made on request (robosc.synthesis.restrictions, robosc.synthesis.warnings).
    ``fleet`` says how a fleet's copies were synthesized ("counted (...)" or "monolithic: why";
    empty where synthesis did not look for copies), ``fleet_note`` what a user of the fleet
    should know of it; ``effort`` the BDD library's machine-independent figures;
    ``plant_states`` the explicit method's count of the uncontrolled plant's states."""

    network: Network
    method: str  # "symbolic", "symmetric" or "explicit"
    ok: bool
    guards: tuple[EventGuard, ...] = ()
    reachable_states: int = 0
    seconds: float = 0.0
    explanation: Explanation | None = None
    supervisor: Supervisor | None = field(default=None, repr=False, compare=False)
    fixpoint: Fixpoint | None = field(default=None, repr=False, compare=False)
    fleet: str = ""
    fleet_note: str = ""
    effort: Mapping[str, int] | None = field(default=None, compare=False)
    plant_states: int = 0

    def guard(self, name: str) -> EventGuard:
        return next(g for g in self.guards if g.event.name == name)

    @property
    def added_guards(self) -> tuple[EventGuard, ...]:
        """The controllable events on which synthesis added a condition."""
        return tuple(g for g in self.guards if g.added is not None)

    def state(self, assignment: Mapping[str, object] | None = None) -> NetworkState:
        """A network state from names: ``{"Platform": "turning", "Distance.front": "wall_front"}``
        (automaton -> location, ``Component.variable`` -> value); the rest as initially."""
        assignment = dict(assignment or {})
        network = self.network
        locations = []
        for automaton in network.automata:
            wanted = assignment.pop(automaton.name, None)
            if wanted is None:
                locations.append(automaton.initial)
                continue
            found = next((loc for loc in automaton.locations if loc.name == wanted), None)
            if found is None:
                raise KeyError(f"{automaton.name} has no location '{wanted}'")
            locations.append(found)
        values = []
        for variable in network.variables:
            key = f"{variable.owner}.{variable.name}"
            if key not in assignment:
                values.append(network.initial_values[variable])
                continue
            wanted = assignment.pop(key)
            domain = network.domains[variable]
            found_value = next((v for v in domain if v == wanted or getattr(v, "name", None) == wanted), None)
            if found_value is None:
                raise KeyError(f"{key} cannot be {wanted!r}")
            values.append(found_value)
        if assignment:
            raise KeyError(f"no automaton or synthesis variable named {', '.join(sorted(assignment))}")
        return NetworkState(tuple(locations), tuple(values))

    def allows(self, event: Event | str, state: NetworkState) -> bool:
        """Whether the supervisor lets ``event`` happen in ``state`` (of :attr:`network`)."""
        found = self.network.event(event) if isinstance(event, str) else event
        return self._supervisor().allows(found, state)

    def allowed_events(self, state: NetworkState) -> frozenset[Event]:
        """The events the supervisor lets happen in ``state``: those :meth:`allows` says yes to."""
        return self._supervisor().allowed_events(state)

    def controlled(self, state: NetworkState) -> bool:
        """Whether ``state`` lies inside the controlled behaviour (every requirement can be
        kept from it and a marked state stays reachable)."""
        return self._supervisor().controlled(state)

    def _supervisor(self) -> Supervisor:
        if self.supervisor is None:
            raise ValueError(f"this {self.method} result holds no supervisor to ask")
        return self.supervisor
