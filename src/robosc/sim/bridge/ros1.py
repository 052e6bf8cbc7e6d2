"""The simulator's ROS 1 node (rospy): run as ``python3 -m robosc_sim_bridge.ros1``."""

import threading
from typing import Any, Callable

from .protocol import Channel, FleetWiring, Wiring, node_name, read_setup


def main() -> None:
    import rospy
    from rosgraph_msgs.msg import Clock
    from std_srvs.srv import SetBool, SetBoolResponse, Trigger, TriggerResponse

    setup = read_setup()
    # every node started after this one runs on the simulation's clock
    rospy.set_param("/use_sim_time", True)
    rospy.init_node(node_name(), disable_signals=True)
    channel = Channel()
    clock = rospy.Publisher("/clock", Clock, queue_size=10)

    def button(name: str, press: Callable[[bool], None]) -> Any:
        def serve(request: Any) -> Any:
            press(bool(request.data))
            return SetBoolResponse(True, "pressed" if request.data else "released")

        return rospy.Service(name, SetBool, serve)

    def publisher(name, kind, depth=10):  # type: (str, Any, int) -> Any
        return rospy.Publisher(name, kind, queue_size=depth)

    subscriber = lambda name, kind, callback: rospy.Subscriber(name, kind, callback)  # noqa: E731
    def report_service(name: str, where: Callable[[], str]) -> Any:
        return rospy.Service(name, Trigger, lambda request: TriggerResponse(True, where()))

    if setup.fleet:
        wiring = FleetWiring(setup, channel, publisher, subscriber, report_service)  # type: Any
    else:
        wiring = Wiring(setup, channel, publisher, subscriber, button)

    def stamp(header: Any, t: float) -> None:
        header.stamp = rospy.Time.from_sec(t)

    handle = wiring.handler(lambda t: clock.publish(Clock(rospy.Time.from_sec(t))), stamp)
    done = threading.Event()
    channel.serve(handle, done.set)
    channel.send("ready")
    while not done.is_set() and not rospy.is_shutdown():
        connections = lambda end: int(end.get_num_connections())  # noqa: E731
        channel.send("peers", robots=wiring.peers(connections, connections))
        done.wait(0.2)
    rospy.signal_shutdown("simulation over")


if __name__ == "__main__":
    main()
