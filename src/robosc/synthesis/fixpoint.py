"""The BDDs of one symbolic synthesis run (:func:`robosc.synthesis.symbolic.fixpoint`), kept
for what is asked afterwards: whether the supervisor allows an event in a state, the condition
it adds, and the explanations (robosc.synthesis.why, robosc.synthesis.counting.explain)."""

from __future__ import annotations

from typing import Any

from robosc.language import model as m
from robosc.plant.network import Event
from robosc.record import field, record
from robosc.synthesis.cases import Case, Unions, union
from robosc.synthesis.encoding import BDD, Encoding, Relation
from robosc.synthesis.readable import readable
from robosc.synthesis.state import NetworkState, describe


@record(frozen=False)
class Fixpoint:
    """The BDDs of one synthesis run, kept for questions asked afterwards."""

    enc: Encoding
    relation: dict[Event, Relation]
    cases: dict[Event, tuple[Case, ...]]  # each event's requirements by where its automaton is
    required: Unions  # where the requirements allow each event, among the states where it can happen
    enabled: dict[Event, BDD]
    initial: BDD
    marked: BDD
    requirement_bad: BDD
    bad: BDD  # among the considered states
    considered: BDD  # the states synthesis decided on: every valid one, or those the requirements reach
    allowed: Unions  # controllable events: where the supervisor allows them (a part per case)
    reachable: BDD
    memo: dict[object, Any] = field(default_factory=dict)  # explanations, computed on request, kept
    targets: tuple[m.State, ...] = ()  # locations that must stay reachable besides a marked state (finish.py)
    describer: Any = None  # a state as people read it (None: robosc.synthesis.state.describe)

    def describe(self, state: NetworkState) -> str:
        """``state`` in words, for explanations."""
        if self.describer is not None:
            return str(self.describer(state))
        return describe(self.enc.network, state)

    def allows(self, event: Event, state: NetworkState) -> bool:
        """Whether ``event`` can happen in ``state`` under the supervisor."""
        return self.allows_in(event, self.state(state))

    def allowed_events(self, state: NetworkState) -> frozenset[Event]:
        """The events the supervisor lets happen in ``state`` (:meth:`allows` for each, the state
        encoded once)."""
        here = self.state(state)
        return frozenset(e for e in self.enc.network.events if self.allows_in(e, here))

    def allows_in(self, event: Event, states: BDD) -> bool:
        """Whether ``event`` can happen in one of ``states`` (a controllable one asked case by
        case, without making the union of where it is allowed)."""
        if event.controllable:
            return self.allowed.meets(event, states)
        return bool((states & self.where(event)) != self.enc.false)

    def never_allows(self, event: Event) -> bool:
        """Whether the supervisor allows the controllable ``event`` in no state the controlled
        system reaches."""
        return bool((self.allowed[event] & self.reachable) == self.enc.false)

    def where(self, event: Event) -> BDD:
        """The states where the supervisor lets ``event`` happen."""
        return self.allowed[event] if event.controllable else self.enabled[event] & self.good

    @property
    def good(self) -> BDD:
        """The considered states that are not bad."""
        return self.considered & ~self.bad

    def added(self, event: Event) -> m.Expr | None:
        """The condition synthesis adds to ``event`` beyond its requirements, written over the
        states where the controlled system can do it (None where it adds none)."""
        enc = self.enc
        where = self.reachable & self.enabled[event]
        care = union([where & part for part in self.required.parts[event]])  # without the union of the parts
        beyond = ~enc.pre(self.relation[event], self.bad)
        return readable(enc, beyond, care) if (care & ~beyond) != enc.false else None

    def controlled(self, state: NetworkState) -> bool:
        """Whether ``state`` is inside the controlled behaviour: no requirement can be
        forced to break from it and a marked state stays reachable (where synthesis looked only
        at the states the requirements reach, those it did not look at are outside)."""
        return self.controlled_in(self.state(state))

    def controlled_in(self, states: BDD) -> bool:
        """Whether ``states`` (one state, encoded) lies in the controlled behaviour."""
        return bool((states & self.good) != self.enc.false)

    def state(self, state: NetworkState) -> BDD:
        network = self.enc.network
        locations = dict(zip(network.automata, state.locations, strict=True))
        values = dict(zip(network.variables, state.values, strict=True))
        return self.enc.state(locations, values)
