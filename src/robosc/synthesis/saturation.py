"""Saturation: the least fixed point of many local transition relations, level by level
(Ciardo, Luettgen and Siminiceanu 2001; the constrained form of Zhao and Ciardo 2009),
written with ordinary BDD operations.

Each relation reads and changes only some bits; its *top* is the highest of them in the
variable order. A relation whose top lies below a level cannot tell apart the states
that agree below it, so its fixed point can be taken in each sub-BDD hanging below that
level on its own, once for each distinct sub-BDD. Saturation does so from the bottom
up: a sub-BDD is saturated by the relations with the lowest tops first, then by those a
level higher, going back down whenever a set grows.

Chaining all relations over the whole set builds irregular intermediate sets: a
counted fleet's robot moves touch its own counters and its neighbours', so nearly all
relations are low, and saturation keeps every intermediate set as regular as the last.
On the ring of 32 robots synthesis took 17 minutes and 4.4 M peak nodes chained, nearly
all in the forward reachability, and takes a minute and 3.0 M saturated
(benchmarks/fleet_synthesis.py)."""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterable, Sequence

from robosc.synthesis.encoding import BDD, Encoding, Relation

Step = Callable[[Relation, BDD], BDD]  # Encoding.post (images) or Encoding.pre (preimages)
# entries kept in each of the two caches before it is emptied: every entry keeps BDD nodes
# alive (a warehouse of 16 robots whose every move read the door: 1,030 MB without a bound,
# 794 MB with it, 5 % more time)
CACHE_LIMIT = 1 << 20


Key = tuple[int, int, int]  # a set's and a constraint's node ids, an index into the tops
Entry = tuple[BDD, BDD, BDD]  # the set and the constraint kept alive (their ids stay theirs), the result


def keep(cache: dict[Key, Entry], key: Key, entry: Entry) -> None:
    """``cache[key] = entry``, the cache emptied first when it holds :data:`CACHE_LIMIT` entries."""
    if len(cache) >= CACHE_LIMIT:
        cache.clear()
    cache[key] = entry


def top(enc: Encoding, relation: Relation) -> int:
    """The level of the highest bit ``relation`` reads or changes (0 for one that reads none)."""
    names = set(relation.bdd.support) | set(relation.bits) | set(relation.primed)
    if relation.guard is not None:
        names |= set(relation.guard.support)
    return min((enc.bdd.level_of_var(name) for name in names), default=0)


def local(enc: Encoding, relations: Sequence[Relation]) -> bool:
    """Whether saturation suits ``relations``: at most a third of them reach into the first tenth
    of the variable order. On the benchmark families (benchmarks/explore.py) the models where
    saturation won had at most 21 % of such relations, those where chaining won (fleets whose
    every requirement names every other robot, synthesized monolithically) 57 % or more."""
    levels = max(1, len(enc.bdd.vars))
    high = sum(1 for relation in relations if top(enc, relation) < levels / 10)
    return 3 * high <= len(relations)


def fixed_point(enc: Encoding, start: BDD, relations: Iterable[Relation], step: Step, within: BDD | None = None) -> BDD:
    """The least set holding ``start`` and every ``step(relation, set)`` of it that lies
    ``within`` (everywhere when None): the states reachable from ``start`` (step
    :meth:`Encoding.post`) or that reach it (:meth:`Encoding.pre`), through states within.
    The same set as applying the relations round after round until nothing changes."""
    bdd = enc.bdd
    false = bdd.false
    within = bdd.true if within is None else within
    by_top: dict[int, list[Relation]] = {}
    for relation in relations:
        by_top.setdefault(top(enc, relation), []).append(relation)
    tops = sorted(by_top)
    if not tops:
        return start
    # a level's relations are applied to the same set one after the other: preimages rename it once
    steps = {t: enc.pre_together(by_top[t]) if step == enc.pre else step for t in tops}
    names = {bdd.level_of_var(name): name for name in bdd.vars}
    done: dict[Key, Entry] = {}  # saturated()
    walked: dict[Key, Entry] = {}  # below()

    def node(level: int, low: BDD, high: BDD) -> BDD:
        if low == high:
            return low
        if high.negated:  # CUDD keeps the then-edge regular
            return ~bdd.find_or_add(names[level], ~low, ~high)
        return bdd.find_or_add(names[level], low, high)

    def halves(u: BDD, level: int) -> tuple[BDD, BDD]:
        if u.level != level:
            return u, u
        return (~u.low, ~u.high) if u.negated else (u.low, u.high)

    def below(p: BDD, c: BDD, j: int) -> BDD:
        """``p`` with each of its sub-BDDs from level ``tops[j]`` down saturated by the
        relations whose top is there or lower."""
        if j == len(tops):
            return p
        cut = tops[j]

        def walk(u: BDD, w: BDD) -> BDD:
            if u == false or w == false:
                return u  # nothing new can come where nothing lies within
            level = min(u.level, w.level)
            if level >= cut:
                return saturated(u, w, j)
            key = (int(u), int(w), j)
            got = walked.get(key)
            if got is not None:
                return got[2]
            (u0, u1), (w0, w1) = halves(u, level), halves(w, level)
            result = node(level, walk(u0, w0), walk(u1, w1))
            keep(walked, key, (u, w, result))
            return result

        return walk(p, c)

    def saturated(p: BDD, c: BDD, i: int) -> BDD:
        """The fixed point of ``p`` under the relations whose top is ``tops[i]`` or lower,
        within ``c``."""
        if p == false:
            return p
        key = (int(p), int(c), i)
        got = done.get(key)
        if got is not None:
            return got[2]
        q = below(p, c, i + 1)
        apply = steps[tops[i]]
        while True:
            before = q
            for relation in by_top[tops[i]]:
                grown = q | (apply(relation, q) & c)
                if grown != q:
                    q = below(grown, c, i + 1)
            if q == before:
                break
        keep(done, key, (p, c, q))
        return q

    # one Python frame per level and a few per top at most; levels must not move meanwhile
    depth = sys.getrecursionlimit()
    sys.setrecursionlimit(max(depth, 2 * len(names) + 4 * len(tops) + 1000))
    reordering = bdd.configure()["reordering"]
    bdd.configure(reordering=False)
    try:
        return saturated(start, within, 0)
    finally:
        done.clear()  # the closures above refer to each other: free the BDDs now, not at collection
        walked.clear()
        steps.clear()  # (the preimage steps keep their widened relations and last renaming)
        bdd.configure(reordering=reordering)
        sys.setrecursionlimit(depth)
