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

    def grown(relation: Relation, states: BDD) -> BDD:
        found = step(relation, states)
        return states | (found if inside is None else found & inside)

    result = start
    while True:  # chained: each relation's image is added before the next is applied
        before = result
        for relation in relations:
            result = grown(relation, result)
            # each: a counted fleet's event moves one robot, so k robots in one state need it k times
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
