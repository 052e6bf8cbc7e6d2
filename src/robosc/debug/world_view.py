"""The live view page of a world (``robosc sim --view``) and of a fleet's coordinator: one page
for a whole fleet, or for the robots of a world with a goal. The map (when a world is known)
with every robot, the person, the door, and each cell's occupancy (a robot in it) and
reservation (a robot driving into it); a table of the robots, each one's automaton state and
variables on demand (a click on its row); the other components; the coordinator's events,
filtered by robot. A robot whose state the coordinator has not confirmed, or whose position
has not come for a while, is marked stale.

The page is fed by :mod:`robosc.runtime.onboard.live_server` as the single robot's page is:
event records (``{"time", "event", "controllable", "data", "state"}``) and, from a simulation
or pose topics, frames (``{"time", "frame": {"t", "robots": {name: {"x", "y", "heading",
"doing", "cell", "into", "tasks", "collided"}}, "person", "door"}, "state"}``).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from robosc.codegen.templating import environment
from robosc.plant.network import AutomatonKind
from robosc.synthesis.result import SynthesisResult


def is_fleet(result: SynthesisResult) -> bool:
    """Whether the model has groups of instances (``component bot[3]``): a fleet's page then."""
    return bool(result.network.model.groups)


NO_MAP = '<script type="application/json" id="worldmap">null</script>'  # a page without a world's map


def page_meta(result: SynthesisResult, world_robots: list[str] | None = None) -> dict[str, Any]:
    """What the page knows before any data: the robots (the groups' instances, in order) and the
    other components, each with its locations and variables. A model without groups (a robot's
    controller, one per robot of a world with a goal) shows the ``world_robots`` instead, and
    no other components (each robot's are its controller's own)."""
    model = result.network.model
    if not model.groups and world_robots is not None:
        return {
            "model": model.name,
            "robots": [{"name": name, "group": None, "locations": [], "variables": []} for name in world_robots],
            "others": [],
        }
    automata = {a.name: a for a in result.network.automata if a.kind is AutomatonKind.COMPONENT}

    def entry(component: Any) -> dict[str, Any]:
        automaton = automata.get(component.name)
        locations = [loc.name for loc in automaton.locations] if automaton is not None else []
        variables = [f"{component.name}.{v.name}" for b in component.behaviours for v in b.variables]
        return {"name": component.name, "group": component.group, "locations": locations, "variables": variables}

    robots = [entry(c) for instances in model.groups.values() for c in instances]
    grouped = {r["name"] for r in robots}
    others = [entry(c) for c in model.components if c.name not in grouped]
    return {"model": model.name, "robots": robots, "others": others}


def _script_json(value: Any) -> str:
    return json.dumps(value, sort_keys=True, allow_nan=False).replace("</", "<\\/")


def render_world_page(
    result: SynthesisResult, world_map: dict[str, Any] | None = None, robots: list[str] | None = None
) -> str:
    """The page (HTML, self-contained) for ``result``'s fleet, or for the ``robots`` of a world
    with a goal that ``result``'s controller drives; ``world_map`` from
    :func:`robosc.sim.view.world_map` draws the map."""
    model = result.network.model
    template = environment("robosc.debug").get_template("world.html.j2")
    meta = _script_json(page_meta(result, robots))
    fleet = bool(model.groups) or robots is None
    page = template.render(
        model=model.name, source=Path(model.path).name, meta_json=meta, map_json="null", fleet=fleet
    )
    return page if world_map is None else with_map(page, world_map)


def with_map(page: str, world_map: dict[str, Any]) -> str:
    """A fleet's page without a map (a coordinator's, as it publishes it) with ``world_map``;
    ValueError for a page that is not a fleet's or has a map already."""
    if page.count(NO_MAP) != 1:
        raise ValueError("the page is not a fleet coordinator's live view (or it has a map already)")
    return page.replace(NO_MAP, NO_MAP.replace(">null<", ">" + _script_json(world_map) + "<"))


def robots_on(page: str) -> list[str]:
    """The robots a fleet's page shows, in order (ValueError for a page that is not a fleet's)."""
    start = page.find('<script type="application/json" id="meta">')
    end = page.find("</script>", start)
    if start < 0 or end < 0:
        raise ValueError("the page is not a fleet coordinator's live view")
    text = page[start + len('<script type="application/json" id="meta">') : end].replace("<\\/", "</")
    try:
        meta = json.loads(text)
        return [str(r["name"]) for r in meta["robots"]]
    except (ValueError, KeyError, TypeError):
        raise ValueError("the page is not a fleet coordinator's live view") from None
