"""The simulator's ROS 2 node (rclpy): run as ``python -m robosc_sim_bridge.ros2``."""

import sys
import threading
from typing import Any, Dict, List

from .protocol import (
    BUTTON,
    PUBLISHED,
    SUBSCRIBED,
    Channel,
    message_for,
    peer_counts,
    published_kinds,
    read_setup,
    topic,
)


def main() -> None:
    import rclpy
    from geometry_msgs.msg import Twist
    from rclpy.executors import ExternalShutdownException
    from rclpy.qos import QoSProfile, ReliabilityPolicy
    from rclpy.utilities import ok, try_shutdown
    from rosgraph_msgs.msg import Clock
    from std_msgs.msg import Int16, String
    from std_srvs.srv import SetBool

    setup = read_setup()
    robots, topics, roles = setup.robots, setup.topics, setup.roles
    rclpy.init(args=sys.argv)
    node = rclpy.create_node("robosc_sim")
    channel = Channel()
    kinds = published_kinds()
    reliable = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE)
    clock = node.create_publisher(Clock, "/clock", 10)
    publishers: List[Dict[str, Any]] = []
    subscriptions: List[Dict[str, Any]] = []
    keep: List[Any] = []

    for i, robot in enumerate(robots):
        publishers.append(
            dict(
                (role, node.create_publisher(kinds[role], topic(robot, topics[role]), reliable))
                for role in roles
                if role in PUBLISHED
            )
        )
        subs: Dict[str, Any] = {}
        for role in roles:
            if role == "cmd_vel":
                subs[role] = node.create_subscription(Twist, topic(robot, topics[role]), channel.on_twist(i), reliable)
            elif role in SUBSCRIBED:
                subs[role] = node.create_subscription(
                    Int16, topic(robot, topics[role]), channel.on_number(i, role), reliable
                )
        subscriptions.append(subs)
        keep.append(node.create_subscription(String, topic(robot, "blocked"), channel.on_refused(i), 10))

        def press(request: Any, response: Any, i: int = i) -> Any:
            channel.send("press", robot=i, pressed=bool(request.data))
            response.success = True
            response.message = "pressed" if request.data else "released"
            return response

        keep.append(node.create_service(SetBool, topic(robot, BUTTON), press))

    now = [0.0]

    def stamp(header: Any) -> None:
        header.stamp.sec = int(now[0])
        header.stamp.nanosec = int(round((now[0] - int(now[0])) * 1e9)) % 1000000000

    def handle(message: Dict[str, Any]) -> None:
        op = message.get("op")
        if op == "clock":
            now[0] = float(message["t"])
            out = Clock()
            out.clock.sec = int(now[0])
            out.clock.nanosec = int(round((now[0] - int(now[0])) * 1e9)) % 1000000000
            clock.publish(out)
        elif op == "publish":
            i, role = int(message["robot"]), message["role"]
            publisher = publishers[i].get(role)
            if publisher is None:
                return
            out = message_for(kinds, setup, message, stamp)
            publisher.publish(out)

    def connected(i: int, role: str) -> bool:
        if role in publishers[i]:
            return bool(publishers[i][role].get_subscription_count() > 0)
        return bool(subscriptions[i][role].get_publisher_count() > 0)

    def report() -> None:
        channel.send("peers", robots=peer_counts(robots, connected, roles))

    done = threading.Event()
    channel.serve(handle, done.set)
    node.create_timer(0.2, report)
    channel.send("ready")
    try:
        while not done.is_set() and ok():
            rclpy.spin_once(node, timeout_sec=0.1)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        try_shutdown()


if __name__ == "__main__":
    main()
