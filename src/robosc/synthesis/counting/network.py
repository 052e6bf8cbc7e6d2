"""The counted network (:func:`counted`): one counter per local state of each group, an event
per move of the representative from each local state, the shared automata kept and read
through the counters. It goes through the same fixed point as any network
(robosc.synthesis.symbolic); its size grows polynomially with the number of agents where the
monolithic network's grows exponentially."""

from __future__ import annotations

from robosc.language import model as m
from robosc.plant.expressions import NO_SPAN, all_of
from robosc.plant.network import Automaton, AutomatonKind, Edge, Event, Network, Requirement, Update
from robosc.record import field, record
from robosc.synthesis.counting.groups import Differ, Group, NotSymmetric, groups, map_to_rep, robots_of
from robosc.synthesis.counting.moves import Move, explore, start_of
from robosc.synthesis.counting.translate import Translator, at_least, at_most, check_requirements, requirement_span


@record(eq=False)
class Counted:
    """A network counted: the network synthesis runs on, its groups, and for each of its
    events made for a robot's event from one local state, the group and the moves (one per
    outcome: a controllable event with several is allowed only where none leads to a bad state,
    as the robot's own event)."""

    network: Network
    groups: tuple[Group, ...]
    moves: dict[Event, tuple[Group, tuple[Move, ...]]]  # its outcomes: one event, source and move of the robot
    translator: Translator = field(repr=False)


def with_homes(network: Network, least: int = 2) -> bool:
    """Whether ``network`` has at least ``least`` agents that are copies but for their marked
    states (robots with homes of their own), beyond the groups of plain copies."""
    # (by name: each call of groups makes its own agents)
    alike = {frozenset(a.component.name for a in g.agents) for g in groups(network) if len(g.agents) >= least}
    return any(
        frozenset(a.component.name for a in g.agents) not in alike
        for g in groups(network, marking=False)
        if len(g.agents) >= least
    )


def counted(network: Network, least: int = 2, marking: bool = True) -> Counted:
    """The counter abstraction of ``network`` over its groups of at least ``least`` agents;
    raises :class:`NotSymmetric` saying why there is none. ``marking`` False: copies also where
    they differ in their marked states (robots with homes of their own: the counted network's
    marking then means nothing, see robosc.synthesis.counting.synthesis.synthesize_homes)."""
    found = [group for group in groups(network, marking) if len(group.agents) >= least]
    if not found:
        reason = NotSymmetric(f"no {least} components are copies of each other")
        homes = [group for group in groups(network, marking=False) if len(group.agents) >= least]
        if homes:  # copies but for where each may rest: a home of its own
            names = [a.component.name for a in homes[0].agents]
            reason = NotSymmetric(
                f"they differ in their marked states ({names[0]} .. {names[-1]}: each may rest in a place of its "
                "own), and synthesis counts only robots whose marked states are the same"
            )
            reason.robots = f"{names[0]} .. {names[-1]}"
            reason.homes = True
        raise reason
    copies = "; ".join(robots_of(group) for group in found)
    while True:  # each round splits a group into smaller ones, or ends
        try:
            return _counted(network, found)
        except Differ as differ:  # counted where their requirements say the same: the others apart
            found = _split(found, differ, least)
            if not found:
                differ.robots = copies
                raise
        except NotSymmetric as reason:
            reason.robots = copies
            raise


def apart(network: Network, least: int = 2) -> tuple[Counted, tuple[str, ...]]:
    """The counter abstraction of ``network`` with the first robot of each group of copies kept
    apart (its own automaton, as any component; the others counted where at least ``least`` are
    left): what one robot does can be followed, and stands for each of its group's. Returns the
    counted network and the robots kept apart; raises :class:`NotSymmetric` as :func:`counted`."""
    found = [group for group in groups(network) if len(group.agents) >= 2]
    if not found:
        raise NotSymmetric("no two components are copies of each other")
    kept = tuple(group.agents[0].component.name for group in found)
    rest = []
    for group in found:
        others = group.agents[1:]
        if len(others) >= least:
            rest.append(Group(group.name, others, {id(a): map_to_rep(a, others[0]) for a in others}))
    return _counted(network, rest), kept


def _split(found: list[Group], differ: Differ, least: int) -> list[Group]:
    """``found`` with ``differ.group`` split into its parts of at least ``least`` agents (the
    others tracked each on its own)."""
    group = differ.group
    parts = [part for part in differ.parts if len(part) >= least]
    kept = [g for g in found if g.name != group.name]  # (``_counted`` works on explored copies)
    for number, part in enumerate(parts, 1):
        name = group.name if len(parts) == 1 else f"{group.name}_{number}"
        kept.append(Group(name, tuple(part), {id(a): map_to_rep(a, part[0]) for a in part}))
    return kept


def _counted(network: Network, found: list[Group]) -> Counted:
    explored = [explore(network, group) for group in found]
    found = [group for group, _ in explored]
    translator = Translator(network, found)
    in_agents = {a.name for group in found for agent in group.agents for a in agent.automata}
    agent_events = {e for group in found for agent in group.agents for e in agent.events}
    agent_variables = {v for group in found for agent in group.agents for v in agent.variables}

    automata: list[Automaton] = []
    for automaton in network.automata:  # shared: kept, their guards and updates read through the counters
        if automaton.name in in_agents:
            continue
        shared = tuple(
            Edge(
                e.source,
                e.target,
                e.event,
                translator.about(e.guard, None, f"the guard of {automaton.name}'s {e.event.name}")
                if e.guard is not None
                else None,
                tuple(
                    Update(
                        u.variable, translator.about(u.value, None, f"{automaton.name}'s update of {u.variable.name}")
                    )
                    if u.value is not None
                    else u
                    for u in e.updates
                ),
            )
            for e in automaton.edges
        )
        automata.append(
            Automaton(
                automaton.name,
                automaton.kind,
                automaton.locations,
                automaton.initial,
                shared,
                automaton.alphabet,
                automaton.component,
            )
        )
    events = [e for e in network.events if e not in agent_events]
    requirements = [
        Requirement(r.event, translator.about(r.condition, None, r.said, requirement_span(r)), r.said, r.origin)
        for r in network.requirements
        if r.event not in agent_events
    ]
    moves: dict[Event, tuple[Group, tuple[Move, ...]]] = {}
    markers: list[m.Expr] = []
    initial_values = {v: network.initial_values[v] for v in network.variables if v not in agent_variables}
    for group, group_moves in explored:
        templates = check_requirements(network, translator, group)
        location = m.State("fleet", f"#{group.name}", True, True, NO_SPAN)
        edges: list[Edge] = []
        branches: dict[tuple[Event, int], list[Move]] = {}  # a move's outcomes: one event, as the robot's
        for move in group_moves:
            branches.setdefault((move.event, move.source), []).append(move)
        for (original, source), outcomes in branches.items():
            counter = group.counters[source]
            event = Event(
                f"{original.name}@{source}",
                original.controllable,
                original.kind,
                original.communication,
                original.transition,
                original.provide,
            )
            for move in outcomes:
                guard = at_least(counter, 1)
                if move.guard is not None:
                    template = translator.about(
                        move.guard, group.rep, f"the guard of {group.rep.component.name}'s {original.name}"
                    )
                    guard = all_of([guard, translator.instantiate(template, group, source)])
                updates: tuple[Update, ...] = ()
                if move.source != move.target:
                    target = group.counters[move.target]
                    updates = (
                        Update(counter, _add(counter, -1)),
                        Update(target, _add(target, 1)),
                    )
                edges.append(Edge(location, location, event, guard, updates))
            events.append(event)
            moves[event] = (group, tuple(outcomes))
            for requirement in network.requirements_on(original):
                condition = translator.instantiate(templates[id(requirement)], group, source)
                requirements.append(Requirement(event, condition, requirement.said, requirement.origin))
        automata.append(
            Automaton(
                f"#{group.name}",
                AutomatonKind.DATA,
                (location,),
                location,
                tuple(edges),
                frozenset(e.event for e in edges),
            )
        )
        unmarked = [i for i, (locations, _) in enumerate(group.local) if not all(loc.marked for loc in locations)]
        markers += [at_most(group.counters[i], 0) for i in unmarked]
        starts = [start_of(network, group, agent) for agent in group.agents]
        for state, counter in zip(group.local, group.counters, strict=True):
            initial_values[counter] = starts.count(state)
    variables = tuple(v for v in network.variables if v not in agent_variables) + tuple(
        c for group in found for c in group.counters
    )
    domains = {v: network.domains[v] for v in network.variables if v not in agent_variables}
    for group in found:
        for counter in group.counters:
            domains[counter] = range(len(group.agents) + 1)
    result = Network(
        network.model,
        tuple(events),
        tuple(automata),
        variables,
        domains,
        initial_values,
        tuple(requirements),
        all_of(markers) if markers else None,
        tuple((group.counters, len(group.agents)) for group in found),
    )
    return Counted(result, tuple(found), moves, translator)


def _add(counter: m.Variable, amount: int) -> m.Expr:
    ref = m.VariableRef(counter, (), counter.type, NO_SPAN)
    op = "+" if amount > 0 else "-"
    return m.Binary(op, ref, m.Literal(abs(amount), m.INTEGER, NO_SPAN), m.INTEGER, NO_SPAN)
