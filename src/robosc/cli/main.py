"""``robosc``: the command-line entry point.

Exit codes: 0 success, 1 the model has errors (or ``fmt --check`` found
unformatted files), 2 usage or input problems (missing file, a directory, not
UTF-8), 3 an internal error in robosc itself.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

# dd imports networkx if it can (only for exporting BDDs as graphs, which robosc
# never does); that import alone takes about 0.15 s of every synthesis command.
# dd works without it, so the robosc command keeps it out of its own process.
# (Only here, in the command's entry point: a program that imports robosc as a
# library keeps its networkx.)
if "networkx" not in sys.modules:
    sys.modules["networkx"] = None  # type: ignore[assignment]

import importlib

import click

from robosc import __version__
from robosc.children import Terminated, ending_on_signals

EXIT_INTERNAL = 3

# command name -> (module, function); a command's module is imported only when it runs
# (or for --help), so that `robosc check` does not pay for synthesis, ROS or plotting.
COMMANDS = {
    "check": ("robosc.cli.check", "check"),
    "fmt": ("robosc.cli.fmt", "fmt"),
    "synthesize": ("robosc.cli.synthesize", "synthesize"),
    "cif": ("robosc.cli.cif", "cif"),
    "simulate": ("robosc.cli.simulate", "simulate"),
    "sim": ("robosc.cli.sim", "sim"),
    "generate": ("robosc.cli.generate", "generate"),
    "build": ("robosc.cli.generate", "build"),
    "plot": ("robosc.cli.debug", "plot"),
    "diagram": ("robosc.cli.debug", "diagram"),
    "log": ("robosc.cli.debug", "log_command"),
    "view": ("robosc.cli.view", "view"),
    "lsp": ("robosc.cli.lsp", "lsp"),
}


class LazyGroup(click.Group):
    def list_commands(self, ctx: click.Context) -> list[str]:
        return list(COMMANDS)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name not in COMMANDS:
            return None
        module, name = COMMANDS[cmd_name]
        command = getattr(importlib.import_module(module), name)
        assert isinstance(command, click.Command)
        return command


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="robosc")
def cli() -> None:
    """RoboSC models in, proven supervisory controllers for ROS out."""


def main(argv: Sequence[str] | None = None) -> int:
    try:
        with ending_on_signals():  # SIGTERM and SIGHUP unwind like Ctrl-C: children are ended
            code = cli.main(args=list(argv) if argv is not None else None, prog_name="robosc", standalone_mode=False)
    except Terminated as exc:
        return 128 + exc.signum
    except click.exceptions.Exit as exc:
        return int(exc.exit_code)
    except click.ClickException as exc:
        exc.show()
        return exc.exit_code
    except click.Abort as exc:  # click's name for a KeyboardInterrupt (or Terminated) it caught
        if isinstance(exc.__cause__, Terminated):
            return 128 + exc.__cause__.signum
        click.echo("robosc: aborted", err=True)
        return 130
    except KeyboardInterrupt:
        return 130
    except ImportError as exc:
        click.echo(f"robosc: error: {exc}", err=True)
        return EXIT_INTERNAL
    except Exception as exc:
        click.echo(f"robosc: internal error: {type(exc).__name__}: {exc}", err=True)
        click.echo("please report this with the model that caused it", err=True)
        return EXIT_INTERNAL
    return code if isinstance(code, int) else 0


def run() -> None:
    sys.exit(main())
