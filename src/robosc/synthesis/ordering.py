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


def graph_of(order: list[int], edges: list[list[int]]) -> dict[int, list[int]]:
    """The items linked when a hyperedge ties them together, neighbours in the order's order."""
    where = {item: k for k, item in enumerate(order)}
    linked: dict[int, set[int]] = {i: set() for i in order}
    for e in edges:
        for i in e:
            linked[i].update(j for j in e if j != i)
    return {i: sorted(linked[i], key=where.__getitem__) for i in order}


def _distances(graph: dict[int, list[int]], start: int) -> dict[int, int]:
    found = {start: 0}
    queue = deque([start])
    while queue:
        i = queue.popleft()
        for j in graph[i]:
            if j not in found:
                found[j] = found[i] + 1
                queue.append(j)
    return found


def _ends(graph: dict[int, list[int]], part: list[int]) -> tuple[int, int]:
    """Two items of a connected ``part`` nearly as far apart as any (George and Liu's
    pseudo-peripheral pair): from a least-linked item, to the least-linked of the farthest
    from it, while that goes further."""
    start = min(part, key=lambda i: len(graph[i]))
    far = _distances(graph, start)
    while True:
        depth = max(far.values())
        end = min((i for i, d in far.items() if d == depth), key=lambda i: len(graph[i]))
        beyond = _distances(graph, end)
        if max(beyond.values()) <= depth:
            return start, end
        start, far = end, beyond


def cuthill_mckee(graph: dict[int, list[int]], part: list[int]) -> list[int]:
    start, _ = _ends(graph, part)
    order, placed = [start], {start}
    for i in order:  # breadth-first, the least-linked neighbours first
        for j in sorted((j for j in graph[i] if j not in placed), key=lambda j: len(graph[j])):
            placed.add(j)
            order.append(j)
    return order


def sloan(graph: dict[int, list[int]], part: list[int], w1: int = 1, w2: int = 2) -> list[int]:
    """Sloan's profile reduction: from one end of the part, each step numbers the item whose
    distance to the other end (weight ``w2``) minus its unnumbered links (``w1``) is the highest."""
    start, end = _ends(graph, part)
    distance = _distances(graph, end)
    rank = {i: k for k, i in enumerate(part)}
    inactive, preactive, active, done = 0, 1, 2, 3
    status = dict.fromkeys(part, inactive)
    priority = {i: w2 * distance[i] - w1 * (len(graph[i]) + 1) for i in part}
    status[start] = preactive
    queue = {start}
    order: list[int] = []
    while queue:
        i = max(queue, key=lambda k: (priority[k], -rank[k]))
        queue.discard(i)
        if status[i] == preactive:
            for j in graph[i]:
                priority[j] += w1
                if status[j] == inactive:
                    status[j] = preactive
                    queue.add(j)
        status[i] = done
        order.append(i)
        for j in graph[i]:
            if status[j] != preactive:
                continue
            status[j] = active
            priority[j] += w1
            for k in graph[j]:
                if status[k] == done:
                    continue
                priority[k] += w1
                if status[k] == inactive:
                    status[k] = preactive
                    queue.add(k)
    return order


def dcsh(order: list[int], edges: list[list[int]]) -> list[int]:
    """ESCET's DCSH: Cuthill-McKee and Sloan over the graph of what the hyperedges tie together,
    each also reversed, the one with the smallest total span kept (the order itself if none is
    smaller). Parts that share nothing are ordered one after the other."""
    graph = graph_of(order, edges)
    parts: list[list[int]] = []
    seen: set[int] = set()
    for i in order:
        if i not in seen:
            reached = _distances(graph, i)
            seen.update(reached)
            parts.append([j for j in order if j in reached])
    candidates = []
    for method in (cuthill_mckee, sloan):
        found = [i for part in parts for i in method(graph, part)]
        candidates += [found, [i for part in parts for i in reversed(method(graph, part))]]
    return min([order, *candidates], key=lambda c: total_span(c, edges))


IMPROVEMENTS = {"force": force, "slidwin": sliding_window, "dcsh": dcsh}


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
