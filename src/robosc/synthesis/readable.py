"""A BDD over the network state back to an expression over the model's own names.

Decomposes on one automaton or variable at a time (model order, components
first), groups the values that lead to the same remainder, and writes each group
as briefly as it can: ``Platform.ready``, ``Distance.front = no_wall_front``,
``Arm.picks < 3``. On a counted fleet, a condition on some counters of one group that is a
condition on their sum is written so (``c_depot + c_ready >= 2``: robots in either place), where
taken apart counter by counter it would be a case for each way of splitting the robots.
"""

from __future__ import annotations

import weakref
from typing import Any

from dd import cudd

from robosc.language import model as m
from robosc.language.render import render
from robosc.plant.expressions import FALSE, NO_SPAN, TRUE, all_of, any_of, negate
from robosc.plant.network import Automaton, AutomatonKind
from robosc.synthesis.encoding import BDD, Encoding, Field


def _order(enc: Encoding) -> list[Field]:
    network = enc.network
    components = [a for a in network.automata if a.kind is AutomatonKind.COMPONENT]
    plants = [a for a in network.automata if a.kind is not AutomatonKind.COMPONENT]
    items: list[Any] = [*components, *network.variables, *plants]
    return [enc.field(i) for i in items if enc.field(i).bits]


def _ref(field: Field) -> m.VariableRef:
    variable = field.item
    assert isinstance(variable, m.Variable)
    return m.VariableRef(variable, (), variable.type, NO_SPAN)


def _equals(field: Field, value: Any, op: str = "=") -> m.Expr:
    ref = _ref(field)
    if isinstance(value, bool):
        return ref if value == (op == "=") else negate(ref)
    if isinstance(value, m.EnumValue):
        assert isinstance(field.item, m.Variable) and isinstance(field.item.type, m.EnumType)
        constant: m.Expr = m.EnumLiteral(field.item.type, value, NO_SPAN)
    else:
        constant = m.Literal(value, m.INTEGER, NO_SPAN)
    return m.Binary(op, ref, constant, m.BOOLEAN, NO_SPAN)


def _int_range(ref: m.Expr, chosen: list[Any], free: list[Any], lowest: int, highest: int) -> m.Expr | None:
    """``ref`` (an integer from ``lowest`` to ``highest``) is one of ``chosen`` (values in ``free``
    may go either way) as one comparison or two; None where the chosen values are not one range."""
    values = sorted([*chosen, *free])
    low, high = min(chosen), max(chosen)
    if not all(v in values for v in range(low, high + 1)):  # not a contiguous range (with free values)
        return None

    def compare(op: str, value: int) -> m.Expr:
        return m.Binary(op, ref, m.Literal(value, m.INTEGER, NO_SPAN), m.BOOLEAN, NO_SPAN)

    if low == high and not any(v in free for v in (low - 1, low + 1)):
        return compare("=", low)
    reaches_low = all(v in values for v in range(lowest, low))
    reaches_high = all(v in values for v in range(high + 1, highest + 1))
    bounds = []
    if not reaches_low:
        bounds.append(compare(">=", low))
    if not reaches_high:
        bounds.append(compare("<=", high) if not reaches_low else compare("<", high + 1))
    return all_of(bounds)


def membership(field: Field, chosen: list[Any], free: list[Any]) -> m.Expr | None:
    """``field`` has one of the ``chosen`` values (values in ``free`` may go either way);
    None when no condition is needed."""
    others = [v for v in field.values if v not in chosen and v not in free]
    if not others:
        return None
    if isinstance(field.item, Automaton):
        if len(others) < len(chosen):
            return all_of([negate(m.StateRef(o, NO_SPAN)) for o in others])
        return any_of([m.StateRef(c, NO_SPAN) for c in chosen])
    if all(isinstance(v, int) and not isinstance(v, bool) for v in field.values):
        found = _int_range(_ref(field), chosen, free, min(field.values), max(field.values))
        if found is not None:
            return found
    if len(others) < len(chosen):
        return all_of([_equals(field, v, "!=") for v in others])
    return any_of([_equals(field, v) for v in chosen])


def readable(enc: Encoding, u: BDD, care: BDD | None = None) -> m.Expr:
    """An expression that holds where ``u`` holds, on the states of ``care`` (default:
    every valid state); outside ``care`` it may say anything."""
    region = enc.valid() if care is None else care & enc.valid()
    return _expr(enc, u, region, _order(enc), _SUMS.setdefault(enc, {}))


# each encoding's sums of counters and where each value is taken (made once per encoding: the
# conditions of a counted warehouse of 100 robots made them 200 times over, 78 s of 122)
_SUMS: weakref.WeakKeyDictionary[Encoding, dict[Any, Any]] = weakref.WeakKeyDictionary()


SUMMED_AT_MOST = 4  # counters of a group a condition is tried as a sum of


def _summed(enc: Encoding, u: BDD, care: BDD, support: set[str], sums: dict[Any, Any]) -> m.Expr | None:
    """``u`` on ``care`` as a condition on the sum of the counters of one group it reads (two
    to SUMMED_AT_MOST of them, nothing else): the sum at least, at most, between or equal to
    constants; None where it is not one. ``sums`` keeps each sum's values, made once."""
    for counters, size in enc.network.totals:
        read = [c for c in counters if support & set(enc.field(c).bits)]
        used = [enc.field(c) for c in read]
        if not 2 <= len(used) <= SUMMED_AT_MOST or not support <= {b for f in used for b in f.bits}:
            continue
        key = tuple(f.name for f in used)
        if key not in sums:
            # beyond the group's size a sum is never taken in a valid state (all care is valid)
            sums[key] = (_sum(used), enc.sums(read, size))
        total, values = sums[key]
        chosen, free = [], []
        for value, where in values.items():
            here = where & care
            if here == enc.false:
                free.append(value)
            elif (here & ~u) == enc.false:
                chosen.append(value)
            elif (here & u) != enc.false:
                return None  # the sum alone does not tell
        # the sums beyond the group's size are never taken (free): `>= 3` of 3 robots, not `= 3`
        highest = sum(max(f.values) for f in used)
        free += range(max(values) + 1, highest + 1)
        return _int_range(total, chosen, free, min(values), highest)
    return None


def _nobody(enc: Encoding, u: BDD, care: BDD) -> tuple[m.Expr, BDD] | None:
    """What of ``u`` on ``care`` is "no robot in any of some places", one sum per group
    (``c_out2 + c_shelf + ... = 0``: the places of each group ``u`` keeps empty, of those some
    state of ``care`` has a robot in), and where they are all empty (what is left of ``u`` is
    told there); None where ``u`` keeps no place empty. However many places, it is one condition
    a group, where taken apart counter by counter it is a case for each way of sharing the
    robots out among the other places."""
    empty = enc.true
    sums: list[m.Expr] = []
    for counters, _size in enc.network.totals:
        kept: list[m.Variable] = []
        for counter in counters:
            zero = enc.holds(counter, 0)
            if (care & ~zero) != enc.false and (u & care & ~zero) == enc.false:
                kept.append(counter)
                empty &= zero
        if kept:
            total = _sum([enc.field(counter) for counter in kept])
            sums.append(m.Binary("=", total, m.Literal(0, m.INTEGER, NO_SPAN), m.BOOLEAN, NO_SPAN))
    return (all_of(sums), empty) if sums else None


def _sum(fields: list[Field]) -> m.Expr:
    """The counters of ``fields`` added up: ``c_depot + c_ready``."""
    total: m.Expr = _ref(fields[0])
    for f in fields[1:]:
        total = m.Binary("+", total, _ref(f), m.INTEGER, NO_SPAN)
    return total


def _expr(enc: Encoding, u: BDD, care: BDD, order: list[Field], sums: dict[Any, Any]) -> m.Expr:
    if (u & care) == enc.false:
        return FALSE
    if (care & ~u) == enc.false:
        return TRUE
    u = cudd.restrict(u, care)
    support = enc.bdd.support(u)
    nobody = _nobody(enc, u, care) if enc.network.totals else None
    if nobody is not None:
        kept_empty, empty = nobody
        if (care & empty & ~u) == enc.false:  # that is all u asks
            return kept_empty
        return all_of([kept_empty, _expr(enc, u, care & empty, order, sums)])
    summed = _summed(enc, u, care, support, sums) if enc.network.totals else None
    if summed is not None:
        return summed
    position = next(i for i, f in enumerate(order) if support & set(f.bits))
    field, rest = order[position], order[position + 1 :]
    groups: dict[int, list[Any]] = {}
    remainders: dict[int, tuple[BDD, BDD]] = {}
    free: list[Any] = []
    for index, value in enumerate(field.values):
        assignment = enc.assignment(field, index)
        care_here = enc.bdd.let(assignment, care)
        if care_here == enc.false:
            free.append(value)
            continue
        remainder = cudd.restrict(enc.bdd.let(assignment, u), care_here)
        # a remainder already found that reads as this one where this value applies serves it
        # too: "count(q in east: q.home) < 3 and X or count(q in east: q.home) = 3 and Y" is "X"
        # where X holds when all are home exactly as Y does
        mine = remainder & care_here
        key = next((k for k, (r, _) in remainders.items() if (r & care_here) == mine), int(remainder))
        if key in remainders:
            remainder = remainders[key][0]
        groups.setdefault(key, []).append(value)
        previous = remainders.get(key)
        remainders[key] = (remainder, care_here if previous is None else previous[1] | care_here)
    subs: dict[int, m.Expr] = {}
    written: dict[str, int] = {}  # a remainder's text -> the first group written so
    for key in list(groups):
        remainder, care_here = remainders[key]
        if (remainder & care_here) == enc.false:
            continue
        sub = _expr(enc, remainder, care_here, rest, sums)
        # two groups whose remainders read the same where each applies are one group:
        # "(Lift.ground or Lift.top) and X or (Lift.rising or Lift.sinking) and X" is "X"
        text = render(sub)
        same = written.get(text)
        if same is not None:
            groups[same] += groups.pop(key)
            continue
        written[text] = key
        subs[key] = sub
    # Where the answer is already "true", the other groups need not exclude those values:
    # "A or (!A and B)" reads better as "A or B".
    settled = [v for key, sub in subs.items() if sub is TRUE for v in groups[key]]
    parts = []
    for key, sub in subs.items():
        condition = membership(field, groups[key], free if sub is TRUE else free + settled)
        pieces = [p for p in (condition, sub) if p is not None and p is not TRUE]
        parts.append(all_of(pieces))
    return any_of(parts)
