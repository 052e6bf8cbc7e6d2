"""Requirements and guards translated into counts: an expression that names a group's agents
only through ``all``/``any``/``count`` over the group (or the chains of ``and``/``or`` those
expand to), and its own agent as itself, becomes an expression over the group's counters
(:class:`Translator`); each agent's requirements are checked to say of it what the
representative's say of the representative (:func:`check_requirements`)."""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from typing import Any

from robosc.language import model as m
from robosc.language.render import render
from robosc.language.simplify import boolean_constant, fold, replace
from robosc.plant.expressions import FALSE, NO_SPAN, TRUE, all_of, any_of, negate
from robosc.plant.network import Network, Requirement
from robosc.synthesis.counting.groups import Agent, Differ, Group, NotSymmetric, names_of, owner_of
from robosc.synthesis.evaluate import Undefined, evaluate


def _flatten(e: m.Expr, op: str) -> list[m.Expr]:
    if isinstance(e, m.Binary) and e.op == op:
        return _flatten(e.left, op) + _flatten(e.right, op)
    return [e]


def at_least(counter: m.Variable, bound: int) -> m.Expr:
    ref = m.VariableRef(counter, (), counter.type, NO_SPAN)
    return m.Binary(">=", ref, m.Literal(bound, m.INTEGER, NO_SPAN), m.BOOLEAN, NO_SPAN)


def at_most(counter: m.Variable, bound: int) -> m.Expr:
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
                for name in names_of(agent):
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
                    owner = self.agent_of.get(owner_of(node))
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
                    none = at_most(counter, 0)
                    if mine_in:
                        none = any_of([none, all_of([self.at(group, index), at_most(counter, 1)])])
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
        owner = translator.agent_of.get(owner_of(node))
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


def check_requirements(network: Network, translator: Translator, group: Group) -> dict[int, m.Expr]:
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
        mine = {id(r): (r, translator.about(r.condition, agent, r.said, requirement_span(r))) for r in requirements}
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


def requirement_span(requirement: Requirement) -> Any:
    return requirement.origin.span if requirement.origin is not None else None


def rename_back(e: m.Expr, names: dict[Any, Any]) -> m.Expr:
    """``e`` with the states and variables ``names`` maps renamed (one agent's to another's)."""

    def renamed(node: m.Expr) -> m.Expr | None:
        if isinstance(node, m.StateRef) and node.state in names:
            return m.StateRef(names[node.state], node.span)
        if isinstance(node, m.VariableRef) and node.variable in names:
            return m.VariableRef(names[node.variable], node.steps, node.type, node.span)
        return None

    return replace(e, renamed)
