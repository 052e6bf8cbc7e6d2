"""The simulator's ROS 2 node (rclpy): run as ``python -m robosc_sim_bridge.ros2``."""

import sys
import threading
from typing import Any, Callable

from .protocol import Channel, FleetWiring, Wiring, node_name, read_setup, sec_nanosec


def main() -> None:
    import rclpy
    from rclpy.executors import ExternalShutdownException
    from rclpy.qos import QoSProfile, ReliabilityPolicy
    from rclpy.utilities import ok, try_shutdown
    from rosgraph_msgs.msg import Clock
    from std_srvs.srv import SetBool, Trigger

    setup = read_setup()
    rclpy.init(args=sys.argv)
    node = rclpy.create_node(node_name())
    channel = Channel()
    reliable = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE)
    clock = node.create_publisher(Clock, "/clock", 10)

    def button(name: str, press: Callable[[bool], None]) -> Any:
        def serve(request: Any, response: Any) -> Any:
            press(bool(request.data))
            response.success = True
            response.message = "pressed" if request.data else "released"
            return response

        return node.create_service(SetBool, name, serve)

    def publisher(name: str, kind: Any, depth: int = 10) -> Any:
        return node.create_publisher(kind, name, QoSProfile(depth=depth, reliability=ReliabilityPolicy.RELIABLE))

    subscriber = lambda name, kind, callback: node.create_subscription(kind, name, callback, reliable)  # noqa: E731
    def report_service(name: str, where: Callable[[], str]) -> Any:
        def serve(request: Any, response: Any) -> Any:
            response.success = True
            response.message = where()
            return response

        return node.create_service(Trigger, name, serve)

    if setup.fleet:
        wiring = FleetWiring(setup, channel, publisher, subscriber, report_service)  # type: Any
    else:
        wiring = Wiring(setup, channel, publisher, subscriber, button)

    def stamp(header: Any, t: float) -> None:
        header.stamp.sec, header.stamp.nanosec = sec_nanosec(t)

    def publish_clock(t: float) -> None:
        out = Clock()
        out.clock.sec, out.clock.nanosec = sec_nanosec(t)
        clock.publish(out)

    def report() -> None:
        peers = wiring.peers(lambda p: int(p.get_subscription_count()), lambda s: int(s.get_publisher_count()))
        channel.send("peers", robots=peers)

    done = threading.Event()
    channel.serve(wiring.handler(publish_clock, stamp), done.set)
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
