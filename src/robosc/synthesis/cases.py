"""An event's requirements split by where its own automaton is: one case per location the
event leaves, each with the requirements as they read there.

A requirement written per robot reads the robot's own state and then the others'
(``R3.at5 => !(R0.at6 or R1.at6 or ...)``). As one BDD it must remember, for every robot
above R3 in the variable order, which of R3's cases it spoils: its size grows exponentially
with the robots before R3 (robots with homes of their own, 8 robots: 5.3 M nodes before any
fixed point). With R3's location known, each case is a plain conjunction over the others,
linear in their number. A transition of the event leaves one of these locations, so its
preimages and images need only the case of that location; the union of the cases is the
requirements wherever the event can happen, which is all any use of them asks. Where that
union is not large, it is kept as one case (one relation is cheaper than many small ones)."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator, Mapping, Sequence

from robosc.language import model as m
from robosc.language.simplify import folded, join, literal
from robosc.plant.network import Automaton, Event, Network
from robosc.record import record
from robosc.synthesis.encoding import BDD, Encoding

WHOLE_AT_MOST = 100_000  # BDD nodes: requirements this small where the event can happen stay one case


@record
class Case:
    """Where the event's automaton is in one location it leaves on the event (``region``; the
    whole state space where the requirements are not split), and where the requirements hold
    there (``condition``)."""

    region: BDD
    condition: BDD

    @property
    def allowed(self) -> BDD:
        return self.region & self.condition


class Unions(Mapping[Event, BDD]):
    """Each event's set as the union of its parts (one per case), made on first use and kept: a
    part is small where the union can be as large as the requirements it holds (the ring of 8
    robots copied by hand, where nothing is bad: 5.7 million nodes for where each event is
    allowed). Where the requirements allow each event, and where the supervisor does.
    ``within``: a set each event's parts are intersected with, also on first use only (where the
    supervisor allows it: a ring with homes of 14 robots spent 3 s of 46 intersecting them)."""

    def __init__(self, parts: dict[Event, list[BDD]], within: dict[Event, BDD] | None = None) -> None:
        self.parts = parts
        self.within = within if within is not None else {}
        self.made: dict[Event, BDD] = {}

    def __getitem__(self, event: Event) -> BDD:
        if event not in self.made:
            made = union(self.parts[event])
            self.made[event] = made & self.within[event] if event in self.within else made
        return self.made[event]

    def __iter__(self) -> Iterator[Event]:
        return iter(self.parts)

    def __len__(self) -> int:
        return len(self.parts)

    def meets(self, event: Event, states: BDD) -> bool:
        """Whether ``states`` and ``event``'s set share a state (without making the union)."""
        if event in self.within:
            states = states & self.within[event]
        return any((states & part) != states.bdd.false for part in self.parts[event])


def splitter(network: Network, event: Event, condition: m.Expr) -> Automaton | None:
    """The automaton to split ``event``'s requirements by: of those whose edges take ``event``
    from two or more locations, the one whose locations ``condition`` names most (None where it
    names none)."""
    named = Counter(id(n.state) for n in m.walk(condition) if isinstance(n, m.StateRef))
    best, most = None, 0
    for automaton in network.automata:
        sources = {id(edge.source) for edge in automaton.edges if edge.event is event}
        if len(sources) < 2:
            continue
        score = sum(named[id(location)] for location in automaton.locations)
        if score > most:
            best, most = automaton, score
    return best


def at_location(condition: m.Expr, automaton: Automaton, location: m.State, naming: set[int] | None = None) -> m.Expr:
    """``condition`` where ``automaton`` is in ``location``, its location references decided and
    folded away. ``naming``: :func:`locations_named` of the two, where it is known already (only the
    parts that name a location are rebuilt: a ring with homes of 14 robots, every robot's
    requirement a case per zone naming every other robot, spent 8 s of 46 rebuilding all)."""
    own = {id(s) for s in automaton.locations}
    naming = naming if naming is not None else locations_named(condition, own)

    def at(e: m.Expr) -> m.Expr:
        if id(e) not in naming:
            return e
        if isinstance(e, m.StateRef):
            return literal(e.state is location, e.span)
        if isinstance(e, m.Unary):
            return folded(m.Unary(e.op, at(e.operand), e.type, e.span))
        if isinstance(e, m.Binary):
            return folded(m.Binary(e.op, at(e.left), at(e.right), e.type, e.span))
        assert isinstance(e, m.Count)
        return m.Count(e.group, tuple(at(t) for t in e.terms), e.type, e.span)

    return at(condition)


def locations_named(condition: m.Expr, own: set[int]) -> set[int]:
    """The ids of the parts of ``condition`` that name one of the locations ``own`` (their ids),
    through operators and counts (where :func:`robosc.language.simplify.replace` goes)."""
    naming: set[int] = set()

    def visit(e: m.Expr) -> bool:
        if isinstance(e, m.StateRef):
            named = id(e.state) in own
        elif isinstance(e, m.Unary):
            named = visit(e.operand)
        elif isinstance(e, m.Binary):
            named = visit(e.left) | visit(e.right)  # (both visited)
        elif isinstance(e, m.Count):
            named = any([visit(t) for t in e.terms])
        else:
            named = False
        if named:
            naming.add(id(e))
        return named

    visit(condition)
    return naming


def union(parts: Sequence[BDD]) -> BDD:
    """The states in any of ``parts`` (one at least)."""
    result = parts[0]
    for part in parts[1:]:
        result |= part
    return result


def requirement_cases(enc: Encoding, event: Event, conditions: list[m.Expr]) -> tuple[Case, ...]:
    """``event``'s requirements (their ``conditions``) as cases of where its automaton is (one
    case over everything where none is worth splitting by)."""
    if not conditions:
        return (Case(enc.true, enc.true),)
    network = enc.network
    whole = join("and", conditions, conditions[0].span)  # balanced: many requirements nest shallowly
    automaton = splitter(network, event, whole)
    if automaton is None:
        return (Case(enc.true, enc.boolean(whole)),)
    sources = list({id(e.source): e.source for e in automaton.edges if e.event is event}.values())
    naming = locations_named(whole, {id(s) for s in automaton.locations})
    cases = tuple(
        Case(enc.at(source), enc.boolean(at_location(whole, automaton, source, naming))) for source in sources
    )
    # kept whole where that is not large (one relation instead of one per case): the union is built
    # until it outgrows WHOLE_AT_MOST (it is the requirements where the event can happen). Split
    # at 2,000 nodes, the crossing of 8 robots took 14.0 s against 6.9 whole; at 100,000 it takes
    # 7.4 s and the ring with homes of 8 robots 11.2 s; the ring copied by hand, never split,
    # took 19.3 s against 9.1 (its requirements reach 3 million nodes)
    together = enc.false
    for case in cases:
        together |= case.allowed
        if together.dag_size > WHOLE_AT_MOST:
            return cases
    return (Case(enc.true, together),)
