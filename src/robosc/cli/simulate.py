"""``robosc simulate FILE [--script F | --random N --seed S] [--log F]``."""

from __future__ import annotations

import random
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TextIO

import click

from robosc.cli.common import (
    EXIT_MODEL_ERRORS,
    EXIT_OK,
    EXIT_USAGE,
    exit_with,
    include_option,
    input_problem,
    instances_option,
    say,
    view_port_option,
)
from robosc.cli.results import supervised

if TYPE_CHECKING:
    from robosc.debug.simulator import Outcome, Simulator

HELP = """commands:
  tick [N]              run N controller cycles (default 1)
  EVENT                 perform a controllable event, if the supervisor allows it
  EVENT [DATA]          deliver an uncontrollable event; DATA is JSON ({"ranges": [0.5]}, 0.3, true)
                        or, for enum-typed data, an enum value (wall_front)
  expect NAME VALUE     stop unless an automaton / variable has this value
  sleep SECONDS         wait (to follow a script in the live view)
  state                 show the state again
  help, quit"""


@click.command()
@click.argument("file", type=click.Path())
@click.option("--script", type=click.Path(dir_okay=False), help="Run the commands in this file, one per line.")
@click.option("--random", "steps", type=click.IntRange(min=0), help="Run N random steps (ticks and robot events).")
@click.option("--seed", type=int, default=None, help="Seed for the controller's choices and --random.")
@click.option(
    "--rate",
    type=click.FloatRange(min=0.0, min_open=True),
    help="With --random: steps per second (default: as fast as possible).",
)
@click.option(
    "--log",
    "log_path",
    type=click.Path(dir_okay=False),
    help="Write every event to this file: JSON Lines, or MCAP if it ends in .mcap.",
)
@click.option("--view", is_flag=True, help="Serve the live view on 127.0.0.1 (see --port) while simulating.")
@view_port_option
@click.option("--quiet", is_flag=True, help="Print only problems and the final state.")
@include_option
@instances_option
def simulate(
    file: str,
    script: str | None,
    steps: int | None,
    seed: int | None,
    rate: float | None,
    log_path: str | None,
    view: bool,
    port: int,
    quiet: bool,
    include: tuple[str, ...],
    sizes: dict[str, int],
) -> None:
    """Run the generated supervisor without ROS, checking every step.

    After each event the requirements must hold and a marked state must stay
    reachable; the simulation stops with a report (exit 1) if not."""
    if script is not None and steps is not None:
        raise input_problem("use either --script or --random, not both")
    result, plan = supervised(file, include, "simulation", sizes)
    from robosc.debug.simulator import Simulator, Violation

    sinks: list[Callable[[dict[str, Any]], None]] = []
    closers: list[Callable[[], None]] = []
    log: TextIO | None = None
    if log_path is not None:
        try:
            if log_path.endswith(".mcap"):
                from robosc.debug.eventlog import McapLog

                handle = open(log_path, "wb")  # noqa: SIM115 (closed below)
                mcap = McapLog(handle)
                sinks.append(mcap.write)
                closers += [mcap.close, handle.close]
            else:
                log = open(log_path, "w", encoding="utf-8")  # noqa: SIM115 (closed below)
                closers.append(log.close)
        except OSError as exc:
            raise input_problem(f"{log_path}: cannot write: {exc.strerror or exc}") from None
    live = None
    if view:
        from robosc.debug.layout import LayoutError
        from robosc.debug.live import render_page
        from robosc.runtime.onboard.live_server import LiveView

        try:
            live = LiveView(render_page(result), port=port)
        except LayoutError as exc:
            raise input_problem(f"live view: cannot lay out the diagrams: {exc}") from None
        except OSError as exc:
            raise input_problem(f"live view: cannot serve on 127.0.0.1:{port}: {exc.strerror or exc}") from None
        sinks.append(live.publish)
        closers.append(live.close)
        say(f"live view: {live.url}")

    def on_event(record: dict[str, Any]) -> None:
        for sink in sinks:
            sink(record)

    sim = Simulator(result, plan, seed=seed, log=log, on_event=on_event if sinks else None)
    if live is not None:
        live.last = {"time": 0.0, "event": None, "controllable": False, "data": None, "state": sim.snapshot()}
    try:
        if script is not None:
            code = _scripted(sim, script, quiet)
        elif steps is not None:
            code = _random(sim, steps, seed, quiet, rate)
        else:
            code = _interactive(sim)
        if live is not None and code == EXIT_OK and (script is not None or steps is not None):
            live.end("the simulation is over")
            say(f"still serving the live view on {live.url}; Ctrl-C to stop")
            _show_state(sim)
            _wait_forever()
    except Violation as violation:
        say(f"robosc: violation at {violation}", err=True)
        code = EXIT_MODEL_ERRORS
    except OSError as exc:  # the event log: disk full, a closed pipe
        say(f"robosc: error: {log_path or 'output'}: cannot write: {exc.strerror or exc}", err=True)
        code = EXIT_USAGE
    finally:
        for close in closers:
            try:
                close()
            except OSError as exc:
                say(f"robosc: error: {log_path}: cannot write: {exc.strerror or exc}", err=True)
                code = EXIT_USAGE
    if code == EXIT_OK:
        _show_state(sim)
    raise exit_with(code) from None


def _wait_forever() -> None:
    import time

    try:
        while True:
            time.sleep(3600)
    except KeyboardInterrupt:
        return


def _report(sim: Simulator, outcome: Outcome, quiet: bool) -> None:
    if not quiet:
        steps = outcome.steps or (sim.step,) * len(outcome.events)
        for step, event in zip(steps, outcome.events, strict=True):
            say(f"  {step:>4}  {event}")
        for message in outcome.messages:
            say(f"        {message}")
    if not quiet:
        for warning in sim.warnings:
            say(f"        warning: {warning}", err=True)
        sim.warnings.clear()


def _scripted(sim: Simulator, path: str, quiet: bool) -> int:
    from robosc.debug.simulator import CommandError
    from robosc.language.loader import InputError, regular_file

    try:
        with regular_file(path, "a script").open(encoding="utf-8") as handle:
            lines = handle.read().splitlines()
    except InputError as exc:
        raise input_problem(str(exc)) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise input_problem(f"{path}: cannot read: {exc}") from None
    for number, line in enumerate(lines, 1):
        try:
            outcome = sim.run(line)
        except CommandError as exc:
            column = len(line) - len(line.lstrip()) + 1
            say(f"{path}:{number}:{column}: error: {exc}", err=True)
            return EXIT_USAGE
        _report(sim, outcome, quiet)
    return EXIT_OK


def _random(sim: Simulator, steps: int, seed: int | None, quiet: bool, rate: float | None = None) -> int:
    import time

    from robosc.debug.simulator import SEARCH_LIMIT

    rng = random.Random(seed)
    start = time.monotonic()
    sim.judge("the start", sim.network_state())
    for number in range(steps):
        _report(sim, sim.random_step(rng), quiet)
        if rate is not None:
            time.sleep(max(0.0, start + (number + 1) / rate - time.monotonic()))
    unjudged = f" (searched for in all but {sim.unjudged} states: more than {SEARCH_LIMIT:,} states ahead)" if sim.unjudged else ""
    say(
        f"{steps} random steps, {len(sim.events)} events: every requirement held, a marked state stayed reachable "
        f"under the supervisor that runs{unjudged}"
    )
    if sim.warnings:
        say(f"{len(sim.warnings)} warnings about data, e.g.: {sim.warnings[0]}")
    return EXIT_OK


def _show_state(sim: Simulator) -> None:
    from robosc.cli.table import listing

    snapshot = sim.snapshot()
    rows = list(snapshot["automata"].items())
    # a service or action that is busy
    rows += [(name, location) for name, location in snapshot["communications"].items() if location != "idle"]
    rows += [(name, str(value)) for name, value in snapshot["variables"].items()]
    click.echo(listing(("automaton / variable", "value"), rows))
    say("allowed: " + (", ".join(sim.allowed()) or "(none)"))
    say("robot events possible: " + (", ".join(sim.expected()) or "(none)"))


def _interactive(sim: Simulator) -> int:
    from robosc.debug.simulator import CommandError, Violation

    say(f"simulating {sim.network.model.name}; 'help' lists the commands")
    _show_state(sim)
    while True:
        try:
            line = input("> ")
        except EOFError:
            return EXIT_OK
        word = line.strip()
        if word in ("quit", "exit", "q"):
            return EXIT_OK
        if word == "help":
            click.echo(HELP)
            continue
        if word == "state":
            _show_state(sim)
            continue
        try:
            _report(sim, sim.run(line), False)
        except CommandError as exc:
            say(f"error: {exc}")
            continue
        except Violation as exc:  # a failed expect (or a check): report it, the session goes on
            say(f"failed: {exc}")
            continue
        if word:
            _show_state(sim)
