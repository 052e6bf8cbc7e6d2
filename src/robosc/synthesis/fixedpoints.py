"""The fixed points synthesis is made of: the states that reach a set (preimages) or are reached
from it (images), the least set closed under a list of transition relations, found by
saturation or chained rounds (robosc.synthesis.options.EXPLORATIONS)."""

from __future__ import annotations

from collections.abc import Iterable

from robosc.plant.network import Event, Network
from robosc.synthesis.encoding import BDD, Encoding, Relation
from robosc.synthesis.saturation import Step, fixed_point, local


def closure(enc: Encoding, start: BDD, relations: Iterable[Relation], explore: str = "auto") -> BDD:
    """``start`` and every valid state with a path into it over ``relations``."""
    return within(enc, start, relations, enc.pre, enc.valid(), explore)


def reach(enc: Encoding, start: BDD, relations: Iterable[Relation], explore: str = "auto") -> BDD:
    """``start`` and every state reachable from it over ``relations``."""
    return within(enc, start, relations, enc.post, None, explore)


def within(
    enc: Encoding,
    start: BDD,
    relations: Iterable[Relation],
    step: Step,
    inside: BDD | None,
    explore: str,
    each: bool = False,
) -> BDD:
    """The least set holding ``start`` and each ``step(relation, set)`` of it that lies ``inside``
    (anywhere when None), found the way ``explore`` names (robosc.synthesis.options.EXPLORATIONS).
    ``each``: chained, take each relation to its own fixed point before the next."""
    relations = list(relations)
    if explore == "saturation" or (explore == "auto" and local(enc, relations)):
        return fixed_point(enc, start, relations, step, inside)
    return chained(enc, start, relations, step, inside, each)


def chained(
    enc: Encoding, start: BDD, relations: list[Relation], step: Step, inside: BDD | None, each: bool = False
) -> BDD:
    """:func:`within`'s set, the relations applied over the whole set round after round. Each
    relation is applied only to the states added since it last was (its frontier); the relations
    that change the same bits (one automaton's moves) are applied together until they add
    nothing, so a robot goes as far as it can before the next one moves; and each round takes
    these groups in the opposite order to the last, so that a robot that makes room for another
    is met before it in one round or the next, whichever way the search goes. The ring with
    homes of its own of 14 robots (monolithic, every requirement naming every robot): 250 s
    before, 38 s after (33 rounds of every relation over the whole set before, 8 after). Where
    no two relations change the same bits, :func:`plainly_chained`."""
    groups: dict[tuple[str, ...] | int, list[int]] = {}
    for index, relation in enumerate(relations):  # (one that changes nothing is a group of its own)
        groups.setdefault(tuple(relation.bits) if relation.bits else index, []).append(index)
    order = list(groups.values())
    if all(len(group) == 1 for group in order):
        return plainly_chained(start, relations, step, inside, each)
    false = enc.bdd.false
    done = [false] * len(relations)  # the set each relation was last applied to
    result = start

    def apply(index: int) -> None:
        nonlocal result
        relation = relations[index]
        while True:
            frontier = result & ~done[index]
            done[index] = result
            if frontier == false:
                return
            found = step(relation, frontier)
            grown = result | (found if inside is None else found & inside)
            if grown == result:
                return
            result = grown
            # each: a counted fleet's event moves one robot, so k robots in one state need it k times
            if not each or relation.once:
                return

    rounds = 0
    while True:
        rounds += 1
        before = result
        for group in order if rounds % 2 else order[::-1]:
            while True:  # the group's moves until they add nothing
                start_of_group = result
                for index in group:
                    apply(index)
                if result == start_of_group:
                    break
        if result == before:
            return result


def plainly_chained(start: BDD, relations: list[Relation], step: Step, inside: BDD | None, each: bool = False) -> BDD:
    """:func:`within`'s set, every relation applied to the whole set once per round, its image
    added before the next is applied (``each``: each to its own fixed point). Where no two
    relations change the same bits (a counted fleet's moves, each between two counters of its
    own) this is faster than :func:`chained`'s frontiers and groups: the ring of 16 robots with
    instances, chained, took 22.2 s with those and 11.8 s without."""

    def grown(relation: Relation, states: BDD) -> BDD:
        found = step(relation, states)
        return states | (found if inside is None else found & inside)

    result = start
    while True:
        before = result
        for relation in relations:
            result = grown(relation, result)
            while each and not relation.once and (more := grown(relation, result)) != result:
                result = more
        if result == before:
            return result


def edge_order(network: Network, name: str) -> list[Event]:
    """The network's events in the order ``name`` (see robosc.synthesis.options.EDGE_ORDERS)."""
    events = list(network.events)
    if name == "reverse":
        return events[::-1]
    if name == "sorted":
        return sorted(events, key=lambda e: e.name)
    return events
