"""Why a state must be avoided: the requirement or the blocking situation behind it, and a
shortest sequence of uncontrollable events from that state that leads there. Used for a
failed synthesis (from the initial state) and for an added guard (from the state the
event would lead to, see :mod:`robosc.synthesis.why`)."""

from __future__ import annotations

from typing import Any

from robosc.language.render import render
from robosc.plant.network import AutomatonKind
from robosc.synthesis.encoding import BDD
from robosc.synthesis.result import Explanation, Step
from robosc.synthesis.state import NetworkState, describe


def pick(fp: Any, states: BDD) -> NetworkState:
    """One state of ``states`` (the BDD's choice, so the same every run)."""
    enc = fp.enc
    assignment = enc.bdd.pick(states, care_vars=enc.x_vars) or {}
    decoded = enc.decode(assignment)
    network = enc.network
    return NetworkState(
        tuple(decoded[id(a)] for a in network.automata), tuple(decoded[id(v)] for v in network.variables)
    )


def explain(fp: Any) -> Explanation:
    """Why the initial state is outside the controlled behaviour (synthesis failed)."""
    return explain_from(fp, fp.initial)


def explain_from(fp: Any, start: BDD) -> Explanation:
    """Why the bad state ``start`` must be avoided."""
    enc = fp.enc
    network = enc.network
    uncontrollable = network.uncontrollable
    blocked_at = enc.false
    for event in uncontrollable:
        blocked_at |= enc.pre(fp.relation[event], fp.bad)
    sources = fp.requirement_bad | (fp.bad & ~blocked_at)  # where badness starts
    layers = [start]
    seen = start
    while (layers[-1] & sources) == enc.false:
        image = enc.false
        for event in uncontrollable:
            image |= enc.post(fp.relation[event], layers[-1])
        frontier = image & fp.bad & ~seen
        if frontier == enc.false:
            break
        layers.append(frontier)
        seen |= frontier
    target = layers[-1] & sources
    if target == enc.false:  # cannot happen when the initial state is bad; be safe anyway
        target = layers[-1]
    # walk back to the initial state, one uncontrollable event per layer
    here = pick(fp, target)
    here_bdd = fp.state(here)
    steps: list[Step] = []
    for layer in reversed(layers[:-1]):
        for event in uncontrollable:
            before = layer & enc.pre(fp.relation[event], here_bdd)
            if before != enc.false:
                steps.append(Step(event, describe(network, here)))
                here = pick(fp, before)
                here_bdd = fp.state(here)
                break
    steps.reverse()
    last = pick(fp, target)
    return Explanation(_reason(fp, last), describe(network, pick(fp, start)), tuple(steps))


def _reason(fp: Any, state: NetworkState) -> str:
    enc = fp.enc
    network = enc.network
    where = fp.state(state)
    for event in network.uncontrollable:
        if (where & fp.enabled[event]) == enc.false:
            continue
        for requirement in network.requirements_on(event):
            if (where & ~enc.boolean(requirement.condition)) != enc.false:
                return (
                    f"in state [{describe(network, state)}] the uncontrollable event '{event.name}' can happen, "
                    f"but {requirement.description} does not hold there ({render(requirement.condition)} is false); "
                    "a supervisor cannot prevent uncontrollable events, so it must keep the system out of this state, "
                    "and it cannot"
                )
    unmarked = [
        (a.kind is not AutomatonKind.COMPONENT, f"{a.name}.{loc.name}")
        for a, loc in zip(network.automata, state.locations, strict=True)
        if not loc.marked and a.kind is not AutomatonKind.DATA
    ]
    names = [name for _, name in sorted(unmarked, key=lambda pair: pair[0])]
    stuck = f" (stuck outside a marked state: {', '.join(names)})" if names else ""
    return (
        f"the system would block: from state [{describe(network, state)}]{stuck} no sequence of events that the "
        "requirements allow leads to a state where every component is in a marked state"
    )
