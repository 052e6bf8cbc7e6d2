"""Why a state must be avoided: the requirement or the blocking situation behind it, and a
shortest sequence of uncontrollable events from that state that leads there. Used for a
failed synthesis (from the initial state) and for an added guard (from the state the
event would lead to, see :mod:`robosc.synthesis.why`)."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

from robosc.language.render import render
from robosc.plant.network import AutomatonKind, Event
from robosc.synthesis.encoding import BDD, Relation
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


def layers_from(
    enc: Any, start: BDD, relations: Iterable[Relation], within: BDD | None = None, until: BDD | None = None
) -> list[BDD]:
    """Breadth-first layers from ``start`` over ``relations`` (layer k: the states first
    reached after k events), staying ``within`` those states, up to the first layer that
    meets ``until`` (or until nothing new is reached)."""
    relations = list(relations)
    layers = [start]
    seen = start
    while until is None or (layers[-1] & until) == enc.false:
        image = enc.false
        for relation in relations:
            image |= enc.post(relation, layers[-1])
        frontier = image & ~seen
        if within is not None:
            frontier &= within
        if frontier == enc.false:
            break
        layers.append(frontier)
        seen |= frontier
    return layers


def walk_back(
    fp: Any, layers: list[BDD], end: NetworkState, steps: Sequence[tuple[Event, Relation]]
) -> list[tuple[Event, NetworkState]]:
    """The events from ``layers[0]`` to ``end`` (a state of the last layer), one per layer, each
    with the state it reaches; ``steps`` are tried in order, so the choice is the same every run."""
    enc = fp.enc
    here = end
    path: list[tuple[Event, NetworkState]] = []
    for layer in reversed(layers[:-1]):
        for event, relation in steps:
            before = layer & enc.pre(relation, fp.state(here))
            if before != enc.false:
                path.append((event, here))
                here = pick(fp, before)
                break
    path.reverse()
    return path


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
    layers = layers_from(enc, start, (fp.relation[e] for e in uncontrollable), within=fp.bad, until=sources)
    target = layers[-1] & sources
    if target == enc.false:  # cannot happen when the initial state is bad; be safe anyway
        target = layers[-1]
    last = pick(fp, target)
    path = walk_back(fp, layers, last, [(e, fp.relation[e]) for e in uncontrollable])
    steps = tuple(Step(event, describe(network, reached)) for event, reached in path)
    return Explanation(_reason(fp, last, failed), describe(network, pick(fp, start)), steps)


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
            if not event.controllable:
                never = (where & fp.enabled[event]) == enc.false
                reasons.append(f"waits for {event.name}{', which cannot happen here' if never else ''}")
                continue
            broken = [r for r in network.requirements_on(event) if (where & enc.boolean(r.condition)) == enc.false]
            if broken:
                reasons.append(f"{event.name} is forbidden here by {broken[0].description}")
            elif (where & fp.enabled[event]) == enc.false:
                reasons.append(f"{event.name} cannot happen here")
            else:
                reasons.append(f"{event.name} leads on to states that block as well")
        exits = "; ".join(reasons) if reasons else "it has no way out"
        found.append(f"{automaton.name} stays in {location.name} ({exits})")
    return found


def _required_moves(fp: Any) -> tuple[list[tuple[Event, Relation]], BDD]:
    """Each event's transitions where the requirements allow it, and the states from which
    no marked state can be reached over them at all (supervisor or not). Kept per result."""
    if "required moves" not in fp.memo:
        from robosc.synthesis.symbolic import closure

        enc = fp.enc
        restricted = [(e, fp.relation[e].restrict(fp.required[e])) for e in enc.network.events]
        dead = enc.valid() & ~closure(enc, fp.marked, (r for _, r in restricted))
        fp.memo["required moves"] = (restricted, dead)
    found: tuple[list[tuple[Event, Relation]], BDD] = fp.memo["required moves"]
    return found


def _trap(fp: Any, state: NetworkState) -> str | None:
    """Where the shortest way from ``state`` to a marked state (events the requirements
    allow) is cut: the first state on it where an uncontrollable event leads somewhere no
    marked state can be reached from at all, or where an uncontrollable event breaks a
    requirement. None when the cut is further away than that."""
    enc = fp.enc
    restricted, dead = _required_moves(fp)
    layers = layers_from(enc, fp.state(state), (r for _, r in restricted), until=fp.marked)
    if (layers[-1] & fp.marked) == enc.false:
        return None
    path = walk_back(fp, layers, pick(fp, layers[-1] & fp.marked), restricted)
    network = enc.network
    for index, at in enumerate([state, *(reached for _, reached in path)]):
        route = f"after {', '.join(event.name for event, _ in path[:index])} " if index else ""
        where = fp.state(at)
        for u in network.uncontrollable:
            into = enc.post(fp.relation[u], where)
            cut = f"The shortest way on to a marked state is cut: {route}the uncontrollable event {u.name} can "
            if (into & dead) != enc.false:
                trapped = pick(fp, into & dead)
                stays = "; ".join(_exits(fp, trapped))
                return (
                    f"{cut}happen and lead to [{describe(network, trapped)}], from where no marked state can be "
                    f"reached at all ({stays or 'no component can leave'})"
                )
            if (fp.requirement_bad & into) != enc.false:
                return f"{cut}lead to a state where an uncontrollable event breaks a requirement"
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
