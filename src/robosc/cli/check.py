"""``robosc check FILE... [-I DIR] [--format text|json]``."""

from __future__ import annotations

import click

from robosc.api import InputError, check_file
from robosc.cli.common import (
    EXIT_MODEL_ERRORS,
    EXIT_OK,
    exit_with,
    include_option,
    input_problem,
    instances_option,
    width,
)
from robosc.language.diagnostics import Diagnostic, to_json


@click.command()
@click.argument("files", nargs=-1, type=click.Path(dir_okay=True))
@include_option
@instances_option
@click.option(
    "--format", "output", type=click.Choice(["text", "json"]), default="text", help="How to print diagnostics."
)
@click.option("--list-codes", is_flag=True, help="List every diagnostic code and what it means, then exit.")
def check(
    files: tuple[str, ...], include: tuple[str, ...], sizes: dict[str, int], output: str, list_codes: bool
) -> None:
    """Check RoboSC model files: syntax, references, types and the static rules.

    Exits 0 when every file is valid (warnings allowed), 1 when a model has
    errors, 2 when a file cannot be read.
    """
    if list_codes:
        from robosc.language.codes import Code

        column = max(len(code.value) for code in Code) + 1
        for code in Code:
            click.echo(f"{code.value:<{column}} {code.description}")
        raise exit_with(EXIT_OK)
    if not files:
        raise input_problem("check needs at least one FILE (or --list-codes)")
    diagnostics: list[Diagnostic] = []
    failed = False
    for path in files:
        try:
            result = check_file(path, include, sizes)
        except InputError as exc:
            raise input_problem(str(exc)) from None
        diagnostics += result.diagnostics
        failed = failed or not result.ok
        if output == "text":
            if result.diagnostics:
                click.echo(result.render(width(err=not result.ok)), err=not result.ok)
            if result.ok:
                warnings = len(result.diagnostics)
                suffix = f" ({warnings} warning{'s' if warnings != 1 else ''})" if warnings else ""
                click.echo(f"{path}: ok{suffix}")
            else:
                errors = len(result.errors)
                click.echo(f"{path}: {errors} error{'s' if errors != 1 else ''}", err=True)
    if output == "json":
        click.echo(to_json(diagnostics))
    raise exit_with(EXIT_MODEL_ERRORS if failed else EXIT_OK)
