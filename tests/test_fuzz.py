"""Mutated examples never crash the loader: every outcome is a model or diagnostics."""

from __future__ import annotations

import re
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import EXAMPLES
from robosc.api import check_text, format_text

TOKEN = re.compile(
    r"\s+|[A-Za-z_^][A-Za-z0-9_]*|\d+\.\d+|\d+|\"[^\"]*\"|'[^']*'|//[^\n]*|:=|->|=>|!=|>=|<=|\.\.|.", re.S
)
SOURCES = {p.name: p.read_text() for p in sorted(EXAMPLES.glob("*.rscd"))}


@st.composite
def mutated(draw: st.DrawFn) -> tuple[str, str]:
    name = draw(st.sampled_from(sorted(SOURCES)))
    tokens = TOKEN.findall(SOURCES[name])
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(["delete", "duplicate", "swap", "bytes", "replace"]))
        i = draw(st.integers(0, len(tokens) - 1))
        j = draw(st.integers(0, len(tokens) - 1))
        if kind == "delete":
            del tokens[i]
        elif kind == "duplicate":
            tokens.insert(i, tokens[i])
        elif kind == "swap":
            tokens[i], tokens[j] = tokens[j], tokens[i]
        elif kind == "replace":
            tokens[i] = tokens[j]
        else:
            tokens.insert(i, draw(st.binary(min_size=1, max_size=6)).decode("latin-1"))
    return name, "".join(tokens)


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

    from mutate import mutate, pipeline

    text = mutate(SOURCES[name], random.Random(seed), count)
    outcome = pipeline(text, name, tmp_path_factory.mktemp("pipeline"))
    assert outcome in {"errors", "library", "no supervisor", "refused by ROS", "generated"}
