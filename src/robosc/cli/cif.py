"""``robosc cif FILE -o OUT.cif [-I DIR]``."""

from __future__ import annotations

from pathlib import Path

import click

from robosc.cli.common import EXIT_OK, exit_with, include_option, input_problem, instances_option, load_robot


@click.command()
@click.argument("file", type=click.Path())
@click.option("-o", "--output", type=click.Path(dir_okay=False), required=True, help="The CIF file to write.")
@include_option
@instances_option
def cif(file: str, output: str, include: tuple[str, ...], sizes: dict[str, int]) -> None:
    """Write the model's plants and requirements as CIF 3 text (for Eclipse ESCET)."""
    model = load_robot(file, include, "CIF export", sizes)
    from robosc.codegen.cif import NameClash, to_cif  # jinja2 only when this command runs
    from robosc.plant import build_network

    try:
        text = to_cif(build_network(model), Path(file).name)
    except NameClash as exc:
        raise input_problem(f"{file}: cannot write CIF: {exc}") from None
    try:
        Path(output).write_text(text, encoding="utf-8")
    except OSError as exc:
        raise input_problem(f"{output}: cannot write: {exc.strerror or exc}") from None
    click.echo(f"wrote {output}")
    raise exit_with(EXIT_OK)
