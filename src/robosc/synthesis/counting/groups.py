"""Finding a fleet's copies: an *agent* is a component with its communications' plants;
agents whose automata are the same up to renaming (the instances of ``component bot[N]``, or
components copied and renamed by hand) form a *group*, with each agent's names mapped to the
first agent's (the representative's). :class:`NotSymmetric` says why there is no group to count."""

from __future__ import annotations

import re
from typing import Any

from robosc.language import model as m
from robosc.language.render import render
from robosc.plant.network import Automaton, AutomatonKind, Event, Network
from robosc.record import field, record

LocalState = tuple[tuple[m.State, ...], tuple[object, ...]]  # locations of the agent's automata, its values


class NotSymmetric(Exception):
    """Why the counter abstraction does not apply (synthesis is then monolithic). ``robots``:
    the groups of copies found, when there were some (a fleet that could not be counted)."""

    robots: str = ""
    homes: bool = False  # copies but for their marked states (robots with homes of their own)


class Differ(NotSymmetric):
    """The agents of ``group`` are copies, but their requirements say different things of them
    (one singled out, ``r != bot1``): ``parts``, the agents whose requirements say the same."""

    def __init__(self, message: str, group: Group, parts: list[list[Agent]]) -> None:
        super().__init__(message)
        self.group = group
        self.parts = parts


@record(eq=False)
class Agent:
    component: m.Component
    automata: tuple[Automaton, ...]  # the component's automaton, then its communications' plants
    variables: tuple[m.Variable, ...]
    events: tuple[Event, ...]  # in the order the automata's edges first name them


@record(eq=False)
class Group:
    """Agents that are copies of ``agents[0]`` (the representative); ``to_rep``: each agent's
    states, variables and events -> the representative's."""

    name: str
    agents: tuple[Agent, ...]
    to_rep: dict[int, dict[Any, Any]] = field(repr=False)
    local: tuple[LocalState, ...] = ()  # the representative's local states
    counters: tuple[m.Variable, ...] = ()  # how many agents are in each local state

    @property
    def rep(self) -> Agent:
        return self.agents[0]


def _agents(network: Network) -> list[Agent]:
    by_name = {a.name: a for a in network.automata}
    agents = []
    for automaton in network.automata:
        component = automaton.component
        if automaton.kind is not AutomatonKind.COMPONENT or component is None:
            continue
        plants = []
        for c in component.communications:
            plants += [by_name[n] for n in (c.name, f"{c.name}_data") if n in by_name]
        automata = (automaton, *plants)
        events: list[Event] = []
        for a in automata:
            for edge in a.edges:
                if edge.event not in events:
                    events.append(edge.event)
        variables = tuple(v for v in network.variables if v.owner == component.name)
        agents.append(Agent(component, automata, variables, tuple(events)))
    return agents


def _own(agent: Agent) -> re.Pattern[str]:
    names = [re.escape(a.name) for a in agent.automata] + [re.escape(agent.component.name)]
    return re.compile(r"(?<![\w.])(" + "|".join(sorted(set(names), key=len, reverse=True)) + r")(?=\.)")


def _signature(agent: Agent, marking: bool = True) -> tuple[Any, ...]:
    """What two copies have in common: the automata's shapes, their own names replaced by
    their position, events by the order they first appear."""
    own = _own(agent)
    automaton_index = {a.name: f"#{i}" for i, a in enumerate(agent.automata)}
    automaton_index[agent.component.name] = "#0"

    def text(e: m.Expr | None) -> str:
        return "" if e is None else own.sub(lambda found: automaton_index[found.group(1)], render(e))

    event_index = {e: i for i, e in enumerate(agent.events)}
    shapes = []
    for a in agent.automata:
        locations = tuple((loc.name, loc.marked if marking else None) for loc in a.locations)
        edges = tuple(
            (
                edge.source.name,
                edge.target.name,
                event_index[edge.event],
                edge.event.controllable,
                edge.event.kind.value,
                text(edge.guard),
                tuple((u.variable.name, text(u.value)) for u in edge.updates),
            )
            for edge in a.edges
        )
        shapes.append((a.kind.value, locations, edges))
    variables = tuple((v.name, str(v.type)) for v in agent.variables)
    return tuple(shapes), variables


def map_to_rep(agent: Agent, rep: Agent) -> dict[Any, Any]:
    """The agent's states, variables, events and automata names -> the representative's."""
    found: dict[Any, Any] = {}
    for a, r in zip(agent.automata, rep.automata, strict=True):
        found[a.name] = r.name
        for loc, rloc in zip(a.locations, r.locations, strict=True):
            found[loc] = rloc
    found[agent.component.name] = rep.component.name
    for v, rv in zip(agent.variables, rep.variables, strict=True):
        found[v] = rv
    for e, re_ in zip(agent.events, rep.events, strict=True):
        found[e] = re_
    return found


def groups(network: Network, marking: bool = True) -> list[Group]:
    """The groups of two or more agents that are copies of each other (instances of one array,
    or components copied by hand), and whose events no automaton outside the agent shares.
    With ``marking`` False, copies but for which of their states are marked."""
    agents = _agents(network)
    owner_of_event: dict[Event, set[str]] = {}
    for automaton in network.automata:
        for event in automaton.alphabet:
            owner_of_event.setdefault(event, set()).add(automaton.name)
    by_signature: dict[Any, list[Agent]] = {}
    for agent in agents:
        names = {a.name for a in agent.automata}
        if any(not owner_of_event.get(e, set()) <= names for e in agent.events):
            continue  # an event shared with something outside the agent
        # instances of two arrays (`component east[4]`, `component south[4]`) are two kinds of
        # robots, even where their automata are alike: the requirements say which is which
        by_signature.setdefault((agent.component.group, _signature(agent, marking)), []).append(agent)
    found = []
    for members in by_signature.values():
        if len(members) < 2:
            continue
        group = members[0].component.group or members[0].component.name
        to_rep = {id(a): map_to_rep(a, members[0]) for a in members}
        found.append(Group(group, tuple(members), to_rep))
    return found


def robots_of(group: Group) -> str:
    names = [a.component.name for a in group.agents]
    return f"{names[0]} .. {names[-1]}" if len(names) > 2 else " and ".join(names)


MIN_AGENTS = 3  # a pair of copies (two bumpers, say) is synthesized monolithically: counting buys nothing


def owner_of(node: m.Expr) -> str:
    if isinstance(node, m.StateRef):
        return node.state.owner
    assert isinstance(node, m.VariableRef)
    return node.variable.owner


def names_of(agent: Agent) -> set[str]:
    return {a.name for a in agent.automata} | {agent.component.name}
