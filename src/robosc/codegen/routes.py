"""What the generated module says of each component's automaton besides its conditions: for the
generated README, what each component's driver does (:class:`Driver`); for the coordinator's
task policy (robosc.runtime.onboard.tasks), each automaton's edges and marked locations
(:class:`Route` and the shapes the instances of a group share)."""

from __future__ import annotations

from collections.abc import Mapping

from robosc.plant.network import Automaton, AutomatonKind, Network
from robosc.plant.network import EventKind as K
from robosc.record import record


@record
class Driver:
    """What a component's driver does for the node, as the model says it (for the generated
    README): the locations its report names, and after each command (an incoming message), the
    messages the model expects the driver to send back (the uncontrollable events that leave
    the locations the command leads to)."""

    component: str
    locations: tuple[str, ...]
    answers: tuple[tuple[str, tuple[str, ...]], ...]  # (command's communication, the answers' communications)


@record
class Route:
    """A component's automaton as the coordinator's task policy walks it: its location field and
    its shape, an index into the plan's shapes (the instances of a group share one)."""

    component: str
    group: str | None  # the group of instances it is one of (``bot`` for bot1), or None
    field: str
    shape: int


# a shape: the edges (from, event, to), an event of the component's own written ".go" (self-loops
# left out: they lead nowhere), its marked locations, its initial location, the locations no
# controlled run reaches
Shape = tuple[tuple[tuple[str, str, str], ...], tuple[str, ...], str, tuple[str, ...]]


def drivers(network: Network) -> tuple[Driver, ...]:
    """Each component's :class:`Driver`: what its report names, and what answers each command."""
    out = []
    for automaton in network.automata:
        if automaton.kind is not AutomatonKind.COMPONENT or automaton.component is None:
            continue
        answers: dict[str, list[str]] = {}
        for edge in automaton.edges:
            event, c = edge.event, edge.event.communication
            if not event.controllable or event.kind is not K.MESSAGE or c is None:
                continue
            found = answers.setdefault(c.name, [])
            for after in automaton.edges:
                reply = after.event.communication
                leaves = after.source is edge.target and after.target is not edge.target
                answer = not after.event.controllable and after.event.kind is K.MESSAGE
                if leaves and answer and reply is not None and reply.name not in found:
                    found.append(reply.name)
        out.append(
            Driver(
                automaton.component.name,
                tuple(location.name for location in automaton.locations),
                tuple((command, tuple(replies)) for command, replies in answers.items()),
            )
        )
    return tuple(out)


def routes(
    network: Network, field_of: Mapping[Automaton, str], reached: Mapping[str, frozenset[str]]
) -> tuple[tuple[Route, ...], tuple[Shape, ...]]:
    """Each component automaton as a :class:`Route` (``field_of``: its location field;
    ``reached``: the names of its locations a controlled run reaches, by automaton), and the
    shapes they share (an instance's own events written from its ".": the copies share one)."""
    found: list[Route] = []
    shapes: dict[Shape, int] = {}
    for automaton in network.automata:
        component = automaton.component
        if automaton.kind is not AutomatonKind.COMPONENT or component is None:
            continue
        own = component.name + "."
        edges = tuple(
            (e.source.name, e.event.name[len(component.name) :] if e.event.name.startswith(own) else e.event.name,
             e.target.name)
            for e in automaton.edges
            if e.source is not e.target
        )
        marked = tuple(location.name for location in automaton.locations if location.marked)
        seen = reached.get(automaton.name)
        never = tuple(loc.name for loc in automaton.locations if seen is not None and loc.name not in seen)
        shape = shapes.setdefault((edges, marked, automaton.initial.name, never), len(shapes))
        found.append(Route(component.name, component.group, field_of[automaton], shape))
    return tuple(found), tuple(shapes)
