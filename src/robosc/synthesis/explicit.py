"""Explicit-state synthesis: enumerate the reachable states and compute the same fixed
point as :mod:`.symbolic` on sets of states. Independent of the BDD code, for
cross-checking it on small models."""

from __future__ import annotations

import itertools
import time
from collections import deque
from collections.abc import Iterator
from typing import Any

from robosc.plant.network import Edge, Event, Network
from robosc.record import field, record
from robosc.synthesis.evaluate import Undefined, evaluate
from robosc.synthesis.result import SynthesisResult
from robosc.synthesis.state import NetworkState, initial_state


class TooManyStates(Exception):
    pass


def _holds(edge_guard: Any, locations: set[Any], values: dict[Any, Any]) -> bool:
    if edge_guard is None:
        return True
    try:
        return bool(evaluate(edge_guard, locations, values))
    except Undefined:
        return False


def marked(network: Network, state: NetworkState) -> bool:
    """Whether ``state`` is marked: every automaton in a marked location, and the network's
    marker (a counted fleet's) holding."""
    if not all(loc.marked for loc in state.locations):
        return False
    values = dict(zip(network.variables, state.values, strict=True))
    return network.marker is None or _holds(network.marker, set(state.locations), values)


class Edges:
    """A network's edges by event, then by automaton (its index) and source location."""

    def __init__(self, network: Network) -> None:
        self.network = network
        self.by_event: dict[Event, list[tuple[int, dict[Any, list[Edge]]]]] = {e: [] for e in network.events}
        for index, automaton in enumerate(network.automata):
            for event in automaton.alphabet:
                by_source: dict[Any, list[Edge]] = {}
                for edge in automaton.edges:
                    if edge.event is event:
                        by_source.setdefault(edge.source, []).append(edge)
                self.by_event[event].append((index, by_source))


def successors(edges: Edges, state: NetworkState, event: Event) -> Iterator[NetworkState]:
    """Every state ``event`` can lead to from ``state`` (none when it is disabled), over the
    edges of ``edges.network``."""
    network = edges.network
    locations = set(state.locations)
    values = dict(zip(network.variables, state.values, strict=True))
    choices: list[list[tuple[int, Edge]]] = []
    for index, by_source in edges.by_event[event]:
        here = state.locations[index]
        enabled = [(index, e) for e in by_source.get(here, ()) if _holds(e.guard, locations, values)]
        if not enabled:
            return
        choices.append(enabled)
    for combination in itertools.product(*choices):
        new_locations = list(state.locations)
        options: list[list[Any]] = [[v] for v in state.values]
        possible = True
        for index, edge in combination:
            new_locations[index] = edge.target
            for update in edge.updates:
                position = network.variables.index(update.variable)
                domain = network.domains[update.variable]
                if update.value is None:
                    options[position] = list(domain)
                    continue
                try:
                    value = evaluate(update.value, locations, values)
                except Undefined:
                    possible = False
                    break
                if value not in domain:
                    possible = False  # outside the variable's range: no such transition
                    break
                options[position] = [domain[domain.index(value)]]
        if possible:
            for new_values in itertools.product(*options):
                yield NetworkState(tuple(new_locations), tuple(new_values))


@record(frozen=False)
class ExplicitSupervisor:
    network: Network
    states: list[NetworkState]
    transitions: dict[NetworkState, list[tuple[Event, NetworkState]]]
    required_ok: dict[tuple[NetworkState, Event], bool]
    bad: set[NetworkState]
    allowed: dict[NetworkState, frozenset[Event]] = field(default_factory=dict)  # allowed_events, kept

    def allows(self, event: Event, state: NetworkState) -> bool:
        return event in self.allowed_events(state)

    def allowed_events(self, state: NetworkState) -> frozenset[Event]:
        """The events the supervisor lets happen in ``state``: uncontrollable ones the plant allows,
        controllable ones its requirements allow too, none of whose outcomes is bad."""
        found = self.allowed.get(state)
        if found is None:
            found = frozenset()
            if state not in self.bad and state in self.transitions:
                outcomes: dict[Event, list[NetworkState]] = {}
                for event, target in self.transitions[state]:
                    outcomes.setdefault(event, []).append(target)
                found = frozenset(
                    e
                    for e, targets in outcomes.items()
                    if not e.controllable or (self.required_ok[(state, e)] and all(t not in self.bad for t in targets))
                )
            self.allowed[state] = found
        return found

    def controlled(self, state: NetworkState) -> bool:
        """Whether ``state`` is inside the controlled behaviour (not bad)."""
        return state not in self.bad

    def controlled_states(self) -> list[NetworkState]:
        """The states reachable under the supervisor, in breadth-first order."""
        start = self.states[0]
        if start in self.bad:
            return []
        reached = {start}
        order = [start]
        queue = deque([start])
        while queue:
            state = queue.popleft()
            allowed = self.allowed_events(state)
            for event, target in self.transitions[state]:
                if target not in reached and event in allowed:
                    reached.add(target)
                    order.append(target)
                    queue.append(target)
        return order


MAX_STATES = 200_000  # explicit synthesis is a cross-check for small models


def synthesize_explicit(network: Network, max_states: int | None = None) -> SynthesisResult:
    start = time.perf_counter()
    init = initial_state(network)
    transitions: dict[NetworkState, list[tuple[Event, NetworkState]]] = {}
    queue = deque([init])
    transitions[init] = []
    order = [init]
    edges = Edges(network)
    while queue:
        state = queue.popleft()
        out = transitions[state]
        for event in network.events:
            for target in successors(edges, state, event):
                out.append((event, target))
                if target not in transitions:
                    if len(transitions) >= (max_states or MAX_STATES):
                        raise TooManyStates(f"more than {max_states or MAX_STATES} states")
                    transitions[target] = []
                    order.append(target)
                    queue.append(target)
    required_ok: dict[tuple[NetworkState, Event], bool] = {}
    for state in order:
        locations = set(state.locations)
        values = dict(zip(network.variables, state.values, strict=True))
        for event in {e for e, _ in transitions[state]}:
            required_ok[(state, event)] = all(
                _holds(r.condition, locations, values) for r in network.requirements_on(event)
            )
    predecessors: dict[NetworkState, list[tuple[Event, NetworkState]]] = {s: [] for s in order}
    for state in order:
        for event, target in transitions[state]:
            predecessors[target].append((event, state))

    bad = {s for s in order if any(not e.controllable and not required_ok[(s, e)] for e, _ in transitions[s])}
    while True:
        stack = list(bad)
        while stack:  # controllability: uncontrollable predecessors of bad states are bad
            state = stack.pop()
            for event, source in predecessors[state]:
                if not event.controllable and source not in bad:
                    bad.add(source)
                    stack.append(source)
        good = {s for s in order if s not in bad and marked(network, s)}
        stack = list(good)
        while stack:  # nonblocking: who can reach a marked state through good states, by events
            state = stack.pop()  # the supervisor may allow there (a controllable one: no outcome bad)
            for event, source in predecessors[state]:
                if source in bad or source in good or not required_ok[(source, event)]:
                    continue
                if event.controllable and any(e is event and t in bad for e, t in transitions[source]):
                    continue
                good.add(source)
                stack.append(source)
        new_bad = {s for s in order if s not in good}
        if new_bad == bad:
            break
        bad = new_bad

    supervisor = ExplicitSupervisor(network, order, transitions, required_ok, bad)
    reachable = supervisor.controlled_states()
    return SynthesisResult(
        network,
        "explicit",
        init not in bad,
        reachable_states=len(reachable),
        seconds=time.perf_counter() - start,
        supervisor=supervisor,
        plant_states=len(order),
    )
