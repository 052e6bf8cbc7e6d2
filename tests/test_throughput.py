"""The throughput benchmark's bound (benchmarks/throughput.py): a street's crossings read from
the spans a robot's body spent in its cells, and the time a run of K tasks must take in a street
one robot wide that robots from both ends cross both ways."""

from __future__ import annotations

import pytest

import throughput


def test_a_crossing_is_read_from_the_spans_of_a_robots_body_in_the_streets_cells() -> None:
    street = ("gw", "l1", "l2", "ge")
    spans = [  # (cell, from, to), seconds: out through gw, l1, l2 into ge, back, and a visit to l1 alone
        ("gw", 0.0, 3.0), ("l1", 2.5, 6.5), ("l2", 6.0, 10.0), ("ge", 9.5, 14.0),
        ("ge", 20.0, 24.0), ("l2", 23.0, 27.5), ("l1", 27.0, 31.0), ("gw", 30.5, 33.0),
        ("l1", 40.0, 41.0),
    ]
    out = throughput.crossings(spans, street)
    assert out == [
        throughput.Crossing(through=7.5, by=4.0, gate_in=2.5, gate_out=4.0),
        throughput.Crossing(through=8.0, by=4.0, gate_in=3.0, gate_out=2.0),
    ]


def _lone(first_at_west: bool) -> throughput.Lone:
    alone = throughput.Lone()
    alone.time = 30.0
    alone.first = {"l1": 5.0 if first_at_west else 30.0, "l2": 9.0 if first_at_west else 26.0}
    alone.after = {"l1": 20.0, "l2": 24.0}
    alone.inside.update({"l1": 8.0, "l2": 8.0})
    crossing = throughput.Crossing(through=8.0, by=4.0, gate_in=2.0, gate_out=3.0)
    alone.crossings = {("gw", "l1", "l2", "ge"): [crossing, crossing]}
    return alone


@pytest.mark.parametrize("tasks", [1, 3])
def test_a_street_crossed_both_ways_takes_2k_plus_1_turns_of_one_direction(tasks: int) -> None:
    """Two robots from each end, K tasks each: 4 K crossings in 2 K + 1 turns. The run takes at
    least: the way in (5 s) + (2K + 1) crossings (8 s) + the other crossings' time in the last
    cell (4 s each) + 2K changes at a gate (3 + 2 s) + the way home (20 s)."""
    alone = [_lone(True), _lone(True), _lone(False), _lone(False)]
    assert throughput.streets(alone) == [("gw", "l1", "l2", "ge")]
    turns, total = 2 * tasks + 1, 4 * 2 * tasks
    least = 5.0 + turns * 8.0 + (total - turns) * 4.0 + (turns - 1) * 5.0 + 20.0
    rate, what = throughput.bound("lane", tasks, alone, 0.0)
    assert what == f"l1-l2 ({turns} turns of one direction)"
    assert rate == pytest.approx(3600.0 * 4 * tasks / least)


def test_a_street_crossed_from_one_end_only_has_no_turns_to_count() -> None:
    alone = [_lone(True), _lone(True)]
    assert throughput.streets(alone) == []
    _, what = throughput.bound("lane", 1, alone, 0.0)
    assert "turns" not in what
