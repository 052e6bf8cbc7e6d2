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


def hyperedges(network: Network, items: list[Any]) -> list[list[int]]:
    """What each event ties together, as lists of positions in ``items``: the automata that take
    part in it, what their guards and updates read and change, and what its requirements read;
    and each variable with the automaton that owns it. The improving orders below keep each
    such group close (Eclipse ESCET's FORCE and sliding window work on the same hyperedges)."""
    index = {id(item): i for i, item in enumerate(items)}
    automaton_of = {id(loc): a for a in network.automata for loc in a.locations}

    def position(item: Any) -> int:
        return index[id(automaton_of.get(id(item), item))]

    by_event: dict[Any, set[int]] = {}
    for automaton in network.automata:
        for event in automaton.alphabet:
            by_event.setdefault(event, set()).add(index[id(automaton)])
        for edge in automaton.edges:
            tied = by_event.setdefault(edge.event, set())
            tied.update(position(read) for read in _reads(edge.guard))
            for update in edge.updates:
                tied.add(position(update.variable))
                tied.update(position(read) for read in _reads(update.value))
    for requirement in network.requirements:
        by_event.setdefault(requirement.event, set()).update(position(read) for read in _reads(requirement.condition))
    edges = [sorted(tied) for tied in by_event.values() if len(tied) > 1]
    owners = {a.component.name: index[id(a)] for a in network.automata if a.component is not None}
    for variable in network.variables:
        if variable.owner in owners:
            edges.append(sorted({index[id(variable)], owners[variable.owner]}))
    return [e for e in edges if len(e) > 1]


def total_span(order: list[int], edges: list[list[int]]) -> int:
    """ESCET's measure of an order: the sum over the hyperedges of the distance between their
    first and last member (smaller: what interacts is closer)."""
    where = {item: k for k, item in enumerate(order)}
    return sum(max(where[i] for i in e) - min(where[i] for i in e) for e in edges)


def force(order: list[int], edges: list[list[int]]) -> list[int]:
    """FORCE (Aloul, Markov and Sakallah, 2003): each hyperedge pulls its members to its centre
    of gravity; items are sorted by the mean of their hyperedges' centres, again and again, and
    the order with the smallest total span is kept."""
    member_of: dict[int, list[int]] = {}
    for k, e in enumerate(edges):
        for i in e:
            member_of.setdefault(i, []).append(k)
    best, best_span = order, total_span(order, edges)
    for _ in range(10 * max(1, len(order).bit_length())):  # ESCET: 10 * log2(n) rounds at the most
        where = {item: k for k, item in enumerate(best)}
        centre = [sum(where[i] for i in e) / len(e) for e in edges]
        pull = {i: sum(centre[k] for k in member_of[i]) / len(member_of[i]) if i in member_of else where[i] for i in best}
        current = sorted(best, key=lambda i: (pull[i], where[i]))
        span = total_span(current, edges)
        if span >= best_span:  # no better: done
            break
        best, best_span = current, span
    return best


def sliding_window(order: list[int], edges: list[list[int]], size: int = 4) -> list[int]:
    """ESCET's sliding window: every window of ``size`` consecutive items is put in the
    permutation with the smallest total span, the window moving one item at a time."""
    import itertools

    current = list(order)
    member_of: dict[int, list[list[int]]] = {}
    for e in edges:
        for i in e:
            member_of.setdefault(i, []).append(e)
    for start in range(max(0, len(current) - size + 1)):
        window = current[start : start + size]
        touched = {id(e): e for i in window for e in member_of.get(i, [])}
        if not touched:
            continue
        best, best_span = window, None
        for permutation in itertools.permutations(window):
            trial = current[:start] + list(permutation) + current[start + size :]
            span = total_span(trial, list(touched.values()))
            if best_span is None or span < best_span:
                best, best_span = list(permutation), span
        current[start : start + size] = best
    return current


IMPROVEMENTS = {"force": force, "slidwin": sliding_window}


def initial_order(network: Network, name: str) -> list[Any]:
    """The automata and variables in the order ``name``: an initial order, optionally followed
    by improvements, as ``interaction->force->slidwin`` (see robosc.synthesis.options)."""
    first, *then = [part.strip() for part in name.split("->")]
    items: list[Any] = [*network.automata, *network.variables]
    if first == "model":
        found = items
    elif first == "sorted":
        found = sorted(items, key=lambda item: (getattr(item, "owner", ""), item.name))
    else:
        found = interaction_order(network)
        if first == "reverse":
            found = found[::-1]
    if not then:
        return found
    edges = hyperedges(network, found)
    order = list(range(len(found)))
    for step in then:
        order = order[::-1] if step == "reverse" else IMPROVEMENTS[step](order, edges)
    return [found[i] for i in order]
