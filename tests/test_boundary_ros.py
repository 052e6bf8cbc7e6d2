"""Where the proof meets the robot, on real ROS 2 (rclpy, Fast DDS) and ROS 1 (rosmaster,
rospy): a controller killed with ``kill -9`` and started again with the same command line
(it holds until the robots' drivers report, issue 29),
a supervision layer offered commands that are almost an allowed event, scans that cannot be
read, and a start before any data. Each test fails on the behaviour of cd9e530 (issue 21),
where a restart forgot the emergency stop, the layer forwarded a Twist with ``linear.y = 2``
as ``halt``, an empty or NaN scan counted as ``safe``, and a fresh node moved blind."""

from __future__ import annotations

import json
import signal
import time
from pathlib import Path
from typing import Any

from ros_support import Ros1, Ros2, build_package, laser_scan

MOVE = 0.15  # the line follower's move speed



def _health(texts: list[Any]) -> dict[str, Any]:
    return json.loads(texts[-1].data) if texts else {}


def _latched(ros: Ros2, topic: str) -> list[Any]:
    """Every message on a latched (transient local) topic, the one published before too."""
    from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
    from std_msgs.msg import String

    got: list[Any] = []
    qos = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    ros.node.create_subscription(String, topic, got.append, qos)
    return got


class LineRobot:
    """The line follower's robot on ROS 2: a scan and a correction every 0.1 s (what the robot
    sends while it stands on the line), the emergency stop's topics, and the commands it got."""

    def __init__(self, ros: Ros2, scan: list[float] | None = None) -> None:
        from geometry_msgs.msg import Twist
        from std_msgs.msg import Empty, Float32

        self.ros = ros
        self.ranges = scan if scan is not None else [5.0] * 360
        self.cmd = ros.record(Twist, "/cmd_vel")
        self.health = _latched(ros, "/health")
        self.scan = ros.node.create_publisher(laser_scan([]).__class__, "/scan", 10)
        self.correction = ros.node.create_publisher(Float32, "/line/correction", 10)
        self.stop = ros.node.create_publisher(Empty, "/emergency_stop/stop", 10)
        self.on = True
        self._float, self._empty = Float32, Empty
        ros.node.create_timer(0.1, self.publish)

    def publish(self) -> None:
        if self.on:
            self.scan.publish(laser_scan(self.ranges))
            self.correction.publish(self._float(data=10.0))

    def press_stop(self) -> None:
        self.stop.publish(self._empty())

    def moves(self) -> int:
        return sum(1 for m in self.cmd if m.linear.x == MOVE)



def test_ros2_a_controller_killed_with_the_stop_held_does_not_move_after_its_restart(
    ros2: Ros2, tmp_path: Path
) -> None:
    package = build_package("examples/line_follower.rscd", 2, "controller", tmp_path)
    params = {"rate": 20.0, "seed": 3}
    stop_driver = ros2.reports({"EmergencyStop": "in_service"})  # the stop node says where the stop is
    node = ros2.start(package, **params)
    robot = LineRobot(ros2)
    ros2.wait_subscribed(robot.scan, 20)
    ros2.wait_subscribed(robot.stop, 20)
    assert ros2.spin_until(lambda: robot.moves() > 0, 10), "the line follower never moved"
    robot.press_stop()  # ... and held: no continue is ever published
    stop_driver.clear()  # a stop node that cannot report (stopped, but it does not say so when asked)
    assert ros2.spin_until(lambda: robot.cmd[-1].linear.x == 0.0, 5), "no halt after the stop"
    ros2.spin(0.5)
    node.send_signal(signal.SIGKILL)
    node.wait(10)
    ros2.spin(0.5)  # what the killed node sent before it died, taken off the wire
    robot.cmd.clear()
    again = ros2.start(package, **params)  # the same command line, no extra parameter
    ros2.spin(8.0)
    assert again.poll() is None, ros2.processes.output()
    assert robot.moves() == 0, f"{robot.moves()} move commands after the restart"
    assert robot.cmd == [], "commanded with the stop unconfirmed"
    assert _health(robot.health)["unconfirmed"]["EmergencyStop"]["why"] == "not confirmed since the start"
    stop_driver["EmergencyStop"] = "stopped"  # the stop node reports: the stop is held
    assert ros2.spin_until(lambda: bool(robot.cmd), 10), "no halt once the stop was confirmed"
    ros2.spin(1.0)
    assert robot.moves() == 0 and {m.linear.x for m in robot.cmd} == {0.0}
    assert "EmergencyStop confirmed by its driver: stopped" in ros2.processes.output()


def test_ros2_unreadable_scans_are_not_values(ros2: Ros2, tmp_path: Path) -> None:
    """An obstacle, then empty and NaN scans: halt stays the only command; NaN scans for longer
    than data_timeout: nothing that reads the scan is commanded, until a readable scan."""
    package = build_package("examples/line_follower.rscd", 2, "controller", tmp_path)
    ros2.reports({"EmergencyStop": "in_service"})
    ros2.start(package, rate=20.0, seed=4, data_timeout=3.0)
    robot = LineRobot(ros2)
    ros2.wait_subscribed(robot.scan, 20)
    assert ros2.spin_until(lambda: robot.moves() > 0, 10), "the line follower never moved"
    robot.ranges = [0.2] + [5.0] * 359  # an obstacle in front
    assert ros2.spin_until(lambda: robot.cmd[-1].linear.x == 0.0, 5)
    for ranges in ([], [float("nan")] * 360):
        robot.ranges = ranges
        ros2.spin(0.2)
        robot.cmd.clear()
        ros2.spin(0.6)
        assert robot.cmd and robot.moves() == 0, f"moved on {ranges[:1]} scans after an obstacle"
    assert ros2.spin_until(lambda: _health(robot.health).get("stale") == ["scan"], 5)
    assert _health(robot.health)["unreadable"]["scan"] > 10
    robot.cmd.clear()
    ros2.spin(1.0)
    assert robot.cmd == [], "commanded from a scan it could not read for longer than data_timeout"
    robot.ranges = [5.0] * 360  # readable again: it moves again
    assert ros2.spin_until(lambda: robot.moves() > 0, 5)
    assert ros2.spin_until(lambda: _health(robot.health).get("stale") == [], 5)


def test_ros2_a_fresh_node_commands_nothing_before_its_data(ros2: Ros2, tmp_path: Path) -> None:
    from geometry_msgs.msg import Twist
    from std_msgs.msg import Int16

    package = build_package("examples/maze_solver.rscd", 2, "controller", tmp_path)
    ros2.start(package, rate=20.0)
    moves = ros2.record(Twist, "/cmd_vel")
    lefts = ros2.record(Int16, "/rotate_left")
    health = _latched(ros2, "/health")
    assert ros2.spin_until(lambda: bool(health), 20), "no health report"
    ros2.spin(2.0)
    assert moves == [] and lefts == []
    assert _health(health)["held"] is True
    assert _health(health)["waiting_for"] == ["scan_diag_right", "scan_front", "scan_right"]


def test_ros2_the_maze_solver_killed_mid_turn_waits_for_its_platform(ros2: Ros2, tmp_path: Path) -> None:
    from geometry_msgs.msg import Twist
    from std_msgs.msg import Empty, Int16

    package = build_package("examples/maze_solver.rscd", 2, "controller", tmp_path)
    platform = ros2.reports({"Platform": "ready"})
    node = ros2.start(package, rate=20.0, seed=5, publish_state=True)
    moves = ros2.record(Twist, "/cmd_vel")
    lefts = ros2.record(Int16, "/rotate_left")
    health = _latched(ros2, "/health")
    scan = ros2.node.create_publisher(laser_scan([]).__class__, "/scan", 10)
    done = ros2.node.create_publisher(Empty, "/rotate_done", 10)
    wall = [0.3] + [5.0] * 359
    ranges = [wall]
    ros2.node.create_timer(0.1, lambda: scan.publish(laser_scan(ranges[0])))
    ros2.wait_subscribed(scan, 20)
    assert ros2.spin_until(lambda: bool(lefts), 10), "no turn at the wall"
    platform["Platform"] = "turning"
    node.send_signal(signal.SIGKILL)  # in the middle of the turn
    node.wait(10)
    ranges[0] = [5.0] * 360  # the turn goes on while the controller is dead: the way is free
    moves.clear()
    lefts.clear()
    ros2.start(package, rate=20.0, seed=5, publish_state=True)
    assert ros2.spin_until(lambda: "Platform confirmed by its driver: turning" in ros2.processes.output(), 20)
    ros2.spin(1.0)
    assert moves == [] and lefts == [], "commanded while the robot was still turning"
    # the turn ends; said again until the restarted node, whose subscription DDS may match
    # late on a loaded machine, has heard it (a repeat while it is ready is ignored)
    platform["Platform"] = "ready"
    end = time.monotonic() + 15
    while not moves and time.monotonic() < end:
        done.publish(Empty())
        ros2.spin_until(lambda: bool(moves), 0.5)
    assert moves, "no movement after the turn"
    assert moves[0].linear.x == 0.3
    assert _health(health)["unconfirmed"] == {}


def _twist(**fields: float) -> Any:
    from geometry_msgs.msg import Twist

    message = Twist()
    for name, value in fields.items():
        part, axis = name.split("_")
        setattr(getattr(message, part), axis, value)
    return message


# almost halt (which alone is allowed while the stop is pressed): motion nobody allowed
ALMOST_HALT = [
    {"linear_y": 2.0},
    {"angular_x": 1.5},
    {"linear_x": 1e-7},
    {"linear_z": -0.5},
    {"angular_y": 0.3},
]


def test_ros2_the_layer_forwards_only_exactly_the_allowed_event(ros2: Ros2, tmp_path: Path) -> None:
    from geometry_msgs.msg import Twist
    from std_msgs.msg import Empty, Float32, String

    package = build_package("examples/line_follower.rscd", 2, "supervisor", tmp_path)
    ros2.start(package, rate=20.0, publish_state=True)
    robot = ros2.record(Twist, "/cmd_vel")
    blocked = ros2.record(String, "/blocked")
    states = ros2.record(String, "/state")
    controller = ros2.node.create_publisher(Twist, "/robosc/controller/cmd_vel", 10)
    stop = ros2.node.create_publisher(Empty, "/emergency_stop/stop", 10)
    scan = ros2.node.create_publisher(laser_scan([]).__class__, "/scan", 10)
    correction = ros2.node.create_publisher(Float32, "/line/correction", 10)
    for publisher in (controller, stop, scan, correction):
        ros2.wait_subscribed(publisher, 20)
    ros2.wait_publishing("/blocked")

    def data() -> bool:  # scans come best effort: until the node has had them
        scan.publish(laser_scan([5.0] * 360))
        correction.publish(Float32(data=10.0))
        return bool(states) and not json.loads(states[-1].data)["health"]["held"]

    assert ros2.spin_until(data, 10)
    stop.publish(Empty())
    assert ros2.spin_until(
        lambda: bool(states) and json.loads(states[-1].data)["automata"]["EmergencyStop"] == "stopped", 5
    )
    for fields in ALMOST_HALT:
        controller.publish(_twist(**fields))
    assert ros2.spin_until(lambda: len(blocked) >= len(ALMOST_HALT), 5), f"reported: {len(blocked)}"
    ros2.spin(0.3)
    assert robot == [], "forwarded with motion"
    controller.publish(_twist())  # halt, exactly
    assert ros2.spin_until(lambda: bool(robot), 5), "halt was not forwarded"
    ros2.spin(0.3)
    assert len(robot) == 1 and robot[0] == Twist()


# ---- ROS 1 ---------------------------------------------------------------------------------------


def test_ros1_a_controller_killed_with_the_stop_held_does_not_move_after_its_restart(
    ros1: Ros1, tmp_path: Path
) -> None:
    package = build_package("examples/line_follower.rscd", 1, "controller", tmp_path)
    params = {"rate": 20, "seed": 3}
    node = ros1.node(package, **params)
    robot = """
start()
cmd = Recorder("/cmd_vel", Twist)
scan_pub = publisher("/scan", LaserScan, timeout=30)
correction = publisher("/line/correction", Float32, timeout=30)
stop = publisher("/emergency_stop/stop", Empty, timeout=30)
def moves():
    return sum(1 for m in cmd.messages() if m.linear.x == 0.15)
def feed(seconds):
    end = time.time() + seconds
    while time.time() < end:
        scan_pub.publish(scan([5.0] * 360))
        correction.publish(Float32(data=10.0))
        rospy.sleep(0.1)
"""
    first = ros1.client(
        robot
        + """
end = time.time() + 15
while not moves() and time.time() < end:
    feed(0.2)
stop.publish(Empty())
feed(1.0)
done({"moved": moves(), "last": cmd.messages()[-1].linear.x})
""",
        reports={"": {"EmergencyStop": "in_service"}},
    )
    assert first["moved"] > 0 and first["last"] == 0.0
    node.send_signal(signal.SIGKILL)
    node.wait(10)
    again = ros1.node(package, **params)  # the same command line, no extra parameter
    time.sleep(1.0)
    second = ros1.client(  # a stop node that does not report
        robot
        + """
feed(8.0)
done({"moves": moves(), "commands": len(cmd.messages())})
"""
    )
    assert again.poll() is None
    assert second == {"moves": 0, "commands": 0}, "commanded with the stop unconfirmed"
    third = ros1.client(  # one that does: the stop is held
        robot
        + """
feed(3.0)
done({"moves": moves(), "commands": len(cmd.messages())})
""",
        reports={"": {"EmergencyStop": "stopped"}},
    )
    assert third["moves"] == 0 and third["commands"] > 0, third
    assert "EmergencyStop confirmed by its driver: stopped" in ros1.processes.output()


def test_ros1_the_layer_forwards_only_exactly_the_allowed_event(ros1: Ros1, tmp_path: Path) -> None:
    package = build_package("examples/line_follower.rscd", 1, "supervisor", tmp_path)
    ros1.node(package, rate=20, publish_state=True)
    result = ros1.client(
        f"""
start()
robot = Recorder("/cmd_vel", Twist)
blocked = Recorder("/blocked", String)
state = State()
controller = publisher("/robosc/controller/cmd_vel", Twist, timeout=30)
stop = publisher("/emergency_stop/stop", Empty, timeout=30)
scan_pub = publisher("/scan", LaserScan, timeout=30)
correction = publisher("/line/correction", Float32, timeout=30)
scan_pub.publish(scan([5.0] * 360))
correction.publish(Float32(data=10.0))
stop.publish(Empty())
assert wait_for(lambda: state.value("EmergencyStop") == "stopped", 5)
for fields in {ALMOST_HALT!r}:
    message = Twist()
    for name, value in fields.items():
        part, axis = name.split("_")
        setattr(getattr(message, part), axis, value)
    controller.publish(message)
assert wait_for(lambda: len(blocked.messages()) >= {len(ALMOST_HALT)}, 5)
rospy.sleep(0.3)
forwarded = len(robot.messages())
controller.publish(Twist())
assert wait_for(lambda: robot.messages(), 5)
rospy.sleep(0.3)
done({{"forwarded": forwarded, "then": len(robot.messages())}})
"""
    )
    assert result == {"forwarded": 0, "then": 1}
