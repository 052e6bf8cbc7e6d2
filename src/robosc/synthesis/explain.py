"""Why a state must be avoided: the requirement or the blocking situation behind it, and a
shortest sequence of uncontrollable events from that state that leads there. Used for a
failed synthesis (from the initial state) and for an added guard (from the state the
event would lead to, see :mod:`robosc.synthesis.why`)."""

from __future__ import annotations

from typing import Any

from robosc.language.render import render
from robosc.plant.network import AutomatonKind, Event
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
    return explain_from(fp, fp.initial, failed=True)


def explain_from(fp: Any, start: BDD, failed: bool = False) -> Explanation:
    """Why the bad state ``start`` must be avoided (``failed``: it is the initial state)."""
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
    return Explanation(_reason(fp, last, failed), describe(network, pick(fp, start)), tuple(steps))


def _exits(fp: Any, state: NetworkState) -> list[str]:
    """For each component stuck outside a marked state: how it could leave, and what stops it."""
    enc = fp.enc
    network = enc.network
    where = fp.state(state)
    found = []
    for automaton, location in zip(network.automata, state.locations, strict=True):
        if location.marked or automaton.kind is not AutomatonKind.COMPONENT:
            continue
        reasons = []
        for edge in automaton.edges:
            if edge.source is not location or edge.target is location:
                continue
            event = edge.event
            broken = [r for r in network.requirements_on(event) if (where & enc.boolean(r.condition)) == enc.false]
            if not event.controllable:
                never = (where & fp.enabled[event]) == enc.false
                reasons.append(f"waits for {event.name}{', which cannot happen here' if never else ''}")
            elif broken:
                reasons.append(f"{event.name} is forbidden here by {broken[0].description}")
            elif (where & fp.enabled[event]) == enc.false:
                reasons.append(f"{event.name} cannot happen here")
            else:
                reasons.append(f"{event.name} leads on to states that block as well")
        exits = "; ".join(reasons) if reasons else "it has no way out"
        found.append(f"{automaton.name} stays in {location.name} ({exits})")
    return found


def _trap(fp: Any, state: NetworkState) -> str | None:
    """Where the shortest way from ``state`` to a marked state (events the requirements
    allow) is cut: the first state on it where an uncontrollable event leads somewhere no
    marked state can be reached from at all, or where an uncontrollable event breaks a
    requirement. None when the cut is further away than that."""
    enc = fp.enc
    network = enc.network
    restricted = {e: fp.relation[e].restrict(fp.required[e]) for e in network.events}
    # states from which a marked state can be reached at all (supervisor or not)
    hopeful = fp.marked
    while True:
        before = hopeful
        for relation in restricted.values():
            hopeful |= enc.pre(relation, hopeful) & enc.valid()
        if hopeful == before:
            break
    dead = enc.valid() & ~hopeful
    # breadth-first from the stuck state to a marked state
    layers = [fp.state(state)]
    seen = layers[0]
    while (layers[-1] & fp.marked) == enc.false:
        image = enc.false
        for relation in restricted.values():
            image |= enc.post(relation, layers[-1])
        frontier = image & ~seen
        if frontier == enc.false:
            return None
        layers.append(frontier)
        seen |= frontier
    here = pick(fp, layers[-1] & fp.marked)
    path: list[tuple[Event, NetworkState]] = []
    for layer in reversed(layers[:-1]):
        for event, relation in restricted.items():
            before = layer & enc.pre(relation, fp.state(here))
            if before != enc.false:
                path.append((event, here))
                here = pick(fp, before)
                break
    path.reverse()
    walked: list[str] = []
    at = state
    for event, reached in [(None, state), *path]:
        if event is not None:
            walked.append(event.name)
            at = reached
        where = fp.state(at)
        for u in network.uncontrollable:
            into = enc.post(fp.relation[u], where)
            if (into & dead) != enc.false:
                trapped = pick(fp, into & dead)
                stays = "; ".join(_exits(fp, trapped))
                route = f"after {', '.join(walked)} " if walked else ""
                return (
                    f"The shortest way on to a marked state is cut: {route}the uncontrollable event {u.name} can "
                    f"happen and lead to [{describe(network, trapped)}], from where no marked state can be reached "
                    f"at all ({stays or 'no component can leave'})"
                )
            if (fp.requirement_bad & into) != enc.false:
                route = f"after {', '.join(walked)} " if walked else ""
                return (
                    f"The shortest way on to a marked state is cut: {route}the uncontrollable event {u.name} can "
                    "lead to a state where an uncontrollable event breaks a requirement"
                )
    return None


def _reason(fp: Any, state: NetworkState, failed: bool = False) -> str:
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
                    "a supervisor cannot prevent uncontrollable events, so it must keep the system out of this state"
                    + (", and it cannot" if failed else "")
                )
    unmarked = [
        (a.kind is not AutomatonKind.COMPONENT, f"{a.name}.{loc.name}")
        for a, loc in zip(network.automata, state.locations, strict=True)
        if not loc.marked and a.kind is not AutomatonKind.DATA
    ]
    components = [name for plant, name in unmarked if not plant]
    names = components or [name for _, name in unmarked]
    stuck = f" (stuck outside a marked state: {', '.join(names)})" if names else ""
    exits = _exits(fp, state)
    because = f": {'; '.join(exits)}" if exits else ""
    trap = _trap(fp, state)
    if trap:
        because += f". {trap}"
    return (
        f"the system would block: from state [{describe(network, state)}]{stuck} no sequence of events that the "
        f"requirements allow leads to a state where every component is in a marked state{because}"
    )
