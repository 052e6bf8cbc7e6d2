"""A BDD variable order that keeps interacting automata and variables close together.

Nodes are the network's automata and variables; two are linked when they share
an event, when one's guard or update reads the other, when a requirement on one's
event reads the other, or when a variable belongs to an automaton. The order is
breadth-first over that graph (Cuthill-McKee style), which for chains such as a
transfer line puts each buffer next to the machines it sits between.
"""

from __future__ import annotations

from collections import deque
from typing import Any

from robosc.language import model as m
from robosc.plant.network import Network


def _reads(e: m.Expr | None) -> list[Any]:
    if e is None:
        return []
    found: list[Any] = []
    for node in m.walk(e):
        if isinstance(node, m.StateRef):
            found.append(node.state)
        elif isinstance(node, m.VariableRef):
            found.append(node.variable)
    return found


def interaction_order(network: Network) -> list[Any]:
    items: list[Any] = [*network.automata, *network.variables]
    index = {id(item): i for i, item in enumerate(items)}
    automaton_of = {id(loc): a for a in network.automata for loc in a.locations}
    links: list[set[int]] = [set() for _ in items]

    def node(item: Any) -> int:
        return index[id(automaton_of.get(id(item), item))]

    def link(a: int, b: int) -> None:
        if a != b:
            links[a].add(b)
            links[b].add(a)

    participants: dict[Any, list[int]] = {}
    for automaton in network.automata:
        me = index[id(automaton)]
        for event in automaton.alphabet:
            participants.setdefault(event, []).append(me)
        for edge in automaton.edges:
            for read in _reads(edge.guard):
                link(me, node(read))
            for update in edge.updates:
                link(me, node(update.variable))
                for read in _reads(update.value):
                    link(node(update.variable), node(read))
    for variable in network.variables:
        for automaton in network.automata:
            if automaton.component is not None and automaton.component.name == variable.owner:
                link(index[id(variable)], index[id(automaton)])
    for group in participants.values():
        for a in group:
            for b in group:
                link(a, b)
    for requirement in network.requirements:
        for a in participants.get(requirement.event, []):
            for read in _reads(requirement.condition):
                link(a, node(read))

    order: list[int] = []
    placed = [False] * len(items)
    for start in range(len(items)):
        if placed[start]:
            continue
        placed[start] = True
        queue = deque([start])
        while queue:
            current = queue.popleft()
            order.append(current)
            for neighbour in sorted(links[current]):
                if not placed[neighbour]:
                    placed[neighbour] = True
                    queue.append(neighbour)
    return [items[i] for i in order]


def initial_order(network: Network, name: str) -> list[Any]:
    """The automata and variables in the initial order ``name`` (see robosc.synthesis.options)."""
    items: list[Any] = [*network.automata, *network.variables]
    if name == "model":
        return items
    if name == "sorted":
        return sorted(items, key=lambda item: (getattr(item, "owner", ""), item.name))
    found = interaction_order(network)
    return found[::-1] if name == "reverse" else found
