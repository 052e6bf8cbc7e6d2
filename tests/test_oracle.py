"""The random-model oracle (issue 28): random fleets, each synthesized by the default method,
by counting robots (pairs of copies too), monolithically, explicitly, and by libFAUDES, and
compared state by state and event by event.

``ROBOSC_ORACLE_EXAMPLES`` sets how many fleets (CI: the default); the features the models
used, and how many were compared by each method, are printed at the end of the run."""

from __future__ import annotations

import collections
import os

from hypothesis import HealthCheck, assume, given, settings

from faudes_oracle import libfaudes_supervisor, robosc_figures
from fleet_models import FEATURES, fleets
from module_check import module_agrees
from random_models import robots
from robosc.api import check_text
from robosc.codegen import pyexpr
from robosc.plant import build_network
from robosc.synthesis.compare import compare
from robosc.synthesis.counting.synthesis import synthesize_counted
from robosc.synthesis.explicit import TooManyStates, synthesize_explicit
from robosc.synthesis.methods import synthesize_symbolic
from robosc.synthesis.symbolic import synthesize_monolithic

EXAMPLES = int(os.environ.get("ROBOSC_ORACLE_EXAMPLES", "1000"))
MAX_STATES = 1_000  # the explicit reference enumerates them all; larger fleets are left out (and counted)

# what the run met: printed by conftest.py's terminal summary
SEEN: collections.Counter[str] = collections.Counter()


def summary() -> list[str]:
    lines = []
    if SEEN["models"]:
        lines.append(
            f"fleet oracle: {SEEN['models']} random fleets compared ({SEEN['too large']} left out: over {MAX_STATES} "
            f"states); counted by the default method: {SEEN['counted (default)']}, counting pairs too: "
            f"{SEEN['counted (pairs)']} ({SEEN['counted, homes of their own']} of them copies with homes of their own); every one also against libFAUDES; no supervisor: {SEEN['no supervisor']}"
        )
        lines += [f"  {feature}: {SEEN[feature]}" for feature in FEATURES]
    if SEEN["modules"]:
        lines.append(
            f"generated modules: {SEEN['modules']} fleets run at random, {SEEN['module states']} states, "
            "each decision the monolithic supervisor's"
        )
    return lines


def oracle(text: str) -> collections.Counter[str]:
    """Every method on ``text``'s network, against explicit synthesis; libFAUDES against it."""
    checked = check_text(text)
    assert checked.model is not None, checked.render() + "\n" + text
    network = build_network(checked.model)
    try:
        explicit = synthesize_explicit(network, max_states=MAX_STATES)
    except TooManyStates:
        SEEN["too large"] += 1
        assume(False)
    default = synthesize_symbolic(network)
    pairs = synthesize_counted(network, least=2)
    results = [("default", default), ("monolithic", synthesize_monolithic(network))]
    if pairs.fleet != default.fleet:  # else the same groups: the same computation
        results.append(("counting pairs", pairs))
    for name, result in results:
        comparison = compare(explicit, result)
        assert comparison.agree, (
            f"{name} ({result.fleet or result.method}): {comparison.differences}\n{text}"
        )
    expected = libfaudes_supervisor(explicit)
    found = robosc_figures(explicit.supervisor) if explicit.ok else (0, 0)
    assert found == expected, f"robosc {found}, libFAUDES {expected}\n{text}"
    return collections.Counter(
        {
            "counted (default)": default.method == "symmetric",
            "counted (pairs)": pairs.method == "symmetric",
            "counted, homes of their own": "homes of their own" in str(pairs.fleet),
            "no supervisor": not explicit.ok,
        }
    )


@settings(max_examples=EXAMPLES, deadline=None, database=None, suppress_health_check=list(HealthCheck))
@given(fleets())
def test_random_fleets_every_method_gives_the_same_supervisor(model: tuple[str, frozenset[str]]) -> None:
    text, features = model
    SEEN.update(oracle(text))
    SEEN["models"] += 1
    SEEN.update(features)


@settings(max_examples=300, deadline=None, database=None, suppress_health_check=list(HealthCheck))
@given(robots())
def test_random_robots_with_events_of_several_outcomes_match_libfaudes(text: str) -> None:
    """Single robots (variables and guards too), where an event often has two outcomes."""
    oracle(text)


@settings(
    max_examples=int(os.environ.get("ROBOSC_ORACLE_MODULES", "200")),
    deadline=None,
    database=None,
    suppress_health_check=list(HealthCheck),
)
@given(fleets())
def test_random_fleets_generated_module_decides_as_the_monolithic_supervisor(model: tuple[str, frozenset[str]]) -> None:
    """A sample of the oracle's fleets: the module ``robosc generate`` writes from the default
    method's result, run at random, allows what the monolithic supervisor allows."""
    text, _ = model
    network = build_network(check_text(text).model)
    default, monolithic = synthesize_symbolic(network), synthesize_monolithic(network)
    assert default.ok == monolithic.ok, text
    assume(default.ok)
    SEEN["modules"] += 1
    # every other fleet: a tally from groups of two robots (robosc's tallies start at four)
    tallied_from = pyexpr.TALLIED_FROM
    pyexpr.TALLIED_FROM = 2 if SEEN["modules"] % 2 else tallied_from
    try:
        SEEN["module states"] += module_agrees(default, monolithic, runs=2, steps=25)
    finally:
        pyexpr.TALLIED_FROM = tallied_from
