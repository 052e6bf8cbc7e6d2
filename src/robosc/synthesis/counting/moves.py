"""A group's local states and moves: every state the representative's automata and variables
can be in, reached from its start by its own edges, and each edge taken from each of them."""

from __future__ import annotations

import itertools
from collections.abc import Iterator, Sequence

from robosc.language import model as m
from robosc.plant.expressions import NO_SPAN, all_of
from robosc.plant.network import Edge, Event, Network, Update
from robosc.record import record
from robosc.synthesis.counting.groups import Agent, Group, LocalState, NotSymmetric, names_of, owner_of
from robosc.synthesis.evaluate import Undefined, evaluate


@record(eq=False)
class Move:
    """A local transition of the representative: ``event`` from ``source`` to ``target``
    where ``guard`` holds (over its own state, shared state and the other agents)."""

    event: Event
    source: int  # indices into Group.local
    target: int
    guard: m.Expr | None


def _moves_from(network: Network, agent: Agent, state: LocalState) -> Iterator[tuple[Event, LocalState, m.Expr | None]]:
    locations, values = state
    environment = dict(zip(agent.variables, values, strict=True))
    for event in agent.events:
        options: list[list[Edge]] = []
        for automaton, location in zip(agent.automata, locations, strict=True):
            if event not in automaton.alphabet:
                options.append([])
                continue
            edges = [e for e in automaton.edges if e.source is location and e.event is event]
            if not edges:
                break
            options.append(edges)
        else:
            choices: list[list[Edge | None]] = [list(o) if o else [None] for o in options]
            for chosen in itertools.product(*choices):
                targets = tuple(
                    edge.target if edge is not None else loc for edge, loc in zip(chosen, locations, strict=True)
                )
                guards = [e.guard for e in chosen if e is not None and e.guard is not None]
                updates = [u for e in chosen if e is not None for u in e.updates]
                for new_values in _updated(network, agent, environment, updates, set(locations)):
                    yield event, (targets, new_values), all_of(guards) if guards else None


def _updated(
    network: Network, agent: Agent, values: dict[m.Variable, object], updates: Sequence[Update], at: set[m.State]
) -> Iterator[tuple[object, ...]]:
    choices: list[Sequence[object]] = []
    for variable in agent.variables:
        update = next((u for u in updates if u.variable is variable), None)
        if update is None:
            choices.append((values[variable],))
        elif update.value is None:
            choices.append(network.domains[variable])
        else:
            if any(
                isinstance(n, (m.StateRef, m.VariableRef)) and owner_of(n) not in names_of(agent)
                for n in m.walk(update.value)
            ):
                raise NotSymmetric(f"an update of {variable.name} reads another agent")
            try:
                value = evaluate(update.value, at, values)
            except (Undefined, KeyError) as exc:
                raise NotSymmetric(f"an update of {variable.name} cannot be computed locally") from exc
            if value not in network.domains[variable]:
                return
            choices.append((value,))
    yield from itertools.product(*choices)


def start_of(network: Network, group: Group, agent: Agent) -> LocalState:
    """Where ``agent`` starts, as a local state of the group's representative."""
    mapping = group.to_rep[id(agent)]
    return tuple(mapping[a.initial] for a in agent.automata), tuple(network.initial_values[v] for v in agent.variables)


def explore(network: Network, group: Group) -> tuple[Group, list[Move]]:
    """The group with its local states (those reachable from its agents' start, guards
    aside) and counters; the representative's moves between them."""
    rep = group.rep
    starts = [start_of(network, group, agent) for agent in group.agents]
    index: dict[LocalState, int] = {}
    order: list[LocalState] = []
    found: dict[LocalState, list[tuple[Event, LocalState, m.Expr | None]]] = {}
    for start in starts:  # breadth-first from each start in turn: a route's states come in its order
        if start in index:
            continue
        index[start] = len(order)
        order.append(start)
        at = index[start]
        while at < len(order):  # grows while it is walked
            state = order[at]
            at += 1
            found[state] = list(_moves_from(network, rep, state))
            for _, target, _ in found[state]:
                if target not in index:
                    index[target] = len(order)
                    order.append(target)
    moves = [
        Move(event, index[state], index[target], guard) for state in order for event, target, guard in found[state]
    ]
    n = len(group.agents)
    counters = tuple(
        m.Variable(f"{group.name}[{i}]", f"#{group.name}", m.BasicType(m.BasicKind.INTEGER, 0, n), None, NO_SPAN)
        for i in range(len(order))
    )
    return Group(group.name, group.agents, group.to_rep, tuple(order), counters), moves
