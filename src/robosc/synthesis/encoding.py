"""Binary encoding of a network's state for BDDs (``dd.cudd``).

Every automaton with more than one location and every variable gets
``ceil(log2(n))`` bits for its ``n`` locations or values; each bit ``b`` has a
primed twin ``b'`` (the next state) right after it in the variable order.
Codes past ``n - 1`` are invalid and excluded by :meth:`Encoding.valid`.

Expressions become BDDs: a boolean expression directly, other expressions as
a map from each value they can take to the BDD of where they take it.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Sequence
from typing import Any

from dd import cudd

from robosc.language import model as m
from robosc.plant.network import Automaton, Network
from robosc.record import record
from robosc.synthesis.evaluate import ARITHMETIC, COMPARE
from robosc.synthesis.options import DEFAULT, SynthesisOptions
from robosc.synthesis.ordering import initial_order
from robosc.synthesis.progress import Watch

BDD = Any  # dd.cudd.Function
CACHE_SLOTS = 2**16
Item = Automaton | m.Variable


@record
class Field:
    """The bits of one automaton's location or one variable's value."""

    item: Item
    name: str  # a readable, unique prefix for the bits
    values: tuple[Any, ...]  # locations or domain values, in code order
    bits: tuple[str, ...]

    @property
    def primed(self) -> tuple[str, ...]:
        return tuple(b + "'" for b in self.bits)


SMALL_GUARD = 2000  # BDD nodes: a condition this small is conjoined into a relation, a larger one kept apart


@record
class Relation:
    """A transition relation that changes only ``bits``: every other bit keeps its value.

    Partitioning this way keeps each relation small, and images rename and
    quantify only the bits that change.
    """

    bdd: BDD
    bits: list[str]
    primed: list[str]
    guard: BDD | None = None  # only from states where this holds (kept apart: see restrict)
    # where every transition sets the changed bits to the same values (an edge from a known
    # location): those values, and the states the transitions leave (see Encoding.fixed_target)
    target: dict[str, bool] | None = None
    source: BDD | None = None
    once: bool = False  # no state it leaves has the target's values: applying it twice finds nothing new
    # where, besides, every transition leaves from the same values of the changed bits (from one
    # location): those values, and what the states it leaves need of the other bits (source is
    # their conjunction), so that an image is a cofactor too
    origin: dict[str, bool] | None = None
    beside: BDD | None = None

    @property
    def to_primed(self) -> dict[str, str]:
        return dict(zip(self.bits, self.primed, strict=True))

    @property
    def from_primed(self) -> dict[str, str]:
        return dict(zip(self.primed, self.bits, strict=True))

    def restrict(self, condition: BDD) -> Relation:
        """The same relation, only from states where ``condition`` holds. A large condition is
        kept apart from the relation's BDD and applied to the state sets instead (a preimage is
        and-ed with it, a source set before an image): a requirement that reads the whole fleet
        is then never multiplied into the relation (on the ring family, conjoining them took a
        quarter of synthesis; 8 robots: 39 s and 16 M peak nodes before, 24 s and 10.5 M after).
        A small one is conjoined, which is as fast for the other families."""
        if condition.dag_size <= SMALL_GUARD:  # small: into the relation, as it costs nothing per step
            source = None if self.source is None else self.source & condition
            return Relation(self.bdd & condition, self.bits, self.primed, self.guard, self.target, source, self.once)
        guard = condition if self.guard is None else self.guard & condition
        return Relation(
            self.bdd, self.bits, self.primed, guard, self.target, self.source, self.once, self.origin, self.beside
        )


class Encoding:
    watch: Watch | None = None  # told of each image and preimage, for a progress display

    def __init__(self, network: Network, options: SynthesisOptions = DEFAULT) -> None:
        self.network = network
        # CUDD grows its computed table as it pays off: starting at 2^16 slots instead of
        # dd's 2^18 takes 3 ms instead of 15 (a tenth of `robosc synthesize` on an example)
        # and is as fast on the benchmark families (benchmarks/bdd_cache.py)
        self.bdd = cudd.BDD(initial_cache_size=CACHE_SLOTS)
        # By default the initial order is kept: on the benchmark families CUDD's dynamic
        # reordering (sifting) cost 1.2x to 4x the time it saved (the option turns it on).
        self.bdd.configure(reordering=options.reorder)
        self.fields: dict[int, Field] = {}
        self.images = self.preimages = 0  # post() and pre() calls: effort that does not depend on the machine
        order: list[str] = []
        items: list[tuple[Item, str, Sequence[Any]]] = [
            (item, item.name, item.locations)
            if isinstance(item, Automaton)
            else (item, f"{item.owner}.{item.name}", network.domains[item])
            for item in initial_order(network, options.order)
        ]
        for index, (item, name, values) in enumerate(items):
            width = max(0, (len(values) - 1).bit_length())
            bits = tuple(f"b{index}_{k}" for k in range(width))
            self.fields[id(item)] = Field(item, name, tuple(values), bits)
            for bit in bits:
                order += [bit, bit + "'"]
        if order:
            self.bdd.declare(*order)
        self.x_vars = [b for f in self.fields.values() for b in f.bits]
        # location -> (its automaton's field, its code), for the many location references
        self._locations = {
            id(location): (field, index)
            for field in self.fields.values()
            if isinstance(field.item, Automaton)
            for index, location in enumerate(field.values)
        }
        self.true = self.bdd.true
        self.false = self.bdd.false
        every = list(self.fields.values())
        self._valid = {False: self.valid_fields(every, False), True: self.valid_fields(every, True)}
        for counters, total in network.totals:
            self._valid[False] &= self.sums_to(counters, total)

    def sums_to(self, counters: Sequence[m.Variable], total: int) -> BDD:
        """The states where ``counters`` add up to ``total`` (a counted fleet's agents are all
        somewhere)."""
        return self.sums(counters, total).get(total, self.false)

    def sums(self, counters: Sequence[m.Variable], at_most: int) -> dict[int, BDD]:
        """Each sum of ``counters`` up to ``at_most``, and where they add up to it: summed counter
        by counter, partial sums above ``at_most`` dropped. The counters are taken from the
        bottom of the variable order up, so that each step puts a counter's few nodes above
        BDDs already built instead of going through them (ring of 24 robots: 14 s before)."""
        partial = {0: self.true}
        deepest_first = sorted(counters, key=lambda c: -self.bdd.level_of_var(self.field(c).bits[0]))
        for counter in deepest_first:
            field = self.field(counter)
            codes = [self.code(field, index) for index in range(len(field.values))]
            step: dict[int, BDD] = {}
            for so_far, where in partial.items():
                for value, code in zip(field.values, codes, strict=True):
                    if so_far + value <= at_most:
                        step[so_far + value] = step.get(so_far + value, self.false) | (where & code)
            partial = step
        return partial

    # -- fields and codes -----------------------------------------------------------
    def field(self, item: Item) -> Field:
        return self.fields[id(item)]

    def code(self, field: Field, index: int, primed: bool = False) -> BDD:
        """The BDD of ``field`` holding its ``index``-th value."""
        return self.bdd.cube(self.assignment(field, index, primed))

    def assignment(self, field: Field, index: int, primed: bool = False) -> dict[str, bool]:
        names = field.primed if primed else field.bits
        return {bit: bool((index >> k) & 1) for k, bit in enumerate(names)}

    def at(self, location: m.State, primed: bool = False) -> BDD:
        field, index = self._locations[id(location)]
        return self.code(field, index, primed)

    def holds(self, variable: m.Variable, value: Any, primed: bool = False) -> BDD:
        field = self.field(variable)
        return self.code(field, field.values.index(value), primed)

    def valid(self, primed: bool = False) -> BDD:
        return self._valid[primed]

    def valid_fields(self, fields: Sequence[Field], primed: bool) -> BDD:
        result = self.true
        for field in fields:
            if len(field.values) < 2 ** len(field.bits):
                allowed = self.false
                for index in range(len(field.values)):
                    allowed |= self.code(field, index, primed)
                result &= allowed
        return result

    def unchanged(self, field: Field) -> BDD:
        result = self.true
        for bit in field.bits:
            result &= self.bdd.var(bit).equiv(self.bdd.var(bit + "'"))
        return result

    # -- effort ------------------------------------------------------------------------
    def effort(self) -> dict[str, int]:
        """Deterministic figures of the work done so far (they do not depend on the machine's
        speed): CUDD's peak of live BDD nodes, the nodes in the unique table now, and the
        image and preimage computations."""
        figures = self.statistics()
        return {
            "peak_live_nodes": int(figures["peak_live_nodes"]),
            "nodes": int(figures["n_nodes"]),
            "images": self.images,
            "preimages": self.preimages,
            "variables": len(self.x_vars),
        }

    def statistics(self) -> dict[str, Any]:
        """CUDD's figures (dd's ``statistics``). Its node count reads CUDD's tally of live nodes
        (15 ms for a manager of 700,000 nodes, from walking its tables' slots), where ``len`` of the
        manager visits every node (100 ms; read every quarter of a second for the progress
        display, that made a ring with homes of 16 robots 387 s instead of 86)."""
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # dd's note that 'mem' is now in bytes
            return dict(self.bdd.statistics())

    def live_nodes(self) -> int:
        """The BDD nodes in use now (see :meth:`statistics`)."""
        return int(self.statistics()["n_nodes"])

    # -- state sets ------------------------------------------------------------------------
    def pre(self, relation: Relation, target: BDD) -> BDD:
        """States with a transition in ``relation`` into ``target``."""
        self.preimages += 1
        if self.watch is not None:
            self.watch.step()
        if not relation.primed:
            found = relation.bdd & target
        elif relation.target is not None:
            found = relation.source & self.bdd.let(relation.target, target)
        else:
            found = cudd.and_exists(relation.bdd, self.bdd.let(relation.to_primed, target), relation.primed)
        return found if relation.guard is None else found & relation.guard

    def fixed_target(self, relation: Relation) -> Relation:
        """``relation`` with its target noted where all its transitions set the bits they change
        to the same values (one edge's, from one location): its preimage is then the set with
        those values put in (a cofactor) and its image needs no renaming, where renaming the
        whole set to the next state would cost time proportional to its size for each."""
        if not relation.primed or relation.target is not None:
            return relation
        source = self.bdd.exist(relation.primed, relation.bdd)
        landing = self.bdd.exist([b for b in relation.bdd.support if not b.endswith("'")], relation.bdd)
        if landing == self.bdd.false or self.bdd.count(landing, nvars=len(relation.primed)) != 1:
            return relation  # (with one target, the relation is its sources times it)
        values = self.bdd.pick(landing, care_vars=relation.primed)
        target = {bit: bool(values[primed]) for bit, primed in zip(relation.bits, relation.primed, strict=True)}
        once = (source & self.bdd.cube(target)) == self.bdd.false
        beside = self.bdd.exist(relation.bits, source)
        leaving = self.bdd.exist([b for b in source.support if b not in relation.bits], source)
        origin = None
        if self.bdd.count(leaving, nvars=len(relation.bits)) == 1:
            leaves = self.bdd.pick(leaving, care_vars=relation.bits)
            if self.bdd.cube(leaves) & beside == source:
                origin = {bit: bool(leaves[bit]) for bit in relation.bits}
        if origin is None:
            beside = None  # (only an image from one origin uses it)
        return Relation(
            relation.bdd, relation.bits, relation.primed, relation.guard, target, source, once, origin, beside
        )

    def pre_together(self, relations: Sequence[Relation]) -> Callable[[Relation, BDD], BDD]:
        """:meth:`pre` for ``relations`` applied one after the other to the same sets (saturation's
        relations of one level): the target is renamed to the next state once for all of them, not
        once per relation. Each relation is widened to keep the bits the others change (``b' = b``),
        so that one renaming of those bits serves all; renaming was half of a counted warehouse's
        synthesis (8 robots: 2.6 s of 4.1, 50,514 preimages)."""
        relations = [r for r in relations if r.target is None]  # the others need no renaming
        changed = sorted({b for r in relations for b in r.bits}, key=self.bdd.level_of_var)
        if len(relations) < 2 or not changed:
            return self.pre
        primed = [b + "'" for b in changed]
        to_primed = dict(zip(changed, primed, strict=True))
        widened: dict[int, BDD] = {}
        for relation in relations:
            kept = self.bdd.true
            for bit in changed:
                if bit not in relation.bits:
                    kept &= self.bdd.var(bit).equiv(self.bdd.var(bit + "'"))
            widened[id(relation)] = relation.bdd & kept
        last: list[BDD] = []  # the last target and its renaming

        def pre(relation: Relation, target: BDD) -> BDD:
            if relation.target is not None:
                return self.pre(relation, target)
            self.preimages += 1
            if self.watch is not None:
                self.watch.step()
            if not last or last[0] != target:
                last[:] = [target, self.bdd.let(to_primed, target)]
            found = cudd.and_exists(widened[id(relation)], last[1], primed)
            return found if relation.guard is None else found & relation.guard

        return pre

    def post(self, relation: Relation, source: BDD) -> BDD:
        """States reached by a transition in ``relation`` from ``source``."""
        self.images += 1
        if self.watch is not None:
            self.watch.step()
        if relation.guard is not None:
            source = source & relation.guard
        if not relation.bits:
            return relation.bdd & source
        if relation.origin is not None:  # (ring with homes of 12 robots: images 20 % faster than below)
            return self.bdd.let(relation.origin, source) & relation.beside & self.bdd.cube(relation.target)
        if relation.target is not None:
            return cudd.and_exists(relation.source, source, relation.bits) & self.bdd.cube(relation.target)
        return self.bdd.let(relation.from_primed, cudd.and_exists(relation.bdd, source, relation.bits))

    def enabled(self, relation: Relation) -> BDD:
        """States where a transition in ``relation`` can happen."""
        found = cudd.and_exists(relation.bdd, self.true, relation.primed) if relation.primed else relation.bdd
        return found if relation.guard is None else found & relation.guard

    def relation(self, bdd: BDD, fields: Sequence[Field]) -> Relation:
        bits = [b for f in fields for b in f.bits]
        return Relation(bdd, bits, [b + "'" for b in bits])

    def count(self, states: BDD) -> int:
        """How many states ``states`` holds (exact, also beyond what a double can hold)."""
        if not self.x_vars:
            return int(states == self.true)
        try:
            counted = self.bdd.count(states, nvars=len(self.x_vars))
            if counted < 2**52:  # a double counts exactly below 2^53
                return int(counted)
        except (RuntimeError, OverflowError):  # CUDD counts in doubles: more than about 2^1024 states
            pass
        total = len(self.bdd.vars)
        return _minterms(self.bdd, states, total) >> (total - len(self.x_vars))

    def state(self, locations: dict[Automaton, m.State], values: dict[m.Variable, Any]) -> BDD:
        """The BDD of one concrete state."""
        result = self.true
        for location in locations.values():
            result &= self.at(location)
        for variable, value in values.items():
            result &= self.holds(variable, value)
        return result

    def decode(self, assignment: dict[str, bool]) -> dict[int, Any]:
        """Field values (by item id) of a satisfying assignment over the unprimed bits."""
        result = {}
        for key, field in self.fields.items():
            index = sum(1 << k for k, bit in enumerate(field.bits) if assignment.get(bit, False))
            result[key] = field.values[index] if index < len(field.values) else None
        return result

    # -- expressions -------------------------------------------------------------------------
    def boolean(self, e: m.Expr) -> BDD:
        """The states where a boolean expression holds."""
        if isinstance(e, m.Literal) and isinstance(e.value, bool):
            return self.true if e.value else self.false
        if isinstance(e, m.StateRef):
            return self.at(e.state)
        if isinstance(e, m.Unary) and e.op == "!":
            return ~self.boolean(e.operand)
        if isinstance(e, m.Binary) and e.op in ("and", "or", "=>"):
            left, right = self.boolean(e.left), self.boolean(e.right)
            if e.op == "and":
                return left & right
            return left | right if e.op == "or" else (~left) | right
        if isinstance(e, m.Binary) and e.op in COMPARE:
            if e.op in ("=", "!=") and _is_boolean(e.left):
                same = self.boolean(e.left).equiv(self.boolean(e.right))
                return same if e.op == "=" else ~same
            compare = COMPARE[e.op]
            result = self.false
            for a, when_a in self.values(e.left).items():
                for b, when_b in self.values(e.right).items():
                    if compare(a, b):
                        result |= when_a & when_b
            return result
        values = self.values(e)
        return values.get(True, self.false)

    def values(self, e: m.Expr) -> dict[Any, BDD]:
        """For a non-boolean expression: each value it can take, and where it takes it."""
        if isinstance(e, m.Literal):
            return {e.value: self.true}
        if isinstance(e, m.EnumLiteral):
            return {e.value: self.true}
        if isinstance(e, m.VariableRef):
            field = self.field(e.variable)
            return {value: self.code(field, i) for i, value in enumerate(field.values)}
        if isinstance(e, m.Unary) and e.op == "-":
            return _merge((-v, u) for v, u in self.values(e.operand).items())
        if isinstance(e, m.Binary) and e.op in ARITHMETIC:
            apply = ARITHMETIC[e.op]
            pairs = []
            for a, when_a in self.values(e.left).items():
                for b, when_b in self.values(e.right).items():
                    if e.op == "/" and b == 0:
                        continue  # division by zero: no value (the edge cannot be taken)
                    pairs.append((apply(a, b), when_a & when_b))
            return _merge(pairs)
        if isinstance(e, m.Count):  # how many terms hold: counted term by term
            counts = {0: self.true}
            for term in e.terms:
                holds = self.boolean(term)
                step: dict[int, BDD] = {}
                for n, where in counts.items():
                    step[n] = step.get(n, self.false) | (where & ~holds)
                    step[n + 1] = step.get(n + 1, self.false) | (where & holds)
                counts = {n: where for n, where in step.items() if where != self.false}
            return counts
        if _is_boolean(e):
            holds = self.boolean(e)
            return {True: holds, False: ~holds}
        raise ValueError(f"cannot encode expression of type {e.type}")


def _is_boolean(e: m.Expr) -> bool:
    return isinstance(e.type, m.BasicType) and e.type.kind is m.BasicKind.BOOLEAN


def _merge(pairs: Any) -> dict[Any, BDD]:
    result: dict[Any, BDD] = {}
    for value, where in pairs:
        result[value] = result[value] | where if value in result else where
    return result


def _minterms(bdd: Any, root: BDD, levels: int) -> int:
    """Satisfying assignments of ``root`` over all ``levels`` variables, counted exactly with
    Python integers (CUDD's count is a double). Iterative, as BDDs can be deep; complement
    edges (``negated``) are followed."""
    memo: dict[tuple[int, bool], tuple[int, int]] = {}

    def leaf(u: Any) -> tuple[int, int] | None:
        if u == bdd.false:
            return (0, levels)
        if u == bdd.true:
            return (1, levels)
        return memo.get((int(u), u.negated))

    stack = [root]
    while stack:
        u = stack[-1]
        if leaf(u) is not None:
            stack.pop()
            continue
        low, high = (~u.low, ~u.high) if u.negated else (u.low, u.high)
        lo, hi = leaf(low), leaf(high)
        if lo is None or hi is None:
            stack += [c for c, r in ((low, lo), (high, hi)) if r is None]
            continue
        level = u.level
        memo[(int(u), u.negated)] = (lo[0] << (lo[1] - level - 1)) + (hi[0] << (hi[1] - level - 1)), level
        stack.pop()
    count, level = leaf(root) or (0, levels)
    return count << level
