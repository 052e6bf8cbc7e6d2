"""Why synthesis restricts a controllable event, made on request from a result (results are
records; the explanations are made by the explain modules): a counted fleet's explanation
(robosc.synthesis.fleet_why) or the monolithic method's (robosc.synthesis.why)."""

from __future__ import annotations

from typing import Any

from robosc.plant.network import Event
from robosc.synthesis.fleet_why import counted_why
from robosc.synthesis.result import Restriction, SynthesisResult
from robosc.synthesis.why import why


def restriction(result: SynthesisResult, event: Event | str) -> Restriction | None:
    """Why synthesis restricts ``event`` (None when it adds nothing to it). Computed on request
    from the symbolic synthesis' BDDs."""
    found = result.network.event(event) if isinstance(event, str) else event
    fixpoint: Any = result.details.get("fixpoint")
    if result.ok and found.controllable and fixpoint is None and "counted" in result.details:
        return counted_why(result, found)
    if not result.ok or fixpoint is None or not found.controllable:
        return None
    return why(fixpoint, found)
