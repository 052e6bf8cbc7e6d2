"""Options and helpers shared by the commands."""

from __future__ import annotations

import contextlib
import signal
import sys
import threading
from collections.abc import Callable, Iterator, Mapping
from typing import TYPE_CHECKING, Any

import click

from robosc.language.diagnostics import Diagnostic
from robosc.language.model import Model

if TYPE_CHECKING:
    from robosc.synthesis.progress import Progress

EXIT_OK = 0
EXIT_MODEL_ERRORS = 1
EXIT_USAGE = 2


def view_port_option(f: Callable[..., Any]) -> Callable[..., Any]:
    """--port: where on 127.0.0.1 the live view is served."""
    return click.option(
        "--port",
        type=click.IntRange(0, 65535),
        default=8765,
        show_default=True,
        help="Port of the live view on 127.0.0.1 (0: any free one).",
    )(f)


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


def _sizes(context: click.Context, parameter: click.Parameter, values: tuple[str, ...]) -> dict[str, int]:
    sizes: dict[str, int] = {}
    for value in values:
        name, equals, number = value.partition("=")
        if not equals or not name.isidentifier() or not number.strip().isdigit():
            raise click.BadParameter(f"'{value}' is not NAME=N (e.g. bot=8)", context, parameter)
        sizes[name] = int(number)
    return sizes


def instances_option(f: Callable[..., Any]) -> Callable[..., Any]:
    """--instances NAME=N: how many instances a ``component NAME[N]`` has, without editing the
    model (a fleet of another size); the ``sizes`` parameter, NAME -> N."""
    return click.option(
        "--instances",
        "sizes",
        multiple=True,
        callback=_sizes,
        metavar="NAME=N",
        help="Make 'component NAME[...]' N instances, without editing the model (e.g. --instances bot=8; "
        "repeatable).",
    )(f)


def width(err: bool = False) -> int | None:
    """The width to fit standard output (or error) to: COLUMNS, else the terminal's; None
    when it is piped."""
    import sys

    from robosc.cli.table import terminal_width

    return terminal_width(sys.stderr if err else sys.stdout)


def say(text: str, err: bool = False) -> None:
    """``click.echo`` of prose, wrapped to the terminal (or COLUMNS); unwrapped when piped."""
    from robosc.wrapping import fill

    click.echo(fill(text, width(err)), err=err)


def exit_with(code: int) -> click.exceptions.Exit:
    """The exception that ends a command with exit code ``code`` (messages already printed)."""
    return click.exceptions.Exit(code)


def input_problem(message: str) -> click.exceptions.Exit:
    say(f"robosc: error: {message}", err=True)
    return exit_with(EXIT_USAGE)


def load_robot(
    file: str,
    include: tuple[str, ...],
    purpose: str,
    sizes: Mapping[str, int] | None = None,
    warnings: list[Diagnostic] | None = None,
) -> Model:
    """The checked robot model in ``file`` (``sizes``: --instances), or the command ends: exit 2
    when the file cannot be read or holds a library, exit 1 (diagnostics printed) when it has
    errors. ``warnings``: a list the check's warnings are added to, for the command to say
    (a ``=>`` that binds otherwise than it reads: what ``robosc check`` says, the commands that
    act on the model say too); None leaves them out."""
    from robosc.api import InputError, check_file

    try:
        checked = check_file(file, include, sizes)
    except InputError as exc:
        raise input_problem(str(exc)) from None
    if checked.model is None:
        click.echo(checked.render(width(err=True)), err=True)
        raise exit_with(EXIT_MODEL_ERRORS) from None
    model = checked.model
    if model.kind != "robot":
        raise input_problem(f"{file} is a library; {purpose} needs a robot")
    if warnings is not None:
        warnings += [d for d in checked.diagnostics if not d.is_error]
    return model


def progress_line(progress: Progress) -> str:
    """One line saying how far synthesis is."""
    phase = progress.phase + (f", round {progress.round}" if progress.round else "")
    return (
        f"synthesizing (Ctrl-C stops): {phase} · {progress.steps:,} steps · {progress.live_nodes:,} BDD nodes "
        f"· {progress.seconds:.1f} s"
    )


@contextlib.contextmanager
def synthesis_running(show: bool = True) -> Iterator[Callable[[Progress], None] | None]:
    """While synthesis runs: Ctrl-C (and SIGTERM, SIGHUP) ends the process at once (the BDD
    library holds Python's own handlers off until an operation ends, which can take many
    seconds on a large fleet; synthesis writes nothing and starts no process), and, where
    standard error is a terminal and ``show``, a callback that keeps one line there saying how
    far it is (cleared at the end; pipes and ``--json`` output stay clean)."""
    main = threading.current_thread() is threading.main_thread()
    ending = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
    before = [signal.signal(number, signal.SIG_DFL) for number in ending] if main else []
    shown = [False]

    def report(progress: Progress) -> None:
        text = progress_line(progress)[: max(20, (width(err=True) or 80) - 1)]
        sys.stderr.write("\r\x1b[K" + text)
        sys.stderr.flush()
        shown[0] = True

    try:
        yield report if show and sys.stderr.isatty() else None
    finally:
        if shown[0]:
            sys.stderr.write("\r\x1b[K")
            sys.stderr.flush()
        for number, handler in zip(ending, before, strict=False):  # none where it is not main
            signal.signal(number, handler)
