"""Why synthesis restricted a controllable event: a shortest run of the controlled system
from the initial state to a state where the supervisor disables the event (although the
plant and the user's requirements allow it), the state the event would lead to, and what
would go wrong from there (an uncontrollable path to a broken requirement, or a blocking
state: which automaton is stuck where)."""

from __future__ import annotations

from typing import Any

from robosc.plant.network import Event
from robosc.record import record
from robosc.synthesis.encoding import BDD, Relation
from robosc.synthesis.explain import explain_path, grow_layers, pick, walk_back
from robosc.synthesis.result import Explanation, Restriction, Step
from robosc.synthesis.state import NetworkState

Path = list[tuple[Event, NetworkState]]  # events, each with the state it reaches


@record
class Reasons:
    """A :class:`Restriction` before its states are put in words."""

    event: Event
    run: Path  # from the initial state to ``state``
    state: NetworkState
    after: NetworkState
    consequence: Path  # uncontrollable events from ``after``
    reason: str
    fixes: tuple[Any, ...]
    never: bool


def _steps(fp: Any) -> list[tuple[Event, Relation]]:
    """Each event's transitions in the controlled system."""
    network = fp.enc.network
    return [
        (e, fp.relation[e].restrict(fp.allowed[e]) if e.controllable else fp.relation[e].restrict(fp.good))
        for e in network.events
    ]


def _layers(fp: Any, target: BDD) -> tuple[list[tuple[Event, Relation]], list[BDD]]:
    """The controlled system's transitions, and its breadth-first layers from the initial
    state (layer k: the states first reached after k events), at least up to the first that
    meets ``target`` or to the last. Kept per synthesis result and grown on request: a large
    fleet has many layers, and a run to a restriction is usually short."""
    enc = fp.enc
    if "controlled layers" not in fp.memo:
        steps = _steps(fp)
        fp.memo["controlled layers"] = (steps, grow_layers(enc, fp.initial, [r for _, r in steps]), [])
    steps, growing, found = fp.memo["controlled layers"]
    if not any((layer & target) != enc.false for layer in found):
        for layer in growing:
            found.append(layer)
            if (layer & target) != enc.false:
                break
    return steps, found


def shortest_path(fp: Any, target: BDD) -> tuple[NetworkState, Path] | None:
    """A state of ``target`` reached by the fewest events of the controlled system, and
    those events with the states they reach; None when the controlled system never reaches
    ``target``."""
    enc = fp.enc
    steps, layers = _layers(fp, target)
    depth = next((k for k, layer in enumerate(layers) if (layer & target) != enc.false), None)
    if depth is None:
        return None
    end = pick(fp, layers[depth] & target)
    return end, walk_back(fp, layers[: depth + 1], end, steps)


def why(fp: Any, event: Event) -> Restriction | None:
    """Why the supervisor disables controllable ``event`` somewhere the plant and the
    requirements allow it; None when it never does. Kept per result and event."""
    key = ("why", event)
    if key not in fp.memo:
        found = reasons(fp, event)
        fp.memo[key] = None if found is None else in_words(fp, found)
    restriction: Restriction | None = fp.memo[key]
    return restriction


def in_words(fp: Any, found: Reasons) -> Restriction:
    consequence = Explanation(
        found.reason,
        fp.describe(found.after),
        tuple(Step(event, fp.describe(reached)) for event, reached in found.consequence),
        found.fixes,
    )
    run = tuple(Step(event, fp.describe(reached)) for event, reached in found.run)
    return Restriction(found.event, run, fp.describe(found.state), fp.describe(found.after), consequence, found.never)


def reasons(fp: Any, event: Event) -> Reasons | None:
    """:func:`why`'s parts, the states not yet in words."""
    enc = fp.enc
    into_bad = enc.pre(fp.relation[event], fp.bad)
    disabled = fp.reachable & fp.enabled[event] & fp.required[event] & into_bad
    if disabled == enc.false:
        return None
    found = shortest_path(fp, disabled)
    if found is None:
        return None
    state, run = found
    after = pick(fp, enc.post(fp.relation[event], fp.state(state)) & fp.bad)
    _, consequence, reason, fixes = explain_path(fp, fp.state(after))
    return Reasons(event, run, state, after, consequence, reason, fixes, fp.never_allows(event))
