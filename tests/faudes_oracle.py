"""libFAUDES (SupCon: the supremal controllable, nonblocking sublanguage) as an oracle for any
small network: nondeterministic events, variables, guards and fleets included.

The plant is the network's reachable state space as explicit synthesis enumerated it (the
plant's meaning is robosc's, the synthesis is libFAUDES's). libFAUDES needs a
deterministic plant, so an event with several outcomes from a state goes first to a state of
its own, from which an uncontrollable event per outcome leads on: the supervisor decides the
event, the robot its outcome. The specification is the plant without the transitions a
requirement forbids.

Where robosc's controlled system has S states and T transitions, and allows a branching event
in B of its states, libFAUDES's supervisor has S + B states and T + B transitions (each allowed
branching event: one transition to its own state, then one per outcome instead of one per
outcome)."""

from __future__ import annotations

import contextlib
import io

from robosc.plant.network import Event
from robosc.synthesis.explicit import marked

with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
    import faudes


def libfaudes_supervisor(explicit) -> tuple[int, int]:
    """(states, transitions) of libFAUDES's supervisor (0, 0 when there is none) of the plant
    that ``explicit`` (an explicit synthesis' result) enumerated."""
    enumerated = explicit.supervisor
    network = enumerated.network
    order = enumerated.states
    index = {state: i for i, state in enumerate(order)}
    moves: list[tuple[int, Event, list[int]]] = []  # source, event, targets
    for state in order:
        outcomes: dict[Event, list[int]] = {}
        for event, target in enumerated.transitions[state]:
            targets = outcomes.setdefault(event, [])
            if index[target] not in targets:
                targets.append(index[target])
        moves += [(index[state], event, targets) for event, targets in outcomes.items()]
    plant, spec = faudes.System(), faudes.Generator()
    labels = {}  # libFAUDES's index of each event, the same in every generator
    for event in network.events:
        labels[event] = plant.InsEvent(event.name)
        spec.InsEvent(event.name)
        if event.controllable:
            plant.SetControllable(event.name)
    for g in (plant, spec):
        for i, state in enumerate(order):
            g.InsState(i + 1)
            if i == 0:
                g.SetInitState(i + 1)
            if marked(network, state):
                g.SetMarkedState(i + 1)
    extra = len(order) + 1
    for source, event, targets in moves:
        label, name = labels[event], event.name
        allowed = enumerated.required_ok[(order[source], event)]  # the requirements allow it here
        if len(targets) == 1:
            plant.SetTransition(source + 1, label, targets[0] + 1)
            if allowed:
                spec.SetTransition(source + 1, label, targets[0] + 1)
            continue
        middle = extra  # the event happened, its outcome is still open
        extra += 1
        for g in (plant, spec):
            g.InsState(middle)
        plant.SetTransition(source + 1, label, middle)
        if allowed:
            spec.SetTransition(source + 1, label, middle)
        for k, target in enumerate(targets):
            outcome = plant.InsEvent(f"{name}~{k}")
            spec.InsEvent(f"{name}~{k}")
            for g in (plant, spec):
                g.SetTransition(middle, outcome, target + 1)
    supervisor = faudes.Generator()
    faudes.SupCon(plant, spec, supervisor)
    faudes.Accessible(supervisor)
    return supervisor.Size(), supervisor.TransRelSize()


def robosc_figures(explicit_supervisor) -> tuple[int, int]:
    """robosc's controlled system as libFAUDES counts it (see the module's docstring)."""
    reached = explicit_supervisor.controlled_states()
    states = transitions = 0
    for state in reached:
        states += 1
        for event in explicit_supervisor.allowed_events(state):
            targets = {t for e, t in explicit_supervisor.transitions[state] if e is event}
            transitions += len(targets)
            if len(targets) > 1:
                states += 1
                transitions += 1
    return states, transitions
