"""``robosc synthesize FILE [-I DIR] [--json]``."""

from __future__ import annotations

import contextlib
from typing import Any

import click

from robosc.api import SynthesisResult, cross_check, synthesize_model
from robosc.cli.common import (
    EXIT_MODEL_ERRORS,
    EXIT_OK,
    exit_with,
    include_option,
    input_problem,
    load_robot,
    say,
    synthesis_running,
    width,
)
from robosc.cli.table import Cell, boxed
from robosc.language.diagnostics import Diagnostic, render_text, to_json
from robosc.language.render import render
from robosc.plant.show import show_network as network_listing
from robosc.synthesis.compare import Comparison
from robosc.synthesis.options import (
    EDGE_ORDERS,
    EXPLORATIONS,
    FLEETS,
    FORWARDS,
    IMPROVEMENTS,
    ORDERS,
    SynthesisOptions,
    order_problem,
)
from robosc.synthesis.restrictions import restriction as why_restricted
from robosc.synthesis.result import Explanation, Restriction
from robosc.synthesis.warnings import synthesis_warnings, why_lines
from robosc.wrapping import fill


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
        "fleet": result.details.get("symmetry"),
        "fleet_note": result.details.get("fleet_note"),
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
    # COLUMNS, each condition and sentence stays on one line
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
    click.echo(boxed(headers, rows, title=f"supervisor for {name}", no_wrap=(0,), width=columns))
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
    note = result.details.get("fleet_note")
    if note:
        show(f"note: {note}", "      ")


def _print_cross_check(
    result: SynthesisResult, cross_check: tuple[SynthesisResult, Comparison] | None, show: Any
) -> None:
    """Explicit-state synthesis computes the supervisor's states, not conditions per event: it
    is a cross-check of the symbolic method, and says so with the figures it compares."""
    plant = result.details.get("plant_states")
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
    elif "counted" in symbolic.details:
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


def _order(context: click.Context, parameter: click.Parameter, value: str) -> str:
    problem = order_problem(value)
    if problem is not None:
        raise click.BadParameter(problem, context, parameter)
    return value


@click.command()
@click.argument("file", type=click.Path())
@include_option
@click.option("--json", "as_json_output", is_flag=True, help="Print the result as JSON.")
@click.option("--explicit", is_flag=True, help="Use explicit-state synthesis (small models; for cross-checking).")
@click.option("--show-network", is_flag=True, help="Also print the automata network that synthesis works on.")
@click.option(
    "--order",
    default="interaction",
    show_default=True,
    callback=_order,
    help=f"The BDD variable order (docs/synthesis-options.md): one of {', '.join(ORDERS)}, optionally followed by "
    f"improvements, each after '->': {', '.join(IMPROVEMENTS)} (e.g. 'interaction->force->slidwin'). Speed and "
    "memory only, never the result.",
)
@click.option(
    "--reorder",
    is_flag=True,
    help="Let CUDD improve the variable order while it works (dynamic sifting): less memory, usually more time.",
)
@click.option(
    "--edge-order",
    "edges",
    type=click.Choice(list(EDGE_ORDERS)),
    default="model",
    show_default=True,
    help="The order in which the fixed points apply the events (docs/synthesis-options.md): speed only.",
)
@click.option(
    "--explore",
    type=click.Choice(list(EXPLORATIONS)),
    default="auto",
    show_default=True,
    help="How the fixed points apply the events (docs/synthesis-options.md): saturation, from the bottom of the "
    "variable order up, or chained over the whole state set; auto: saturation where most events read few "
    "bits low in the order, chained otherwise. Speed and memory only.",
)
@click.option(
    "--forward",
    type=click.Choice(list(FORWARDS)),
    default="auto",
    show_default=True,
    help="Whether the search for bad states is confined to the states the requirements let the system reach "
    "(docs/synthesis-options.md); auto: on counted fleets. The supervisor is the same wherever it can get to.",
)
@click.option(
    "--fleet",
    type=click.Choice(list(FLEETS)),
    default="counted",
    show_default=True,
    help="How fleets of identical robots are synthesized (docs/synthesis-options.md): the supervisor is the same.",
)
@click.option(
    "--stats",
    is_flag=True,
    help="Also print the effort of symbolic synthesis in figures that do not depend on the machine: "
    "CUDD's peak live BDD nodes, image and preimage computations.",
)
def synthesize(
    file: str,
    include: tuple[str, ...],
    as_json_output: bool,
    explicit: bool,
    show_network: bool,
    order: str,
    reorder: bool,
    edges: str,
    explore: str,
    forward: str,
    fleet: str,
    stats: bool,
) -> None:
    """Synthesize the supervisor of a model: for each controllable event, your condition
    and the condition synthesis added. Exits 1 (and explains why) when no supervisor exists."""
    model = load_robot(file, include, "synthesis")
    options = SynthesisOptions(order, reorder, fleet, edges, explore, forward)
    comparison = None
    if explicit:
        from robosc.synthesis.explicit import TooManyStates

        try:
            result, symbolic, comparison = cross_check(model, options)
        except TooManyStates as exc:
            raise input_problem(
                f"{file}: explicit-state synthesis lists every state, and this model has {exc}: it is a cross-check "
                "for small models (leave out --explicit, or try it on a smaller fleet)"
            ) from None
    else:
        with synthesis_running(not as_json_output) as progress:
            result = synthesize_model(model, "symbolic", options, progress)
    if show_network:
        click.echo(network_listing(result.network))
        click.echo()
    warnings = synthesis_warnings(result)
    if as_json_output:
        import json

        data = as_json(result, warnings)
        if stats:
            data["effort"] = result.details.get("effort")
        if comparison is not None:
            data["cross_check"] = {
                "method": symbolic.method,
                "ok": symbolic.ok,
                "reachable_states": symbolic.reachable_states if symbolic.ok else None,
                "explicit_states_counted_so": comparison.reference_states,
                "agree": comparison.agree,
                "differences": list(comparison.differences),
            }
        click.echo(json.dumps(data, indent=2))
    else:
        print_result(result, (symbolic, comparison) if comparison is not None else None)
        effort: Any = result.details.get("effort")
        if stats and effort is not None:
            say(
                f"effort: {effort['peak_live_nodes']:,} peak live BDD nodes, {effort['images']:,} images, "
                f"{effort['preimages']:,} preimages, {effort['variables']} state bits; "
                f"{result.details.get('symmetry', 'monolithic')}; "
                f"{result.seconds * 1000:.1f} ms"
            )
        print_warnings(warnings)
    raise exit_with(EXIT_OK if result.ok else EXIT_MODEL_ERRORS)
