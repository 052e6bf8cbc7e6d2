"""Why synthesis restricted a controllable event: a shortest run of the controlled system
from the initial state to a state where the supervisor disables the event (although the
plant and the user's requirements allow it), the state the event would lead to, and what
would go wrong from there (an uncontrollable path to a broken requirement, or a blocking
state: which automaton is stuck where)."""

from __future__ import annotations

from typing import Any

from robosc.plant.network import Event
from robosc.synthesis.encoding import BDD, Relation
from robosc.synthesis.explain import explain_from, layers_from, pick, walk_back
from robosc.synthesis.result import Restriction, Step
from robosc.synthesis.state import describe


def _steps(fp: Any) -> list[tuple[Event, Relation]]:
    """Each event's transitions in the controlled system."""
    network = fp.enc.network
    return [
        (e, fp.relation[e].restrict(fp.allowed[e]) if e.controllable else fp.relation[e].restrict(~fp.bad))
        for e in network.events
    ]


def _controlled(fp: Any) -> tuple[list[tuple[Event, Relation]], list[BDD]]:
    """The controlled system's transitions, and its breadth-first layers from the initial
    state (layer k: the states first reached after k events). Kept per synthesis result."""
    if "controlled layers" not in fp.memo:
        steps = _steps(fp)
        fp.memo["controlled layers"] = steps, layers_from(fp.enc, fp.initial, (r for _, r in steps))
    found: tuple[list[tuple[Event, Relation]], list[BDD]] = fp.memo["controlled layers"]
    return found


def shortest_run(fp: Any, target: BDD) -> tuple[Any, tuple[Step, ...]] | None:
    """A state of ``target`` reached by the fewest events of the controlled system, and
    those events; None when the controlled system never reaches ``target``."""
    enc = fp.enc
    steps, layers = _controlled(fp)
    depth = next((k for k, layer in enumerate(layers) if (layer & target) != enc.false), None)
    if depth is None:
        return None
    end = pick(fp, layers[depth] & target)
    path = walk_back(fp, layers[: depth + 1], end, steps)
    return end, tuple(Step(event, describe(enc.network, reached)) for event, reached in path)


def why(fp: Any, event: Event) -> Restriction | None:
    """Why the supervisor disables controllable ``event`` somewhere the plant and the
    requirements allow it; None when it never does. Kept per result and event."""
    key = ("why", event)
    if key not in fp.memo:
        fp.memo[key] = _why(fp, event)
    found: Restriction | None = fp.memo[key]
    return found


def _why(fp: Any, event: Event) -> Restriction | None:
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
