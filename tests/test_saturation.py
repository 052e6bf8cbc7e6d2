"""Saturation (robosc.synthesis.saturation) against an explicit fixed point: random local
relations over a few bits, forward and backward, with and without a set to stay within."""

from __future__ import annotations

import random

from dd import cudd
from hypothesis import given, settings
from hypothesis import strategies as st

from robosc.synthesis.encoding import Encoding, Relation
from robosc.synthesis.fixedpoints import within
from robosc.synthesis.saturation import fixed_point, top

BITS = 6
STATES = range(2**BITS)


def bit(state: int, k: int) -> bool:
    return bool((state >> k) & 1)


class System:
    """Random relations, each changing a bit or two and reading a few bits near them."""

    def __init__(self, seed: int, single: float = 0.0) -> None:
        """``single``: the share of relations that set the bits they change to one value."""
        rng = random.Random(seed)
        self.enc = Encoding.__new__(Encoding)  # only the BDD manager and the image counters
        self.enc.bdd = cudd.BDD()
        self.enc.images = self.enc.preimages = 0
        names = [f"x{k}" for k in range(BITS)]
        self.enc.bdd.declare(*[n for name in names for n in (name, name + "'")])
        self.enc.bdd.configure(reordering=False)
        self.edges: list[set[tuple[int, int]]] = []
        self.relations: list[Relation] = []
        self.tables: list[tuple[list[int], list[int], set[tuple[tuple[bool, ...], tuple[bool, ...]]]]] = []
        for _ in range(rng.randint(1, 6)):
            low = rng.randrange(BITS)
            changed = sorted(rng.sample(range(low, min(BITS, low + 3)), rng.randint(1, min(2, BITS - low))))
            read = sorted(set(changed) | set(rng.sample(range(low, min(BITS, low + 3)), 1)))
            guarded = rng.random() < 0.3
            guard_bits = sorted(rng.sample(range(BITS), 2)) if guarded else []
            guard_ok = {values for values in _tuples(len(guard_bits)) if rng.random() < 0.6}
            table = {
                (old, new) for old in _tuples(len(read)) for new in _tuples(len(changed)) if rng.random() < 0.35
            }
            if rng.random() < single:  # one edge from known places: every transition lands on one value
                one = rng.choice(_tuples(len(changed)))
                table = {(old, one) for old, _ in table}
            edges = set()
            for s in STATES:
                if guarded and tuple(bit(s, k) for k in guard_bits) not in guard_ok:
                    continue
                for t in STATES:
                    if any(bit(s, k) != bit(t, k) for k in range(BITS) if k not in changed):
                        continue
                    if (tuple(bit(s, k) for k in read), tuple(bit(t, k) for k in changed)) in table:
                        edges.add((s, t))
            self.edges.append(edges)
            self.tables.append((read, changed, table))
            bdd = self.enc.bdd.false
            for old, new in table:
                bdd |= self.cube(dict(zip(read, old, strict=True))) & self.cube(dict(zip(changed, new, strict=True)), "'")
            guard = None
            if guarded:
                guard = self.enc.bdd.false
                for values in guard_ok:
                    guard |= self.cube(dict(zip(guard_bits, values, strict=True)))
            bits = [names[k] for k in changed]
            self.relations.append(Relation(bdd, bits, [b + "'" for b in bits], guard))

    def cube(self, values: dict[int, bool], prime: str = "") -> object:
        result = self.enc.bdd.true
        for k, value in values.items():
            var = self.enc.bdd.var(f"x{k}{prime}")
            result &= var if value else ~var
        return result

    def states(self, chosen: set[int]) -> object:
        result = self.enc.bdd.false
        for s in chosen:
            result |= self.cube({k: bit(s, k) for k in range(BITS)})
        return result

    def members(self, u: object) -> set[int]:
        return {s for s in STATES if (u & self.states({s})) != self.enc.bdd.false}


def _tuples(n: int) -> list[tuple[bool, ...]]:
    return [tuple(bool((i >> k) & 1) for k in range(n)) for i in range(2**n)]


def explicit(edges: list[set[tuple[int, int]]], start: set[int], inside: set[int] | None, forward: bool) -> set[int]:
    """The least set holding ``start`` and every successor (predecessor) of it within ``inside``."""
    result, frontier = set(start), list(start)
    while frontier:
        s = frontier.pop()
        for pairs in edges:
            for a, b in pairs:
                nxt = b if forward and a == s else a if not forward and b == s else None
                if nxt is not None and nxt not in result and (inside is None or nxt in inside):
                    result.add(nxt)
                    frontier.append(nxt)
    return result


@settings(max_examples=150, deadline=None)
@given(st.integers(0, 2**32), st.booleans(), st.booleans(), st.sampled_from([1, 3, 1 << 20]))
def test_saturation_finds_the_least_fixed_point(seed: int, forward: bool, constrained: bool, cache: int) -> None:
    """``cache``: how many entries its caches keep before they are emptied (all but none, some, all)."""
    from robosc.synthesis import saturation

    saturation.CACHE_LIMIT, kept = cache, saturation.CACHE_LIMIT
    try:
        check_least_fixed_point(seed, forward, constrained)
    finally:
        saturation.CACHE_LIMIT = kept


def check_least_fixed_point(seed: int, forward: bool, constrained: bool) -> None:
    system = System(seed)
    rng = random.Random(seed + 1)
    start = {s for s in STATES if rng.random() < 0.08} or {0}
    inside = {s for s in STATES if rng.random() < 0.7} if constrained else None
    step = system.enc.post if forward else system.enc.pre
    found = fixed_point(
        system.enc, system.states(start), system.relations, step, None if inside is None else system.states(inside)
    )
    assert system.members(found) == explicit(system.edges, start, inside, forward)


def test_a_relations_top_is_its_highest_bit_read_guard_included() -> None:
    system = System(7)
    enc = system.enc
    relation = Relation(enc.bdd.var("x3") & enc.bdd.var("x4'"), ["x4"], ["x4'"])
    assert top(enc, relation) == enc.bdd.level_of_var("x3")
    guarded = Relation(relation.bdd, relation.bits, relation.primed, enc.bdd.var("x1"))
    assert top(enc, guarded) == enc.bdd.level_of_var("x1")


def test_saturation_is_chosen_where_few_relations_reach_the_top_of_the_order() -> None:
    """The automatic choice: saturation unless more than a third of the relations read the first
    tenth of the order (here the first of 12 levels, x0)."""
    from robosc.synthesis.saturation import local

    enc = System(7).enc

    def moving(k: int, reading: int | None = None) -> Relation:
        bdd = enc.bdd.var(f"x{k}'")
        if reading is not None:
            bdd &= enc.bdd.var(f"x{reading}")
        return Relation(bdd, [f"x{k}"], [f"x{k}'"])

    spread = [moving(k) for k in range(1, 6)]
    assert local(enc, spread)
    assert local(enc, [*spread[:4], moving(0)])  # one in five from the top
    assert local(enc, [*spread[:2], moving(2, reading=0)])  # one in three
    assert not local(enc, [*spread[:3], moving(2, reading=0), moving(4, reading=0)])  # two in five


@settings(max_examples=150, deadline=None)
@given(st.integers(0, 2**32), st.booleans(), st.booleans(), st.sampled_from(["saturation", "chained", "each"]))
def test_relations_landing_on_one_value_step_as_any_other(seed: int, forward: bool, constrained: bool, how: str) -> None:
    """A relation whose transitions all set the bits they change to the same values steps by a
    cofactor (preimages) or without renaming (images), and one that cannot land where it starts
    is applied once per round: the same least fixed point as the explicit one, every way."""
    system = System(seed, single=0.6)
    enc = system.enc
    relations = [enc.fixed_target(r) for r in system.relations]
    for relation, (read, changed, table) in zip(relations, system.tables, strict=True):
        targets = {new for _, new in table}
        assert (relation.target is not None) == (len(targets) == 1), (relation.target, targets)
        if relation.target is not None:
            (target,) = targets
            assert relation.target == {f"x{k}": value for k, value in zip(changed, target, strict=True)}
            starts = {tuple(old[read.index(k)] for k in changed) for old, _ in table}
            assert relation.once == (target not in starts)
    rng = random.Random(seed + 1)
    start = {s for s in STATES if rng.random() < 0.08} or {0}
    inside = {s for s in STATES if rng.random() < 0.7} if constrained else None
    step = enc.post if forward else enc.pre
    within_bdd = None if inside is None else system.states(inside)
    explore = "chained" if how == "each" else how
    found = within(enc, system.states(start), relations, step, within_bdd, explore, each=how == "each")
    assert system.members(found) == explicit(system.edges, start, inside, forward)
