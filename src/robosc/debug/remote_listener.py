# -*- coding: utf-8 -*-
"""The ROS side of ``robosc view``: finds the running controllers (the namespaces that
publish ``live_view/page``) and passes one's page and event records on, one JSON object per
line on standard output. Run by ``robosc view`` under the middleware's own interpreter (ROS 1:
Debian's python3; ROS 2: the tool's), so it needs only the standard library and the
middleware, on Python 3.8 and later::

    python3 remote_listener.py 1|2 [SECONDS_TO_DISCOVER]

out: {"op": "robots", "robots": ["/robot1", ...]}   (after discovery)
in:  {"op": "watch", "namespace": "/robot1"}
out: {"op": "page", "html": ...}, then {"op": "event", "record": {...}} for each event
in:  {"op": "poses", "poses": [[name, topic], ...]}   (a fleet's view: topics relative to the
     namespace watched, "bot1/pose")
out: {"op": "pose", "name": name, "pose": [x, y, theta]} for each geometry_msgs/Pose2D on them
in:  {"op": "quit"} (or the end of standard input)
"""

import json
import sys
import threading
import time
from typing import Any, Callable, Dict, List, Optional

PAGE = "live_view/page"
EVENTS = "live_view/events"


class Out(object):
    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.stream = sys.stdout
        sys.stdout = sys.stderr  # whatever else prints goes to the log

    def send(self, op: str, **fields: Any) -> None:
        fields["op"] = op
        with self.lock:
            self.stream.write(json.dumps(fields) + "\n")
            self.stream.flush()


def namespaces(topics: List[str]) -> List[str]:
    """The namespaces of the ``.../live_view/page`` topics: "/robot1/live_view/page" -> "/robot1"."""
    found = set()
    for name in topics:
        if name.endswith("/" + PAGE):
            found.add(name[: -len(PAGE) - 1] or "/")
    return sorted(found)


def topic(namespace: str, name: str) -> str:
    return namespace.rstrip("/") + "/" + name


def record_of(text: str) -> Optional[Dict[str, Any]]:
    try:
        value = json.loads(text)
    except ValueError:
        return None
    return value if isinstance(value, dict) else None


def on_page(out: Out) -> Callable[[Any], None]:
    """The callback of ``live_view/page`` (std_msgs/String)."""

    def page(message: Any) -> None:
        out.send("page", html=str(message.data))

    return page


def on_event(out: Out) -> Callable[[Any], None]:
    """The callback of ``live_view/events``: each record that is a JSON object."""

    def event(message: Any) -> None:
        record = record_of(str(message.data))
        if record is not None:
            out.send("event", record=record)

    return event


def on_pose(out: Out, name: str) -> Callable[[Any], None]:
    """The callback of a pose topic (geometry_msgs/Pose2D)."""

    def pose(message: Any) -> None:
        out.send("pose", name=name, pose=[float(message.x), float(message.y), float(message.theta)])

    return pose


def poses_of(message: Dict[str, Any]) -> List[List[str]]:
    """The [name, topic] pairs of a watch line's ``poses`` (others are left out)."""
    found = message.get("poses")
    pairs = found if isinstance(found, list) else []
    return [[str(p[0]), str(p[1])] for p in pairs if isinstance(p, list) and len(p) == 2]


SETTLE = 1.0  # seconds without a new controller before discovery counts as done


def discover_robots(look: Callable[[], List[str]], seconds: float) -> List[str]:
    """The controllers found by calling ``look`` (about ten times a second) for at least
    ``seconds``, until what it finds has not changed for :data:`SETTLE` seconds (ROS 2 learns of
    the graph's nodes one after another); with nothing found, up to three times as long."""
    start = time.monotonic()
    robots = []  # type: List[str]
    changed = start
    while True:
        found = look()
        now = time.monotonic()
        if found != robots:
            robots, changed = found, now
        if now - start >= seconds and robots and now - changed >= SETTLE:
            return robots
        if now - start >= 3 * seconds + SETTLE:
            return robots


def serve(
    out: Out, robots: List[str], watch: Callable[[str], None], follow: Callable[[str, List[List[str]]], None]
) -> None:
    """Say which robots there are, then watch the one asked for (and follow the pose topics
    asked for in its namespace), until told to quit."""
    out.send("robots", robots=robots)
    watched = []  # type: List[str]
    for line in sys.stdin:
        message = record_of(line)
        if message is None:
            continue
        if message.get("op") == "watch":
            watched.append(str(message.get("namespace")))
            watch(watched[-1])
        elif message.get("op") == "poses" and watched:
            follow(watched[-1], poses_of(message))
        elif message.get("op") == "quit":
            break


def ros1(discover: float) -> None:
    import rospy
    from std_msgs.msg import String

    rospy.init_node("robosc_view", anonymous=True, disable_signals=True)
    out = Out()

    def look() -> List[str]:
        time.sleep(0.1)
        return namespaces([name for name, _ in rospy.get_published_topics()])

    robots = discover_robots(look, min(discover, 1.0))
    keep = []

    def watch(namespace: str) -> None:
        keep.append(rospy.Subscriber(topic(namespace, PAGE), String, on_page(out)))
        keep.append(rospy.Subscriber(topic(namespace, EVENTS), String, on_event(out), queue_size=1000))

    def follow(namespace: str, poses: List[List[str]]) -> None:
        from geometry_msgs.msg import Pose2D

        for name, relative in poses:
            keep.append(rospy.Subscriber(topic(namespace, relative), Pose2D, on_pose(out, name), queue_size=100))

    serve(out, robots, watch, follow)
    rospy.signal_shutdown("robosc view ended")


def ros2(discover: float) -> None:
    import rclpy
    from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
    from rclpy.utilities import try_shutdown
    from std_msgs.msg import String

    rclpy.init()
    node = rclpy.create_node("robosc_view")
    out = Out()

    def look() -> List[str]:
        rclpy.spin_once(node, timeout_sec=0.1)
        return namespaces([name for name, _ in node.get_topic_names_and_types()])

    robots = discover_robots(look, discover)
    latched = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    keep = []

    def watch(namespace: str) -> None:
        keep.append(node.create_subscription(String, topic(namespace, PAGE), on_page(out), latched))
        keep.append(node.create_subscription(String, topic(namespace, EVENTS), on_event(out), latched))

    def follow(namespace: str, poses: List[List[str]]) -> None:  # best effort: matches a
        from geometry_msgs.msg import Pose2D  # robot's sensor-data publisher and a reliable one
        from rclpy.qos import qos_profile_sensor_data

        for name, relative in poses:
            keep.append(
                node.create_subscription(Pose2D, topic(namespace, relative), on_pose(out, name), qos_profile_sensor_data)
            )

    done = threading.Event()

    def commands() -> None:
        serve(out, robots, watch, follow)
        done.set()

    threading.Thread(target=commands, daemon=True).start()
    try:
        while not done.is_set():
            rclpy.spin_once(node, timeout_sec=0.1)
    except KeyboardInterrupt:
        pass
    finally:
        node.destroy_node()
        try_shutdown()


if __name__ == "__main__":
    seconds = float(sys.argv[2]) if len(sys.argv) > 2 else 2.0
    if sys.argv[1:2] == ["1"]:
        ros1(seconds)
    else:
        ros2(seconds)
