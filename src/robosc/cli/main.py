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

import click

from robosc.cli.check import check
from robosc.cli.cif import cif
from robosc.cli.debug import diagram, log_command, plot
from robosc.cli.fmt import fmt
from robosc.cli.generate import build, generate
from robosc.cli.simulate import simulate
from robosc.cli.synthesize import synthesize

EXIT_INTERNAL = 3


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="robosc", prog_name="robosc")
def cli() -> None:
    """RoboSC models in, proven supervisory controllers for ROS out."""


cli.add_command(check)
cli.add_command(fmt)
cli.add_command(synthesize)
cli.add_command(cif)
cli.add_command(simulate)
cli.add_command(generate)
cli.add_command(build)
cli.add_command(plot)
cli.add_command(diagram)
cli.add_command(log_command)


def main(argv: Sequence[str] | None = None) -> int:
    try:
        code = cli.main(args=list(argv) if argv is not None else None, prog_name="robosc", standalone_mode=False)
    except click.exceptions.Exit as exc:
        return int(exc.exit_code)
    except click.ClickException as exc:
        exc.show()
        return exc.exit_code
    except click.Abort:
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
