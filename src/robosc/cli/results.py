"""How a synthesis result is shown: the table of conditions, why synthesis added them, why
none exists, the cross-check, warnings (text), the same as JSON; and :func:`supervised`, which
the commands that need a supervisor share (it ends the command with the printed reason when
none exists)."""

from __future__ import annotations

import contextlib
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import click

from robosc.api import SynthesisResult, plan_supervisor, synthesize_model
from robosc.cli.common import EXIT_MODEL_ERRORS, exit_with, load_robot, say, synthesis_running, width
from robosc.cli.table import Cell, boxed, table_width
from robosc.language.diagnostics import Diagnostic, render_text, to_json
from robosc.language.render import render
from robosc.synthesis.compare import Comparison
from robosc.synthesis.finish import Finish
from robosc.synthesis.restrictions import restriction as why_restricted
from robosc.synthesis.result import Explanation, Restriction
from robosc.synthesis.warnings import why_lines
from robosc.wrapping import fill

if TYPE_CHECKING:
    from robosc.codegen.plan import Plan


def _explanation(explanation: Explanation) -> dict[str, Any]:
    return {
        "reason": explanation.reason,
        "initial_state": explanation.initial_state,
        "path": [{"event": s.event.name, "state": s.state} for s in explanation.path],
        "fixes": [
            {
                "text": f.text,
                **({"path": f.span.path, "line": f.span.line, "column": f.span.column} if f.span is not None else {}),
            }
            for f in explanation.fixes
        ],
    }


def _why(restriction: Restriction | None) -> dict[str, Any] | None:
    if restriction is None:
        return None
    return {
        "never": restriction.never,
        "note": restriction.note,
        "path": [{"event": s.event.name, "state": s.state} for s in restriction.path],
        "state": restriction.state,
        "after": restriction.after,
        "consequence": _explanation(restriction.consequence),
    }


def as_json(result: SynthesisResult, warnings: list[Diagnostic] | None = None) -> dict[str, Any]:
    import json

    explanation = result.explanation
    return {
        "model": result.network.model.name,
        "ok": result.ok,
        "method": result.method,
        "reachable_states": result.reachable_states if result.ok else None,
        "fleet": result.fleet or None,
        "fleet_note": result.fleet_note or None,
        "seconds": round(result.seconds, 6),
        "events": [
            {
                "event": g.event.name,
                "kind": g.event.kind.value,
                "required": render(g.required) if g.required is not None else None,
                "added": render(g.added) if g.added is not None else None,
                "why": _why(why_restricted(result, g.event)) if g.added is not None else None,
            }
            for g in result.guards
        ],
        "explanation": None if explanation is None else _explanation(explanation),
        "warnings": json.loads(to_json(warnings or [])),
    }


def print_warnings(warnings: list[Diagnostic]) -> None:
    from robosc.api import InputError
    from robosc.language.loader import read_source

    sources = {}
    for path in {d.span.path for d in warnings}:
        with contextlib.suppress(InputError):
            sources[path] = read_source(path)
    columns = width(err=True)
    for diagnostic in warnings:
        click.echo(render_text(diagnostic, sources, columns), err=True)


def print_result(result: SynthesisResult, cross_check: tuple[SynthesisResult, Comparison] | None = None) -> None:
    # fitted to the terminal (or COLUMNS); piped to a file or another program without
    # COLUMNS, each sentence stays on one line and the table is kept to PIPED_WIDTH
    columns = width()

    def show(text: str, indent: str = "    ") -> None:  # fitted prose
        click.echo(fill(text, columns, indent))

    name = result.network.model.name
    if result.method == "explicit":
        _print_cross_check(result, cross_check, show)
        return
    if not result.ok:
        explanation = result.explanation
        assert explanation is not None
        failed = click.style("synthesis failed", fg="red", bold=True)
        click.echo(f"{failed} for {name}: no supervisor can keep the requirements")
        show(f"  initial state: {explanation.initial_state}")
        if explanation.path:
            click.echo("  uncontrollable events from the initial state:")
            for number, step in enumerate(explanation.path, 1):
                show(f"    {number}. {step.event.name}  ->  {step.state}", "      ")
        else:
            click.echo("  (the problem is already in the initial state)")
        show(f"  why: {explanation.reason}")
        for fix in explanation.fixes:
            show(f"  fix: {fix}")
        _print_fleet_note(result, show)
        return
    rows = []
    for guard in result.guards:
        required = render(guard.required) if guard.required is not None else "-"
        added = Cell(render(guard.added)) if guard.added is not None else "-"
        rows.append((guard.event.name, required, added))
    headers = ("controllable event", "your condition", "added by synthesis")
    click.echo(boxed(headers, rows, title=f"supervisor for {name}", no_wrap=(0,), width=table_width()))
    restrictions = [r for r in (why_restricted(result, g.event) for g in result.added_guards) if r is not None]
    if result.method == "symmetric":  # a fleet's robots are restricted alike: each explanation once
        once: dict[str, Restriction] = {}
        for restriction in restrictions:
            once.setdefault(restriction.note or restriction.event.name, restriction)
        restrictions = list(once.values())
    if restrictions:
        click.echo("why synthesis added these conditions:")
        for restriction in restrictions:
            for line in why_lines(restriction):
                show("  " + line, "      ")
    counted = " (counted: robots in the same states, in any order, count once)" if result.method == "symmetric" else ""
    show(
        f"{result.reachable_states} reachable state{'s' if result.reachable_states != 1 else ''} in the controlled "
        f"system{counted}; "
        f"synthesis added a condition to {len(result.added_guards)} of {len(result.guards)} controllable events; "
        f"{result.seconds * 1000:.1f} ms",
        "",
    )
    _print_fleet_note(result, show)


def _print_fleet_note(result: SynthesisResult, show: Any) -> None:
    note = result.fleet_note
    if note:
        show(f"note: {note}", "      ")


def _print_cross_check(
    result: SynthesisResult, cross_check: tuple[SynthesisResult, Comparison] | None, show: Any
) -> None:
    """Explicit-state synthesis computes the supervisor's states, not conditions per event: it
    is a cross-check of the symbolic method, and says so with the figures it compares."""
    plant = result.plant_states
    show(
        f"explicit-state synthesis of {result.network.model.name} (a cross-check of the symbolic method; "
        "it computes states, not conditions per event):",
        "    ",
    )
    controlled = f"{result.reachable_states} reachable states" if result.ok else "no supervisor"
    show(
        f"  uncontrolled plant: {plant} states; controlled system: {controlled} ({result.seconds * 1000:.1f} ms)",
        "    ",
    )
    if cross_check is None:
        return
    symbolic, comparison = cross_check
    if not symbolic.ok:
        found = "no supervisor"
    elif symbolic.method == "symmetric":
        found = (
            f"{symbolic.reachable_states} reachable states counted (robots in the same states, in any order, "
            f"count once; explicit: {comparison.reference_states} counted so)"
        )
    else:
        found = f"{symbolic.reachable_states} reachable states"
    if symbolic.ok:
        found += f", a condition added to {len(symbolic.added_guards)} of {len(symbolic.guards)} controllable events"
    verdict = (
        "they agree in every controlled state and event"
        if comparison.agree
        else click.style("they DISAGREE: please report this model", fg="red", bold=True)
    )
    show(f"  {symbolic.method} synthesis: {found}; {verdict}", "    ")
    for difference in comparison.differences:
        show(f"    {difference}", "      ")


def finish_json(finish: Finish) -> dict[str, Any]:
    """What ``robosc synthesize --finish`` found, as JSON."""
    return {
        "ok": finish.ok,
        "robots": list(finish.robots),
        "stands_for": list(finish.stands_for),
        "places": list(finish.places),
        "starved": [
            {"robot": s.robot, "place": s.location, "run": [step.event.name for step in s.path], "state": s.state,
             "loop": [step.event.name for step in s.loop], "also": list(s.others)}
            for s in finish.starved
        ],
    }


def print_finish(finish: Finish, enforced: bool = False) -> None:
    """What ``robosc synthesize --finish`` found, in words."""
    if not finish.robots:
        say("every robot can finish: nothing to check (no robots that are copies of each other)")
        return
    robots = ", ".join(f"{r} (for {s})" if s != r else r for r, s in zip(finish.robots, finish.stands_for, strict=False))
    if finish.ok:
        how = "under the supervisor made to keep it so" if enforced else "under the supervisor"
        places = ", ".join(finish.places) if len(finish.places) <= 6 else f"its {len(finish.places)} places"
        say(f"every robot can finish: {robots} can always get to each of {places} again, {how}")
        return
    say(f"a robot can be starved ({robots} followed):")
    for starved in finish.starved:
        say(f"  {starved}")
        say(f"    where it is stuck: [{starved.state}]")
    say("  (robosc synthesize --finish enforce makes the supervisor keep every robot able to finish)")


def supervised(
    file: str, include: tuple[str, ...], purpose: str, sizes: Mapping[str, int] | None = None, warn: bool = False
) -> tuple[SynthesisResult, Plan]:
    """Load, synthesize and lay out ``file``; the command ends with exit 1 (and the reason
    printed) when no supervisor exists. ``warn``: say the check's warnings first."""
    checked: list[Diagnostic] = []
    model = load_robot(file, include, purpose, sizes, checked if warn else None)
    print_warnings(checked)
    with synthesis_running() as progress:
        result = synthesize_model(model, progress=progress)
    if not result.ok:
        print_result(result)
        raise exit_with(EXIT_MODEL_ERRORS)
    return result, plan_supervisor(result)
