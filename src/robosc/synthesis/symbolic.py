"""Symbolic supervisor synthesis with BDDs (Ramadge-Wonham, in the data-based form of
Ouedraogo et al. / CIF 3).

Bad states start as those where an uncontrollable event can happen that a
requirement forbids. Then, until nothing changes: every state from which an
uncontrollable event leads to a bad state is bad (controllability), and every
state that cannot reach a marked state through good states, using events the
requirements allow, is bad (nonblocking). A controllable event is allowed where
the plant allows it, its requirements hold, and none of its successors is bad.
"""

from __future__ import annotations

import time
from collections.abc import Sequence

from robosc.language import model as m
from robosc.plant.expressions import all_of
from robosc.plant.network import Event, Network
from robosc.synthesis.cases import Unions, requirement_cases
from robosc.synthesis.encoding import BDD, Encoding, Relation
from robosc.synthesis.explain import explain
from robosc.synthesis.fixedpoints import edge_order, within
from robosc.synthesis.fixpoint import Fixpoint
from robosc.synthesis.options import DEFAULT, SynthesisOptions
from robosc.synthesis.progress import Watch
from robosc.synthesis.relations import event_relation
from robosc.synthesis.result import EventGuard, SynthesisResult


def fixpoint(
    network: Network,
    options: SynthesisOptions = DEFAULT,
    watch: Watch | None = None,
    fleet: bool = False,
    to_start: bool = False,
    targets: Sequence[m.State] = (),
) -> Fixpoint:
    """The fixed points of synthesis over ``network``; ``fleet``: it is a fleet of copies (for
    :data:`robosc.synthesis.options.FORWARDS`' auto, as a counted network is); ``to_start``:
    the initial state is the only marked one, whatever the model marks (a state is then bad
    where the system cannot get back to its start: see robosc.synthesis.counted.synthesize_homes);
    ``targets``: locations each of which must stay reachable from every good state besides a
    marked state (a state that cannot reach one of them is bad: robosc.synthesis.finish)."""
    watch = watch if watch is not None else Watch.quiet()
    watch.phase("encoding")
    enc = Encoding(network, options)
    watch.nodes = enc.live_nodes
    enc.watch = watch
    relation = {}
    for event in network.events:
        relation[event] = event_relation(enc, event)
        watch.beat()
    cases = {}
    for event in network.events:
        cases[event] = requirement_cases(enc, event, [r.condition for r in network.requirements_on(event)])
        watch.beat()
    enabled = {}
    for event, moves in relation.items():
        enabled[event] = enc.enabled(moves) & enc.valid()
        watch.beat()
    marked = enc.valid()
    for automaton in network.automata:
        here = enc.false
        for location in automaton.marked:
            here |= enc.at(location)
        marked &= here
    if network.marker is not None:
        marked &= enc.boolean(network.marker)
    initial = enc.state(
        {a: a.initial for a in network.automata}, {v: network.initial_values[v] for v in network.variables}
    )
    if to_start:
        marked = initial
    explore = options.explore
    events = edge_order(network, options.edges)  # the order the chained loops apply the events in
    uncontrollable = [relation[e] for e in events if not e.controllable]
    # where the requirements allow each event, and its transitions there: a part, a relation per case
    required = {e: [case.allowed for case in cases[e]] for e in events}
    restricted = {e: [enc.fixed_target(relation[e].restrict(part)) for part in required[e]] for e in events}

    def steps_of(event: Event) -> list[Relation]:  # where the requirements let it happen
        return restricted[event] if event.controllable else [relation[event]]

    # the states synthesis decides on: every valid one, or (forward) those the requirements let
    # the system reach, forward-closed under every event they allow, so each fixed point below
    # stays among them and finds there what it would find among all
    considered = enc.valid()
    forward = options.forward == "first" or (options.forward == "auto" and (fleet or bool(network.totals)))
    if forward:
        watch.phase("forward")
        considered = within(enc, initial, [r for e in events for r in steps_of(e)], enc.post, None, explore)
    requirement_bad = enc.false
    for event in network.uncontrollable:
        for case in cases[event]:
            requirement_bad |= enabled[event] & case.region & ~case.condition & considered

    # a controllable event with several outcomes is allowed only where none of them is bad, so
    # a state reaches a marked one through it only from there (one outcome good is not enough)
    branching = {e for e in events if e.controllable and network.branching(e)}
    bad = requirement_bad
    rounds = 0
    while True:
        rounds += 1
        watch.phase("bad states", rounds)
        closed = within(enc, bad, uncontrollable, enc.pre, considered, explore)
        # from the second round on, bad holds every state the last round found unable to reach a
        # marked one; where no uncontrollable event leads into it from outside and no event
        # branches (so the steps are the same), this round's nonblocking would find the same good
        # states (each reaches a marked state through good ones only): done, without computing it
        # again (it was 6.5 s of a 16-robot warehouse's 14.6)
        if rounds > 1 and closed == bad and not branching and not targets:
            break
        bad = closed
        steps = []
        for event in events:
            if event in branching:
                outside = ~enc.pre(relation[event], bad)
                steps += [r.restrict(outside) for r in restricted[event]]
            else:
                steps += restricted[event]
        # nonblocking: who reaches a marked state through good states (chained, each event to
        # its own fixed point: ring of 16 robots, 1,696 preimages in 3.7 s before, 768 in 1.7 s)
        watch.phase("nonblocking", rounds)
        good = within(enc, marked & considered & ~bad, steps, enc.pre, considered & ~bad, explore, each=True)
        for target in targets:  # each robot's places, each a marking of its own
            good &= within(enc, enc.at(target) & considered & ~bad, steps, enc.pre, considered & ~bad, explore, each=True)
        new_bad = considered & ~good
        if new_bad == bad:
            break
        bad = new_bad

    # the supervised reachability (below) stays in the good states: from a good state a
    # controllable event is allowed where its requirements hold and it leads to no bad state, and
    # an uncontrollable one never leads to one. So a controllable event needs only its
    # requirements there (what its move reads: saturation keeps it low in the order), except where
    # it can lead both to a bad and to a good state (nondeterministic), where the supervisor
    # disables it: there it also needs to lead to no bad state. (The allowed sets read every
    # counter of a fleet through the valid states.)
    kept = considered & ~bad
    reaching = (initial & kept) != enc.false
    free: dict[Event, BDD] = {}  # where the supervisor allows each, its requirements apart
    supervised: dict[Event, list[Relation]] = {}  # a controllable event's transitions the supervisor allows
    for e in network.controllable:
        into_bad = enc.pre(relation[e], bad)
        free[e] = enabled[e] & kept & ~into_bad
        supervised[e] = restricted[e]
        if reaching:
            mixed = into_bad & enc.pre(relation[e], kept) & kept  # (kept: valid states only)
            if any((mixed & part) != enc.false for part in required[e]):
                supervised[e] = [r.restrict(~into_bad) for r in restricted[e]]
    reachable = enc.false
    watch.phase("reachable")
    if reaching and forward and bad == enc.false:
        reachable = considered  # nothing bad: the supervisor's reach is the requirements'
    elif reaching:
        steps = []
        for e in events:  # in the events' order (a chained round's reach depends on it)
            steps += supervised[e] if e.controllable else [relation[e]]
        reachable = within(enc, initial, steps, enc.post, kept, explore)
    return Fixpoint(
        enc,
        relation,
        cases,
        Unions(required),
        enabled,
        initial,
        marked,
        requirement_bad,
        bad,
        considered,
        Unions({e: required[e] for e in network.controllable}, free),
        reachable,
        targets=tuple(targets),
    )


def synthesize_monolithic(
    network: Network, options: SynthesisOptions = DEFAULT, watch: Watch | None = None, fleet: bool = False,
    targets: Sequence[m.State] = (),
) -> SynthesisResult:
    """The maximally permissive controllable, nonblocking supervisor of ``network``, over one
    BDD of the whole network's state (the reference method; ``options``: how to compute it,
    never what; ``watch``: told how far it is; ``fleet``: a fleet of copies that could not be
    counted)."""
    start = time.perf_counter()
    watch = watch if watch is not None else Watch.quiet()
    fp = fixpoint(network, options, watch, fleet, targets=targets)
    enc = fp.enc
    if (fp.initial & fp.bad) != enc.false:
        explanation = explain(fp)
        seconds = time.perf_counter() - start
        return SynthesisResult(
            network,
            "symbolic",
            False,
            explanation=explanation,
            seconds=seconds,
            supervisor=fp,
            fixpoint=fp,
            effort=enc.effort(),
        )
    watch.phase("conditions")
    guards = []
    for event in network.controllable:
        conditions = [r.condition for r in network.requirements_on(event)]
        required: m.Expr | None = all_of(conditions) if conditions else None
        guards.append(EventGuard(event, required, fp.added(event)))
    return SynthesisResult(
        network,
        "symbolic",
        True,
        tuple(guards),
        enc.count(fp.reachable),
        time.perf_counter() - start,
        supervisor=fp,
        fixpoint=fp,
        effort=enc.effort(),
    )
