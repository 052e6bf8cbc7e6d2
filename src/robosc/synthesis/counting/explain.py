"""Explanations on a counted fleet (:mod:`robosc.synthesis.counting`), naming its robots.

Synthesis on a counted fleet knows how many robots are in each local state, not which. An
explanation is found on the counted network as on any network (:mod:`robosc.synthesis.why`:
a shortest run to a state where the supervisor disables the event, and what goes wrong
after it), and then followed with real robots: each counted step moves one robot from a
local state to another, so the run is replayed from the fleet's start with, at each step,
the first robot (in the model's order) that is in that local state. By symmetry this is a
run of the fleet itself, every step allowed by its supervisor; the explanation names
``bot2.go``, not "a robot". Its cost is the counted system's, a few breadth-first layers of
it, never the fleet's exponential state space."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from robosc.language.render import literal
from robosc.plant.network import Event, Network, Requirement
from robosc.synthesis.counting.groups import Agent, Group
from robosc.synthesis.counting.moves import start_of
from robosc.synthesis.counting.supervisor import CountedSupervisor
from robosc.synthesis.evaluate import Undefined, evaluate
from robosc.synthesis.explain import Probe, blocking, breaking, cut_way, cut_words, fixes, likeliest, ways_out
from robosc.synthesis.explicit import Edges, successors
from robosc.synthesis.result import Explanation, Fix, Restriction, Step
from robosc.synthesis.state import NetworkState, describe, describe_parts
from robosc.synthesis.why import Reasons, reasons


def local_label(group: Group, index: int) -> str:
    """A local state of a group's robots in words: its component's state, the states of its
    communications that are busy, its variables."""
    locations, values = group.local[index]
    rep = group.rep
    parts = [locations[0].name]
    parts += [
        f"{a.name.split('.')[-1]} {loc.name}" for a, loc in zip(rep.automata[1:], locations[1:], strict=True) if loc is not a.initial
    ]
    parts += [f"{v.name} = {literal(value)}" for v, value in zip(rep.variables, values, strict=True)]
    return ", ".join(parts)


def describer(supervisor: CountedSupervisor) -> Callable[[NetworkState], str]:
    """A counted network's state in words: the shared components as usual, and for each group
    how many of its robots are in each local state (``bot: 2 in depot, 1 in out1``)."""
    fleet = supervisor.fleet
    counted = fleet.network
    counters = {c for group in fleet.groups for c in group.counters}

    def words(state: NetworkState) -> str:
        parts = describe_parts(
            ((a, loc) for a, loc in zip(counted.automata, state.locations, strict=True) if not a.name.startswith("#")),
            ((v, x) for v, x in zip(counted.variables, state.values, strict=True) if v not in counters),
        )
        values = dict(zip(counted.variables, state.values, strict=True))
        for group in fleet.groups:
            held = [f"{values[c]} in {local_label(group, i)}" for i, c in enumerate(group.counters) if values[c]]
            parts.append(f"{group.name}: {'; '.join(held)}")
        return ", ".join(parts)

    return words


class Robots:
    """A run of the counted network followed with the fleet's robots: which robot is in which
    local state, and the fleet's state and events that go with each counted step."""

    def __init__(self, supervisor: CountedSupervisor, replay: list[Agent] | None = None) -> None:
        self.supervisor = supervisor
        self.moved: list[Agent] = []  # the robot that made each move, in turn
        self.replay = list(replay) if replay is not None else None  # the robots to move, in turn
        self.network = supervisor.network
        fleet = supervisor.fleet
        self.where: dict[int, int] = {}  # agent (id) -> index of its local state
        self.owner: dict[str, tuple[Group, Agent, int]] = {}  # automaton name -> its agent, its place
        self.owner_of_variable: dict[Any, tuple[Group, Agent, int]] = {}  # an agent's variable -> the same
        for group in fleet.groups:
            index = supervisor.index[group.name]
            for agent in group.agents:
                self.where[id(agent)] = index[start_of(self.network, group, agent)]
                for place, automaton in enumerate(agent.automata):
                    self.owner[automaton.name] = (group, agent, place)
                for place, variable in enumerate(agent.variables):
                    self.owner_of_variable[variable] = (group, agent, place)
        self.back = {
            id(agent): {rep: mine for mine, rep in group.to_rep[id(agent)].items()}
            for group in fleet.groups
            for agent in group.agents
        }
        self.started = dict(self.where)  # where each robot starts
        self.counted_at = {a.name: i for i, a in enumerate(fleet.network.automata)}
        self.counted_value = {v: i for i, v in enumerate(fleet.network.variables)}

    def step(
        self, event: Event, reached: NetworkState, prefer: Event | None = None, spare: Event | None = None
    ) -> tuple[Event, NetworkState]:
        """The fleet's event for counted ``event`` and the fleet's state after it: the first robot
        in its source state moves; the robot of ``prefer`` if it is there; the robot of
        ``spare`` only if no other is there (kept for the restricted event at the end)."""
        move = self.supervisor.fleet.moves.get(event)
        if move is not None:
            group, outcomes = move
            source = outcomes[0].source
            here = [a for a in group.agents if self.where[id(a)] == source]
            wanted = self.agent(prefer)
            kept = self.agent(spare)
            agent = wanted if wanted in here else next((a for a in here if a is not kept), here[0])
            if self.replay:
                agent = self.replay.pop(0)
            self.moved.append(agent)
            counts = [reached.values[self.counted_value[c]] for c in group.counters]
            for outcome in outcomes:  # the outcome that leads to the counts reached
                self.where[id(agent)] = outcome.target
                if [sum(self.where[id(a)] == i for a in group.agents) for i in range(len(group.local))] == counts:
                    break
            event = self.back[id(agent)][outcomes[0].event]
        return event, self.state(reached)

    def swapped(self, one: Agent, other: Agent) -> Robots | None:
        """A new follower that moves ``other`` where this one moved ``one`` and the other way
        round; None unless the two start in the same place (then they are alike: a run of one
        is a run of the other)."""
        if self.started[id(one)] != self.started[id(other)]:
            return None
        swap = {id(one): other, id(other): one}
        return Robots(self.supervisor, [swap.get(id(a), a) for a in self.moved])

    def agent(self, event: Event | None) -> Agent | None:
        owner = self.supervisor.agent_of_event.get(event) if event is not None else None
        return owner[1] if owner is not None else None

    def state(self, counted: NetworkState) -> NetworkState:
        """The fleet's state: shared parts from the counted state, each robot's from where it is."""
        locations = []
        for automaton in self.network.automata:
            owner = self.owner.get(automaton.name)
            if owner is None:
                locations.append(counted.locations[self.counted_at[automaton.name]])
                continue
            group, agent, place = owner
            locations.append(self.back[id(agent)][group.local[self.where[id(agent)]][0][place]])
        values = []
        for variable in self.network.variables:
            mine = self.owner_of_variable.get(variable)
            if mine is None:
                values.append(counted.values[self.counted_value[variable]])
                continue
            group, agent, place = mine
            values.append(group.local[self.where[id(agent)]][1][place])
        return NetworkState(tuple(locations), tuple(values))


def explicit_probe(network: Network) -> Probe:
    """A :class:`Probe` of the fleet's own network, asked state by state (its states are too
    many for BDDs over each robot, but one state is cheap to ask about)."""

    def holds(requirement: Requirement, state: NetworkState) -> bool:
        try:
            return bool(evaluate(requirement.condition, set(state.locations), dict(zip(network.variables, state.values, strict=True))))
        except Undefined:
            return False

    edges = Edges(network)
    return Probe(network, lambda event, state: next(successors(edges, state, event), None) is not None, holds)


def counted_reasons(fp: Any, candidates: list[Event]) -> list[Reasons]:
    """The counted explanations of those of ``candidates`` the supervisor restricts."""
    found = []
    for candidate in candidates:
        key = ("counted reasons", candidate)
        if key not in fp.memo:
            fp.memo[key] = reasons(fp, candidate)
        if fp.memo[key] is not None:
            found.append(fp.memo[key])
    return found


def counted_why(supervisor: CountedSupervisor, event: Event) -> Restriction | None:
    """Why the supervisor of a counted fleet disables ``event`` (of the fleet's network)
    somewhere its plant and requirements allow it, with the fleet's robots named; None when it
    never does. When the robot of ``event`` cannot be the one restricted in that run (robots
    that start elsewhere), the run is shown for the robot that is, and the restriction says so."""
    fp = supervisor.fp
    found = counted_reasons(fp, supervisor.restricted_of(event))
    if not found:
        return None
    best = min(found, key=lambda r: len(r.run))
    network = supervisor.network
    robots = Robots(supervisor)

    def follow() -> tuple[list[tuple[Event, NetworkState]], NetworkState, Event, NetworkState, list[tuple[Event, NetworkState]]]:
        run = [robots.step(e, reached, spare=event) for e, reached in best.run]
        there = robots.state(best.state)
        restricted, after = robots.step(best.event, best.after, prefer=event)
        return run, there, restricted, after, [robots.step(e, reached) for e, reached in best.consequence]

    run, state, restricted, after, consequence = follow()
    mine, theirs = robots.agent(event), robots.agent(restricted)
    if restricted is not event and mine is not None and theirs is not None:
        # the robot of the run is another that started where event's robot did: the same run
        # with the two swapped is event's own
        alike_robots = robots.swapped(theirs, mine)
        if alike_robots is not None:
            robots = alike_robots
            run, state, restricted, after, consequence = follow()

    def steps(path: list[tuple[Event, NetworkState]]) -> tuple[Step, ...]:
        return tuple(Step(e, describe(network, reached)) for e, reached in path)

    last = consequence[-1][1] if consequence else after  # where it breaks a requirement, or blocks
    asked = explicit_probe(network)
    described = describe(network, last)
    reason = breaking(asked, last, described)
    found_fixes: tuple[Fix, ...] = ()
    if reason is None:
        # where the shortest way on is cut, found on the counted network and followed with the robots
        cut = cut_way(fp, best.consequence[-1][1] if best.consequence else best.after)
        trap = None
        proposed = fixes(asked, last)
        if cut is not None:
            route, counted_event, counted_reached, dead = cut
            events = [robots.step(e, reached)[0] for e, reached in route]
            event_there, reached = robots.step(counted_event, counted_reached)
            exits = ways_out(asked, reached) if dead else []
            trap = cut_words(events, event_there, describe(network, reached), dead, exits)
            if dead:
                proposed += fixes(asked, reached)
        reason = blocking(asked, last, described, trap)
        found_fixes = likeliest(proposed)
    explanation = Explanation(reason, describe(network, after), steps(consequence), found_fixes)
    owner = supervisor.agent_of_event.get(event)
    alike = ""
    if owner is not None:
        names = [a.component.name for a in owner[0].agents]
        alike = f"the same for every robot of {owner[0].name} ({names[0]} .. {names[-1]})"
        if restricted is not event:
            alike += f"; shown for {restricted.name}, as {event.name} cannot be the one restricted here"
    return Restriction(
        restricted,
        steps(run),
        describe(network, state),
        describe(network, after),
        explanation,
        supervisor.never_allows(event),  # from no local state
        alike,
    )
