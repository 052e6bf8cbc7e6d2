"""The live view page: each component's automaton (laid out once, by Graphviz), its
variables, the busy communications, and the latest events. The page switches CSS
classes only: the current location is highlighted, each transition flashes as it
is taken. Events arrive from :mod:`robosc.runtime.onboard.live_server` as Server-Sent Events."""

from __future__ import annotations

import json
import re
from pathlib import Path

from robosc.codegen.templating import environment
from robosc.debug.diagram import Diagram, diagrams, svg
from robosc.debug.world_view import is_fleet, render_world_page
from robosc.record import record
from robosc.synthesis.result import SynthesisResult


@record
class Card:
    diagram: Diagram
    svg: str
    variables: tuple[str, ...]  # "Component.variable"


def _inline(svg_text: str) -> str:
    """Graphviz's SVG without the XML prologue, sized by its container."""
    start = svg_text.find("<svg")
    body = svg_text[start:]
    return re.sub(r'<svg width="[^"]*" height="[^"]*"', "<svg", body, count=1)


def render_page(result: SynthesisResult) -> str:
    model = result.network.model
    all_diagrams = diagrams(result)
    variables = {
        c.name: tuple(f"{c.name}.{v.name}" for b in c.behaviours for v in b.variables) for c in model.components
    }
    cards = [
        Card(d, _inline(svg(d, title=False)), variables.get(d.name, ())) for d in all_diagrams if d.kind == "component"
    ]
    plants = [d.name for d in all_diagrams if d.kind in ("service", "action")]
    meta = {
        "robot": model.name,
        "automata": {
            d.name: {
                "locations": {loc.name: loc.id for loc in d.locations},
                "edges": [
                    {"id": t.id, "source": t.source, "target": t.target, "event": t.event} for t in d.transitions
                ],
            }
            for d in all_diagrams
            if d.kind == "component"
        },
        "plants": plants,
    }
    meta_json = json.dumps(meta, sort_keys=True).replace("</", "<\\/")
    template = environment("robosc.debug").get_template("live.html.j2")
    return template.render(
        robot=model.name, cards=cards, plants=plants, meta_json=meta_json, source=Path(model.path).name
    )


def live_page(result: SynthesisResult) -> str:
    """The page a node serves and publishes: a fleet's page (robosc.debug.world_view) for a
    model with groups of instances, which a fleet's coordinator runs; else the automata's."""
    return render_world_page(result) if is_fleet(result) else render_page(result)
