"""Why synthesis restricted a controllable event: a shortest run of the controlled system
from the initial state to a state where the supervisor disables the event (although the
plant and the user's requirements allow it), the state the event would lead to, and what
would go wrong from there (an uncontrollable path to a broken requirement, or a blocking
state: which automaton is stuck where)."""

from __future__ import annotations

from typing import Any

from robosc.plant.network import Event
from robosc.synthesis.encoding import BDD, Relation
from robosc.synthesis.explain import explain_from, pick
from robosc.synthesis.result import Restriction, Step
from robosc.synthesis.state import describe


def _steps(fp: Any) -> list[tuple[Event, Relation]]:
    """Each event's transitions in the controlled system."""
    network = fp.enc.network
    return [
        (e, fp.relation[e].restrict(fp.allowed[e]) if e.controllable else fp.relation[e].restrict(~fp.bad))
        for e in network.events
    ]


def _layers(fp: Any) -> list[BDD]:
    """Breadth-first layers of the controlled system from the initial state (layer k: the
    states first reached after k events). Computed once per synthesis result."""
    cached: list[BDD] | None = getattr(fp, "_layers", None)
    if cached is not None:
        return cached
    enc = fp.enc
    steps = _steps(fp)
    layers = [fp.initial]
    seen = fp.initial
    while True:
        image = enc.false
        for _event, relation in steps:
            image |= enc.post(relation, layers[-1])
        frontier = image & ~seen
        if frontier == enc.false:
            break
        layers.append(frontier)
        seen |= frontier
    fp._layers = layers
    return layers


def shortest_run(fp: Any, target: BDD) -> tuple[Any, tuple[Step, ...]] | None:
    """A state of ``target`` reached by the fewest events of the controlled system, and
    those events; None when the controlled system never reaches ``target``."""
    enc = fp.enc
    network = enc.network
    layers = _layers(fp)
    depth = next((k for k, layer in enumerate(layers) if (layer & target) != enc.false), None)
    if depth is None:
        return None
    end = pick(fp, layers[depth] & target)
    here = end
    steps: list[Step] = []
    relations = _steps(fp)
    for layer in reversed(layers[:depth]):
        here_bdd = fp.state(here)
        for event, relation in relations:
            before = layer & enc.pre(relation, here_bdd)
            if before != enc.false:
                steps.append(Step(event, describe(network, here)))
                here = pick(fp, before)
                break
    steps.reverse()
    return end, tuple(steps)


def why(fp: Any, event: Event) -> Restriction | None:
    """Why the supervisor disables controllable ``event`` somewhere the plant and the
    requirements allow it; None when it never does."""
    enc = fp.enc
    network = enc.network
    into_bad = enc.pre(fp.relation[event], fp.bad)
    disabled = fp.reachable & fp.enabled[event] & fp.required[event] & into_bad
    found = shortest_run(fp, disabled)
    if found is None:
        return None
    state, run = found
    after = pick(fp, enc.post(fp.relation[event], fp.state(state)) & fp.bad)
    consequence = explain_from(fp, fp.state(after))
    never = (fp.allowed[event] & fp.reachable) == enc.false
    return Restriction(event, run, describe(network, state), describe(network, after), consequence, never)
