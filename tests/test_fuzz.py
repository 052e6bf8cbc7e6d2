"""Mutated examples never crash the loader: every outcome is a model or diagnostics."""

from __future__ import annotations

from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mutate import SOURCES, mutate, pipeline
from robosc.api import check_text, format_text


@st.composite
def mutated(draw: st.DrawFn) -> tuple[str, str]:
    """A bundled example with 1 to 4 token mutations (``benchmarks/mutate.py``)."""
    name = draw(st.sampled_from(sorted(SOURCES)))
    return name, mutate(SOURCES[name], draw(st.randoms(use_true_random=False)), draw(st.integers(1, 4)))


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated())
def test_loading_mutated_models_only_ever_gives_diagnostics(tmp_path_factory, case: tuple[str, str]) -> None:
    name, text = case
    directory: Path = tmp_path_factory.mktemp("fuzz")
    (directory / "emergency_stop.rscd").write_text(SOURCES["emergency_stop.rscd"])
    path = str(directory / name)
    result = check_text(text, path)
    if not result.ok:
        assert result.model is None and result.errors
        for diagnostic in result.diagnostics:
            assert diagnostic.span.line >= 1 and diagnostic.span.column >= 1
            assert diagnostic.message
        result.render()
    formatted = format_text(text, path)
    if isinstance(formatted, str):
        assert format_text(formatted, path) == formatted


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(sorted(SOURCES)), st.integers(0, 2**32 - 1), st.integers(1, 4))
def test_mutated_models_through_check_synthesize_and_generate(tmp_path_factory, name: str, seed: int, count: int):
    """The whole pipeline: a mutated example ends as diagnostics, a library, no supervisor,
    a refusal by the ROS generator, or generated packages; never as another exception.
    (``python benchmarks/fuzz.py`` runs 10,000 of these.)"""
    import random

    text = mutate(SOURCES[name], random.Random(seed), count)
    outcome = pipeline(text, name, tmp_path_factory.mktemp("pipeline"))
    assert outcome in {"errors", "library", "no supervisor", "refused by ROS", "generated"}
