"""The supervisor a counted synthesis found, asked about states of the original network
(:class:`CountedSupervisor`), and its conditions read back in the fleet's names (:func:`lift`:
a counter becomes ``count(...)`` over the group, which the runtime evaluates as it is)."""

from __future__ import annotations

from typing import Any

from robosc.language import model as m
from robosc.language.simplify import replace
from robosc.plant.expressions import NO_SPAN, any_of
from robosc.plant.network import Automaton, AutomatonKind, Event, Network
from robosc.synthesis.counting.groups import Agent, Group, LocalState
from robosc.synthesis.counting.network import Counted
from robosc.synthesis.counting.translate import rename_back
from robosc.synthesis.fixpoint import Fixpoint


class CountedSupervisor:
    """The supervisor a counted synthesis found, asked about states of the original network."""

    def __init__(self, network: Network, fleet: Counted, fixpoint: Fixpoint) -> None:
        self.network = network
        self.fleet = fleet
        self.fp = fixpoint
        self.agent_of_event: dict[Event, tuple[Group, Agent]] = {}
        for group in fleet.groups:
            for agent in group.agents:
                for event in agent.events:
                    self.agent_of_event[event] = (group, agent)
        # the representative's event -> the counted events of its moves (from each local state)
        self.counted_events: dict[Event, list[Event]] = {}
        for counted_event, (_, outcomes) in fleet.moves.items():
            self.counted_events.setdefault(outcomes[0].event, []).append(counted_event)
        self.index = {group.name: {s: i for i, s in enumerate(group.local)} for group in fleet.groups}
        self.by_name = {a.name: a for a in network.automata}  # the counted network rebuilds the shared ones

    def _places(self, state: Any) -> tuple[dict[Automaton, m.State], dict[m.Variable, object], dict[int, int]]:
        """An original network state's locations and values, and each agent's local state (by id)."""
        where = dict(zip(self.network.automata, state.locations, strict=True))
        values = dict(zip(self.network.variables, state.values, strict=True))
        places = {
            id(agent): self.index[group.name][self.local(group, agent, where, values)]
            for group in self.fleet.groups
            for agent in group.agents
        }
        return where, values, places

    def _state(self, state: Any) -> tuple[Any, dict[int, int]]:
        """The counted state of an original network state, and each agent's local state (by id)."""
        fleet, enc = self.fleet, self.fp.enc
        where, values, places = self._places(state)
        by_name = self.by_name
        locations = {a: where[by_name[a.name]] if a.name in by_name else a.initial for a in fleet.network.automata}
        counted_values = {v: values[v] for v in fleet.network.variables if v in values}
        for group in fleet.groups:
            counts = [0] * len(group.local)
            for agent in group.agents:
                counts[places[id(agent)]] += 1
            counted_values.update(zip(group.counters, counts, strict=True))
        return enc.state(locations, counted_values), places

    def key(self, state: Any) -> tuple[Any, ...]:
        """The orbit of an original network state: its shared part, and how many agents of
        each group are in each local state (hashable)."""
        where, values, places = self._places(state)
        shared = tuple(where[self.by_name[a.name]] for a in self.fleet.network.automata if a.name in self.by_name)
        counted = tuple(values[v] for v in self.fleet.network.variables if v in values)
        counts = tuple(tuple(sorted(places[id(agent)] for agent in group.agents)) for group in self.fleet.groups)
        return shared, counted, counts

    @staticmethod
    def local(
        group: Group, agent: Agent, where: dict[Automaton, m.State], values: dict[m.Variable, object]
    ) -> LocalState:
        mapping = group.to_rep[id(agent)]
        return tuple(mapping[where[a]] for a in agent.automata), tuple(values[v] for v in agent.variables)

    def counted_of(self, event: Event) -> list[Event]:
        """The counted network's events for ``event`` of the fleet: for a robot's event, one per
        local state its robot may do it from; a shared event is its own."""
        owner = self.agent_of_event.get(event)
        if owner is None:
            return [event]
        group, agent = owner
        return self.counted_events.get(group.to_rep[id(agent)][event], [])

    def restricted_of(self, event: Event) -> list[Event]:
        """The counted events of ``event`` (:meth:`counted_of`) that synthesis may restrict."""
        return [c for c in self.counted_of(event) if c in self.fp.allowed]

    def never_allows(self, event: Event) -> bool:
        """Whether the supervisor allows the controllable ``event`` in no state the controlled
        system reaches (from no local state of its robot)."""
        return all(self.fp.never_allows(c) for c in self.restricted_of(event))

    def allows(self, event: Event, state: Any) -> bool:
        return self._allows(event, *self._state(state))

    def allowed_events(self, state: Any) -> frozenset[Event]:
        """The events the supervisor lets happen in ``state`` (the state counted once)."""
        here, places = self._state(state)
        return frozenset(e for e in self.network.events if self._allows(e, here, places))

    def _allows(self, event: Event, here: Any, places: dict[int, int]) -> bool:
        fp, false = self.fp, self.fp.enc.false
        owner = self.agent_of_event.get(event)
        if owner is None:
            return bool((here & fp.where(event)) != false)
        source = places[id(owner[1])]
        return any(
            (here & fp.where(counted_event)) != false
            for counted_event in self.counted_of(event)
            if self.fleet.moves[counted_event][1][0].source == source
        )

    def controlled(self, state: Any) -> bool:
        return bool(self.fp.controlled_in(self._state(state)[0]))


def lift(e: m.Expr, fleet: Counted, network: Network) -> m.Expr:
    """An expression over the counted network with each counter written as a ``count(...)``
    of the original model: how many of the group's agents are in that local state."""
    counters = {c: (group, i) for group in fleet.groups for i, c in enumerate(group.counters)}
    translator = fleet.translator
    # a count over every instance of an array, in order, is written `count(q in bot: ...)`;
    # one over some of them (a robot singled out, copies by hand) names each
    sizes: dict[str | None, int] = {}
    for automaton in network.automata:
        if automaton.kind is AutomatonKind.COMPONENT and automaton.component is not None:
            sizes[automaton.component.group] = sizes.get(automaton.component.group, 0) + 1
    whole = {group.name: _whole_array(group, sizes) for group in fleet.groups}

    def agent_at(group: Group, agent: Agent, index: int) -> m.Expr:
        back = {v: k for k, v in group.to_rep[id(agent)].items()}
        return rename_back(translator.at(group, index), back)

    def places(node: m.Expr) -> list[m.VariableRef] | None:
        """The counters a sum of counters adds up (``c_depot + c_ready``), or None."""
        if isinstance(node, m.VariableRef) and node.variable in counters:
            return [node]
        if isinstance(node, m.Binary) and node.op == "+":
            left, right = places(node.left), places(node.right)
            if left is not None and right is not None:
                return left + right
        return None

    def counted(node: m.Expr) -> m.Expr | None:
        added = places(node)
        if added is None or len({id(counters[r.variable][0]) for r in added}) != 1:
            return None
        # robots in one place or another of the group: one count of either, robot by robot
        group = counters[added[0].variable][0]
        indices = [counters[r.variable][1] for r in added]
        terms = tuple(any_of([agent_at(group, agent, i) for i in indices]) for agent in group.agents)
        name = group.name if whole[group.name] else ""
        return m.Count(name, terms, m.BasicType(m.BasicKind.INTEGER, 0, len(terms)), NO_SPAN)

    return replace(e, counted)


def _whole_array(group: Group, sizes: dict[str | None, int]) -> bool:
    """Whether ``group``'s agents are the instances of one array (``sizes``: how many each
    array has), all of them, in order."""
    components = [agent.component for agent in group.agents]
    in_order = all(c.group == group.name and c.index == i for i, c in enumerate(components, 1))
    return in_order and sizes.get(group.name) == len(components)


