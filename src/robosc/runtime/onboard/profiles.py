# -*- coding: utf-8 -*-
"""The Fast DDS profile a ROS 2 node loads (unless the user names one of their own).

``fastdds.xml`` makes every writer of the node ask its readers for acknowledgements every
10 ms while a message is unacknowledged, so that a command that moves the belief is known
delivered within milliseconds (``delivery.py``). That heartbeat has a price on every
message a writer sends (measured with ``benchmarks/relay.py``: about half a millisecond
more from ``publish()`` to the robot's callback, on a 2-core machine), and a command topic
whose events change nothing (a stream of velocities) never waits for an acknowledgement.
So each such topic gets a profile of its own, by its resolved name, with Fast DDS's own
heartbeat (3 s); every other writer keeps the 10 ms one.

Names are resolved as ROS 2 resolves them (the namespace given with ``-r __ns:=``);
where that cannot be told for sure (a topic remapped on the command line, a private
name), the topic keeps the default profile: slower, never less sure. Standard library
only.
"""

from __future__ import absolute_import, annotations

import os
import tempfile
from typing import Any, Dict, List, Optional, Sequence
from xml.sax.saxutils import quoteattr

DEFAULT = "fastdds.xml"  # next to this module
# Fast DDS's own heartbeat period (its default): for writers nothing waits on
STREAM_PROFILE = (
    "    <data_writer profile_name=%s>\n"
    "        <times><heartbeatPeriod><sec>3</sec><nanosec>0</nanosec></heartbeatPeriod></times>\n"
    "    </data_writer>\n"
)


def stream_topics(robot_class: Any) -> List[str]:
    """The command topics (as the model names them) on which every event changes nothing
    (``STILL``): no belief waits for what is sent on them."""
    topics: Dict[str, bool] = {}  # ROS name -> whether every event on it is still
    ros_name = dict((c.name, c.ros_name) for c in robot_class.COMMUNICATIONS if c.kind == "incoming")
    still = frozenset(robot_class.STILL)
    for event in robot_class.EVENTS:
        if event.controllable and event.communication in ros_name and event.kind == "message":
            name = ros_name[event.communication]
            topics[name] = topics.get(name, True) and event.name in still
    return sorted(name for name, only_still in topics.items() if only_still)


def namespace(args: Sequence[str]) -> Optional[str]:
    """The node's namespace from its ROS arguments (``/`` when none is given); None when the
    arguments remap anything but the namespace and the node's name, or remap for one node
    (``node:from:=to``): a topic's name cannot then be told for sure without ROS."""
    found = "/"
    inside = False
    arguments = list(args)
    i = 0
    while i < len(arguments):
        argument = arguments[i]
        if argument == "--ros-args":
            inside = True
        elif argument == "--":
            inside = False
        elif inside and argument in ("-r", "--remap"):
            if i + 1 >= len(arguments):
                return None
            rule = arguments[i + 1]
            i += 1
            target, _, value = rule.rpartition(":=")
            if target == "__ns":
                found = value if value.startswith("/") else "/" + value
            elif target != "__node":
                return None
        i += 1
    return found.rstrip("/") or "/"


def resolve(name: str, space: str) -> Optional[str]:
    """``name`` as ROS 2 resolves it in namespace ``space``; None for a private name."""
    if name.startswith("~") or "{" in name:
        return None
    if name.startswith("/"):
        return name
    return (space.rstrip("/") + "/" + name) if space != "/" else "/" + name


def profile_text(base: str, names: Sequence[str]) -> str:
    """``base`` (fastdds.xml) with a profile of Fast DDS's own heartbeat for each topic in ``names``."""
    extra = "".join(STREAM_PROFILE % quoteattr(name) for name in names)
    at = base.rindex("</profiles>")
    return base[:at] + extra + base[at:]


def write(robot_class: Any, args: Sequence[str]) -> str:
    """A profile file for this node (in memory where there is /dev/shm: nothing on the robot's
    storage); the caller removes it once the node is made (Fast DDS has read it then)."""
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), DEFAULT)) as handle:
        base = handle.read()
    space = namespace(args)
    names: List[str] = []
    if space is not None:
        for topic in stream_topics(robot_class):
            resolved = resolve(topic, space)
            if resolved is not None:
                names.append(resolved)
    folder = "/dev/shm" if os.access("/dev/shm", os.W_OK) else None
    descriptor, path = tempfile.mkstemp(prefix="robosc-fastdds-", suffix=".xml", dir=folder)
    with os.fdopen(descriptor, "w") as handle:
        handle.write(profile_text(base, names))
    return path
