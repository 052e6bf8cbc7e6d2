"""Synthesis's one entry: the symbolic method picks how to synthesize a network from its
options (robosc.synthesis.options.FLEETS): a fleet's robots counted where they can be
(robosc.synthesis.counting), one BDD of the whole state otherwise (robosc.synthesis.symbolic).
Whatever it picks, the supervisor is the same (tests/test_oracle.py checks it)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from robosc.plant.network import Network
from robosc.synthesis.counting.synthesis import synthesize_counted
from robosc.synthesis.options import DEFAULT, SynthesisOptions
from robosc.synthesis.progress import Progress, Watch
from robosc.synthesis.result import SynthesisResult
from robosc.synthesis.symbolic import synthesize_monolithic


def synthesize_symbolic(
    network: Network, options: SynthesisOptions = DEFAULT, progress: Callable[[Progress], Any] | None = None
) -> SynthesisResult:
    """The maximally permissive controllable, nonblocking supervisor of ``network``
    (``options``: how to compute it; the supervisor is the same whatever they are).
    ``progress``: called with a :class:`~robosc.synthesis.progress.Progress` every quarter of
    a second or so while it works, after the first."""
    watch = Watch(progress) if progress is not None else None
    if options.fleet == "counted":
        return synthesize_counted(network, options, watch=watch)
    return synthesize_monolithic(network, options, watch)
