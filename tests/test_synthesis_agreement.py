"""Symbolic (BDD) and explicit synthesis agree on random small models: same success,
same controlled state count, and the same decision for every event in every state."""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings

from random_models import robots
from robosc.api import check_text
from robosc.plant import build_network
from robosc.synthesis import synthesize, synthesize_explicit
from robosc.synthesis.evaluate import evaluate


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(robots())
def test_symbolic_and_explicit_synthesis_agree(text: str) -> None:
    checked = check_text(text)
    assert checked.model is not None, checked.render() + "\n" + text
    network = build_network(checked.model)
    symbolic = synthesize(network)
    explicit = synthesize_explicit(network)
    assert symbolic.ok == explicit.ok, text
    assert symbolic.reachable_states == explicit.reachable_states, text
    supervisor = explicit.supervisor
    for state in supervisor.states:
        for event in network.events:
            assert symbolic.allows(event, state) == explicit.allows(event, state), (event.name, state, text)
    if not symbolic.ok:
        assert symbolic.explanation is not None and symbolic.explanation.reason
        return
    assert_readable_guards_are_exact(symbolic, supervisor)


def assert_readable_guards_are_exact(symbolic, supervisor) -> None:
    """On every reachable state: plant allows, requirements hold and the readable added
    guard holds, exactly when the supervisor allows the event."""
    network = symbolic.network
    for state in supervisor.controlled_states():
        locations = set(state.locations)
        values = dict(zip(network.variables, state.values, strict=True))
        for guard in symbolic.guards:
            if not any(e is guard.event for e, _ in supervisor.transitions[state]):
                continue  # the plant does not allow it here
            required = guard.required is None or evaluate(guard.required, locations, values)
            added = guard.added is None or evaluate(guard.added, locations, values)
            assert bool(required and added) == symbolic.allows(guard.event, state), (guard.event.name, state)
