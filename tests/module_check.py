"""The generated supervisor module against a reference supervisor, on random runs: in every
state a run reaches, the module allows exactly the controllable events the reference allows,
and expects exactly the uncontrollable events the plant can take there."""

from __future__ import annotations

import random

from robosc.api import plan_supervisor
from robosc.debug.simulator import Simulator
from robosc.plant.network import Event
from robosc.synthesis.evaluate import evaluate
from robosc.synthesis.explicit import Edges, successors
from robosc.synthesis.result import SynthesisResult
from robosc.synthesis.state import NetworkState


def module_agrees(result: SynthesisResult, reference: SynthesisResult, runs: int = 3, steps: int = 30, seed: int = 0) -> int:
    """Random runs of ``result``'s generated module, each decision compared with ``reference``
    (synthesized on the same network); the number of states compared. Raises AssertionError at
    the first difference (and the simulator's Violation where a step breaks its checks)."""
    network = result.network
    edges = Edges(network)
    plan = plan_supervisor(result)
    rng = random.Random(seed)
    compared = 0
    refused: set[tuple[object, str]] = set()
    for run in range(runs):
        sim = Simulator(result, plan, seed=seed + run)
        for _ in range(steps):
            state = sim.network_state()
            allowed = reference.allowed_events(state)
            wanted = sorted(e.name for e in allowed if e.controllable)
            possible = sorted(e.name for e in network.uncontrollable if next(successors(edges, state, e), None) is not None)
            assert sorted(sim.allowed()) == wanted, f"in [{sim.describe()}]: the module allows {sorted(sim.allowed())}, the reference {wanted}"
            expected = set(sim.expected())
            # README, limitations: the module also takes a report synthesis assumed could not come
            # because an update would leave a variable's range (its edge is there, its guard holds)
            beyond = {e.name for e in network.uncontrollable if e.name in expected and _edge_there(edges, state, e)}
            assert set(possible) <= expected and expected - set(possible) <= beyond, (
                f"in [{sim.describe()}]: the module expects {sorted(expected)}, the plant {possible}"
            )
            compared += 1
            options = [("perform", name) for name in wanted] + [("deliver", name) for name in possible]
            options = [o for o in options if (state, o[1]) not in refused]
            if not options:
                break
            how, name = rng.choice(options)
            outcome = sim.perform(name) if how == "perform" else sim.deliver(name, sim.random_data(name, rng))
            if not outcome.events:
                assert how == "deliver", (name, outcome)
                if any("does not expect it where it is" in m for m in outcome.messages):
                    # an answer no component waits for here: the module ignores it, where the plant
                    # takes it on the self-loop responsiveness adds, which changes nothing
                    assert set(successors(edges, state, network.event(name))) == {state}, (name, outcome)
                else:  # README, limitations: a report whose update leaves the range of a variable
                    # synthesis does not read is refused at run time, where the model takes it
                    assert any("is outside its type" in w for w in sim.warnings), (name, outcome, sim.warnings)
                refused.add((state, name))
    return compared



def _edge_there(edges: Edges, state: NetworkState, event: Event) -> bool:
    """Every automaton that takes part in ``event`` has an edge on it from where it is, whose
    guard holds (where the updates lead is not asked)."""
    values = dict(zip(edges.network.variables, state.values, strict=True))
    here = set(state.locations)
    for index, by_source in edges.by_event[event]:
        if not any(e.guard is None or evaluate(e.guard, here, values) for e in by_source.get(state.locations[index], ())):
            return False
    return True
