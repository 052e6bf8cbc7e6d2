"""``robosc fmt FILE [--check | --write]``."""

from __future__ import annotations

from pathlib import Path

import click

from robosc.api import CheckResult, InputError, format_text
from robosc.cli.common import EXIT_MODEL_ERRORS, EXIT_OK, exit_with, input_problem, width
from robosc.language.loader import read_source


@click.command()
@click.argument("file", type=click.Path())
@click.option("--check", "check_only", is_flag=True, help="Exit 1 if the file is not in canonical layout.")
@click.option("--write", "-w", is_flag=True, help="Rewrite the file in place.")
def fmt(file: str, check_only: bool, write: bool) -> None:
    """Print a model in robosc's canonical layout (comments kept)."""
    try:
        source = read_source(file)
    except InputError as exc:
        raise input_problem(str(exc)) from None
    formatted = format_text(source.text, source.path)
    if isinstance(formatted, CheckResult):
        click.echo(formatted.render(width(err=True)), err=True)
        raise exit_with(EXIT_MODEL_ERRORS)
    if check_only:
        if formatted != source.text:
            click.echo(f"{file}: not in canonical layout (run 'robosc fmt --write {file}')", err=True)
            raise exit_with(EXIT_MODEL_ERRORS)
        click.echo(f"{file}: ok")
    elif write:
        if formatted != source.text:
            Path(file).write_text(formatted, encoding="utf-8")
    else:
        click.echo(formatted, nl=False)
    raise exit_with(EXIT_OK)
