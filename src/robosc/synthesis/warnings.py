"""Warnings about a synthesized model that point at likely modelling mistakes: a
controllable event the supervisor never allows, a requirement whose condition holds in no
reachable state, a component state that no controlled run reaches. Each is a
:class:`~robosc.language.diagnostics.Diagnostic`, shown like ``robosc check``'s."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, warning
from robosc.language.render import render
from robosc.language.source import Span
from robosc.plant.network import AutomatonKind, Event, Network, Requirement
from robosc.synthesis.counting.groups import robots_of
from robosc.synthesis.counting.supervisor import CountedSupervisor
from robosc.synthesis.counting.translate import at_least
from robosc.synthesis.fixedpoints import reach
from robosc.synthesis.reached import reached_locations
from robosc.synthesis.restrictions import never_allows
from robosc.synthesis.restrictions import restriction as why_restricted
from robosc.synthesis.result import Restriction, SynthesisResult


def event_span(event: Event) -> Span | None:
    """Where the model declares ``event``: its transition, provide statement or communication."""
    for origin in (event.transition, event.provide, event.communication):
        if origin is not None:
            return origin.span
    return None


def why_lines(restriction: Restriction) -> list[str]:
    """The explanation of one added condition, as indented lines."""
    name = restriction.event.name
    lines = [f"{name}{' (never allowed)' if restriction.never else ''}:"]
    if restriction.note:
        lines.append(f"    ({restriction.note})")
    if restriction.path:
        lines.append("    a shortest run to a state where synthesis disables it:")
        lines += [f"      {n}. {s.event.name}  ->  {s.state}" for n, s in enumerate(restriction.path, 1)]
    else:
        lines.append("    synthesis disables it in the initial state")
    lines.append(f"    there [{restriction.state}], '{name}' would lead to [{restriction.after}]")
    if restriction.consequence.path:
        lines.append("    from there, events the supervisor cannot prevent:")
        lines += [f"      {n}. {s.event.name}  ->  {s.state}" for n, s in enumerate(restriction.consequence.path, 1)]
    lines.append(f"    so: {restriction.consequence.reason}")
    lines += [f"    fix: {fix}" for fix in restriction.consequence.fixes]
    return lines


def consequence(restriction: Restriction) -> str:
    """What goes wrong after the event, in one sentence."""
    steps = [step.event.name for step in restriction.consequence.path]
    then = f"then {', '.join(steps)} can follow, and " if steps else ""
    return f"it would lead to [{restriction.after}]; {then}{restriction.consequence.reason}"


def never_holding(network: Network, holds: Callable[[Requirement], bool]) -> list[Diagnostic]:
    """A ``never-holds`` warning for each requirement statement one of whose requirements
    ``holds`` says is false in every reachable state (once per statement)."""
    found = []
    seen: set[int] = set()
    for requirement in network.requirements:
        origin = requirement.origin
        if origin is None or id(origin) in seen or holds(requirement):
            continue
        seen.add(id(origin))
        found.append(
            warning(
                origin.span,
                f"{requirement.description} never holds in a reachable state: "
                f"'{requirement.event.name}' can never happen ({render(requirement.condition)} is always false)",
                Code.NEVER_HOLDS,
            )
        )
    return found


def never_allowed(result: SynthesisResult) -> list[Diagnostic]:
    """A ``never-allowed`` warning for each controllable event the supervisor never allows
    (once per place in the model: a fleet's robots share their transitions)."""
    found: list[Diagnostic] = []
    places: set[Span] = set()
    for guard in result.added_guards:
        span = event_span(guard.event)
        if span is None or span in places or not never_allows(result, guard.event):
            continue
        restriction = why_restricted(result, guard.event)
        if restriction is None or not restriction.never:
            continue
        places.add(span)
        alike = f" ({restriction.note})" if restriction.note else ""
        found.append(
            warning(
                span,
                f"synthesis never allows '{guard.event.name}'{alike} (it adds the condition false): in "
                f"[{restriction.state}] {consequence(restriction)}",
                Code.NEVER_ALLOWED,
                "; ".join(f"fix: {fix}" for fix in restriction.consequence.fixes)
                or "run 'robosc synthesize' for the whole explanation; change the model so that this cannot happen",
            )
        )
    return found


def synthesis_warnings(result: SynthesisResult) -> list[Diagnostic]:
    fixpoint = result.fixpoint
    if result.ok and isinstance(result.supervisor, CountedSupervisor):
        return counted_warnings(result, result.supervisor)
    if not result.ok or fixpoint is None:
        return []
    enc = fixpoint.enc
    reachable = fixpoint.reachable
    found = never_allowed(result)
    found += never_holding(result.network, lambda r: (reachable & enc.boolean(r.condition)) != enc.false)
    plant: Any = None
    reached = reached_locations(result)
    for automaton in result.network.automata:
        if automaton.kind is not AutomatonKind.COMPONENT:
            continue
        for location in automaton.locations:
            if location.name in reached[automaton.name]:
                continue
            # the states the plant reaches without a supervisor (requirements ignored)
            plant = reach(enc, fixpoint.initial, fixpoint.relation.values()) if plant is None else plant
            name = f"{automaton.name}.{location.name}"
            if (plant & enc.at(location)) == enc.false:
                message, hint = f"state '{name}' can never be reached: no run of the model leads there", None
            else:
                message = f"no controlled run reaches state '{name}': the supervisor keeps the robot out of it"
                hint = "fine for a state to avoid (an error); otherwise see why in the explanations of the added conditions"
            found.append(warning(location.span, message, Code.UNREACHED_STATE, hint))
    found.sort(key=lambda d: (d.span.path, d.span.line, d.span.column))
    return found


def counted_warnings(result: SynthesisResult, supervisor: CountedSupervisor) -> list[Diagnostic]:
    """The warnings of :func:`robosc.synthesis.warnings.synthesis_warnings` from a counted
    synthesis: a requirement that never holds in a reachable state, a state no robot of a group
    reaches (named for the group's robots), and a controllable event it never allows (from
    the explanations of :mod:`robosc.synthesis.counting.explain`)."""
    fp = supervisor.fp
    fleet, enc = supervisor.fleet, fp.enc
    reachable = fp.reachable

    def holds_somewhere(requirement: Requirement) -> bool:
        owner = supervisor.agent_of_event.get(requirement.event)
        if owner is None:
            return bool((reachable & enc.boolean(fleet.translator.template(requirement.condition, None))) != enc.false)
        group, agent = owner
        template = fleet.translator.template(requirement.condition, agent)
        for index, counter in enumerate(group.counters):  # some robot at this local state: maybe this one
            here = reachable & enc.boolean(at_least(counter, 1))
            if (
                here != enc.false
                and (here & enc.boolean(fleet.translator.instantiate(template, group, index))) != enc.false
            ):
                return True
        return False

    found = never_allowed(result) + never_holding(result.network, holds_somewhere)
    plant = None
    reached = reached_locations(result)
    for group in fleet.groups:
        rep = group.rep.automata[0]
        robots = robots_of(group)
        for location in rep.locations:
            if location.name in reached[rep.name]:
                continue
            holding = [i for i, (locations, _) in enumerate(group.local) if locations[0] is location]
            somewhere = enc.false
            for index in holding:
                somewhere |= enc.boolean(at_least(group.counters[index], 1))
            plant = reach(enc, fp.initial, fp.relation.values()) if plant is None else plant
            if (plant & somewhere) == enc.false:
                message, hint = (
                    f"state '{location.name}' of {robots} can never be reached: no run of the model leads there",
                    None,
                )
            else:
                message = f"no controlled run brings any of {robots} to state '{location.name}': the supervisor keeps them out"
                hint = (
                    "fine for a state to avoid (an error); otherwise see why with --fleet monolithic on a small fleet"
                )
            found.append(warning(location.span, message, Code.UNREACHED_STATE, hint))
    found.sort(key=lambda d: (d.span.path, d.span.line, d.span.column))
    return found
