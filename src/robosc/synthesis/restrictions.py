"""Why synthesis restricts a controllable event, made on request from a result (results are
records; the explanations are made by the explain modules): a counted fleet's explanation
(robosc.synthesis.counting.explain) or the monolithic method's (robosc.synthesis.why)."""

from __future__ import annotations

from robosc.plant.network import Event
from robosc.synthesis.counting.explain import counted_why
from robosc.synthesis.counting.supervisor import CountedSupervisor
from robosc.synthesis.result import Restriction, SynthesisResult
from robosc.synthesis.why import why


def restriction(result: SynthesisResult, event: Event | str) -> Restriction | None:
    """Why synthesis restricts ``event`` (None when it adds nothing to it). Computed on request
    from the symbolic synthesis' BDDs."""
    found = result.network.event(event) if isinstance(event, str) else event
    if not result.ok or not found.controllable:
        return None
    if isinstance(result.supervisor, CountedSupervisor):
        return counted_why(result.supervisor, found)
    if result.fixpoint is None:
        return None
    return why(result.fixpoint, found)


def never_allows(result: SynthesisResult, event: Event) -> bool:
    """Whether the supervisor allows ``event`` (controllable) in no state the controlled system
    reaches: the one part of :func:`restriction` (its ``never``) that needs no explanation, so
    that a caller looking for events never allowed explains only those (a counted warehouse of
    16 robots: 60 s of explanations for none)."""
    if not result.ok or not event.controllable:
        return False
    if isinstance(result.supervisor, CountedSupervisor):
        return result.supervisor.never_allows(event)
    return result.fixpoint is not None and result.fixpoint.never_allows(event)
