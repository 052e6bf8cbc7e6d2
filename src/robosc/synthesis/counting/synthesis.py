"""Synthesis of a fleet by counting its robots (the wing's other modules find the copies and
build the counted network): the same fixed point as any network (robosc.synthesis.symbolic),
its conditions read back in the fleet's terms; the monolithic method where the fleet cannot
be counted, saying why."""

from __future__ import annotations

import time

from robosc.language import model as m
from robosc.language.render import render
from robosc.plant.expressions import NO_SPAN, all_of, any_of
from robosc.plant.network import Event, Network
from robosc.synthesis.counting.explain import describer
from robosc.synthesis.counting.groups import MIN_AGENTS, NotSymmetric, robots_of
from robosc.synthesis.counting.network import Counted, counted, with_homes
from robosc.synthesis.counting.supervisor import CountedSupervisor, lift
from robosc.synthesis.counting.translate import rename_back
from robosc.synthesis.explain import explain
from robosc.synthesis.fixpoint import Fixpoint
from robosc.synthesis.options import DEFAULT, SynthesisOptions
from robosc.synthesis.progress import Watch
from robosc.synthesis.result import EventGuard, SynthesisResult
from robosc.synthesis.symbolic import fixpoint, synthesize_monolithic


def synthesize_counted(
    network: Network, options: SynthesisOptions | None = None, least: int = MIN_AGENTS, watch: Watch | None = None
) -> SynthesisResult:
    """Synthesis by the counter abstraction where the network has a group of at least ``least``
    symmetric agents (or agents that are copies but for their homes, where
    :func:`synthesize_homes` applies); the monolithic method (saying why in the result's
    ``fleet``) where not. ``watch``: told how far it is."""
    options = options or DEFAULT
    watch = watch if watch is not None else Watch.quiet()
    start = time.perf_counter()
    watch.phase("counting")
    homes_why = None
    if with_homes(network, least):  # copies but for their homes: all counted where that is exact
        homes, homes_why = synthesize_homes(network, options, least, watch, start)
        if homes is not None:
            return homes
    try:
        fleet = counted(network, least)
    except NotSymmetric as reason:
        why = homes_why if reason.homes and homes_why else str(reason)
        result = synthesize_monolithic(network, options, watch, fleet=bool(reason.robots))
        note = (  # a fleet: say why it was not counted
            f"{reason.robots} are copies of each other, but synthesis did not count them: {why}; "
            "the supervisor is the monolithic method's (exact; slower on large fleets)"
            if reason.robots
            else ""
        )
        return SynthesisResult(
            result.network,
            result.method,
            result.ok,
            result.guards,
            result.reachable_states,
            time.perf_counter() - start,
            result.explanation,
            result.supervisor,
            result.fixpoint,
            fleet=f"monolithic: {why}",
            fleet_note=note,
            effort=result.effort,
        )
    fp = fixpoint(fleet.network, options, watch)
    return _counted_result(network, fleet, fp, watch, start)


def synthesize_homes(
    network: Network, options: SynthesisOptions, least: int, watch: Watch, start: float
) -> tuple[SynthesisResult | None, str]:
    """The supervisor of robots that are copies but for their homes (each may rest only in a
    place of its own), by counting them, where that is exact; else None and why not.

    Counting forgets which robot is where, so it cannot say whether each robot can get home.
    It can say whether the fleet can always get back to *a* start: to the robots in the same
    places as at the start, each perhaps in another's place. Where the system starts in a
    marked state and, counted with its start as the only marked state, has no bad state, that
    is enough. Take a state ``x`` the requirements reach, and a path from it to the start with
    the robots permuted, ``p(start)``. The permutations ``p`` with a path from ``start`` to
    ``p(start)`` form a group: from ``p(start)``, the path to ``q(start)`` with its robots
    permuted by ``p`` leads to ``pq(start)`` (the copies behave alike; only their homes
    differ, and homes are not in the paths), and a finite set closed under composition holds
    each one's inverse. ``p`` is in it (``start`` reaches ``x``, which reaches ``p(start)``),
    so is its inverse, and permuting the path from ``start`` to ``p⁻¹(start)`` by ``p`` leads
    from ``p(start)`` back to ``start``, which is marked. So every state the requirements
    reach can get home with every robot at once, nothing is bad, and the supervisor is the
    requirements, as the counted one is. Where something is bad, which robot is where
    matters: the monolithic method decides (the caller's fallback)."""
    if network.marker is not None or any(a.initial not in a.marked for a in network.automata):
        return None, (
            "they differ in their marked states (each may rest in a place of its own), and not every component "
            "starts in a marked state, so counting them cannot show that each robot can get home"
        )
    try:
        fleet = counted(network, least, marking=False)
    except NotSymmetric as reason:
        return None, str(reason)
    fp = fixpoint(fleet.network, options, watch, to_start=True)
    if fp.bad != fp.enc.false:
        return None, (
            "they differ in their marked states (each may rest in a place of its own), and counted, the fleet "
            "cannot always get back to where it started, so which robot is where matters"
        )
    robots = "; ".join(robots_of(group) for group in fleet.groups)
    note = (
        f"{robots} differ in their marked states (homes of their own); synthesis counted them all the same, as "
        "from every state the requirements reach the fleet can get back to where it started, with every robot home"
    )
    return _counted_result(network, fleet, fp, watch, start, note), ""


def _counted_result(
    network: Network, fleet: Counted, fp: Fixpoint, watch: Watch, start: float, note: str = ""
) -> SynthesisResult:
    """The supervisor a counted synthesis found (``note``: what the fleet should know of how)."""
    enc = fp.enc
    described = ", ".join(f"{g.name}: {len(g.agents)} agents, {len(g.local)} local states" for g in fleet.groups)
    supervisor = CountedSupervisor(network, fleet, fp)
    fp.describer = describer(supervisor)
    how = f"counted ({described})" + ("; homes of their own, every state gets back to the start" if note else "")
    if (fp.initial & fp.bad) != enc.false:
        return SynthesisResult(
            network,
            "symmetric",
            False,
            seconds=time.perf_counter() - start,
            explanation=explain(fp),
            supervisor=supervisor,
            fixpoint=fp,
            fleet=how,
            fleet_note=note,
            effort=enc.effort(),
        )
    translator = fleet.translator
    watch.phase("conditions")
    guards = []
    # a counted event's added condition, the same for every robot whose event it counts (made
    # once: for each of 500 robots it took minutes); None where it adds nothing
    made: dict[Event, m.Expr | None] = {}

    def added_to(counted_event: Event) -> m.Expr | None:
        if counted_event not in made:
            added = fp.added(counted_event)
            made[counted_event] = lift(added, fleet, network) if added is not None else None
        return made[counted_event]

    for event in network.controllable:
        conditions = [r.condition for r in network.requirements_on(event)]
        required: m.Expr | None = all_of(conditions) if conditions else None
        owner = supervisor.agent_of_event.get(event)
        pairs = [
            (ce, fleet.moves[ce][1][0].source if owner is not None else None) for ce in supervisor.counted_of(event)
        ]
        # the condition from each place the robot does the event in; places with the same
        # condition are written once: (bot1.depot or bot1.ready) => ...
        written: dict[str, tuple[m.Expr, list[m.Expr]]] = {}  # a condition's text -> it, its places
        for counted_event, source in pairs:
            added = added_to(counted_event)
            if added is None:
                continue
            places = written.setdefault(render(added), (added, []))[1]
            if source is not None and owner is not None:
                group, agent = owner
                back = {v: k for k, v in group.to_rep[id(agent)].items()}
                places.append(rename_back(translator.at(group, source), back))
        parts = [
            m.Binary("=>", any_of(places), added, m.BOOLEAN, NO_SPAN) if places else added
            for added, places in written.values()
        ]
        guards.append(EventGuard(event, required, all_of(parts) if parts else None))
    return SynthesisResult(
        network,
        "symmetric",
        True,
        tuple(guards),
        enc.count(fp.reachable),
        time.perf_counter() - start,
        supervisor=supervisor,
        fixpoint=fp,
        fleet=how,
        fleet_note=note,
        effort=enc.effort(),
    )
