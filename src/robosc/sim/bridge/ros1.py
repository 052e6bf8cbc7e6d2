"""The simulator's ROS 1 node (rospy): run as ``python3 -m robosc_sim_bridge.ros1``."""

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
    import rospy
    from geometry_msgs.msg import Twist
    from rosgraph_msgs.msg import Clock
    from std_msgs.msg import Int16, String
    from std_srvs.srv import SetBool, SetBoolResponse

    setup = read_setup()
    robots, topics, roles = setup.robots, setup.topics, setup.roles
    # every node started after this one runs on the simulation's clock
    rospy.set_param("/use_sim_time", True)
    rospy.init_node("robosc_sim", disable_signals=True)
    channel = Channel()
    kinds = published_kinds()
    clock = rospy.Publisher("/clock", Clock, queue_size=10)
    publishers: List[Dict[str, Any]] = []
    subscriptions: List[Dict[str, Any]] = []
    keep: List[Any] = []
    for i, robot in enumerate(robots):
        publishers.append(
            dict(
                (role, rospy.Publisher(topic(robot, topics[role]), kinds[role], queue_size=10))
                for role in roles
                if role in PUBLISHED
            )
        )
        subs: Dict[str, Any] = {}
        for role in roles:
            if role == "cmd_vel":
                subs[role] = rospy.Subscriber(topic(robot, topics[role]), Twist, channel.on_twist(i))
            elif role in SUBSCRIBED:
                subs[role] = rospy.Subscriber(topic(robot, topics[role]), Int16, channel.on_number(i, role))
        subscriptions.append(subs)
        keep.append(rospy.Subscriber(topic(robot, "blocked"), String, channel.on_refused(i)))

        def press(request: Any, i: int = i) -> Any:
            channel.send("press", robot=i, pressed=bool(request.data))
            return SetBoolResponse(True, "pressed" if request.data else "released")

        keep.append(rospy.Service(topic(robot, BUTTON), SetBool, press))

    now = [0.0]

    def stamp(header: Any) -> None:
        header.stamp = rospy.Time.from_sec(now[0])

    def handle(message: Dict[str, Any]) -> None:
        op = message.get("op")
        if op == "clock":
            now[0] = float(message["t"])
            clock.publish(Clock(rospy.Time.from_sec(now[0])))
        elif op == "publish":
            i, role = int(message["robot"]), message["role"]
            publisher = publishers[i].get(role)
            if publisher is None:
                return
            out = message_for(kinds, setup, message, stamp)
            publisher.publish(out)

    def connected(i: int, role: str) -> bool:
        if role in publishers[i]:
            return bool(publishers[i][role].get_num_connections() > 0)
        return bool(subscriptions[i][role].get_num_connections() > 0)

    done = threading.Event()
    channel.serve(handle, done.set)
    channel.send("ready")
    while not done.is_set() and not rospy.is_shutdown():
        channel.send("peers", robots=peer_counts(robots, connected, roles))
        done.wait(0.2)
    rospy.signal_shutdown("simulation over")


if __name__ == "__main__":
    main()
