"""``robosc view --ros 1|2 [--namespace NS] [--port PORT]``: the live view of a running controller."""

from __future__ import annotations

import sys
import time
from typing import TYPE_CHECKING

import click

from robosc.cli.common import EXIT_OK, exit_with, input_problem, view_port_option

if TYPE_CHECKING:
    from robosc.sim.view import PoseFeed


@click.command()
@click.option("--ros", type=click.Choice(["1", "2"]), required=True, help="The ROS graph to look on.")
@click.option("--namespace", help="The controller to watch, by namespace (/robot1); asked for when there are several.")
@view_port_option
@click.option(
    "--discover",
    type=click.FloatRange(0.1, 60.0),
    default=2.0,
    show_default=True,
    help="Seconds to look for running controllers.",
)
@click.option("--list", "list_only", is_flag=True, help="Only list the controllers found.")
@click.option(
    "--world",
    "world_file",
    type=click.Path(),
    help="A fleet's world file: draw the fleet's coordinator's robots on its map, from the poses "
    "they publish (ROBOT/pose, ROBOT/destination, person/pose: geometry_msgs/Pose2D).",
)
def view(ros: str, namespace: str | None, port: int, discover: float, list_only: bool, world_file: str | None) -> None:
    """Watch a controller that runs elsewhere on the ROS graph: its live view (the page it
    publishes on live_view/page, fed by live_view/events) served on this machine's 127.0.0.1.
    The environment says where the graph is (ROS_MASTER_URI; ROS_DOMAIN_ID)."""
    from robosc.debug.remote import Listener, RemoteError, find_robots, watch

    poses = _poses(world_file) if world_file is not None else None
    try:
        listener = Listener(int(ros), discover)
    except RemoteError as exc:
        raise input_problem(str(exc)) from None
    try:
        robots = find_robots(listener)
        if list_only:
            for robot in robots:
                click.echo(robot)
            raise exit_with(EXIT_OK)
        chosen = _choose(robots, namespace, ros)
        served = watch(listener, chosen, port, poses=poses)
        click.echo(f"live view of {chosen} on {served.url}  (Ctrl-C to stop)", err=True)
        try:
            while listener.process.poll() is None:
                time.sleep(0.2)
        except KeyboardInterrupt:
            pass
        served.close()
        if listener.process.poll() is not None and listener.process.returncode not in (0, None):
            raise input_problem("the ROS listener ended" + listener.why())
    except RemoteError as exc:
        raise input_problem(str(exc)) from None
    except ValueError as exc:  # --world: the page is not a fleet's
        raise input_problem(f"{world_file}: {chosen}: {exc}") from None
    finally:
        listener.close()
    raise exit_with(EXIT_OK)


def _choose(robots: list[str], namespace: str | None, ros: str) -> str:
    if not robots:
        raise input_problem(f"no running robosc controller publishes its live view on this ROS {ros} graph")
    if namespace is not None:
        wanted = "/" + namespace.strip("/") if namespace.strip("/") else "/"
        if wanted not in robots:
            raise input_problem(f"no controller in {wanted}; found: {', '.join(robots)}")
        return wanted
    if len(robots) == 1:
        return robots[0]
    if not sys.stdin.isatty():
        raise input_problem(f"{len(robots)} controllers found ({', '.join(robots)}): choose one with --namespace")
    for i, robot in enumerate(robots, 1):
        click.echo(f"  {i}. {robot}", err=True)
    index = click.prompt("watch which", type=click.IntRange(1, len(robots)), default=1, err=True)
    return robots[index - 1]


def _poses(world_file: str) -> PoseFeed:
    """The feed that draws a fleet's world for ``--world`` (its errors: file, line, column)."""
    from robosc.sim.view import PoseFeed
    from robosc.sim.world import WorldError, load_world

    try:
        world = load_world(world_file)
    except WorldError as exc:
        raise input_problem(str(exc).replace(": error: ", ": ", 1)) from None
    try:
        return PoseFeed(world)
    except ValueError as exc:
        raise input_problem(str(exc)) from None
