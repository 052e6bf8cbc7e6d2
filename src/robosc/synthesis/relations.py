"""Transition relations of a network's events, as BDDs over current and next state."""

from __future__ import annotations

from robosc.language import model as m
from robosc.plant.network import Automaton, Edge, Event, Network
from robosc.synthesis.encoding import BDD, Encoding, Relation


def edge_relation(enc: Encoding, automaton: Automaton, edge: Edge) -> BDD:
    """One edge: source location, guard, target location, updates; the automaton's
    other variables (those its edges on the event may change) keep their values."""
    relation = enc.at(edge.source) & enc.at(edge.target, primed=True)
    if edge.guard is not None:
        relation &= enc.boolean(edge.guard)
    updated = set()
    for update in edge.updates:
        updated.add(update.variable)
        field = enc.field(update.variable)
        if update.value is None:
            continue  # any value of the domain (primed validity is added by the caller)
        next_value = enc.false
        for value, where in enc.values(update.value).items():
            if value in field.values:  # a value outside the domain: no transition
                next_value |= where & enc.holds(update.variable, value, primed=True)
        relation &= next_value
    for variable in owned_variables(enc.network, automaton, edge.event):
        if variable not in updated:
            relation &= enc.unchanged(enc.field(variable))
    return relation


def owned_variables(network: Network, automaton: Automaton, event: Event | None = None) -> list[m.Variable]:
    """The variables ``automaton`` owns (with ``event``: those its edges on it may change)."""
    if automaton.component is None:
        if not automaton.name.startswith("#"):
            return []  # a plant owns none
        # a counted group (robosc.synthesis.symmetry) owns its counters; an event moves two
        changed = {u.variable for e in automaton.edges if event is None or e.event is event for u in e.updates}
        return [v for v in network.variables if v in changed]
    return [v for v in network.variables if v.owner == automaton.component.name]


def event_relation(enc: Encoding, event: Event) -> Relation:
    """All automata that know ``event`` take one of their edges on it; everything
    else keeps its value (implicitly: the relation covers only the fields that change)."""
    relation = enc.true
    fields = []
    for automaton in enc.network.automata:
        if event in automaton.alphabet:
            choice = enc.false
            for edge in automaton.edges:
                if edge.event is event:
                    choice |= edge_relation(enc, automaton, edge)
            relation &= choice
            fields.append(enc.field(automaton))
            fields += [enc.field(v) for v in owned_variables(enc.network, automaton, event)]
    relation &= enc.valid_fields(fields, primed=True)
    return enc.relation(relation, fields)
