"""``robosc sim WORLD MODEL [--ros none|1|2] [--robots N] [--timeout S] [--record DIR]``."""

from __future__ import annotations

import importlib.util
import math
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
    view_port_option,
)
from robosc.cli.results import supervised

if TYPE_CHECKING:
    from robosc.sim.run import Report


FLEET_SECONDS = 300.0  # a fleet's default time-out: simulated seconds per robot and task


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
    help="In a fleet's world: the tasks each robot must do before the run ends well.",
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
    help="In a fleet's world: serve the fleet's live view on 127.0.0.1 (see --port) while it runs, "
    "and after it until Ctrl-C.",
)
@view_port_option
@include_option
def sim(
    world_file: str,
    model: str,
    ros: str,
    robots: int | None,
    tasks: int,
    timeout: float | None,
    speed: float,
    rate: float,
    seed: int,
    record: str | None,
    domain: int | None,
    view: bool,
    port: int,
    include: tuple[str, ...],
) -> None:
    """Drive robots in a 2D WORLD with the controller synthesized from MODEL, end to end:
    the controller package is generated, the simulator's node and one controller node per
    robot run on a private ROS graph (loopback only), and the run ends when every robot
    has reached the goal (exit 0), one touched a wall, or the timeout passed (exit 1)."""
    from robosc.sim.world import WorldError, load_world

    try:
        world = load_world(world_file)
    except WorldError as exc:
        raise input_problem(str(exc).replace(": error: ", ": ", 1)) from None
    if importlib.util.find_spec("irsim") is None:
        raise input_problem("robosc sim needs IR-SIM: pip install 'robosc[sim]'")
    if world.fleet is not None:
        _fleet(world, model, include, ros, robots, tasks, timeout, speed, rate, seed, record, domain,
               port if view else None)
    if view:
        raise input_problem(
            f"{world_file}: --view draws a fleet's world (one with 'fleet'); to watch a robot's controller "
            "here, run robosc view while robosc sim runs"
        )
    timeout = timeout if timeout is not None else 300.0
    robots = robots or 1
    crowded = world.room_for(robots)
    if crowded is not None:
        raise input_problem(crowded)
    result, plan = supervised(model, include, "a simulation")
    if ros != "none":
        _check_middleware(int(ros))
    folder = Path(record) if record else Path(tempfile.mkdtemp(prefix="robosc-sim-"))
    try:
        page = None
        if ros != "none":
            from robosc.cli.generate import live_page

            page = live_page(result)
        report = _run(
            model, result, world, ros, folder, page,
            plan=plan, robots=robots, timeout=timeout, speed=speed, rate=rate, seed=seed, domain=domain,
            on_note=lambda note: click.echo(f"robosc: note: {note}", err=True),
        )
        _print(report, ros)
        if record:
            from robosc.sim.recording import write_recording

            for written in write_recording(report, world, folder):
                click.echo(f"recorded {written}")
    finally:
        if not record:
            shutil.rmtree(folder, ignore_errors=True)
    raise exit_with(EXIT_OK if report.ok else EXIT_MODEL_ERRORS)


def _run(
    model: str, result: object, world: object, ros: str, folder: Path, page: str | None, **options: Any
) -> Report:
    from robosc.api import run_world
    from robosc.sim.run import Misfit
    from robosc.sim.session import SessionError

    try:
        if ros == "none":
            return run_world(world, result, None, folder=folder, **options)  # type: ignore[arg-type]
        return run_world(world, result, int(ros), folder=folder, page=page, on_start=_say_where, **options)  # type: ignore[arg-type]
    except Misfit as exc:
        raise input_problem(f"{model} {exc}") from None
    except SessionError as exc:
        raise input_problem(f"the simulation could not run on ROS {ros}: {exc}") from None


def _fleet(
    world: Any, model: str, include: tuple[str, ...], ros: str, robots: int | None, tasks: int,
    timeout: float | None, speed: float, rate: float, seed: int, record: str | None, domain: int | None,
    port: int | None,
) -> None:
    """A fleet's world: the coordinator commanding a driver per robot, on ROS (the generated
    package and the simulator's node) or in this process (exits). ``port``: serve the fleet's
    live view there."""
    from robosc.debug.fleet_view import render_fleet_page
    from robosc.debug.simulator import load_module
    from robosc.sim.fleet import FleetMisfit, FleetRun, check_size, instances
    from robosc.sim.fleet_ros import run_fleet_ros
    from robosc.sim.fleet_view import FleetFeed
    from robosc.sim.session import SessionError, pace

    result, plan = supervised(model, include, "a simulation")
    module = load_module(plan)
    robots = robots if robots is not None else len(instances(module))
    limit = timeout if timeout is not None else FLEET_SECONDS * robots * tasks
    if ros != "none":
        _check_middleware(int(ros))
    try:
        check_size(instances(module), robots)
    except FleetMisfit as exc:
        raise input_problem(f"{model}: {exc}") from None
    live = _fleet_view(result, world, port) if port is not None else None
    folder = Path(record) if record else Path(tempfile.mkdtemp(prefix="robosc-fleet-"))
    try:
        if ros == "none":
            runs: list[FleetRun] = []
            hooks: dict[str, Any] = {}
            if live is not None:  # watched: at --speed times real time
                feed = FleetFeed(live.publish)
                started = time.monotonic()

                def step() -> None:
                    feed.step(runs[0].world)
                    pace(started, runs[0].sim.time, speed)

                hooks = {"on_event": feed.event, "on_step": step}
            runs.append(FleetRun(world, module, robots, seed=seed, rate=rate, **hooks))
            report = runs[0].run(tasks=tasks, timeout=limit)
        else:  # it checks the fleet's size before it starts anything
            report = run_fleet_ros(
                world, plan, module, int(ros), robots, tasks=tasks, timeout=limit, speed=speed, rate=rate,
                seed=seed, folder=folder, domain=domain, on_start=_say_where_fleet,
                on_step=_ros_feed(live, folder) if live is not None else None, page=render_fleet_page(result),
            )
    except (FleetMisfit, ValueError) as exc:
        raise input_problem(f"{model}: {exc}") from None
    except SessionError as exc:
        raise input_problem(f"the simulation could not run on ROS {ros}: {exc}") from None
    finally:
        if not record:
            shutil.rmtree(folder, ignore_errors=True)
    where = "no middleware" if ros == "none" else f"ROS {ros}"
    click.echo(fleet_table(report, f"{len(report.robots)} robot(s) in {world.name}, {where}"))
    verdict = "ok" if report.ok else "FAILED"
    click.echo(f"{verdict}: {report.why} ({report.simulated:.1f} s simulated in {report.wall:.1f} s)")
    if record:
        from robosc.sim.recording import animate_fleet

        folder.mkdir(parents=True, exist_ok=True)
        animate_fleet(report, world, folder / "fleet.gif")
        kept = "" if ros == "none" else ", the coordinator's package, its event log and the nodes' logs"
        click.echo(f"recorded {folder} (fleet.gif: an animation of the run{kept})")
    if live is not None:
        live.end(report.why)
        click.echo(f"still serving the fleet's live view on {live.url}; Ctrl-C to stop", err=True)
        _serve_until_interrupted(live)
    raise exit_with(EXIT_OK if report.ok else EXIT_MODEL_ERRORS)


def _fleet_view(result: Any, world: Any, port: int) -> Any:
    """The fleet's live view, served on 127.0.0.1:``port`` (its URL said)."""
    from robosc.debug.fleet_view import render_fleet_page
    from robosc.runtime.onboard.live_server import LiveView
    from robosc.sim.fleet_view import fleet_map

    try:
        live = LiveView(render_fleet_page(result, fleet_map(world)), port=port)
    except OSError as exc:
        raise input_problem(f"live view: cannot serve on 127.0.0.1:{port}: {exc.strerror or exc}") from None
    click.echo(f"robosc: the fleet's live view: {live.url}", err=True)
    return live


def _ros_feed(live: Any, folder: Path) -> Any:
    """A step hook for a fleet on ROS: the coordinator's events from its event log, and frames."""
    from robosc.sim.fleet_view import EventTail, FleetFeed

    tail = EventTail(folder / "events" / "coordinator.jsonl")
    feed = FleetFeed(live.publish)

    def step(world: Any) -> None:
        for record in tail.read():
            feed.event(record)
        feed.step(world)

    return step


def _serve_until_interrupted(live: Any) -> None:
    try:
        while True:
            time.sleep(0.5)
    except KeyboardInterrupt:
        pass
    finally:
        live.close()


def fleet_table(report: Any, title: str) -> str:
    """A fleet run's table: per robot its tasks, waiting, distance, closest approaches, stops
    and collision."""
    from robosc.cli.table import boxed, terminal_width

    headers: tuple[str, ...] = ("robot", "tasks", "waiting", "distance", "closest robot", "stops", "collision")
    if report.person:
        headers = (*headers[:5], "closest person", *headers[5:])
    rows = []
    for status, state, closest in zip(report.robots, report.status, report.closest_robot, strict=True):
        hit = "-" if state.collided_at is None else f"at {state.collided_at:.1f} s"
        row = [
            status.name, str(status.tasks), f"{status.waiting:.0f} s", f"{state.distance:.1f} m", f"{closest:.2f} m",
            str(status.stops), hit,
        ]
        if report.person:
            row.insert(5, f"{state.closest_person:.2f} m")
        rows.append(tuple(row))
    return boxed(headers, rows, title=title, right=range(1, len(headers)), width=terminal_width())


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


def _print(report: Report, ros: str) -> None:
    from robosc.cli.table import boxed, terminal_width

    shared = any(math.isfinite(r.closest_robot) for r in report.robots)
    headers: tuple[str, ...] = ("robot", "time to goal", "distance", "closest approach", "commands", "refused")
    if shared:  # the robots are bodies to each other
        headers = (*headers[:4], "closest robot", *headers[4:])
    rows = []
    for r in report.robots:
        if r.reached is not None:
            goal = f"{r.reached:.1f} s"
        elif r.collided_at is not None:
            goal = f"hit at {r.collided_at:.1f} s"
        else:
            goal = "not reached"
        row = [r.name, goal, f"{r.distance:.2f} m", f"{r.closest:.2f} m", str(r.commands), str(r.refused)]
        if shared:
            row.insert(4, f"{r.closest_robot:.2f} m")
        rows.append(tuple(row))
    title = f"{len(report.robots)} robot(s), ROS: {ros}"
    click.echo(boxed(headers, rows, title=title, right=range(1, len(headers)), width=terminal_width()))
    verdict = "ok" if report.ok else "FAILED"
    click.echo(f"{verdict}: {report.why} ({report.simulated:.1f} s simulated in {report.wall:.1f} s)")
