"""``robosc sim WORLD MODEL [--ros none|1|2] [--robots N] [--timeout S] [--record DIR]``."""

from __future__ import annotations

import importlib.util
import os
import shutil
import tempfile
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from robosc.cli.common import (
    EXIT_MODEL_ERRORS,
    EXIT_OK,
    exit_with,
    include_option,
    input_problem,
    instances_option,
    view_port_option,
)
from robosc.cli.results import supervised

if TYPE_CHECKING:
    from robosc.sim.report import Report



PROGRESS_SECONDS = 5.0  # real seconds between two progress lines of a fleet's run


@click.command()
@click.argument("world_file", metavar="WORLD", type=click.Path())
@click.argument("model", type=click.Path())
@click.option(
    "--ros",
    type=click.Choice(["none", "1", "2"]),
    default="2",
    show_default=True,
    help="Middleware: 2 (rclpy, Fast DDS), 1 (rospy, a rosmaster of its own) or none "
    "(the supervisors in this process, no ROS).",
)
@click.option(
    "--robots",
    type=click.IntRange(1, 64),
    default=None,
    help="Robots in the world (default: 1; in a fleet's world, the model's count of robots).",
)
@click.option(
    "--tasks",
    type=click.IntRange(1, 1000),
    default=1,
    show_default=True,
    help="In a fleet's world: the tasks given per robot (each the world's stops), all to be done for the run to "
    "end well.",
)
@click.option(
    "--policy",
    type=click.Choice(["purpose", "random"]),
    default="purpose",
    show_default=True,
    help="In a fleet's world: how the coordinator chooses among what its supervisor allows: purpose "
    "(what gets the tasks done, the robot waiting longest first) or random (for testing).",
)
@click.option(
    "--timeout",
    type=click.FloatRange(min=0.0, min_open=True, max=86400.0),
    default=None,
    help="Seconds of simulated time before the run counts as failed (default: 300; in a fleet's world, "
    "300 per robot and task).",
)
@click.option(
    "--speed",
    type=click.FloatRange(min=0.0, min_open=True, max=1000.0),
    default=4.0,
    show_default=True,
    help="Simulated seconds per real second (ROS runs, whose nodes follow /clock, and runs with --view).",
)
@click.option(
    "--rate",
    type=click.FloatRange(min=0.0, min_open=True, max=1000.0),
    default=10.0,
    show_default=True,
    help="Controller cycles per simulated second.",
)
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the controllers' choices (robot k: seed + k - 1).")
@click.option(
    "--record",
    type=click.Path(file_okay=False),
    help="Keep everything in DIR: the package, node logs, event logs (JSON Lines), the trajectory (MCAP), "
    "the sequence-of-events plot and an animation of the run.",
)
@click.option(
    "--domain",
    type=click.IntRange(0, 232),
    help="ROS 2 domain id of the private graph (default: one picked from the process id).",
)
@click.option(
    "--view",
    is_flag=True,
    help="Serve the world's live view on 127.0.0.1 (see --port) while it runs, and after it until Ctrl-C: "
    "the map with every robot, and the events (a fleet's coordinator's, or each robot's controller's).",
)
@view_port_option
@include_option
@instances_option
def sim(
    world_file: str,
    model: str,
    ros: str,
    robots: int | None,
    tasks: int,
    policy: str,
    timeout: float | None,
    speed: float,
    rate: float,
    seed: int,
    record: str | None,
    domain: int | None,
    view: bool,
    port: int,
    include: tuple[str, ...],
    sizes: dict[str, int],
) -> None:
    """Drive robots in a 2D WORLD with the controller synthesized from MODEL, end to end:
    the controller package is generated, the simulator's node and one controller node per
    robot run on a private ROS graph (loopback only), and the run ends when every robot
    has reached the goal (exit 0), one touched a wall, or the timeout passed (exit 1)."""
    from robosc.sim.report import verdict
    from robosc.sim.world import WorldError, load_world

    try:
        world = load_world(world_file)
    except WorldError as exc:
        raise input_problem(str(exc).replace(": error: ", ": ", 1)) from None
    if importlib.util.find_spec("irsim") is None:
        raise input_problem("robosc sim needs IR-SIM: pip install 'robosc[sim]'")
    fleet = world.fleet is not None
    if not fleet:
        crowded = world.room_for(robots or 1)
        if crowded is not None:
            raise input_problem(crowded)
    result, plan = supervised(model, include, "a simulation", sizes)
    if ros != "none":
        _check_middleware(int(ros))
    live = _world_view(result, world, None if fleet else robots or 1, port) if view else None
    folder = Path(record) if record else Path(tempfile.mkdtemp(prefix="robosc-fleet-" if fleet else "robosc-sim-"))
    try:
        try:
            report = _run(model, result, world, ros, folder, live, fleet, plan=plan, robots=robots, tasks=tasks,
                          policy=policy, timeout=timeout, speed=speed, rate=rate, seed=seed, domain=domain)
        except BaseException:  # no run (a misfit, the middleware, Ctrl-C): nothing to serve
            if live is not None:
                live.close()
            raise
        click.echo(report_table(report, _title(report, world, ros)))
        click.echo(verdict(report))
        if record:
            _record(report, world, folder, ros)
    finally:
        if not record:
            shutil.rmtree(folder, ignore_errors=True)
    if live is not None:
        live.end(report.why)
        what = "the fleet's live view" if fleet else "the live view"
        click.echo(f"still serving {what} on {live.url}; Ctrl-C to stop", err=True)
        _serve_until_interrupted(live)
    raise exit_with(EXIT_OK if report.ok else EXIT_MODEL_ERRORS)


def _run(
    model: str, result: Any, world: Any, ros: str, folder: Path, live: Any, fleet: bool, speed: float,
    **options: Any,
) -> Report:
    """The run, through the API (robosc.api.run_world): in this process or on ROS, one robot or
    a fleet; a fleet's live view fed as it goes (``live``)."""
    from robosc.api import run_world
    from robosc.sim.fleet import FleetMisfit
    from robosc.sim.run import Misfit
    from robosc.sim.session import SessionError

    hooks: dict[str, Any] = {"on_note": lambda note: click.echo(f"robosc: note: {note}", err=True)}
    if live is not None and ros == "none":
        hooks.update(_local_feed(live, speed))
    elif live is not None:
        hooks["on_step"] = _ros_feed(live, folder, None if fleet else options.get("robots") or 1)
    if fleet:
        hooks["on_step"] = _with_progress(hooks.get("on_step"))
    try:
        if ros == "none":
            return run_world(world, result, None, folder=folder, speed=speed, **hooks, **options)
        from robosc.cli.generate import live_page

        return run_world(
            world, result, int(ros), folder=folder, page=live_page(result), speed=speed,
            on_start=_say_where_fleet if fleet else _say_where, **hooks, **options,
        )
    except Misfit as exc:
        raise input_problem(f"{model} {exc}") from None
    except (FleetMisfit, ValueError) as exc:
        raise input_problem(f"{model}: {exc}") from None
    except SessionError as exc:
        raise input_problem(f"the simulation could not run on ROS {ros}: {exc}") from None


def _with_progress(step: Any) -> Any:
    """``step`` (or nothing) and, every PROGRESS_SECONDS of real time, a line on stderr saying
    where a fleet's run is (robosc.sim.fleet.FleetWorld.progress_line)."""
    said = [time.monotonic()]

    def hook(world: Any) -> None:
        if step is not None:
            step(world)
        now = time.monotonic()
        if now - said[0] >= PROGRESS_SECONDS:
            said[0] = now
            click.echo(f"robosc: {world.progress_line()}", err=True)

    return hook


def _title(report: Report, world: Any, ros: str) -> str:
    """The run table's title: how many robots, and where they ran."""
    if report.fleet:
        where = "no middleware" if ros == "none" else f"ROS {ros}"
        return f"{len(report.robots)} robot(s) in {world.name}, {where}"
    return f"{len(report.robots)} robot(s), ROS: {ros}"


def report_table(report: Report, title: str) -> str:
    """A run's table (robosc.sim.report.columns), fitted to the terminal."""
    from robosc.cli.table import boxed, table_width
    from robosc.sim.report import columns

    headers, rows = columns(report)
    return boxed(headers, rows, title=title, right=range(1, len(headers)), width=table_width())


def _record(report: Report, world: Any, folder: Path, ros: str) -> None:
    """What --record keeps besides the packages and logs: for a world with a goal the MCAP file,
    the plots and the animation; for a fleet the animation."""
    from robosc.sim.recording import animate, write_recording

    if not report.fleet:
        for written in write_recording(report, world, folder):
            click.echo(f"recorded {written}")
        return
    folder.mkdir(parents=True, exist_ok=True)
    animate(report, world, folder / "fleet.gif")
    kept = "" if ros == "none" else ", the coordinator's package, its event log and the nodes' logs"
    click.echo(f"recorded {folder} (fleet.gif: an animation of the run{kept})")


def _local_feed(live: Any, speed: float) -> dict[str, Any]:
    """The hooks that feed the live view in this process, the run paced at ``speed`` times real
    time (watched)."""
    from robosc.sim.session import pace
    from robosc.sim.view import WorldFeed

    feed = WorldFeed(live.publish)
    started = time.monotonic()

    def step(world: Any) -> None:
        feed.step(world)
        pace(started, world.sim.time, speed)

    return {"on_event": feed.event, "on_step": step}


def _world_view(result: Any, world: Any, robots: int | None, port: int) -> Any:
    """The world's live view, served on 127.0.0.1:``port`` (its URL said): a fleet's, or that of
    the ``robots`` of a world with a goal."""
    from robosc.debug.world_view import render_world_page
    from robosc.runtime.onboard.live_server import LiveView
    from robosc.sim.report import robot_names
    from robosc.sim.view import world_map

    names = robot_names(robots) if robots is not None else None
    try:
        live = LiveView(render_world_page(result, world_map(world), names), port=port)
    except OSError as exc:
        raise input_problem(f"live view: cannot serve on 127.0.0.1:{port}: {exc.strerror or exc}") from None
    what = "the fleet's live view" if robots is None else "the live view"
    click.echo(f"robosc: {what}: {live.url}", err=True)
    return live


def _ros_feed(live: Any, folder: Path, robots: int | None) -> Any:
    """A step hook for a run on ROS: the events from the event logs the nodes write (the
    coordinator's, or each robot's controller's, named for its robot), and frames."""
    from robosc.sim.local import SimulationFrames, named
    from robosc.sim.report import robot_names
    from robosc.sim.view import EventTail, WorldFeed

    names = robot_names(robots) if robots is not None else [""]
    tails = {name: EventTail(folder / "events" / f"{name or 'coordinator'}.jsonl") for name in names}
    feed = WorldFeed(live.publish)

    def step(world: Any) -> None:
        for name, tail in tails.items():
            for record in tail.read():
                feed.event(named(record, name) if name else record)
        feed.step(world if robots is None else SimulationFrames(world))

    return step


def _serve_until_interrupted(live: Any) -> None:
    try:
        while True:
            time.sleep(0.5)
    except KeyboardInterrupt:
        pass
    finally:
        live.close()


def _where(graph: object) -> tuple[str, int]:
    env = getattr(graph, "env", {})
    if getattr(graph, "ros", 2) == 1:
        return f"ROS_MASTER_URI={env.get('ROS_MASTER_URI')} ROS_HOSTNAME=127.0.0.1", 1
    return f"ROS_DOMAIN_ID={env.get('ROS_DOMAIN_ID')} ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST", 2


def _say_where(graph: object) -> None:
    """Where the private graph is, so that the robots can be watched (robosc view) meanwhile."""
    where, ros = _where(graph)
    click.echo(f"robosc: the robots run on {where} (watch: {where} robosc view --ros {ros})", err=True)


def _say_where_fleet(graph: object) -> None:
    """Where a fleet's private graph is (its coordinator: namespace /fleet), and how to watch it."""
    where, ros = _where(graph)
    click.echo(f"robosc: the fleet runs on {where}, its coordinator in the namespace /fleet "
               f"(watch: {where} robosc view --ros {ros} --world WORLD)", err=True)


def _check_middleware(ros: int) -> None:
    if ros == 2:
        if importlib.util.find_spec("rclpy") is None:
            raise input_problem("--ros 2 needs rclpy in this Python: pip install 'robosc[ros2]'")
        return
    python = os.environ.get("ROBOSC_ROS1_PYTHON", "/usr/bin/python3")
    if not Path(python).exists() or not Path("/usr/bin/rosmaster").exists():
        raise input_problem(
            f"--ros 1 needs rospy and rosmaster for {python} (Debian: apt-get install python3-rospy python3-rosmaster)"
        )
