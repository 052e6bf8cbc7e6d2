"""Golden tests of the automata network: one small model per rule of SEMANTICS.md
sections 1-4 in ``tests/network/NAME.rscd`` (its first comment says which rule), and the
network robosc builds for it, as ``robosc synthesize --show-network`` lists it, in
``tests/network/NAME.network``. A change in how the network is built changes a listing,
so it cannot pass unnoticed; each listing was checked by hand against the rule.

``ROBOSC_UPDATE_GOLDEN=1 pytest tests/test_network.py`` rewrites the listings (then read
the diff: it is the change in meaning).
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from robosc.api import load_model
from robosc.plant import build_network
from robosc.plant.show import show_network

CASES = Path(__file__).parent / "network"


@pytest.mark.parametrize("model", sorted(CASES.glob("*.rscd")), ids=lambda p: p.stem)
def test_network_is_as_the_rule_says(model: Path) -> None:
    listing = show_network(build_network(load_model(model))) + "\n"
    golden = model.with_suffix(".network")
    if os.environ.get("ROBOSC_UPDATE_GOLDEN"):
        golden.write_text(listing)
    assert golden.exists(), f"no listing for {model.name}: run with ROBOSC_UPDATE_GOLDEN=1 and check it"
    assert listing == golden.read_text()


def test_every_section_has_cases() -> None:
    sections = {p.name.split("_")[0] for p in CASES.glob("*.rscd")}
    assert sections == {"s1", "s2", "s3", "s4"}


def test_start_values_follow_cif() -> None:
    """SEMANTICS 2 directly, besides its listing: integers start at the value closest to 0."""
    network = build_network(load_model(CASES / "s2_start_values.rscd"))
    start = {v.name: network.initial_values[v] for v in network.variables}
    assert (start["b"], start["around_zero"], start["positive"], start["negative"], start["given"]) == (
        False,
        0,
        3,
        -2,
        4,
    )
    assert start["level"].name == "low"
    assert "unused" not in start  # no guard reads it: not part of synthesis
