"""``robosc plot``, ``robosc diagram`` and ``robosc log``: seeing what a controller did."""

from __future__ import annotations

from pathlib import Path

import click

from robosc.cli.common import (
    EXIT_MODEL_ERRORS,
    EXIT_OK,
    exit_with,
    include_option,
    input_problem,
    instances_option,
    load_robot,
)


def _records(log: str) -> list:  # type: ignore[type-arg]
    from robosc.debug.eventlog import LogError, read_log

    try:
        records = read_log(log)
    except LogError as exc:
        click.echo(f"robosc: error: {exc}", err=True)
        raise exit_with(EXIT_MODEL_ERRORS) from None
    return records


@click.command()
@click.argument("log", type=click.Path())
@click.option("-o", "--output", type=click.Path(dir_okay=False), required=True, help="The image: .png, .svg or .pdf.")
@click.option("--title", help="Title above the plot.")
def plot(log: str, output: str, title: str | None) -> None:
    """Draw the sequence-of-events plot of an event log (JSON Lines or MCAP): time on the
    x axis, one row per event, controllable events orange, uncontrollable blue."""
    if Path(output).suffix not in (".png", ".svg", ".pdf"):
        raise input_problem(f"{output}: the plot is written as .png, .svg or .pdf")
    records = _records(log)
    from robosc.debug.plot import MAX_ROWS
    from robosc.debug.plot import plot as draw

    try:
        draw(records, output, title)
    except OSError as exc:
        raise input_problem(f"{output}: cannot write: {exc.strerror or exc}") from None
    names = len({r.event for r in records})
    click.echo(f"wrote {output}: {len(records):,} events")
    if names > MAX_ROWS:
        click.echo(f"{names:,} different events: the {MAX_ROWS - 1} most frequent have a row each, the others share one")
    raise exit_with(EXIT_OK)


@click.command()
@click.argument("file", type=click.Path())
@click.option(
    "-o", "--output", type=click.Path(file_okay=False), required=True, help="Directory for the .dot and .svg files."
)
@include_option
@instances_option
def diagram(file: str, output: str, include: tuple[str, ...], sizes: dict[str, int]) -> None:
    """Draw each component automaton and each communication plant (Graphviz DOT and SVG);
    edges the synthesized supervisor restricts are red, with the condition it added."""
    model = load_robot(file, include, "a diagram", sizes)
    from robosc.api import synthesize_model
    from robosc.debug.diagram import write_diagrams
    from robosc.debug.layout import LayoutError

    result = synthesize_model(model)
    if not result.ok:
        click.echo("robosc: note: no supervisor exists; drawing the plants without its conditions", err=True)
    try:
        written = write_diagrams(result, output)
    except LayoutError as exc:
        raise input_problem(f"cannot lay out the diagrams: {exc}") from None
    except OSError as exc:
        raise input_problem(f"{output}: cannot write: {exc.strerror or exc}") from None
    restricted = sum(1 for g in result.added_guards)
    click.echo(
        f"wrote {len(written) // 2} diagrams to {output} (.dot and .svg); {restricted} events restricted by the supervisor"
    )
    raise exit_with(EXIT_OK)


@click.command("log")
@click.argument("log", type=click.Path())
@click.option(
    "-o", "--output", type=click.Path(dir_okay=False), required=True, help="The converted log: .mcap or .jsonl."
)
def log_command(log: str, output: str) -> None:
    """Convert an event log between JSON Lines and MCAP (for Foxglove and the ROS bag tools)."""
    import json

    from robosc.debug.eventlog import write_mcap

    records = _records(log)
    try:
        if output.endswith(".mcap"):
            with open(output, "wb") as handle:
                write_mcap(records, handle)
        else:
            with open(output, "w", encoding="utf-8") as text:
                for r in records:
                    text.write(json.dumps(r.as_json(), sort_keys=True) + "\n")
    except OSError as exc:
        raise input_problem(f"{output}: cannot write: {exc.strerror or exc}") from None
    click.echo(f"wrote {output}: {len(records):,} events")
    raise exit_with(EXIT_OK)
