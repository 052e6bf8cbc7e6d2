"""Whether every robot of a fleet can always finish what it does.

Nonblocking is about the fleet: from every state the supervisor allows, the robots can get
back to a marked state together. It does not say that each robot can always get on with its
own work: a supervisor may let the others go round for ever in a way that keeps one robot
from ever reaching the shelf again, and still get everyone home. Here, as in multitasking
supervisory control (one marking per task), each place a robot goes to is a task: for each
robot and each location of its automaton that the controlled fleet reaches, the check asks
whether that location stays reachable from every state the supervisor allows. Where it does
not, the robot can be starved: :class:`Starved` gives a shortest run of the controlled fleet
to a state from which the robot can never get there again, and the loop the fleet can then go
round in without it.

A counted fleet is checked on its counter abstraction with the first robot of each group kept
apart (robosc.synthesis.counting.network.apart): it stands for every robot of its group, as
they are copies. With ``enforce``, :func:`finish_supervisor` makes the supervisor under which
every robot can always get to each of those locations (the monolithic method, one marking per
robot and location: generalized nonblocking)."""

from __future__ import annotations

import time

from robosc.plant.network import Automaton, Event, Network
from robosc.record import record
from robosc.synthesis.counting.groups import NotSymmetric, groups, robots_of
from robosc.synthesis.counting.network import apart
from robosc.synthesis.encoding import BDD, Relation
from robosc.synthesis.explain import layers_from, pick, walk_back
from robosc.synthesis.fixedpoints import within
from robosc.synthesis.fixpoint import Fixpoint
from robosc.synthesis.options import DEFAULT, SynthesisOptions
from robosc.synthesis.result import Step, SynthesisResult
from robosc.synthesis.symbolic import fixpoint, synthesize_monolithic

LOOP_STEPS = 200  # events followed at most to find the loop a starved robot's fleet goes round


@record
class Starved:
    """``robot`` can be kept from ever reaching ``location`` again: ``path`` is a shortest run
    of the controlled fleet from its initial state to ``state``, from which it cannot;
    ``loop`` the events the fleet can then go round in for ever (empty where it comes to rest);
    ``others``: the other locations it can be kept from in the same way."""

    robot: str
    location: str
    path: tuple[Step, ...]
    state: str
    loop: tuple[Step, ...]
    others: tuple[str, ...] = ()

    def __str__(self) -> str:
        run = ", ".join(step.event.name for step in self.path) or "(at the start)"
        text = f"{self.robot} can be starved: after {run} it can never reach {self.location} again"
        if self.loop:
            text += "; the others can go round " + ", ".join(step.event.name for step in self.loop) + " for ever"
        if self.others:
            text += f" (nor {', '.join(self.others)})"
        return text


@record
class Finish:
    """What the check found: the robots it followed (``stands_for``: which robots each stands for,
    where a counted fleet's one robot stands for its copies), those that can be starved."""

    robots: tuple[str, ...]
    stands_for: tuple[str, ...]
    starved: tuple[Starved, ...]
    seconds: float = 0.0
    places: tuple[str, ...] = ()  # the locations the robots followed reach under the supervisor (their tasks)

    @property
    def ok(self) -> bool:
        return not self.starved


def _robots(network: Network) -> list[tuple[Automaton, str]]:
    """The component automaton of every robot of a group of copies, with the robots it stands for."""
    out = []
    for group in groups(network):
        for agent in group.agents:
            out.append((agent.automata[0], agent.component.name))
    return out


def controlled_steps(fp: Fixpoint) -> list[tuple[Event, Relation]]:
    """Each event's transitions under the supervisor, among the good states."""
    return [(e, fp.relation[e].restrict(fp.where(e))) for e in fp.enc.network.events]


def never_again(fp: Fixpoint, location: object, steps: list[Relation], explore: str) -> BDD | None:
    """The reachable states from which ``location`` cannot be reached any more (None: the
    controlled fleet never reaches it at all)."""
    enc = fp.enc
    there = enc.at(location) & fp.reachable  # type: ignore[arg-type]
    if there == enc.false:
        return None
    back = within(enc, there, steps, enc.pre, fp.good, explore)
    return fp.reachable & ~back


def starved(fp: Fixpoint, robot: str, location: str, stuck: BDD, steps: list[tuple[Event, Relation]]) -> Starved:
    """:class:`Starved` for ``robot`` kept from ``location`` in the states ``stuck``."""
    enc = fp.enc
    layers = layers_from(enc, fp.initial, (r for _, r in steps), within=fp.good, until=stuck)
    end = pick(fp, layers[-1] & stuck)
    path = walk_back(fp, layers, end, steps)
    loop: list[tuple[Event, object]] = []
    seen = {end: 0}
    here = end
    for _ in range(LOOP_STEPS):
        moved = None
        for event, relation in steps:
            after = enc.post(relation, fp.state(here)) & stuck
            if after != enc.false:
                moved = (event, pick(fp, after))
                break
        if moved is None:
            break
        loop.append(moved)
        here = moved[1]
        if here in seen:
            loop = loop[seen[here] :]
            break
        seen[here] = len(loop)
    return Starved(
        robot, location, tuple(Step(e, fp.describe(s)) for e, s in path), fp.describe(end),
        tuple(Step(e, fp.describe(s)) for e, s in loop),  # type: ignore[arg-type]
    )


def check_finish(result: SynthesisResult, options: SynthesisOptions = DEFAULT) -> Finish:
    """Whether every robot of ``result``'s fleet can always get to each place it goes to (see
    the module's description); a network without copies has no robots to check."""
    start = time.perf_counter()
    network = result.network
    fp = result.fixpoint if result.method == "symbolic" else None
    robots = _robots(network)
    stands_for = tuple(name for _, name in robots)
    if result.method == "symmetric" or (fp is None and robots):
        try:
            fleet, kept = apart(network)
            fp = fixpoint(fleet.network, options, fleet=True)
            by_name = {a.component.name: a for a in fleet.network.automata if a.component is not None}
            robots = [(by_name[name], name) for name in kept]
            stands_for = tuple(robots_of(g) for g in groups(network))
        except NotSymmetric:  # the copies' requirements differ: each robot followed on its own
            fp = fixpoint(network, options)
    if fp is None or not robots:
        return Finish((), (), (), time.perf_counter() - start)
    steps = controlled_steps(fp)
    relations = [r for _, r in steps]
    found = []
    places: list[str] = []
    for automaton, name in robots:
        lost = []
        for location in automaton.locations:
            stuck = never_again(fp, location, relations, options.explore)
            if stuck is not None and location.name not in places:
                places.append(location.name)
            if stuck is not None and stuck != fp.enc.false:
                lost.append((location.name, stuck))
        if lost:
            first = starved(fp, name, lost[0][0], lost[0][1], steps)
            found.append(Starved(first.robot, first.location, first.path, first.state, first.loop,
                                 tuple(place for place, _ in lost[1:])))
    return Finish(
        tuple(name for _, name in robots), stands_for, tuple(found), time.perf_counter() - start, tuple(places)
    )


def finish_supervisor(result: SynthesisResult, finish: Finish, options: SynthesisOptions = DEFAULT) -> SynthesisResult:
    """The maximally permissive supervisor of ``result``'s network under which, besides, every
    robot can always get to each of the places ``finish`` found it going to (the monolithic
    method, a marking per robot and place); ``result`` itself where nobody can be starved."""
    if finish.ok:
        return result
    start = time.perf_counter()
    places = set(finish.places)
    targets = [location for automaton, _ in _robots(result.network) for location in automaton.locations
               if location.name in places]
    enforced = synthesize_monolithic(result.network, options, targets=targets)
    note = (
        "every robot can always get to each of its places (" + ", ".join(finish.places) + "): "
        "the supervisor also keeps the fleet where none can be starved (monolithic: one marking per robot and place)"
    )
    return SynthesisResult(
        enforced.network, enforced.method, enforced.ok, enforced.guards, enforced.reachable_states,
        time.perf_counter() - start, enforced.explanation, enforced.supervisor, enforced.fixpoint,
        fleet=f"monolithic: {note}", fleet_note=note, effort=enforced.effort,
    )
