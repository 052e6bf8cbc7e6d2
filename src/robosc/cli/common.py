"""Options and helpers shared by the commands."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import click

EXIT_OK = 0
EXIT_MODEL_ERRORS = 1
EXIT_USAGE = 2


def include_option(f: Callable[..., Any]) -> Callable[..., Any]:
    return click.option(
        "-I",
        "--include",
        "include",
        multiple=True,
        type=click.Path(file_okay=False),
        help="Also look for libraries in DIR (repeatable).",
        metavar="DIR",
    )(f)


def exit_with(code: int) -> click.exceptions.Exit:
    """The exception that ends a command with exit code ``code`` (messages already printed)."""
    return click.exceptions.Exit(code)


def input_problem(message: str) -> click.exceptions.Exit:
    click.echo(f"robosc: error: {message}", err=True)
    return exit_with(EXIT_USAGE)
