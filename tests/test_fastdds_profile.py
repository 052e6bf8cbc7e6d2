"""The Fast DDS profile a ROS 2 node writes for itself (``onboard/profiles.py``): the 10 ms
heartbeat for every writer but the command topics nothing waits on, found by their resolved
names; without ROS (the node that loads it is run in test_ros2.py and benchmarks/relay.py)."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import pytest

from robosc.api import load_model, plan_supervisor, synthesize_model
from robosc.debug.simulator import load_module
from robosc.runtime.onboard import profiles

ROOT = Path(__file__).resolve().parent.parent
NS = "{http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles}"


def robot(model: str) -> Any:
    return load_module(plan_supervisor(synthesize_model(load_model(ROOT / "examples" / model)))).Robot


def periods(text: str) -> dict[str, tuple[int, int]]:
    """Each data_writer profile's heartbeat period (seconds, nanoseconds), by profile name."""
    out = {}
    for writer in ET.fromstring(text).iter(NS + "data_writer"):
        period = writer.find(f"{NS}times/{NS}heartbeatPeriod")
        assert period is not None
        out[writer.get("profile_name", "")] = (int(period.findtext(NS + "sec") or 0), int(period.findtext(NS + "nanosec") or 0))
    return out


def test_the_still_events_are_those_that_change_nothing() -> None:
    # movement sends a Twist and leaves Platform where it is; a turn puts Platform in turning
    assert robot("maze_solver.rscd").STILL == ("movement",)
    assert robot("warehouse.rscd").STILL == ()


def test_a_stream_topic_is_one_whose_every_command_changes_nothing() -> None:
    assert profiles.stream_topics(robot("maze_solver.rscd")) == ["/cmd_vel"]
    assert profiles.stream_topics(robot("warehouse.rscd")) == []  # every command moves a robot or the door


@pytest.mark.parametrize(
    "args, expected",
    [
        (["node"], "/"),
        (["node", "--ros-args", "-p", "rate:=5.0"], "/"),
        (["node", "--ros-args", "-r", "__ns:=/depot"], "/depot"),
        (["node", "--ros-args", "--remap", "__ns:=/depot/"], "/depot"),
        (["node", "--ros-args", "-r", "__node:=other", "-r", "__ns:=/a/b"], "/a/b"),
        (["node", "-r", "cmd_vel:=x"], "/"),  # outside --ros-args: not ROS's
        (["node", "--ros-args", "-r", "cmd_vel:=x"], None),  # a topic remapped: not told for sure
        (["node", "--ros-args", "-r", "bench:__ns:=/x"], None),  # for one node
        (["node", "--ros-args", "-r"], None),
        (["node", "--ros-args", "--", "-r", "cmd_vel:=x"], "/"),
    ],
)
def test_the_namespace_is_read_from_the_ros_arguments(args: list[str], expected: str | None) -> None:
    assert profiles.namespace(args) == expected


def test_names_resolve_as_ros_resolves_them() -> None:
    assert profiles.resolve("/cmd_vel", "/depot") == "/cmd_vel"
    assert profiles.resolve("cmd_vel", "/depot") == "/depot/cmd_vel"
    assert profiles.resolve("bot1/go", "/") == "/bot1/go"
    assert profiles.resolve("~/cmd", "/") is None
    assert profiles.resolve("{node}/cmd", "/") is None


def test_the_written_profile_gives_stream_topics_fast_dds_own_heartbeat_and_is_in_memory() -> None:
    path = profiles.write(robot("maze_solver.rscd"), ["node", "--ros-args", "-r", "__ns:=/robot2"])
    try:
        if os.access("/dev/shm", os.W_OK):
            assert path.startswith("/dev/shm/")
        found = periods(Path(path).read_text())
    finally:
        os.remove(path)
    assert found == {"robosc_writers": (0, 10_000_000), "/cmd_vel": (3, 0)}  # absolute: not in the namespace


def test_a_relative_stream_topic_is_named_in_the_namespace_and_a_remapped_one_not_at_all() -> None:
    maze = robot("maze_solver.rscd")

    class Relative:  # the maze solver with its velocities on a relative name
        COMMUNICATIONS = tuple(
            type(c)(c.name, c.kind, "cmd_vel", c.interface, c.data) if c.ros_name == "/cmd_vel" else c
            for c in maze.COMMUNICATIONS
        )
        EVENTS, STILL = maze.EVENTS, maze.STILL

    path = profiles.write(Relative, ["n", "--ros-args", "-r", "__ns:=/robot2"])
    remapped = profiles.write(Relative, ["n", "--ros-args", "-r", "__ns:=/robot2", "-r", "cmd_vel:=/x"])
    try:
        assert periods(Path(path).read_text()) == {"robosc_writers": (0, 10_000_000), "/robot2/cmd_vel": (3, 0)}
        assert periods(Path(remapped).read_text()) == {"robosc_writers": (0, 10_000_000)}
    finally:
        os.remove(path)
        os.remove(remapped)


def test_a_name_is_escaped_in_the_profile() -> None:
    text = profiles.profile_text((ROOT / "src/robosc/runtime/onboard/fastdds.xml").read_text(), ['/a"b<c'])
    assert '/a"b<c' in periods(text)
