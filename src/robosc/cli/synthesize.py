"""``robosc synthesize FILE [-I DIR] [--json]``."""

from __future__ import annotations

import click

from robosc.api import check_finish, cross_check, enforce_finish, synthesize_model
from robosc.cli.common import (
    EXIT_MODEL_ERRORS,
    EXIT_OK,
    exit_with,
    include_option,
    input_problem,
    instances_option,
    load_robot,
    say,
    synthesis_running,
)
from robosc.cli.results import as_json, finish_json, print_finish, print_result, print_warnings
from robosc.language.diagnostics import Diagnostic
from robosc.plant.show import show_network as network_listing
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
from robosc.synthesis.warnings import synthesis_warnings


def _order(context: click.Context, parameter: click.Parameter, value: str) -> str:
    problem = order_problem(value)
    if problem is not None:
        raise click.BadParameter(problem, context, parameter)
    return value


@click.command()
@click.argument("file", type=click.Path())
@include_option
@instances_option
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
    "--finish",
    type=click.Choice(["check", "enforce"]),
    default=None,
    help="A fleet: check that every robot can always get to each place it goes to (not just the fleet back "
    "home together), naming a robot that can be starved and the loop that starves it (exit 1); enforce: "
    "make the supervisor keep that so (the monolithic method).",
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
    sizes: dict[str, int],
    as_json_output: bool,
    explicit: bool,
    show_network: bool,
    order: str,
    reorder: bool,
    edges: str,
    explore: str,
    forward: str,
    fleet: str,
    finish: str | None,
    stats: bool,
) -> None:
    """Synthesize the supervisor of a model: for each controllable event, your condition
    and the condition synthesis added. Exits 1 (and explains why) when no supervisor exists."""
    checked: list[Diagnostic] = []
    model = load_robot(file, include, "synthesis", sizes, checked)
    if not as_json_output:
        print_warnings(checked)
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
    finished = None
    if finish is not None and result.ok:
        finished = check_finish(result, options)
        if finish == "enforce" and not finished.ok:
            result = enforce_finish(result, options, finished)
            finished = check_finish(result, options) if result.ok else None
    if show_network:
        click.echo(network_listing(result.network))
        click.echo()
    warnings = synthesis_warnings(result)
    if as_json_output:
        warnings = checked + warnings
        import json

        data = as_json(result, warnings)
        if stats:
            data["effort"] = dict(result.effort) if result.effort is not None else None
        if finished is not None:
            data["finish"] = finish_json(finished)
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
        effort = result.effort
        if stats and effort is not None:
            say(
                f"effort: {effort['peak_live_nodes']:,} peak live BDD nodes, {effort['images']:,} images, "
                f"{effort['preimages']:,} preimages, {effort['variables']} state bits; "
                f"{result.fleet or 'monolithic'}; "
                f"{result.seconds * 1000:.1f} ms"
            )
        if finished is not None:
            print_finish(finished, finish == "enforce")
        print_warnings(warnings)
    starved = finished is not None and not finished.ok
    raise exit_with(EXIT_OK if result.ok and not starved else EXIT_MODEL_ERRORS)
