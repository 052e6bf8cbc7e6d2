"""The locations of each component that the controlled system reaches: what a task may name
(a fleet's coordinator refuses at once a task whose stop the supervisor never lets a robot
reach: robosc.runtime.onboard.tasks)."""

from __future__ import annotations

from robosc.plant.network import AutomatonKind
from robosc.synthesis.counting.supervisor import CountedSupervisor
from robosc.synthesis.counting.translate import at_least
from robosc.synthesis.result import SynthesisResult


def reached_locations(result: SynthesisResult) -> dict[str, frozenset[str]]:
    """Component automaton name -> the names of its locations some controlled run reaches
    (every location where the result holds no fixed point to ask: the explicit method's)."""
    out: dict[str, frozenset[str]] = {}
    components = [a for a in result.network.automata if a.kind is AutomatonKind.COMPONENT]
    supervisor = result.supervisor
    if isinstance(supervisor, CountedSupervisor):
        fp, fleet = supervisor.fp, supervisor.fleet
        enc = fp.enc
        counted: dict[str, set[str]] = {}
        for group in fleet.groups:
            seen = set()
            for index, counter in enumerate(group.counters):
                if (fp.reachable & enc.boolean(at_least(counter, 1))) != enc.false:
                    seen.add(group.local[index][0][0].name)  # the robot's own automaton comes first
            for agent in group.agents:
                counted[agent.automata[0].name] = seen
        for automaton in components:
            if automaton.name in counted:
                out[automaton.name] = frozenset(counted[automaton.name])
            else:
                shared = supervisor.by_name.get(automaton.name, automaton)
                out[automaton.name] = frozenset(
                    loc.name for loc in shared.locations if (fp.reachable & enc.at(loc)) != enc.false
                )
        return out
    whole = result.fixpoint
    for automaton in components:
        if whole is None:
            out[automaton.name] = frozenset(loc.name for loc in automaton.locations)
        else:
            out[automaton.name] = frozenset(
                loc.name for loc in automaton.locations if (whole.reachable & whole.enc.at(loc)) != whole.enc.false
            )
    return out
