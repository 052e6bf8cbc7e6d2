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


class CommandExit(click.ClickException):
    """Ends a command with a given exit code (the message is already printed)."""

    def __init__(self, code: int) -> None:
        super().__init__("")
        self.exit_code = code

    def show(self, file: Any = None) -> None:
        pass


def input_problem(message: str) -> CommandExit:
    click.echo(f"robosc: error: {message}", err=True)
    return CommandExit(EXIT_USAGE)
