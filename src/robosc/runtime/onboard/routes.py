# -*- coding: utf-8 -*-
"""The components' automata as the task policy walks them (``tasks.py``): a generated module's
``SHAPES`` (edges, marked and initial locations, those the supervisor never lets it reach) and
``ROUTES``. A component's location is where it is on its route; the distance
from a location to a set of locations counts the edges (commands and answers alike) on the
shortest way there in the component's own automaton, whatever the others do."""

from __future__ import absolute_import, annotations

from collections import deque
from typing import Any, Dict, FrozenSet, Iterable, List, Optional, Sequence, Tuple

Edge = Tuple[str, str, str]  # (from, event, to); ".go" is the component's own go


class Route(object):
    """One component's automaton: its location field, its group of instances (or None), its
    edges by the location they leave (full event names), its marked and initial locations."""

    __slots__ = ("component", "field", "group", "initial", "leaving", "locations", "marked", "never", "shape")

    def __init__(self, component: str, group: Optional[str], field: str, shape: int,
                 edges: Sequence[Edge], marked: Sequence[str], initial: str, never: Sequence[str] = ()) -> None:
        self.component, self.group, self.field, self.shape = component, group, field, shape
        self.leaving: Dict[str, List[Tuple[str, str]]] = {}
        locations = set([initial])
        for source, event, target in edges:
            name = component + event if event.startswith(".") else event
            self.leaving.setdefault(source, []).append((name, target))
            locations.update((source, target))
        self.locations: FrozenSet[str] = frozenset(locations)
        self.marked: FrozenSet[str] = frozenset(marked)
        self.initial = initial
        self.never: FrozenSet[str] = frozenset(never)  # no controlled run reaches these

    def events(self) -> FrozenSet[str]:
        return frozenset(name for edges in self.leaving.values() for name, _ in edges)


class Routes(object):
    """Every component's :class:`Route`, with distances computed once per shape and target set."""

    def __init__(self, shapes: Sequence[Tuple[Any, ...]], routes: Sequence[Tuple[Any, ...]]) -> None:
        self.route: Dict[str, Route] = {}
        self.order: List[str] = []  # the components in the module's order
        for component, group, field, shape in routes:
            edges, marked, initial, never = shapes[shape]
            self.route[component] = Route(component, group, field, shape, edges, marked, initial, never)
            self.order.append(component)
        self.shapes = shapes
        self._distances: Dict[Tuple[int, FrozenSet[str]], Dict[str, int]] = {}

    def groups(self) -> Dict[str, List[str]]:
        """Each group of instances and its components, in order."""
        out: Dict[str, List[str]] = {}
        for name in self.order:
            group = self.route[name].group
            if group is not None:
                out.setdefault(group, []).append(name)
        return out

    def distance(self, component: str, targets: Iterable[str]) -> Dict[str, int]:
        """location -> the fewest edges from it to one of ``targets`` (absent: none leads there)."""
        route = self.route[component]
        goal = frozenset(targets)
        key = (route.shape, goal)
        found = self._distances.get(key)
        if found is None:
            entering: Dict[str, List[str]] = {}
            for source, edges in route.leaving.items():
                for _name, target in edges:
                    entering.setdefault(target, []).append(source)
            found = dict((location, 0) for location in goal if location in route.locations)
            todo = deque(found)
            while todo:
                here = todo.popleft()
                for source in entering.get(here, ()):
                    if source not in found:
                        found[source] = found[here] + 1
                        todo.append(source)
            if len(self._distances) > 4096:  # bounded: targets come from tasks at run time
                self._distances.clear()
            self._distances[key] = found
        return found

    def steps(self, component: str, location: str, targets: Iterable[str]) -> List[str]:
        """The events leaving ``location`` that bring ``component`` nearer to ``targets``."""
        far = self.distance(component, targets)
        here = far.get(location)
        if here is None or here == 0:
            return []
        return [name for name, target in self.route[component].leaving.get(location, ())
                if far.get(target, here) < here]

    def reaches(self, component: str, source: str, target: str) -> bool:
        return source in self.distance(component, (target,))
