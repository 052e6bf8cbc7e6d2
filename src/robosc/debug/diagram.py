"""Automaton diagrams: each component automaton and each communication plant as Graphviz
DOT and SVG. Edges whose event the synthesized supervisor restricts (it added a
condition) are drawn red, labelled with the added condition; edges your own
requirements guard are orange, labelled with the requirement.

Node and edge ids are stable (``Platform::ready``, ``Platform::e3``), so the live
view can switch styles on the SVG without laying it out again.
"""

from __future__ import annotations

import re
from pathlib import Path

from robosc.codegen.templating import environment
from robosc.debug.layout import to_svg
from robosc.language import model as m
from robosc.language.render import render, steps
from robosc.plant.network import Automaton, AutomatonKind, Event, event_of
from robosc.record import record
from robosc.synthesis.result import SynthesisResult


@record
class Location:
    id: str
    name: str
    initial: bool
    marked: bool


@record
class Transition:
    id: str
    source: str  # location name
    target: str
    event: str  # the network event's name
    controllable: bool
    detail: str  # guard and assignments, as the model writes them ("" for none)
    required: str | None  # the user's requirement on the event
    added: str | None  # what synthesis added
    port: str | None = None  # for a self-loop: the side of the node it is drawn on

    @property
    def restricted(self) -> bool:
        return self.added is not None


@record
class Diagram:
    name: str  # the automaton's name in the network
    kind: str  # "component", "message", "service", "action"
    locations: tuple[Location, ...]
    transitions: tuple[Transition, ...]
    # a diagram drawn once for every robot of a group: for which ("bot1 .. bot16"), where the
    # diagram's "r" stands for each of them; "" for one automaton
    drawn_for: str = ""

    @property
    def file_stem(self) -> str:
        return ("plant_" if self.kind != "component" else "") + self.name.replace(".", "_")


def _detail(transition: m.Transition) -> str:
    if isinstance(transition, m.TauTransition):
        return f"if {render(transition.guard)}" if transition.guard is not None else ""
    if not transition.assignments:
        return ""
    parts = []
    for a in transition.assignments:
        parts.append(f"{a.variable.name}{steps(a.steps)} := {render(a.value)}")
    return "do " + ", ".join(parts)


class _Builder:
    def __init__(self, result: SynthesisResult) -> None:
        self.result = result
        self.network = result.network

    def guards(self, event: Event) -> tuple[str | None, str | None]:
        if not event.controllable:
            return None, None
        guard = self.result.guard(event.name) if self.result.ok else None
        if guard is None:
            return None, None
        return (
            render(guard.required) if guard.required is not None else None,
            render(guard.added) if guard.added is not None else None,
        )

    def component(self, automaton: Automaton) -> Diagram:
        component = automaton.component
        assert component is not None and component.automaton is not None
        name = automaton.name
        locations = tuple(
            Location(f"{name}::{s.name}", s.name, s is automaton.initial, s.marked) for s in automaton.locations
        )
        transitions: list[Transition] = []
        for transition in component.automaton.transitions:
            event = event_of(self.network, transition)
            required, added = self.guards(event)
            sources = automaton.locations if transition.source is None else (transition.source,)
            for source in sources:
                target = transition.target or source
                transitions.append(
                    Transition(
                        f"{name}::e{len(transitions)}",
                        source.name,
                        target.name,
                        event.name,
                        event.controllable,
                        _detail(transition),
                        required,
                        added,
                    )
                )
        return Diagram(name, "component", locations, tuple(transitions))

    def plant(self, automaton: Automaton) -> Diagram:
        name = automaton.name
        locations = tuple(
            Location(f"{name}::{s.name}", s.name, s is automaton.initial, s.marked) for s in automaton.locations
        )
        transitions: list[Transition] = []
        for edge in automaton.edges:
            required, added = self.guards(edge.event)
            transitions.append(
                Transition(
                    f"{name}::e{len(transitions)}",
                    edge.source.name,
                    edge.target.name,
                    edge.event.name,
                    edge.event.controllable,
                    "",
                    required,
                    added,
                )
            )
        return Diagram(name, automaton.kind.value, locations, tuple(transitions))


SIDES = ("n", "s", "e", "w", "ne", "se", "nw", "sw")


def _spread_loops(diagram: Diagram) -> Diagram:
    """Self-loops of one location on different sides, so their labels do not overlap."""
    count: dict[str, int] = {}
    transitions = []
    for t in diagram.transitions:
        if t.source == t.target:
            n = count.get(t.source, 0)
            count[t.source] = n + 1
            t = Transition(
                t.id, t.source, t.target, t.event, t.controllable, t.detail, t.required, t.added, SIDES[n % len(SIDES)]
            )
        transitions.append(t)
    return Diagram(diagram.name, diagram.kind, diagram.locations, tuple(transitions))


def diagrams(result: SynthesisResult) -> list[Diagram]:
    """A diagram per component automaton, then one per communication plant."""
    builder = _Builder(result)
    out = [builder.component(a) for a in result.network.automata if a.kind is AutomatonKind.COMPONENT]
    out += [
        builder.plant(a)
        for a in result.network.automata
        if a.kind in (AutomatonKind.MESSAGE, AutomatonKind.SERVICE, AutomatonKind.ACTION)
    ]
    return [_spread_loops(d) for d in out]


def _strings(text: str, instance: str, to: str) -> str:
    """``text`` with the instance's name (``bot3``, not ``bot30``, not inside a string) as ``to``."""
    pattern = r'"(?:[^"\\]|\\.)*"|(?<![\w.])' + re.escape(instance) + r"(?!\w)"
    return re.sub(pattern, lambda found: found.group(0) if found.group(0).startswith('"') else to, text)


def _generic(d: Diagram, instance: str, group: str) -> Diagram:
    """``d`` (drawn for ``instance`` of ``group``) for any robot of the group: its name and ids
    with the group's name, its labels with ``r`` for the robot."""

    def label(text: str | None) -> str | None:
        return None if text is None else _strings(text, instance, "r")

    def ident(text: str) -> str:
        return _strings(text, instance, group)

    return Diagram(
        ident(d.name),
        d.kind,
        tuple(Location(ident(loc.id), loc.name, loc.initial, loc.marked) for loc in d.locations),
        tuple(
            Transition(
                ident(t.id), t.source, t.target, label(t.event) or "", t.controllable, label(t.detail) or "",
                label(t.required), label(t.added), t.port,
            )
            for t in d.transitions
        ),
    )


def once_per_group(found: list[Diagram], model: m.Model) -> list[Diagram]:
    """``found`` with the diagrams of a group's robots (their automata, their communications'
    plants) drawn once for the group where they are all the same but for the robot's name (the
    conditions over the group, written once; ``r`` for the robot), in the place of the first."""
    groups = model.groups
    owner = {c.name: c.group for instances in groups.values() for c in instances if c.group is not None}
    generic: dict[int, tuple[str, Diagram]] = {}
    members: dict[tuple[str, str], list[int]] = {}
    for index, d in enumerate(found):
        instance = d.name if d.kind == "component" else d.name.split(".")[0]
        group = owner.get(instance)
        if group is None:
            continue
        g = _generic(d, instance, group)
        generic[index] = (instance, g)
        members.setdefault((group, g.name), []).append(index)
    out: list[Diagram] = []
    done: set[int] = set()
    for index, d in enumerate(found):
        if index in done:
            continue
        if index in generic:
            instance, g = generic[index]
            group = owner[instance]
            same = members[group, g.name]
            if len(same) == len(groups[group]) >= 2 and all(generic[i][1] == g for i in same):
                done.update(same)
                first, last = generic[same[0]][0], generic[same[-1]][0]
                out.append(Diagram(g.name, g.kind, g.locations, g.transitions, f"drawn once for {first} .. {last}"))
                continue
        out.append(d)
    return out


def dot(diagram: Diagram, title: bool = True) -> str:
    return environment("robosc.debug").get_template("automaton.dot.j2").render(d=diagram, title=title)


def svg(diagram: Diagram, title: bool = True) -> str:
    """The diagram laid out by Graphviz, as SVG text (raises ``robosc.debug.layout.LayoutError``)."""
    return to_svg(dot(diagram, title))


def write_diagrams(result: SynthesisResult, output: str | Path) -> list[Path]:
    """DOT and SVG files of every diagram under ``output``, those of a group's robots drawn once
    where they are alike (:func:`once_per_group`); returns the paths written.
    Every diagram is laid out before the first file is written, so a failure (raised as
    :class:`LayoutError`) leaves no partial output."""
    contents: list[tuple[str, str, str]] = []
    for d in once_per_group(diagrams(result), result.network.model):
        text = dot(d)
        contents.append((d.file_stem, text, to_svg(text)))
    out = Path(output)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for stem, text, image in contents:
        dot_path, svg_path = out / f"{stem}.dot", out / f"{stem}.svg"
        dot_path.write_text(text, encoding="utf-8")
        svg_path.write_text(image, encoding="utf-8")
        written += [dot_path, svg_path]
    return written
