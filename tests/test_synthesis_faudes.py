"""libFAUDES (SupCon: supremal controllable, nonblocking) as an independent oracle for
synthesis on models without variables and guards.

The plant is the parallel composition of the network's automata. Each requirement
"e only where C" becomes a specification automaton: a copy of the components C speaks of
(their product, for a fleet's requirement over several robots) in which e is possible only
in the locations where C holds. The supervisor libFAUDES computes must then have exactly the
states and transitions of robosc's controlled system.
"""

from __future__ import annotations

import contextlib
import io
from typing import Any

import pytest
from hypothesis import HealthCheck, assume, given, settings

from random_models import robots
from robosc.api import check_text
from robosc.language import model as m
from robosc.plant import build_network
from robosc.plant.network import Automaton, Network
from robosc.synthesis import synthesize, synthesize_explicit
from robosc.synthesis.evaluate import evaluate
from test_synthesis import SMALL_FACTORY

with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
    import faudes


def _name(text: str) -> str:
    return text.replace(".", "__")


def _generator(automaton: Automaton, network: Network, system: bool) -> faudes.Generator:
    g = faudes.System() if system else faudes.Generator()
    for event in automaton.alphabet:
        g.InsEvent(_name(event.name))
        if system and event.controllable:
            g.SetControllable(_name(event.name))
    for location in automaton.locations:
        index = g.InsInitState(location.name) if location is automaton.initial else g.InsState(location.name)
        if location.marked:
            g.SetMarkedState(index)
    for edge in automaton.edges:
        g.SetTransition(edge.source.name, _name(edge.event.name), edge.target.name)
    return g


def _deterministic(network: Network) -> bool:
    for automaton in network.automata:
        seen = set()
        for edge in automaton.edges:
            key = (edge.source, edge.event)
            if key in seen:
                return False
            seen.add(key)
    return True


def _product_spec(
    network: Network, requirement, owners: list[Automaton], alphabet: faudes.EventSet
) -> faudes.Generator:
    """The product of ``owners`` (deterministic), ``requirement.event`` only where its condition holds."""
    g = faudes.Generator()
    events = {e for a in owners for e in a.alphabet} | {requirement.event}
    for e in events:
        g.InsEvent(_name(e.name))

    def label(state: tuple) -> str:
        return "_".join(loc.name for loc in state)

    start = tuple(a.initial for a in owners)
    g.SetMarkedState(g.InsInitState(label(start)))
    todo, seen = [start], {start}
    while todo:
        state = todo.pop()
        holds = bool(evaluate(requirement.condition, set(state), {}))
        for e in events:
            if e is requirement.event and not holds:
                continue
            target = []
            for a, loc in zip(owners, state, strict=True):
                if e not in a.alphabet:
                    target.append(loc)
                    continue
                edge = next((x for x in a.edges if x.source is loc and x.event is e), None)
                if edge is None:
                    break
                target.append(edge.target)
            else:
                after = tuple(target)
                if after not in seen:
                    seen.add(after)
                    todo.append(after)
                    g.SetMarkedState(g.InsState(label(after)))
                g.SetTransition(label(state), _name(e.name), label(after))
    faudes.InvProject(g, alphabet)
    return g


def _spec(network: Network, requirement, alphabet: faudes.EventSet) -> faudes.Generator | None:
    owners = {n.state.owner for n in m.walk(requirement.condition) if isinstance(n, m.StateRef)}
    if any(isinstance(n, m.VariableRef) for n in m.walk(requirement.condition)):
        return None
    if len(owners) > 1:
        return _product_spec(network, requirement, [a for a in network.automata if a.name in owners], alphabet)
    if len(owners) != 1:
        return None
    automaton = next(a for a in network.automata if a.name in owners)
    g = faudes.Generator()
    event = _name(requirement.event.name)
    for e in automaton.alphabet:
        g.InsEvent(_name(e.name))
    g.InsEvent(event)
    for location in automaton.locations:
        index = g.InsInitState(location.name) if location is automaton.initial else g.InsState(location.name)
        g.SetMarkedState(index)
    holds = {loc: bool(evaluate(requirement.condition, {loc}, {})) for loc in automaton.locations}
    for edge in automaton.edges:
        if edge.event is not requirement.event or holds[edge.source]:
            g.SetTransition(edge.source.name, _name(edge.event.name), edge.target.name)
    if requirement.event not in automaton.alphabet:
        for location in automaton.locations:
            if holds[location]:
                g.SetTransition(location.name, event, location.name)
    faudes.InvProject(g, alphabet)
    return g


def faudes_supervisor(network: Network) -> tuple[int, int] | None:
    """(states, transitions) of libFAUDES's supervisor; None if the requirements are out of its reach."""
    plant = faudes.System()
    generators = [_generator(a, network, True) for a in network.automata]
    plant.Assign(generators[0])
    for g in generators[1:]:
        product = faudes.System()
        faudes.Parallel(plant, g, product)
        plant = product
    for event in network.events:  # Parallel drops attributes: set controllability on the product
        if event.controllable:
            plant.SetControllable(_name(event.name))
    alphabet = plant.Alphabet()
    spec = faudes.Generator()
    index = spec.InsInitState("all")
    spec.SetMarkedState(index)
    spec.InjectAlphabet(alphabet)
    for event in network.events:
        spec.SetTransition("all", _name(event.name), "all")
    for requirement in network.requirements:
        part = _spec(network, requirement, alphabet)
        if part is None:
            return None
        product = faudes.Generator()
        faudes.Parallel(spec, part, product)
        spec = product
    supervisor = faudes.Generator()
    faudes.SupCon(plant, spec, supervisor)
    faudes.Accessible(supervisor)
    return supervisor.Size(), supervisor.TransRelSize()


def robosc_supervisor(network: Network, supervisor: Any = None) -> tuple[int, int]:
    """robosc's explicit supervisor's size as libFAUDES counts it: states, transitions
    (``supervisor``: the explicit supervisor, where it is synthesized already)."""
    if supervisor is None:
        supervisor = synthesize_explicit(network).supervisor
    reachable = supervisor.controlled_states()
    transitions = sum(1 for s in reachable for e, _ in supervisor.transitions[s] if supervisor.allows(e, s))
    return len(reachable), transitions


def test_small_factory_matches_libfaudes():
    network = build_network(check_text(SMALL_FACTORY).model)
    expected = faudes_supervisor(network)
    assert expected is not None
    assert robosc_supervisor(network) == expected
    assert synthesize(network).reachable_states == expected[0]


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(robots(variables=False, guards=False))
def test_random_models_match_libfaudes(text: str) -> None:
    network = build_network(check_text(text).model)
    assume(_deterministic(network))
    expected = faudes_supervisor(network)
    assume(expected is not None)
    symbolic = synthesize(network)
    assert symbolic.ok == (expected[0] > 0), text
    assert robosc_supervisor(network) == expected, text
    assert symbolic.reachable_states == expected[0], text


@pytest.mark.parametrize(
    ("family", "n"),
    [
        ("ring_instances", 2),
        ("ring_instances", 3),
        ("ring_instances", 4),
        ("warehouse_instances", 2),
        ("warehouse_instances", 3),
        ("ring", 3),
        ("lift", 3),
        ("lift", 4),
        ("crossing", 3),
        ("crossing", 4),
        ("ring_homes", 3),
        ("ring_homes", 4),
    ],
)
def test_fleets_match_libfaudes(family: str, n: int) -> None:
    """Fleets written with instances (and one copied), requirements over every robot: the
    explicit and the monolithic supervisors are libFAUDES's; the counted one allows the same
    events in every state libFAUDES's reaches."""
    import families
    from robosc.synthesis.counting.synthesis import synthesize_counted
    from robosc.synthesis.symbolic import synthesize_monolithic

    network = build_network(check_text(families.FLEETS[family](n)).model)
    expected = faudes_supervisor(network)
    assert expected is not None and expected[0] > 0
    explicit = synthesize_explicit(network).supervisor  # once (11 s for the ring of 4)
    assert robosc_supervisor(network, explicit) == expected
    assert synthesize_monolithic(network).reachable_states == expected[0]
    fleet = synthesize_counted(network, least=2)
    assert fleet.method == "symmetric"
    for state in explicit.controlled_states():  # (the state encoded once for all events: the lift of 4, 19,741 states)
        assert fleet.allowed_events(state) == explicit.allowed_events(state)
