"""Generated ROS 2 nodes under real rclpy with Fast DDS (the ros-jazzy-* wheels).

The node runs as a subprocess (``python -m <package>.node --ros-args ...``); the
test is the robot: an in-process rclpy node with publishers, subscriptions, a
real SetBool service server and a real test_msgs/Fibonacci action server. DDS
stays on this machine (``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST``) in a domain
of the test's own.
"""

from __future__ import annotations

import ast
import json
import re
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from robosc.api import load_model, plan_supervisor, synthesize_model
from ros_support import ROOT, Ros2, build_package, initial_states, laser_scan, logged_events


def _state(states: list[Any]) -> dict[str, Any]:
    if not states:
        return {}
    data = json.loads(states[-1].data)
    return {**data["automata"], **data["variables"]}


def _commanding(states: list[Any]) -> bool:
    """Whether the node's last state says it commands (it listened for other controllers first)."""
    return bool(states) and json.loads(states[-1].data)["health"]["coordinator"]["commanding"] is True


def _confirmed(states: list[Any]) -> bool:
    """Whether the node's last state says every component is confirmed (its drivers reported)."""
    return bool(states) and json.loads(states[-1].data)["health"]["unconfirmed"] == {}


def test_maze_solver_turns_left_at_a_wall_and_survives_malformed_scans(ros2: Ros2, tmp_path: Path) -> None:
    from geometry_msgs.msg import Twist
    from std_msgs.msg import Empty, Int16, String

    package = build_package("examples/maze_solver.rscd", 2, "controller", tmp_path)
    ros2.reports(initial_states("examples/maze_solver.rscd"))  # the drivers report where they start
    node = ros2.start(package, rate=20.0, seed=1, publish_state=True)
    moves = ros2.record(Twist, "/cmd_vel")
    lefts = ros2.record(Int16, "/rotate_left")
    states = ros2.record(String, "/state")
    scan = ros2.node.create_publisher(laser_scan([]).__class__, "/scan", 10)
    done = ros2.node.create_publisher(Empty, "/rotate_done", 10)
    ros2.wait_subscribed(scan)
    ros2.spin(0.5)
    assert moves == [] and lefts == [], "commanded before the first scan"
    scan.publish(laser_scan([5.0] * 360))
    assert ros2.spin_until(lambda: len(moves) >= 3, 15), "no movement commands"
    assert moves[-1].linear.x == 0.3
    for bad in ([], [float("nan")] * 360, [5.0]):  # empty, NaN, too short for ranges[270]
        scan.publish(laser_scan(bad))
        ros2.spin(0.2)
    assert not lefts, "turned on malformed data"
    scan.publish(laser_scan([0.3] + [5.0] * 359))
    assert ros2.spin_until(lambda: bool(lefts), 5), "no turn at a wall"
    assert lefts[0].data == 90
    assert ros2.spin_until(lambda: _state(states).get("Platform") == "turning", 5)
    ros2.spin(0.3)
    moves.clear()
    ros2.spin(0.5)
    assert not moves, "moved while turning"
    scan.publish(laser_scan([5.0] * 360))
    done.publish(Empty())
    assert ros2.spin_until(lambda: _state(states).get("Platform") == "ready", 5)
    assert ros2.spin_until(lambda: bool(moves), 5)
    assert node.poll() is None, "the node died"
    assert "unreadable data" in ros2.processes.output()


def test_line_follower_never_moves_while_stopped_or_unsafe(ros2: Ros2, tmp_path: Path) -> None:
    from geometry_msgs.msg import Twist
    from std_msgs.msg import Empty, Float32, String

    package = build_package("examples/line_follower.rscd", 2, "controller", tmp_path)
    ros2.reports(initial_states("examples/line_follower.rscd"))  # the drivers report where they start
    event_log = tmp_path / "events.jsonl"
    node = ros2.start(package, rate=20.0, seed=2, publish_state=True, event_log=str(event_log))
    cmd = ros2.record(Twist, "/cmd_vel")
    states = ros2.record(String, "/state")
    correction = ros2.node.create_publisher(Float32, "/line/correction", 10)
    scan = ros2.node.create_publisher(laser_scan([]).__class__, "/scan", 10)
    stop = ros2.node.create_publisher(Empty, "/emergency_stop/stop", 10)
    resume = ros2.node.create_publisher(Empty, "/emergency_stop/continue", 10)
    for publisher in (correction, scan, stop, resume):
        ros2.wait_subscribed(publisher)

    def speeds(seconds: float) -> list[float]:
        ros2.spin(0.3)
        cmd.clear()
        ros2.spin(seconds)
        return [m.linear.x for m in cmd]

    scan.publish(laser_scan([5.0] * 360))
    assert speeds(0.5) == []  # held: the correction has not come yet

    def data() -> bool:  # scans come best effort: until the node has had them
        scan.publish(laser_scan([5.0] * 360))
        correction.publish(Float32(data=10.0))
        return _state(states).get("Lidar.safety") == "safe" and _state(states).get("LineDetector") == "line_found"

    assert ros2.spin_until(data, 10)
    assert ros2.spin_until(lambda: _commanding(states), 10)  # (2 s of listening for another controller)
    driving = speeds(0.5)
    assert 0.15 in driving
    assert abs(cmd[-1].angular.z - (-0.1)) < 1e-9
    stop.publish(Empty())
    assert ros2.spin_until(lambda: _state(states).get("EmergencyStop") == "stopped", 5)
    stopped = speeds(0.5)
    assert stopped and set(stopped) == {0.0}, "moved while the emergency stop was active"
    resume.publish(Empty())
    assert ros2.spin_until(lambda: _state(states).get("EmergencyStop") == "in_service", 5)
    assert 0.15 in speeds(0.5)
    scan.publish(laser_scan([0.2] + [5.0] * 359))
    assert ros2.spin_until(lambda: _state(states).get("Lidar.safety") == "unsafe", 5)
    unsafe = speeds(0.5)
    assert unsafe and set(unsafe) == {0.0}, "moved while unsafe"
    assert node.poll() is None
    events = logged_events(event_log)
    names = [e["event"] for e in events]
    assert {"stop", "move", "halt", "scan"} <= set(names)


class _Robot:
    """The pick station's servers: SetBool for the light, Fibonacci for the arm."""

    def __init__(self, ros: Ros2, long_goals: bool = False) -> None:
        from rclpy.action import ActionServer, CancelResponse
        from rclpy.callback_groups import ReentrantCallbackGroup
        from std_srvs.srv import SetBool
        from test_msgs.action import Fibonacci

        self.light_calls: list[bool] = []
        self.goals: list[int] = []
        self.cancelled: list[int] = []
        self.long_goals = long_goals
        self.context = ros.context
        group = ReentrantCallbackGroup()
        ros.node.create_service(SetBool, "/light/set", self.light, callback_group=group)
        self.server = ActionServer(
            ros.node,
            Fibonacci,
            "/arm/pick",
            execute_callback=self.pick,
            cancel_callback=lambda _goal: CancelResponse.ACCEPT,
            callback_group=group,
        )

    def light(self, request: Any, response: Any) -> Any:
        self.light_calls.append(request.data)
        response.success = True
        response.message = "ok"
        return response

    def pick(self, goal_handle: Any) -> Any:
        from test_msgs.action import Fibonacci

        self.goals.append(goal_handle.request.order)
        feedback = Fibonacci.Feedback()
        feedback.sequence = [2]
        goal_handle.publish_feedback(feedback)
        result = Fibonacci.Result()
        end = time.monotonic() + (30 if self.long_goals else 0.1)
        while time.monotonic() < end and self.context.ok():
            if goal_handle.is_cancel_requested:
                self.cancelled.append(goal_handle.request.order)
                goal_handle.canceled()
                return result
            time.sleep(0.01)
        if not self.context.ok():
            return result
        result.sequence = [5]
        goal_handle.succeed()
        return result


def _pick_station(ros: Ros2, tmp_path: Path, seed: int) -> tuple[subprocess.Popen[bytes], list[Any], Any, Any]:
    from geometry_msgs.msg import Pose
    from std_msgs.msg import Empty, String

    package = build_package("examples/pick_and_light.rscd", 2, "controller", tmp_path)
    ros.reports(initial_states("examples/pick_and_light.rscd"))  # the drivers report where they start
    node = ros.start(package, rate=20.0, seed=seed, publish_state=True)
    states = ros.record(String, "/state")
    seen = ros.node.create_publisher(Pose, "/camera/object", 10)
    lost = ros.node.create_publisher(Empty, "/camera/lost", 10)
    ros.wait_subscribed(seen)
    ros.wait_subscribed(lost)
    return node, states, seen, lost


def test_pick_station_service_action_and_announcement(ros2: Ros2, tmp_path: Path) -> None:
    from geometry_msgs.msg import Pose
    from rclpy.executors import MultiThreadedExecutor
    from std_msgs.msg import String

    ros2.executor = MultiThreadedExecutor(num_threads=4, context=ros2.context)
    ros2.executor.add_node(ros2.node)
    robot = _Robot(ros2)
    announcements = ros2.record(String, "/speaker/say")
    look_at = ros2.record(Pose, "/camera/look_at")
    node, states, seen, _ = _pick_station(ros2, tmp_path, seed=3)
    target = Pose()
    target.position.x, target.position.y = 1.25, -0.5
    seen.publish(target)
    assert ros2.spin_until(lambda: bool(look_at), 10), "the camera was not pointed at the object"
    assert (look_at[0].position.x, look_at[0].position.y, look_at[0].position.z) == (1.25, -0.5, 0.5)
    assert ros2.spin_until(lambda: len(robot.goals) >= 3, 30), f"picks: {robot.goals}"
    assert ros2.spin_until(lambda: bool(announcements), 10), "the full bin was not announced"
    assert announcements[0].data == "the bin is full"
    assert set(robot.goals) == {1}
    # the light goes on while the arm picks and off after: alternating requests (the light
    # is switched off after the pick's result, which may come after the announcement)
    assert ros2.spin_until(lambda: len(robot.light_calls) >= 4, 10), f"light calls: {robot.light_calls}"
    assert robot.light_calls[:4] == [True, False, True, False]
    assert ros2.spin_until(lambda: _state(states).get("Arm") == "full", 5)
    assert _state(states)["Arm.picks"] == 3
    assert _state(states)["Arm.progress"] == 0  # reset by the response; the feedback had set it to 2
    assert node.poll() is None


def test_pick_cancelled_when_the_object_is_lost(ros2: Ros2, tmp_path: Path) -> None:
    from geometry_msgs.msg import Pose
    from rclpy.executors import MultiThreadedExecutor
    from std_msgs.msg import Empty

    ros2.executor = MultiThreadedExecutor(num_threads=4, context=ros2.context)
    ros2.executor.add_node(ros2.node)
    robot = _Robot(ros2, long_goals=True)
    node, states, seen, lost = _pick_station(ros2, tmp_path, seed=4)
    seen.publish(Pose())
    assert ros2.spin_until(lambda: bool(robot.goals) and _state(states).get("Arm") == "picking", 20)
    assert ros2.spin_until(lambda: _state(states).get("Arm.progress") == 2, 5)  # feedback arrived
    lost.publish(Empty())
    assert ros2.spin_until(lambda: bool(robot.cancelled), 10), "the pick was not cancelled"
    assert ros2.spin_until(lambda: _state(states).get("Arm") == "idle", 5)
    ros2.spin(0.5)
    assert len(robot.goals) == 1  # not started again: the object is gone
    assert node.poll() is None


NEVER_ANSWERS = """
import os, signal, sys, time, rclpy
from std_srvs.srv import SetBool
rclpy.init(domain_id=int(sys.argv[1]))
signal.signal(signal.SIGTERM, lambda *_: os._exit(0))  # its callback never returns: end at once
node = rclpy.create_node("mute_light")
def light(request, response):
    print("called", flush=True)
    time.sleep(3600)
    return response
node.create_service(SetBool, "/light/set", light)
rclpy.spin(node)
"""


def test_a_service_that_never_answers_does_not_stop_the_node(ros2: Ros2, tmp_path: Path) -> None:
    from geometry_msgs.msg import Pose

    server = ros2.processes.start("mute_light", [sys.executable, "-c", NEVER_ANSWERS, str(ros2.domain)], ros2.env)
    from rclpy.executors import MultiThreadedExecutor

    ros2.executor = MultiThreadedExecutor(num_threads=4, context=ros2.context)
    ros2.executor.add_node(ros2.node)
    robot = _Robot.__new__(_Robot)  # only the action server: the light is the mute one
    robot.goals, robot.cancelled, robot.long_goals, robot.light_calls = [], [], True, []
    robot.context = ros2.context
    from rclpy.action import ActionServer, CancelResponse
    from test_msgs.action import Fibonacci

    ActionServer(
        ros2.node, Fibonacci, "/arm/pick", execute_callback=robot.pick, cancel_callback=lambda _g: CancelResponse.ACCEPT
    )
    node, states, seen, _ = _pick_station(ros2, tmp_path, seed=5)
    seen.publish(Pose())
    assert ros2.spin_until(lambda: _state(states).get("Light") == "turning_on", 20)
    count = len(states)
    ros2.spin(1.0)
    assert len(states) - count >= 10  # the cycle goes on at 20 Hz
    assert _state(states).get("Light") == "turning_on"
    assert node.poll() is None
    assert server.poll() is None


def test_supervision_layer_forwards_allowed_and_blocks_forbidden_commands(ros2: Ros2, tmp_path: Path) -> None:
    from geometry_msgs.msg import Twist
    from std_msgs.msg import Int16, String

    package = build_package("examples/maze_solver.rscd", 2, "supervisor", tmp_path)
    ros2.reports(initial_states("examples/maze_solver.rscd"))  # the drivers report where they start
    node = ros2.start(package, rate=20.0, publish_state=True)
    robot_moves = ros2.record(Twist, "/cmd_vel")
    robot_lefts = ros2.record(Int16, "/rotate_left")
    blocked = ros2.record(String, "/blocked")
    states = ros2.record(String, "/state")
    to_controller = ros2.record(laser_scan([]).__class__, "/robosc/controller/scan")
    move = ros2.node.create_publisher(Twist, "/robosc/controller/cmd_vel", 10)
    left = ros2.node.create_publisher(Int16, "/robosc/controller/rotate_left", 10)
    scan = ros2.node.create_publisher(laser_scan([]).__class__, "/scan", 10)
    for publisher in (move, left, scan):
        ros2.wait_subscribed(publisher)
    ros2.wait_publishing("/blocked")
    forward = Twist()
    forward.linear.x = 0.3
    move.publish(forward)  # before any scan: held
    assert ros2.spin_until(lambda: bool(blocked), 5), "a command before the first scan was not reported"
    assert json.loads(blocked[-1].data)["reason"].startswith("held: waiting for the first readable data")
    blocked.clear()
    scan.publish(laser_scan([5.0] * 360))
    assert ros2.spin_until(lambda: _state(states).get("Distance.front") == "no_wall_front", 5)
    # (no_wall_front is also where it starts: the scan has come when the node stops holding)
    assert ros2.spin_until(lambda: json.loads(states[-1].data)["health"]["held"] is False, 5), states[-1].data
    assert ros2.spin_until(lambda: _confirmed(states), 10)  # the platform's driver said where it is
    to_controller.clear()
    move.publish(forward)
    assert ros2.spin_until(lambda: bool(robot_moves), 5), (
        "an allowed command was not forwarded",
        [m.data for m in blocked],
        states[-1].data,
        ros2.processes.output(),
    )
    left.publish(Int16(data=90))
    assert ros2.spin_until(lambda: bool(blocked), 5), "a forbidden command was not reported"
    assert json.loads(blocked[-1].data)["event"] == "turn_left"
    assert not robot_lefts
    scan.publish(laser_scan([0.3] + [5.0] * 359))
    assert ros2.spin_until(lambda: bool(to_controller), 5), "robot data not passed to the controller"
    assert ros2.spin_until(lambda: _state(states).get("Distance.front") == "wall_front", 5)
    before = len(robot_moves)
    move.publish(forward)
    assert ros2.spin_until(lambda: len(blocked) >= 2, 5)
    assert json.loads(blocked[-1].data)["event"] == "movement"
    left.publish(Int16(data=90))
    assert ros2.spin_until(lambda: bool(robot_lefts), 5)
    ros2.spin(0.3)
    assert len(robot_moves) == before
    assert robot_lefts[0].data == 90
    assert _state(states).get("Platform") == "turning"
    assert node.poll() is None


def test_launch_files_compile(tmp_path: Path) -> None:
    for mode in ("controller", "supervisor"):
        package = build_package("examples/maze_solver.rscd", 2, mode, tmp_path)
        launches = list((package / "launch").glob("*.launch.py"))
        assert len(launches) == 1
        text = launches[0].read_text()
        tree = compile(text, str(launches[0]), "exec", flags=ast.PyCF_ONLY_AST)
        nodes = [c for c in ast.walk(tree) if isinstance(c, ast.Call) and getattr(c.func, "id", "") == "Node"]
        supervisor = nodes[0]  # the robot's node is started again when it dies (the drivers confirm its state)
        respawn = {k.arg: k.value for k in supervisor.keywords}
        assert isinstance(respawn["respawn"], ast.Constant) and respawn["respawn"].value is True
        assert 'namespace=LaunchConfiguration("namespace")' in text
        for name in ("rate", "seed", "event_log", "event_log_max_bytes", "qos_depth", "server_timeout"):
            assert f"({name!r}," in text


def test_supervision_layer_forwards_services_and_actions(ros2: Ros2, tmp_path: Path) -> None:
    from geometry_msgs.msg import Pose
    from rclpy.action import ActionClient
    from rclpy.executors import MultiThreadedExecutor
    from std_msgs.msg import Empty, String
    from std_srvs.srv import SetBool
    from test_msgs.action import Fibonacci

    ros2.executor = MultiThreadedExecutor(num_threads=4, context=ros2.context)
    ros2.executor.add_node(ros2.node)
    robot = _Robot(ros2, long_goals=True)
    package = build_package("examples/pick_and_light.rscd", 2, "supervisor", tmp_path)
    ros2.reports(initial_states("examples/pick_and_light.rscd"))  # the drivers report where they start
    node = ros2.start(package, rate=20.0, publish_state=True)
    states = ros2.record(String, "/state")
    blocked = ros2.record(String, "/blocked")
    seen_by_controller = ros2.record(Pose, "/robosc/controller/camera/object")
    seen = ros2.node.create_publisher(Pose, "/camera/object", 10)
    lost = ros2.node.create_publisher(Empty, "/camera/lost", 10)
    light = ros2.node.create_client(SetBool, "/robosc/controller/light/set")
    arm = ActionClient(ros2.node, Fibonacci, "/robosc/controller/arm/pick")
    ros2.wait_subscribed(seen)
    ros2.wait_publishing("/blocked")
    assert ros2.spin_until(lambda: light.service_is_ready() and arm.server_is_ready(), 15)
    assert ros2.spin_until(lambda: _confirmed(states), 10)  # the drivers said where they are

    def wait(future: Any, seconds: float = 10) -> Any:
        assert ros2.spin_until(future.done, seconds)
        return future.result()

    # nothing seen yet: picking is not allowed, nor is the light (it goes on only while picking)
    goal = Fibonacci.Goal()
    goal.order = 1
    handle = wait(arm.send_goal_async(goal))
    result = wait(handle.get_result_async())
    assert result.status == 6  # GoalStatus.STATUS_ABORTED
    assert wait(light.call_async(SetBool.Request(data=True))).success is False
    assert ros2.spin_until(lambda: len(blocked) >= 2, 5)
    assert [json.loads(b.data)["event"] for b in blocked[:2]] == ["pick.c_trigger", "set_light.c_trigger"]
    assert robot.goals == [] and robot.light_calls == []
    # an object: the goal is forwarded, its feedback comes back
    seen.publish(Pose())
    assert ros2.spin_until(lambda: bool(seen_by_controller), 5), "robot data not passed to the controller"
    assert ros2.spin_until(lambda: _state(states).get("Camera") == "seen", 5)
    feedback: list[Any] = []
    handle = wait(arm.send_goal_async(goal, feedback_callback=lambda f: feedback.append(list(f.feedback.sequence))))
    assert handle.accepted
    assert ros2.spin_until(lambda: robot.goals == [1] and bool(feedback), 10)
    assert feedback[0] == [2]
    # while picking the light may go on: forwarded to the real service
    call = light.call_async(SetBool.Request(data=True))
    ros2.spin_until(call.done, 10)
    assert robot.light_calls == [True], robot.light_calls
    assert call.done() and call.result().success is True
    # the object is lost: the supervisor cancels the running pick
    lost.publish(Empty())
    assert ros2.spin_until(lambda: bool(robot.cancelled), 10), "the pick was not cancelled"
    result = wait(handle.get_result_async())
    assert result.status == 6  # aborted towards the controller: the supervisor cancelled it
    assert ros2.spin_until(lambda: _state(states).get("Arm") == "idle", 5)
    assert node.poll() is None


def test_node_serves_the_live_view(ros2: Ros2, tmp_path: Path) -> None:
    """With view_port set, the node serves the page (laid out at generation time) and
    streams its events; nothing but the generated files is needed."""
    import urllib.request

    from robosc.api import load_model, plan_supervisor, synthesize_model
    from robosc.codegen.ros import generate
    from robosc.debug.live import render_page
    from ros_support import free_port

    result = synthesize_model(load_model(ROOT / "examples/maze_solver.rscd"))
    package = tmp_path / "maze_view"
    generate(plan_supervisor(result), 2, "controller", package, render_page(result))
    port = free_port()
    ros2.reports({"Platform": "ready"})
    node = ros2.start(package, rate=20.0, view_port=port)
    scan = ros2.node.create_publisher(laser_scan([]).__class__, "/scan", 10)
    ros2.wait_subscribed(scan)
    from std_msgs.msg import Int16

    ros2.record(Int16, "/rotate_left")  # the robot listens: the node sends it commands

    def page() -> str:
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=2) as response:
            return str(response.read().decode())

    html = page()
    assert "<title>MazeSolver: robosc live view</title>" in html and 'id="Platform::ready"' in html
    with urllib.request.urlopen(f"http://127.0.0.1:{port}/events", timeout=5) as stream:
        scan.publish(laser_scan([0.3] + [5.0] * 359))
        seen: list[str] = []
        end = time.monotonic() + 10
        last = time.monotonic()
        while time.monotonic() < end and not any('"event": "turn_left"' in line for line in seen):
            if time.monotonic() - last > 0.2:  # a LiDAR publishes all the time (best effort), at 5 Hz here,
                # slower than the test reads the stream (the node turns 2 s after it starts: claims.py)
                scan.publish(laser_scan([0.3] + [5.0] * 359))
                last = time.monotonic()
            ros2.spin(0.01)
            seen.append(stream.readline().decode())
    turn = next((line for line in seen if '"event": "turn_left"' in line), None)
    assert turn is not None, (len(seen), seen[-1:], ros2.processes.output())
    record = json.loads(turn.removeprefix("data: "))
    assert record["state"]["automata"]["Platform"] == "turning"
    assert record["controllable"] is True and record["data"] == 90
    assert node.poll() is None


def test_supervision_layer_fails_closed_on_a_shared_topic(ros2: Ros2, tmp_path: Path) -> None:
    """The line follower's move and halt share /cmd_vel. With the emergency stop pressed, a
    controller's command that is neither (5.0, NaN, (-2, 3)) never reaches the robot; halt
    does; move does not."""
    from geometry_msgs.msg import Twist
    from std_msgs.msg import Empty, Float32, String

    package = build_package("examples/line_follower.rscd", 2, "supervisor", tmp_path)
    ros2.reports(initial_states("examples/line_follower.rscd"))  # the drivers report where they start
    node = ros2.start(package, rate=20.0, publish_state=True)
    robot = ros2.record(Twist, "/cmd_vel")
    blocked = ros2.record(String, "/blocked")
    states = ros2.record(String, "/state")
    controller = ros2.node.create_publisher(Twist, "/robosc/controller/cmd_vel", 10)
    stop = ros2.node.create_publisher(Empty, "/emergency_stop/stop", 10)
    scan = ros2.node.create_publisher(laser_scan([]).__class__, "/scan", 10)
    correction = ros2.node.create_publisher(Float32, "/line/correction", 10)
    for publisher in (controller, stop, scan, correction):
        ros2.wait_subscribed(publisher)
    ros2.wait_publishing("/blocked")

    def data() -> bool:  # scans come best effort: until the node has them
        scan.publish(laser_scan([5.0] * 360))
        correction.publish(Float32(data=10.0))
        return _state(states).get("LineDetector") == "line_found" and _state(states).get("Lidar.safety") == "safe"

    assert ros2.spin_until(data, 10)
    stop.publish(Empty())
    assert ros2.spin_until(lambda: _state(states).get("EmergencyStop") == "stopped", 5)

    def twist(x: float, z: float) -> Any:
        message = Twist()
        message.linear.x, message.angular.z = x, z
        return message

    hostile = [twist(5.0, 0.0), twist(float("nan"), 0.0), twist(-2.0, 3.0), twist(0.15, float("inf"))]
    for message in hostile:
        controller.publish(message)
    assert ros2.spin_until(lambda: len(blocked) >= len(hostile), 5), f"reported: {len(blocked)}"
    reports = [json.loads(b.data) for b in blocked]
    assert all(r["event"] is None for r in reports)
    assert {r["reason"] for r in reports} == {"is the data of no event on it now", "a number in it is not finite"}
    controller.publish(twist(0.15, -0.1))  # move: not while stopped
    assert ros2.spin_until(lambda: len(blocked) > len(hostile), 5)
    assert json.loads(blocked[-1].data)["event"] == "move"
    assert robot == []
    controller.publish(twist(0.0, 0.0))  # halt: allowed
    assert ros2.spin_until(lambda: bool(robot), 5), "halt was not forwarded"
    assert (robot[0].linear.x, robot[0].angular.z) == (0.0, 0.0)
    ros2.spin(0.3)
    assert len(robot) == 1
    assert node.poll() is None


def test_two_robots_in_namespaces_on_one_graph(ros2: Ros2, tmp_path: Path) -> None:
    """One package generated with relative names, two instances (__ns /robot1, /robot2),
    two fake robots: each controller commands only its own robot."""
    from geometry_msgs.msg import Twist
    from rclpy.qos import qos_profile_sensor_data
    from sensor_msgs.msg import LaserScan
    from std_msgs.msg import Int16, String

    from robosc.codegen.ros import generate

    result = synthesize_model(load_model(ROOT / "examples/maze_solver.rscd"))
    package = tmp_path / "maze"
    generate(plan_supervisor(result), 2, "controller", package, relative=True)
    nodes, lefts, moves, scans, states = [], {}, {}, {}, {}
    for robot in ("robot1", "robot2"):
        ros2.reports({"Platform": "ready"}, f"/{robot}")  # each robot's driver reports where it is
        nodes.append(ros2.start(package, "-r", f"__ns:=/{robot}", rate=20.0, publish_state=True))
        lefts[robot] = ros2.record(Int16, f"/{robot}/rotate_left")
        moves[robot] = ros2.record(Twist, f"/{robot}/cmd_vel")
        states[robot] = ros2.record(String, f"/{robot}/state")
        # a LiDAR driver publishes with the sensor-data profile (best effort)
        scans[robot] = ros2.node.create_publisher(LaserScan, f"/{robot}/scan", qos_profile_sensor_data)
    for robot in scans:
        ros2.wait_subscribed(scans[robot])

    def clear() -> bool:  # best effort: until each node has a scan
        for robot in scans:
            scans[robot].publish(laser_scan([5.0] * 360))
        return all(moves[r] for r in moves)

    assert ros2.spin_until(clear, 10), "a robot got no movement"

    def wall_for_robot1() -> bool:
        scans["robot1"].publish(laser_scan([0.3] + [5.0] * 359))
        scans["robot2"].publish(laser_scan([5.0] * 360))
        return bool(lefts["robot1"])

    assert ros2.spin_until(wall_for_robot1, 10), "robot1 did not turn at its wall"
    ros2.spin(0.5)
    assert lefts["robot2"] == []  # robot2 sees no wall: it never turns
    assert _state(states["robot1"])["Platform"] == "turning"
    assert _state(states["robot2"])["Platform"] == "ready"
    assert ros2.node.count_publishers("/cmd_vel") == 0  # nothing left in the global namespace
    assert all(n.poll() is None for n in nodes)
    # each wrote its Fast DDS profile (its /cmd_vel with Fast DDS's own heartbeat, by its resolved
    # name), Fast DDS read it without an error, and it is gone
    left = [f for f in Path("/dev/shm").glob("robosc-fastdds-*.xml") if "/robot1/cmd_vel" in f.read_text()]
    assert left == [], "a node left its profile behind"
    logs = "".join(log.read_text(errors="replace") for _, log in ros2.processes.running)
    assert not re.search(r"XML\w* Error", logs), "Fast DDS could not read the profile"


def test_bad_parameters_are_refused_without_a_traceback(ros2: Ros2, tmp_path: Path) -> None:
    from std_msgs.msg import String

    package = build_package("examples/maze_solver.rscd", 2, "controller", tmp_path)
    ros2.reports(initial_states("examples/maze_solver.rscd"))  # the drivers report where they start
    node = ros2.start(
        package,
        rate=0.0,
        view_port=70000,
        qos_depth=-1,
        server_timeout=float("nan"),
        event_log=str(tmp_path / "no/such/dir/log.jsonl"),
        publish_state=True,
    )
    states = ros2.record(String, "/state")
    assert ros2.spin_until(lambda: bool(states), 10), "the node does not run"
    ros2.processes.stop()
    log = ros2.processes.output()
    assert "Traceback" not in log
    for name in ("rate", "view_port", "qos_depth", "server_timeout", "event_log"):
        assert f"parameter refused: {name}" in log, name
    assert node.poll() is not None


def test_a_goal_while_the_server_is_absent_never_hangs_the_node(ros2: Ros2, tmp_path: Path) -> None:
    """No action or service server: after server_timeout the call fails (error event), the
    node keeps its cycle, and says why in its log."""
    from geometry_msgs.msg import Pose
    from std_msgs.msg import String

    package = build_package("examples/pick_and_light.rscd", 2, "controller", tmp_path)
    ros2.reports(initial_states("examples/pick_and_light.rscd"))  # the drivers report where they start
    node = ros2.start(package, rate=20.0, publish_state=True, server_timeout=1.0)
    states = ros2.record(String, "/state")
    seen = ros2.node.create_publisher(Pose, "/camera/object", 10)
    ros2.wait_subscribed(seen)
    seen.publish(Pose())
    assert ros2.spin_until(
        lambda: json.loads(states[-1].data)["communications"]["pick"] == "executing" if states else False, 5
    )
    started = time.monotonic()
    # the pick fails once the timeout passes; the supervisor resets and starts it again
    assert ros2.spin_until(lambda: "action /arm/pick: no server after 1.0 s" in ros2.processes.output(), 5)
    assert 0.8 < time.monotonic() - started < 3.0
    count = len(states)
    ros2.spin(1.0)
    assert len(states) - count >= 10, "the cycle stopped"  # 20 Hz
    assert "not available; waiting up to 1.0 s" in ros2.processes.output()
    assert node.poll() is None
