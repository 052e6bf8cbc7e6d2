"""Why a state must be avoided: the requirement or the blocking situation behind it, and a
shortest sequence of uncontrollable events from that state that leads there. Used for a
failed synthesis (from the initial state) and for an added guard (from the state the
event would lead to, see :mod:`robosc.synthesis.why`)."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import Any

from robosc.language import model as m
from robosc.language.render import render
from robosc.plant.network import Automaton, AutomatonKind, Event, EventKind, Network, Requirement
from robosc.record import record
from robosc.synthesis.encoding import BDD, Relation
from robosc.synthesis.fixedpoints import closure, reach, within
from robosc.synthesis.result import Explanation, Fix, Step
from robosc.synthesis.state import NetworkState


def pick(fp: Any, states: BDD) -> NetworkState:
    """One state of ``states`` (the BDD's choice, so the same every run)."""
    enc = fp.enc
    assignment = enc.bdd.pick(states, care_vars=enc.x_vars) or {}
    decoded = enc.decode(assignment)
    network = enc.network
    return NetworkState(
        tuple(decoded[id(a)] for a in network.automata), tuple(decoded[id(v)] for v in network.variables)
    )


def grow_layers(enc: Any, start: BDD, relations: Iterable[Relation], within: BDD | None = None) -> Iterator[BDD]:
    """Breadth-first layers from ``start`` over ``relations``, one at a time (layer k: the states
    first reached after k events; ``start`` first), staying ``within`` those states, until nothing
    new is reached. Lazy: a caller takes only as many as it needs."""
    relations = list(relations)
    layer = seen = start
    yield start
    while True:
        image = enc.false
        for relation in relations:
            image |= enc.post(relation, layer)
        layer = image & ~seen
        if within is not None:
            layer &= within
        if layer == enc.false:
            return
        yield layer
        seen |= layer


def layers_from(
    enc: Any, start: BDD, relations: Iterable[Relation], within: BDD | None = None, until: BDD | None = None
) -> list[BDD]:
    """The :func:`grow_layers` up to the first that meets ``until`` (or until nothing new is reached)."""
    found = []
    for layer in grow_layers(enc, start, relations, within):
        found.append(layer)
        if until is not None and (layer & until) != enc.false:
            break
    return found


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
    first, path, reason, found = explain_path(fp, start, failed)
    steps = tuple(Step(event, fp.describe(reached)) for event, reached in path)
    return Explanation(reason, fp.describe(first), steps, found)


def explain_path(
    fp: Any, start: BDD, failed: bool = False
) -> tuple[NetworkState, list[tuple[Event, NetworkState]], str, tuple[Fix, ...]]:
    """:func:`explain_from`'s parts: the state of ``start`` explained, the uncontrollable
    events from it (each with the state it reaches), the reason and the fixes."""
    enc = fp.enc
    uncontrollable = list(enc.network.uncontrollable)
    # first without the events of components that are always at rest (a detector's readings,
    # which can come at any time): the trouble is then told where it is, not after them
    quiet = [e for e in uncontrollable if not _resting(enc.network, e)]
    leading_on = {e: enc.pre(_moving(enc, fp.relation[e]), fp.bad) for e in uncontrollable}
    for events in ([quiet, uncontrollable] if len(quiet) < len(uncontrollable) else [uncontrollable]):
        blocked_at = enc.false  # bad states an event leads on from, to another bad state
        for event in events:
            blocked_at |= leading_on[event]
        sources = fp.requirement_bad | (fp.bad & ~blocked_at)  # where badness starts
        if events is not uncontrollable:  # ... and is there, whatever the resting components do
            sources = fp.requirement_bad | (sources & _required_moves(fp, start)[1])
        layers = layers_from(enc, start, (fp.relation[e] for e in events), within=fp.bad, until=sources)
        target = layers[-1] & sources
        if target != enc.false:
            break
    if target == enc.false:  # cannot happen when the initial state is bad; be safe anyway
        target = layers[-1]
    last = pick(fp, target)
    path = walk_back(fp, layers, last, [(e, fp.relation[e]) for e in events])
    reason = _reason(fp, last, failed)
    found = fixes(fp, last) if reason.startswith("the system would block") else []
    trapped = fp.memo.get(("trapped", last))
    if trapped is not None:
        found += fixes(fp, trapped)
    return pick(fp, start), path, reason, likeliest(found)


def _resting(network: Network, event: Event) -> bool:
    """Whether ``event`` belongs only to automata whose every location is marked (a detector, a
    sensor: always at rest) and moves no robot of a counted fleet."""
    counters = {c for counted, _ in network.totals for c in counted}
    owners = [a for a in network.automata if event in a.alphabet]
    moved = {u.variable for a in owners for edge in a.edges if edge.event is event for u in edge.updates}
    return bool(owners) and not moved & counters and all(loc.marked for a in owners for loc in a.locations)


def _moving(enc: Any, relation: Relation) -> Relation:
    """``relation`` without its transitions that change nothing (an answer no component waits
    for, taken on the self-loop the plant has for it)."""
    same = enc.true
    for bit, primed in zip(relation.bits, relation.primed, strict=True):
        same &= enc.bdd.apply("<=>", enc.bdd.var(bit), enc.bdd.var(primed))
    return Relation(relation.bdd & ~same, relation.bits, relation.primed, relation.guard)


def likeliest(found: list[Fix]) -> tuple[Fix, ...]:
    """The fixes once each, a missing transition first: where one is missing, a requirement
    that shuts a way out is its consequence, not the cause, and is left out."""
    unique = list(dict.fromkeys(found))
    kinds = (
        ("missing", "unmarked") if any(f.kind == "missing" for f in unique) else ("missing", "unmarked", "requirement")
    )
    return tuple(f for kind in kinds for f in unique if f.kind == kind)


@record
class _Exit:
    """One way out of a component's location, and what stops it in a state."""

    event: Event
    status: str  # "can happen", "cannot happen", "forbidden", "disabled", "blocks on", "branches"
    requirement: Requirement | None = None
    outcomes: tuple[str, ...] = ()  # "branches": where it may lead


@record(eq=False)
class Probe:
    """What the explanations ask of a state: whether the plant lets ``event`` happen in it, and
    whether ``requirement`` holds in it; answered from a synthesis' BDDs (:func:`probe`), or
    state by state on a fleet whose synthesis counted its robots (robosc.synthesis.fleet_why)."""

    network: Network
    enabled: Callable[[Event, NetworkState], bool]
    holds: Callable[[Requirement, NetworkState], bool]


def probe(fp: Any) -> Probe:
    """The :class:`Probe` of a synthesis' fixed point."""
    enc = fp.enc
    return Probe(
        enc.network,
        lambda event, state: (fp.state(state) & fp.enabled[event]) != enc.false,
        lambda requirement, state: (fp.state(state) & enc.boolean(requirement.condition)) != enc.false,
    )


def _asked(fp: Any) -> Probe:
    """``fp`` itself when it is a :class:`Probe`, else the probe of a fixed point."""
    return fp if isinstance(fp, Probe) else probe(fp)


def _stuck(fp: Any, state: NetworkState) -> list[tuple[Automaton, m.State, list[_Exit]]]:
    """The components stuck outside a marked state in ``state``, each with its ways out and
    what stops each. One that waits for an uncontrollable event that can happen here is not
    stuck (it leaves when the event comes), so it is not named. ``fp``: a fixed point or a
    :class:`Probe`."""
    asked = _asked(fp)
    network = asked.network
    found = []
    for automaton, location in zip(network.automata, state.locations, strict=True):
        if location.marked or automaton.kind is not AutomatonKind.COMPONENT:
            continue
        exits = []
        for edge in automaton.edges:
            if edge.source is not location or edge.target is location:
                continue
            event = edge.event
            possible = asked.enabled(event, state)
            if not event.controllable:
                exits.append(_Exit(event, "can happen" if possible else "cannot happen"))
                continue
            broken = [r for r in network.requirements_on(event) if not asked.holds(r, state)]
            if broken:
                exits.append(_Exit(event, "forbidden", broken[0]))
            elif possible and network.branching(event):
                outcomes = tuple(
                    f"{automaton.name}.{e.target.name}"
                    for e in automaton.edges
                    if e.source is location and e.event is event
                )
                exits.append(_Exit(event, "branches", outcomes=outcomes))
            else:
                exits.append(_Exit(event, "blocks on" if possible else "disabled"))
        if any(e.status == "can happen" for e in exits):
            continue
        found.append((automaton, location, list(dict.fromkeys(exits))))  # an event's several edges: once
    return found


def ways_out(fp: Any, state: NetworkState) -> list[str]:
    """For each component stuck outside a marked state: how it could leave, and what stops it."""
    found = []
    for automaton, location, exits in _stuck(fp, state):
        reasons = []
        for e in exits:
            if e.status == "cannot happen":
                reasons.append(f"waits for {e.event.name}, which cannot happen here")
            elif e.status == "forbidden":
                assert e.requirement is not None
                reasons.append(f"{e.event.name} is forbidden here by {e.requirement.description}")
            elif e.status == "disabled":
                reasons.append(f"{e.event.name} cannot happen here")
            elif e.status == "branches":
                reasons.append(
                    f"{e.event.name} may lead to {' or '.join(e.outcomes)}, and the supervisor can only allow or forbid "
                    "it as a whole: it forbids it where one of them blocks"
                )
            else:
                reasons.append(f"{e.event.name} leads on to states that block as well")
        found.append(f"{automaton.name} stays in {location.name} ({'; '.join(reasons) or 'it has no way out'})")
    return found


_RESULT_WORDS = {EventKind.RESPONSE: "response", EventKind.ERROR: "error"}


def fixes(fp: Any, state: NetworkState) -> list[Fix]:
    """Small changes to the model that would let the components stuck in ``state`` go on:
    a transition for an uncontrollable result the component never handles (a service or
    action failing while the component waits for its response), a requirement that shuts the
    only way out, a state that has no way out and is not marked. ``fp``: a fixed point or a
    :class:`Probe`."""
    network = _asked(fp).network
    plants = {a.name: (a, loc) for a, loc in zip(network.automata, state.locations, strict=True)}
    found: list[Fix] = []
    for automaton, location, exits in _stuck(fp, state):
        if not exits:
            found.append(
                Fix(
                    f"state {location.name} of {automaton.name} has no way out and is not marked: mark it "
                    f"('marked state {location.name}') or add a transition out of it",
                    location.span,
                    "unmarked",
                )
            )
            continue
        for e in exits:
            communication = e.event.communication
            if e.status != "cannot happen" or communication is None or communication.name not in plants:
                continue
            plant, at = plants[communication.name]
            came = [
                edge.event
                for edge in plant.edges
                if edge.target is at and edge.event.kind in _RESULT_WORDS and edge.event not in automaton.alphabet
            ]
            for event in came:
                word = _RESULT_WORDS[event.kind]
                found.append(
                    Fix(
                        f"add 'on {word} from {communication.name}' to state {location.name} of {automaton.name}: "
                        f"{communication.name} can end with {'an error' if word == 'error' else 'a response'} while "
                        f"{automaton.name} waits in {location.name}, and {automaton.name} does not say what happens then",
                        location.span,
                    )
                )
        forbidden = [e for e in exits if e.status == "forbidden"]
        if forbidden and len(forbidden) == len(exits):
            for e in forbidden:
                assert e.requirement is not None
                origin = e.requirement.origin
                found.append(
                    Fix(
                        f"{e.requirement.description} shuts {automaton.name}'s only way out of {location.name} here: "
                        f"allow {e.event.name} in this state, or keep the robot out of it",
                        origin.span if origin is not None else None,
                        "requirement",
                    )
                )
    return found


def _required_moves(fp: Any, near: BDD) -> tuple[list[tuple[Event, Relation]], BDD]:
    """Each event's transitions where the requirements allow it, and the states from which
    no marked state can be reached over them at all (supervisor or not), told for the states
    of ``near`` and what they lead to. Kept per result.

    Those states are first looked for among the states the initial state leads to over these
    moves and every uncontrollable event (where an explanation's states lie): closed under the
    moves, so that a state there reaches a marked state over them exactly when it does within
    them. Over every valid state, as before, only where ``near`` leaves them (a counted
    warehouse of 16 robots: 6 s against 77)."""
    enc = fp.enc
    if "required moves" not in fp.memo:
        restricted = [(e, fp.relation[e].restrict(c.allowed)) for e in enc.network.events for c in fp.cases[e]]
        moves = [r for _, r in restricted] + [fp.relation[u] for u in enc.network.uncontrollable]
        region = reach(enc, fp.initial, moves)
        dead = region & ~within(enc, fp.marked & region, (r for _, r in restricted), enc.pre, region, "auto")
        fp.memo["required moves"] = (restricted, region, dead)
    restricted, region, dead = fp.memo["required moves"]
    if (near & ~region) != enc.false:  # beyond them: over every valid state
        if "required moves everywhere" not in fp.memo:
            fp.memo["required moves everywhere"] = enc.valid() & ~closure(enc, fp.marked, (r for _, r in restricted))
        dead = fp.memo["required moves everywhere"]
    return restricted, dead


def cut_way(fp: Any, state: NetworkState) -> tuple[list[tuple[Event, NetworkState]], Event, NetworkState, bool] | None:
    """Where the shortest way from ``state`` to a marked state (events the requirements allow)
    is cut: the first state on it where an uncontrollable event leads somewhere no marked state
    can be reached from at all, or where an uncontrollable event breaks a requirement. The
    events up to that state (each with the state it reaches), the uncontrollable event, the
    state it leads to, and whether that state is one no marked state can be reached from (else
    an uncontrollable event breaks a requirement there). None when the cut is further away.
    Kept in ``fp.memo``: a counted fleet's robots alike ask about the same counted state."""
    key = ("cut way", state)
    if key not in fp.memo:
        fp.memo[key] = _cut_way(fp, state)
    found: tuple[list[tuple[Event, NetworkState]], Event, NetworkState, bool] | None = fp.memo[key]
    return found


def _cut_way(fp: Any, state: NetworkState) -> tuple[list[tuple[Event, NetworkState]], Event, NetworkState, bool] | None:
    enc = fp.enc
    restricted, dead = _required_moves(fp, fp.state(state))
    layers = layers_from(enc, fp.state(state), (r for _, r in restricted), until=fp.marked)
    if (layers[-1] & fp.marked) == enc.false:
        return None
    path = walk_back(fp, layers, pick(fp, layers[-1] & fp.marked), restricted)
    for index, at in enumerate([state, *(reached for _, reached in path)]):
        where = fp.state(at)
        for u in enc.network.uncontrollable:
            into = enc.post(fp.relation[u], where)
            if (into & dead) != enc.false:
                return path[:index], u, pick(fp, into & dead), True
            if (fp.requirement_bad & into) != enc.false:
                return path[:index], u, pick(fp, fp.requirement_bad & into), False
    return None


def cut_words(route: Sequence[Event], event: Event, reached: str, dead: bool, exits: Sequence[str]) -> str:
    """:func:`cut_way`'s finding in words (``reached`` described, ``exits`` of it when dead)."""
    after = f"after {', '.join(e.name for e in route)} " if route else ""
    cut = f"The shortest way on to a marked state is cut: {after}the uncontrollable event {event.name} can "
    if not dead:
        return f"{cut}lead to a state where an uncontrollable event breaks a requirement"
    stays = "; ".join(exits)
    return (
        f"{cut}happen and lead to [{reached}], from where no marked state can be reached at all "
        f"({stays or 'no component can leave'})"
    )


def _trap(fp: Any, state: NetworkState) -> str | None:
    """:func:`cut_way` in words; the state it leads to is kept for its fixes."""
    found = cut_way(fp, state)
    if found is None:
        return None
    route, event, reached, dead = found
    if dead:
        fp.memo[("trapped", state)] = reached  # its fixes are the explanation's too
    exits = ways_out(fp, reached) if dead else []
    return cut_words([e for e, _ in route], event, fp.describe(reached), dead, exits)


def _reason(fp: Any, state: NetworkState, failed: bool = False) -> str:
    described = fp.describe(state)
    return breaking(probe(fp), state, described, failed) or blocking(fp, state, described, _trap(fp, state))


def breaking(asked: Probe, state: NetworkState, described: str, failed: bool = False) -> str | None:
    """Why ``state`` must be avoided when an uncontrollable event can break a requirement in it,
    in words; None when none can."""
    network = asked.network
    for event in network.uncontrollable:
        if not asked.enabled(event, state):
            continue
        for requirement in network.requirements_on(event):
            if not asked.holds(requirement, state):
                return (
                    f"in state [{described}] the uncontrollable event '{event.name}' can happen, "
                    f"but {requirement.description} does not hold there ({render(requirement.condition)} is false); "
                    "a supervisor cannot prevent uncontrollable events, so it must keep the system out of this state"
                    + (", and it cannot" if failed else "")
                )
    return None


def _lost_places(fp: Any, state: NetworkState) -> list[str]:
    """The places (``Fixpoint.targets``, ``owner.location``) no run the requirements allow leads
    to from ``state`` (none where synthesis had no targets)."""
    targets = getattr(fp, "targets", ())
    if not targets:
        return []
    enc = fp.enc
    steps = [fp.relation[e].restrict(fp.required[e]) if e.controllable else fp.relation[e] for e in enc.network.events]
    ahead = within(enc, fp.state(state), steps, enc.post, fp.considered, "auto")  # where it can still go
    return [f"{t.owner}.{t.name}" for t in targets if (ahead & enc.at(t)) == enc.false]


def blocking(fp: Any, state: NetworkState, described: str, trap: str | None = None) -> str:
    """Why ``state`` blocks, in words: the components stuck outside a marked state, how each
    could leave and what stops it. ``fp``: a fixed point or a :class:`Probe`."""
    network = _asked(fp).network
    unmarked = [
        (a.kind is not AutomatonKind.COMPONENT, f"{a.name}.{loc.name}")
        for a, loc in zip(network.automata, state.locations, strict=True)
        if not loc.marked and a.kind is not AutomatonKind.DATA
    ]
    components = [name for plant, name in unmarked if not plant]
    names = components or [name for _, name in unmarked]
    stuck = f" (stuck outside a marked state: {', '.join(names)})" if names else ""
    exits = ways_out(fp, state)
    because = f": {'; '.join(exits)}" if exits else ""
    if trap:
        because += f". {trap}"
    lost = _lost_places(fp, state) if not names else []
    if lost:
        return (
            f"a robot would be starved: from state [{described}] the requirements leave no way to "
            f"{', '.join(lost)} any more, and every robot must be able to finish (--finish enforce)"
        )
    return (
        f"the system would block: from state [{described}]{stuck} no sequence of events that the "
        f"requirements allow leads to a state where every component is in a marked state{because}"
    )
