"""Two syntheses of one network compared state by state and event by event: the cross-check
behind ``robosc synthesize --explicit`` and the random-model oracle of the tests.

The reference is explicit-state synthesis (it lists the controlled states). The other result
may be monolithic or counted; a counted one keeps a state per *orbit* (robots in the same
states, in any order, count once), so the reference's states are counted the same way before
the figures are compared.
"""

from __future__ import annotations

from robosc.record import record
from robosc.synthesis.counting.supervisor import CountedSupervisor
from robosc.synthesis.explicit import ExplicitSupervisor
from robosc.synthesis.result import SynthesisResult
from robosc.synthesis.state import describe


@record
class Comparison:
    """What ``reference`` and ``other`` found: a supervisor or none, the controlled states
    (the reference's counted as the other counts them), and the first differences."""

    reference_ok: bool
    other_ok: bool
    reference_states: int
    other_states: int
    differences: tuple[str, ...]

    @property
    def agree(self) -> bool:
        return not self.differences


def compare(reference: SynthesisResult, other: SynthesisResult, limit: int = 5) -> Comparison:
    """``reference`` (explicit) against ``other`` on every state the reference's supervisor
    reaches: the same decision for every event, and as many controlled states."""
    supervisor = reference.supervisor
    assert isinstance(supervisor, ExplicitSupervisor), "the reference is explicit synthesis"
    reached = supervisor.controlled_states() if reference.ok else []
    counted = other.supervisor
    states = len({counted.key(s) for s in reached}) if isinstance(counted, CountedSupervisor) else len(reached)
    differences: list[str] = []
    if reference.ok != other.ok:
        found = {True: "a supervisor", False: "none"}
        differences.append(f"{reference.method} synthesis finds {found[reference.ok]}, {other.method} {found[other.ok]}")
    elif reference.ok:
        if states != other.reachable_states:
            differences.append(f"{states} controlled states against {other.reachable_states}")
        network = reference.network
        for state in reached:
            mine, theirs = supervisor.allowed_events(state), other.allowed_events(state)
            for event in network.events:
                if (event in mine) != (event in theirs) and len(differences) < limit:
                    allowed = {True: "allows", False: "forbids"}
                    differences.append(
                        f"in [{describe(network, state)}] {reference.method} synthesis {allowed[event in mine]} "
                        f"{event.name}, {other.method} {allowed[event in theirs]} it"
                    )
    return Comparison(reference.ok, other.ok, states, other.reachable_states if other.ok else 0, tuple(differences))

