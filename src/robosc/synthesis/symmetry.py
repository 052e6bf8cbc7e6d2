"""Synthesis for fleets of identical robots: the counter abstraction of symmetric agents.

An *agent* is a component with its communications' plants. Agents whose automata are the
same up to renaming (the instances of ``component bot[N]``, or components copied and
renamed by hand) form a *group*. When every guard and requirement treats a group's agents
alike (each agent's requirements are the same up to renaming, and other agents appear only
through ``all``/``any``/``count`` over the whole group, or the chains of ``and``/``or`` those
expand to), the state of the fleet matters only up to permuting agents: synthesis may count
how many agents are in each local state instead of tracking which agent is where.

The counted network (one counter per local state, an event per local transition of a
group's representative) goes through the same fixed point as any network (symbolic.py);
its size grows polynomially with the number of agents where the monolithic network's
grows exponentially. Because the system is symmetric, its bad states and the supervisor's
guards are those of the monolithic method, read through the counters: each added guard is
written with ``count(...)`` over the group, which the runtime evaluates as it is.

When no group qualifies, :func:`counted` says why and synthesis is monolithic.
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from robosc.language import model as m
from robosc.language.render import render
from robosc.language.simplify import boolean_constant, fold, replace
from robosc.plant.expressions import FALSE, NO_SPAN, TRUE, all_of, any_of, negate
from robosc.plant.network import Automaton, AutomatonKind, Edge, Event, Network, Requirement, Update
from robosc.record import field, record
from robosc.synthesis.evaluate import Undefined, evaluate

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


# ---- finding the groups ---------------------------------------------------------------------


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


def _map(agent: Agent, rep: Agent) -> dict[Any, Any]:
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
        to_rep = {id(a): _map(a, members[0]) for a in members}
        found.append(Group(group, tuple(members), to_rep))
    return found


# ---- the representative's local states and moves -------------------------------------------


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
                isinstance(n, (m.StateRef, m.VariableRef)) and _owner(n) not in _names(agent)
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


def _owner(node: m.Expr) -> str:
    if isinstance(node, m.StateRef):
        return node.state.owner
    assert isinstance(node, m.VariableRef)
    return node.variable.owner


def _names(agent: Agent) -> set[str]:
    return {a.name for a in agent.automata} | {agent.component.name}


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


# ---- conditions over the fleet, read through the counters -----------------------------------


def _flatten(e: m.Expr, op: str) -> list[m.Expr]:
    if isinstance(e, m.Binary) and e.op == op:
        return _flatten(e.left, op) + _flatten(e.right, op)
    return [e]


def at_least(counter: m.Variable, bound: int) -> m.Expr:
    ref = m.VariableRef(counter, (), counter.type, NO_SPAN)
    return m.Binary(">=", ref, m.Literal(bound, m.INTEGER, NO_SPAN), m.BOOLEAN, NO_SPAN)


def _le(counter: m.Variable, bound: int) -> m.Expr:
    ref = m.VariableRef(counter, (), counter.type, NO_SPAN)
    return m.Binary("<=", ref, m.Literal(bound, m.INTEGER, NO_SPAN), m.BOOLEAN, NO_SPAN)


def _value(variable: m.Variable, value: object) -> m.Expr:
    if isinstance(value, m.EnumValue):
        assert isinstance(variable.type, m.EnumType)
        return m.EnumLiteral(variable.type, value, NO_SPAN)
    return m.Literal(value, variable.type, NO_SPAN)  # type: ignore[arg-type]


class Translator:
    """Conditions over the fleet as conditions over counters. A *template* is written over
    shared state, the counters, and the representative's own state standing for the agent
    the condition is about (``self``: the agent whose event it guards, None for none).

    Exact by construction (docs/synthesis-options.md, *Why counting is exact*): a part of a
    condition that reads one other agent is read at each local state that agent may be in,
    what is left reading shared state and ``self`` only; a chain of such parts over every
    other agent of a group says "some" (``or``) or "every" (``and``) other agent is in a
    local state where the part holds, and a count adds, local state by local state, the
    counter times the number of the agent's terms that hold there. Anything else that names
    an agent of a group (two other agents in one part, some agents and not others, agents
    asked different things, a number read from another agent) raises :class:`NotSymmetric`
    and synthesis is monolithic."""

    def __init__(self, network: Network, found: Sequence[Group]) -> None:
        self.network = network
        self.groups = list(found)
        self.agent_of: dict[str, tuple[Group, Agent]] = {}
        for group in self.groups:
            for agent in group.agents:
                for name in _names(agent):
                    self.agent_of[name] = (group, agent)
        self.by_id = {id(a): (g, a) for g in self.groups for a in g.agents}
        self._agents: dict[int, tuple[m.Expr, frozenset[int]]] = {}  # the expression kept: its id stays its own
        self._residuals: dict[Any, tuple[m.Expr, ...]] = {}

    def agents_in(self, e: m.Expr) -> frozenset[int]:
        """The agents (by id) that ``e`` reads."""
        found = self._agents.get(id(e))
        if found is None:
            ids = set()
            for node in m.walk(e):
                if isinstance(node, (m.StateRef, m.VariableRef)):
                    owner = self.agent_of.get(_owner(node))
                    if owner is not None:
                        ids.add(id(owner[1]))
            found = self._agents[id(e)] = (e, frozenset(ids))
        return found[1]

    def rename(self, e: m.Expr, agent: Agent) -> m.Expr:
        """``e`` with ``agent``'s own states and variables renamed to the representative's."""
        group, _ = self.agent_of[agent.component.name]
        mapping = group.to_rep[id(agent)]
        if agent is group.rep:
            return e

        return rename_back(e, mapping)

    def at(self, group: Group, index: int) -> m.Expr:
        """The representative is in local state ``index``."""
        locations, values = group.local[index]
        parts: list[m.Expr] = [
            m.StateRef(loc, NO_SPAN)
            for a, loc in zip(group.rep.automata, locations, strict=True)
            if len(a.locations) > 1
        ]
        for variable, value in zip(group.rep.variables, values, strict=True):
            parts.append(
                m.Binary(
                    "=",
                    m.VariableRef(variable, (), variable.type, NO_SPAN),
                    _value(variable, value),
                    m.BOOLEAN,
                    NO_SPAN,
                )
            )
        return all_of(parts)

    def residuals(self, group: Group, e: m.Expr, agent: Agent, me: Agent | None) -> tuple[m.Expr, ...]:
        """For each local state of ``group``: ``e`` with ``agent`` (not ``me``) there, its own
        states and variables replaced by their values; what is left reads shared state and
        ``me`` (renamed to its representative's) only."""
        key = (id(group), self._shape(e, group.to_rep[id(agent)], self._names(me)))
        cached = self._residuals.get(key)
        if cached is not None:  # another agent's part, the same up to renaming: the same residuals
            return cached
        found = []
        mine = {id(self.agent_of[me.component.name][0].rep)} if me is not None else set()  # me, renamed
        for index in range(len(group.local)):
            residual = settle(_placed(e, group, agent, index))
            if me is not None:
                residual = self.rename(residual, me)
            if self.agents_in(residual) - mine:
                raise NotSymmetric(f"'{render(e)}' reads two other agents in one part")
            found.append(residual)
        self._residuals[key] = tuple(found)
        return self._residuals[key]

    def _names(self, me: Agent | None) -> dict[Any, Any]:
        if me is None:
            return {}
        return self.agent_of[me.component.name][0].to_rep[id(me)]

    def _shape(self, e: m.Expr, theirs: dict[Any, Any], mine: dict[Any, Any]) -> Any:
        """``e`` as a nested tuple in which another agent's states and variables (``theirs``:
        renamed to the representative's) and ``me``'s (``mine``) are told apart by role, not
        by name: two agents' parts with one shape leave the same residuals."""
        if isinstance(e, m.StateRef):
            ref: Any = e.state
        elif isinstance(e, m.VariableRef):
            ref = e.variable
        elif isinstance(e, m.Unary):
            return (e.op, self._shape(e.operand, theirs, mine))
        elif isinstance(e, m.Binary):
            return (e.op, self._shape(e.left, theirs, mine), self._shape(e.right, theirs, mine))
        elif isinstance(e, m.Count):
            return ("count", *(self._shape(term, theirs, mine) for term in e.terms))
        elif isinstance(e, m.Literal):
            return ("literal", repr(e.value), str(e.type))
        elif isinstance(e, m.EnumLiteral):
            return ("enum", e.value.name)
        else:
            return ("node", id(e))
        steps = tuple(repr(s) for s in e.steps) if isinstance(e, m.VariableRef) else ()
        if ref in theirs:
            return ("theirs", id(theirs[ref]), steps)
        if ref in mine:
            return ("mine", id(mine[ref]), steps)
        return ("shared", id(ref), steps)

    def about(self, e: m.Expr, me: Agent | None, what: str | Callable[[], str], span: Any = None) -> m.Expr:
        """:meth:`template`, a failure said of ``what`` (a requirement, a guard; or how to write
        it) and where it is."""
        try:
            return self.template(e, me)
        except NotSymmetric as reason:
            place = span if span is not None else e.span
            at = f" ({place.path}:{place.line}:{place.column})" if place.line else ""
            said = what if isinstance(what, str) else what()
            raise NotSymmetric(f"{said}{at}: {reason}") from None

    def template(self, e: m.Expr, me: Agent | None) -> m.Expr:
        mine = id(me) if me is not None else None
        others = self.agents_in(e) - {mine}
        if not others:
            return self.rename(e, me) if me is not None else e
        if isinstance(e, m.Unary) and e.op == "!":
            return negate(self.template(e.operand, me))
        if isinstance(e, m.Binary) and e.op in ("and", "or"):
            return self._chain(_flatten(e, e.op), e.op, me)
        if isinstance(e, m.Count):
            return self._count(e, me)
        if len(others) == 1 and _boolean(e):  # of a group of two: `!R1.charging` for R0
            return self._chain([e], "or", me)
        if isinstance(e, m.Binary):  # a comparison or sum of counts, say: each side read through the counters
            return m.Binary(e.op, self.template(e.left, me), self.template(e.right, me), e.type, e.span)
        raise NotSymmetric(f"'{render(e)}' reads a value of one agent of a group of copies")

    def _buckets(
        self, operands: Sequence[m.Expr], me: Agent | None
    ) -> tuple[list[m.Expr], dict[int, tuple[Group, Agent, list[m.Expr]]]]:
        """The operands that name no other agent (as templates), and the others by the one
        other agent they name."""
        mine = id(me) if me is not None else None
        kept: list[m.Expr] = []
        buckets: dict[int, tuple[Group, Agent, list[m.Expr]]] = {}
        for operand in operands:
            others = self.agents_in(operand) - {mine}
            if not others:
                kept.append(self.rename(operand, me) if me is not None else operand)
            elif len(others) == 1 and _boolean(operand):
                (agent_id,) = others
                group, agent = self.by_id[agent_id]
                buckets.setdefault(agent_id, (group, agent, []))[2].append(operand)
            else:
                kept.append(self.template(operand, me))
        return kept, buckets

    def _over_group(
        self, buckets: dict[int, tuple[Group, Agent, list[m.Expr]]], me: Agent | None, op: str | None
    ) -> Iterator[tuple[Group, list[tuple[m.Expr, ...]], bool]]:
        """Per group: for each of an other agent's parts (its operands joined by ``op``, or
        each term for None), what it leaves at each local state (the same for every other agent,
        or not symmetric); and whether ``me`` is one of the group."""
        per_group: dict[str, list[tuple[Group, Agent, list[m.Expr]]]] = {}
        for entry in buckets.values():
            per_group.setdefault(entry[0].name, []).append(entry)
        for entries in per_group.values():
            group = entries[0][0]
            mine_in = me is not None and any(a is me for a in group.agents)
            expected = {id(a) for a in group.agents} - ({id(me)} if mine_in else set())
            if {id(agent) for _, agent, _ in entries} != expected:
                raise NotSymmetric(f"a condition names some agents of '{group.name}' and not the others")
            each = []
            for _, agent, operands in entries:
                joined = [_join(op, operands)] if op is not None else operands
                each.append(sorted((self.residuals(group, part, agent, me) for part in joined), key=id))
            # parts of one shape share their residuals (cached): told apart by identity, and only
            # where that differs by what they leave, written out
            if len({tuple(map(id, parts)) for parts in each}) != 1 and (
                len({tuple(sorted(map(_rendered, parts))) for parts in each}) != 1
            ):
                raise NotSymmetric(f"a condition asks different things of the agents of '{group.name}'")
            yield group, each[0], mine_in

    def _chain(self, operands: Sequence[m.Expr], op: str, me: Agent | None) -> m.Expr:
        kept, buckets = self._buckets(operands, me)
        for group, [residual], mine_in in self._over_group(buckets, me, op):
            parts = []
            for index, holds in enumerate(residual):
                counter = group.counters[index]
                if op == "or":  # another agent of the group is in a local state where its part holds
                    if boolean_constant(holds) is False:
                        continue
                    some = at_least(counter, 1)
                    if mine_in:
                        some = any_of(
                            [at_least(counter, 2), all_of([negate(self.at(group, index)), at_least(counter, 1)])]
                        )
                    parts.append(some if boolean_constant(holds) is True else all_of([some, holds]))
                else:  # every other agent of the group is in a local state where its part holds
                    if boolean_constant(holds) is True:
                        continue
                    none = _le(counter, 0)
                    if mine_in:
                        none = any_of([none, all_of([self.at(group, index), _le(counter, 1)])])
                    parts.append(none if boolean_constant(holds) is False else any_of([none, holds]))
            kept.append(_join(op, parts))
        return _join(op, kept)

    def _count(self, e: m.Count, me: Agent | None) -> m.Expr:
        kept, buckets = self._buckets(e.terms, me)
        total: list[m.Expr] = (
            [m.Count("", tuple(kept), m.BasicType(m.BasicKind.INTEGER, 0, len(kept)), e.span)] if kept else []
        )
        for group, residuals, mine_in in self._over_group(buckets, me, None):
            mine: list[m.Expr] = []  # the terms an other agent has, were it ``me``
            for index, counter in enumerate(group.counters):
                holding = [r[index] for r in residuals if boolean_constant(r[index]) is not False]
                if not holding:
                    continue
                ref: m.Expr = m.VariableRef(counter, (), counter.type, NO_SPAN)
                # how many hold depends on shared state or on me
                if any(boolean_constant(h) is not True for h in holding):
                    weight: m.Expr = m.Count(
                        "", tuple(holding), m.BasicType(m.BasicKind.INTEGER, 0, len(holding)), e.span
                    )
                    total.append(m.Binary("*", ref, weight, m.INTEGER, e.span))
                elif len(holding) == 1:
                    total.append(ref)
                else:
                    total.append(m.Binary("*", ref, m.Literal(len(holding), m.INTEGER, e.span), m.INTEGER, e.span))
                if mine_in:  # the agent itself is counted in the counters, not among the others
                    mine += [all_of([self.at(group, index), h]) for h in holding]
            if mine:
                own = m.Count("", tuple(mine), m.BasicType(m.BasicKind.INTEGER, 0, len(mine)), e.span)
                total.append(m.Unary("-", own, m.INTEGER, e.span))
        if not total:
            return m.Literal(0, m.INTEGER, e.span)
        result = total[0]
        for part in total[1:]:
            result = m.Binary("+", result, part, m.INTEGER, e.span)
        return result

    def instantiate(self, template: m.Expr, group: Group, index: int) -> m.Expr:
        """A template with the representative in local state ``index``: its own state known."""
        return fold(_placed(template, group, group.rep, index))


def _placed(e: m.Expr, group: Group, agent: Agent, index: int) -> m.Expr:
    """``e`` with ``agent``'s own states and variables replaced by their values where the
    representative's are in local state ``index``."""
    mapping = group.to_rep[id(agent)]
    locations, values = group.local[index]
    here = set(locations)
    known = dict(zip(group.rep.variables, values, strict=True))

    def local(node: m.Expr) -> m.Expr | None:
        if isinstance(node, m.StateRef) and node.state in mapping:
            return TRUE if mapping[node.state] in here else FALSE
        if isinstance(node, m.VariableRef) and node.variable in mapping:
            if node.steps:
                raise NotSymmetric(f"'{render(e)}' reads a part of an agent's variable")
            rep = mapping[node.variable]
            return _value(rep, known[rep])
        return None

    return replace(e, local)


def _boolean(e: m.Expr) -> bool:
    return isinstance(e.type, m.BasicType) and e.type.kind is m.BasicKind.BOOLEAN


def _rendered(parts: Sequence[m.Expr]) -> tuple[str, ...]:
    return tuple(render(p) for p in parts)


def settle(e: m.Expr) -> m.Expr:
    """``e`` with every part that reads no state or variable replaced by its value, and the
    boolean constants folded away."""

    def constant(node: m.Expr) -> m.Expr | None:
        if isinstance(node, (m.Literal, m.EnumLiteral)):
            return node
        if any(isinstance(n, (m.StateRef, m.VariableRef, m.DataRef, m.Invalid)) for n in m.walk(node)):
            return None
        try:
            value = evaluate(node, set(), {})
        except Undefined as exc:
            raise NotSymmetric(f"'{render(node)}' has no value") from exc
        if isinstance(value, m.EnumValue):
            assert isinstance(node.type, m.EnumType)
            return m.EnumLiteral(node.type, value, node.span)
        return m.Literal(value, node.type, node.span)

    return fold(replace(e, constant))


def _join(op: str, parts: Sequence[m.Expr]) -> m.Expr:
    return all_of(parts) if op == "and" else any_of(parts)


# ---- the counted network -------------------------------------------------------------------


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
    marking then means nothing, see robosc.synthesis.counted.synthesize_homes)."""
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


def _split(found: list[Group], differ: Differ, least: int) -> list[Group]:
    """``found`` with ``differ.group`` split into its parts of at least ``least`` agents (the
    others tracked each on its own)."""
    group = differ.group
    parts = [part for part in differ.parts if len(part) >= least]
    kept = [g for g in found if g.name != group.name]  # (``_counted`` works on explored copies)
    for number, part in enumerate(parts, 1):
        name = group.name if len(parts) == 1 else f"{group.name}_{number}"
        kept.append(Group(name, tuple(part), {id(a): _map(a, part[0]) for a in part}))
    return kept


def robots_of(group: Group) -> str:
    names = [a.component.name for a in group.agents]
    return f"{names[0]} .. {names[-1]}" if len(names) > 2 else " and ".join(names)


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
        Requirement(r.event, translator.about(r.condition, None, r.said, _span(r)), r.said, r.origin)
        for r in network.requirements
        if r.event not in agent_events
    ]
    moves: dict[Event, tuple[Group, tuple[Move, ...]]] = {}
    markers: list[m.Expr] = []
    initial_values = {v: network.initial_values[v] for v in network.variables if v not in agent_variables}
    for group, group_moves in explored:
        templates = _check_requirements(network, translator, group)
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
        markers += [_le(group.counters[i], 0) for i in unmarked]
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


def _span(requirement: Requirement) -> Any:
    return requirement.origin.span if requirement.origin is not None else None


def _said_of(translator: Translator, e: m.Expr, me: Agent, swapped: Agent) -> str | None:
    """``e`` written out as seen from ``me``, the chains of ``and`` and ``or`` and a count's terms
    in a fixed order: ``me``'s states and variables as ``@`` and its representative's, another
    agent's by its name and its representative's, with ``swapped`` (the group's representative)
    named as ``me``. Seen from the representative and from agent k, a requirement says the same
    where k's says of k and of the representative what the representative's says of itself and
    of k (the two swapped), and of every other agent the same. None for an expression it does
    not know."""
    table = translator.agent_of[me.component.name][0].to_rep[id(me)]

    def ref(node: m.StateRef | m.VariableRef) -> str:
        item: Any = node.state if isinstance(node, m.StateRef) else node.variable
        steps = repr(node.steps) if isinstance(node, m.VariableRef) and node.steps else ""
        owner = translator.agent_of.get(_owner(node))
        if owner is None:
            return f"s{id(item)}{steps}"
        group, agent = owner
        if agent is me:
            return f"@{id(table.get(item, item))}{steps}"
        name = me.component.name if agent is swapped else agent.component.name
        return f"{name}:{id(group.to_rep[id(agent)].get(item, item))}{steps}"

    def said(node: m.Expr) -> str | None:
        if isinstance(node, m.StateRef | m.VariableRef):
            return ref(node)
        if isinstance(node, m.Literal):
            return f"L{node.value!r}:{node.type}"
        if isinstance(node, m.EnumLiteral):
            return f"E{id(node.value)}"
        if isinstance(node, m.Unary):
            inner = said(node.operand)
            return None if inner is None else f"{node.op}({inner})"
        parts: list[str | None]
        if isinstance(node, m.Count):
            parts = [said(term) for term in node.terms]
        elif isinstance(node, m.Binary) and node.op in ("and", "or"):
            parts = []
            stack: list[m.Expr] = [node]
            while stack:  # the chain's operands (a chain over a fleet is as long as the fleet)
                top = stack.pop()
                if isinstance(top, m.Binary) and top.op == node.op:
                    stack += [top.right, top.left]
                else:
                    parts.append(said(top))
        elif isinstance(node, m.Binary):
            left, right = said(node.left), said(node.right)
            return None if left is None or right is None else f"({left}){node.op}({right})"
        else:
            return None
        if any(part is None for part in parts):
            return None
        op = node.op if isinstance(node, m.Binary) else "count"
        return f"{op}[{','.join(sorted(p for p in parts if p is not None))}]"

    return said(e)


def _check_requirements(network: Network, translator: Translator, group: Group) -> dict[int, m.Expr]:
    """Each agent's requirements say of it what the representative's say of the representative;
    the representative's templates, by requirement (``id``).

    An agent whose requirements say of it and the representative what the representative's say
    of itself and of that agent, and of every other agent the same (:func:`_said_of`), has the
    representative's templates without being translated: the translation of the
    representative's requirements treats all other agents alike (or fails), so each agent's
    requirements are the representative's with the two swapped, and the fleet's requirements
    are the same under every permutation of its agents. (Translating each robot's
    requirements, which name every robot, took 118 s for 500 robots.)"""
    templates: dict[int, m.Expr] = {}
    by_texts: dict[tuple[tuple[str, str], ...], list[Agent]] = {}
    described: dict[tuple[str, str], Requirement] = {}  # (event, template) -> the requirement
    rep = group.rep
    seen: tuple[list[tuple[str, str | None]], tuple[tuple[str, str], ...]] | None = None  # the rep's, its texts
    for agent in group.agents:
        mapping = group.to_rep[id(agent)]
        requirements = [r for e in agent.events for r in network.requirements_on(e)]
        says = sorted(
            ((mapping[r.event].name, _said_of(translator, r.condition, agent, rep)) for r in requirements),
            key=lambda pair: (pair[0], pair[1] or ""),
        )
        if seen is not None and all(said is not None for _, said in says) and says == seen[0]:
            by_texts[seen[1]].append(agent)
            continue
        mine = {id(r): (r, translator.about(r.condition, agent, r.said, _span(r))) for r in requirements}
        texts = tuple(sorted((mapping[r.event].name, render(template)) for r, template in mine.values()))
        for r, template in mine.values():
            described.setdefault((mapping[r.event].name, render(template)), r)
        if not by_texts:
            templates = {key: template for key, (_, template) in mine.items()}
            seen = (says, texts)
        by_texts.setdefault(texts, []).append(agent)
    if len(by_texts) > 1:
        first, other = list(by_texts)[:2]
        agent = by_texts[other][0]
        differs = sorted(set(first) ^ set(other))
        lacking = group.rep.component.name if differs[0] in other else agent.component.name
        raise Differ(
            f"the requirements of '{agent.component.name}' differ from those of '{group.rep.component.name}' "
            f"({described[differs[0]].description} has no counterpart for '{lacking}')",
            group,
            list(by_texts.values()),
        )
    return templates


# ---- synthesis ------------------------------------------------------------------------------


class CountedSupervisor:
    """The supervisor a counted synthesis found, asked about states of the original network."""

    def __init__(self, network: Network, fleet: Counted, fixpoint: Any) -> None:
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


def rename_back(e: m.Expr, names: dict[Any, Any]) -> m.Expr:
    """``e`` with the states and variables ``names`` maps renamed (one agent's to another's)."""

    def renamed(node: m.Expr) -> m.Expr | None:
        if isinstance(node, m.StateRef) and node.state in names:
            return m.StateRef(names[node.state], node.span)
        if isinstance(node, m.VariableRef) and node.variable in names:
            return m.VariableRef(names[node.variable], node.steps, node.type, node.span)
        return None

    return replace(e, renamed)


MIN_AGENTS = 3  # a pair of copies (two bumpers, say) is synthesized monolithically: counting buys nothing
