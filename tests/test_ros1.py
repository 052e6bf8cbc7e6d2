"""Generated ROS 1 nodes on a real rosmaster and rospy (Debian's packages, Debian's python3).

Each test starts a rosmaster on 127.0.0.1 on a free port, generates the package
of an example, runs its node under Debian's python3, and plays the robot in a
client script: it publishes sensor data and asserts on what the node publishes.
"""

from __future__ import annotations

import json
from pathlib import Path

from ros_support import ROOT, Ros1, build_package, initial_states, logged_events


def test_maze_solver_turns_left_at_a_wall_and_survives_malformed_scans(ros1: Ros1, tmp_path: Path) -> None:
    package = build_package("examples/maze_solver.rscd", 1, "controller", tmp_path)
    node = ros1.node(package, rate=20, seed=1, publish_state=True)
    result = ros1.client(
        """
start()
moves = Recorder("/cmd_vel", Twist)
lefts = Recorder("/rotate_left", Int16)
state = State()
scan_pub = publisher("/scan", LaserScan)
done_pub = publisher("/rotate_done", Empty)
rospy.sleep(0.5)
before_scan = len(moves.messages()) + len(lefts.messages())
scan_pub.publish(scan([5.0] * 360))
assert wait_for(lambda: len(moves.messages()) >= 3), "no movement commands"
speed = moves.messages()[-1].linear.x
# malformed data: an empty array, NaN, a short array: not delivered, the state is kept
for bad in ([], [float("nan")] * 360, [5.0]):
    scan_pub.publish(scan(bad))
    rospy.sleep(0.2)
alive_moves = len(moves.messages())
assert not lefts.messages(), "turned on malformed data"
# a wall right in front
scan_pub.publish(scan([0.3] + [5.0] * 359))
assert wait_for(lambda: lefts.messages(), 5), "no turn at a wall"
assert wait_for(lambda: state.value("Platform") == "turning", 5)
rospy.sleep(0.3)
moves.clear()
rospy.sleep(0.5)
moving_while_turning = len(moves.messages())
# the turn is done and the way is free again
scan_pub.publish(scan([5.0] * 360))
done_pub.publish(Empty())
assert wait_for(lambda: state.value("Platform") == "ready", 5)
assert wait_for(lambda: len(moves.messages()) > 0, 5)
done({"speed": speed, "turn": lefts.messages()[0].data, "alive_moves": alive_moves, "before_scan": before_scan,
      "moving_while_turning": moving_while_turning, "front": state.value("Distance.front")})
""",
        reports={"": initial_states("examples/maze_solver.rscd")},
    )
    assert result["before_scan"] == 0  # nothing is commanded before the first scan
    assert result["speed"] == 0.3
    assert result["turn"] == 90
    assert result["alive_moves"] >= 3
    assert result["moving_while_turning"] == 0  # movement needs Platform.ready
    assert result["front"] == "no_wall_front"
    assert node.poll() is None, "the node died"
    output = ros1.processes.output()
    assert "unreadable data" in output  # the malformed scans were logged


def test_line_follower_never_moves_while_stopped_or_unsafe(ros1: Ros1, tmp_path: Path) -> None:
    package = build_package("examples/line_follower.rscd", 1, "controller", tmp_path)
    event_log = tmp_path / "events.jsonl"
    node = ros1.node(package, rate=20, seed=2, publish_state=True, event_log=event_log)
    result = ros1.client(
        """
start()
cmd = Recorder("/cmd_vel", Twist)
state = State()
correction = publisher("/line/correction", Float32)
scan_pub = publisher("/scan", LaserScan)
stop = publisher("/emergency_stop/stop", Empty)
resume = publisher("/emergency_stop/continue", Empty)

def speeds(seconds):
    rospy.sleep(0.3)  # let commands already on the way arrive
    cmd.clear()
    rospy.sleep(seconds)
    return [m.linear.x for m in cmd.messages()]

report = {}
scan_pub.publish(scan([5.0] * 360))
report["start"] = speeds(0.5)  # held: no correction yet
correction.publish(Float32(data=10.0))
assert wait_for(lambda: state.value("Lidar.safety") == "safe" and state.value("LineDetector") == "line_found")
assert wait_for(lambda: state.last()["health"]["coordinator"]["commanding"])  # (2 s of listening for another)
report["driving"] = speeds(0.5)
report["steer"] = cmd.messages()[-1].angular.z
stop.publish(Empty())
assert wait_for(lambda: state.value("EmergencyStop") == "stopped")
report["stopped"] = speeds(0.5)
resume.publish(Empty())
assert wait_for(lambda: state.value("EmergencyStop") == "in_service")
report["resumed"] = speeds(0.5)
scan_pub.publish(scan([0.2] + [5.0] * 359))
assert wait_for(lambda: state.value("Lidar.safety") == "unsafe")
report["unsafe"] = speeds(0.5)
done(report)
""",
        reports={"": initial_states("examples/line_follower.rscd")},
    )
    assert result["start"] == []
    assert 0.15 in result["driving"]
    assert abs(result["steer"] - (-0.1)) < 1e-9
    assert result["stopped"] and set(result["stopped"]) == {0.0}, "moved while the emergency stop was active"
    assert 0.15 in result["resumed"]
    assert result["unsafe"] and set(result["unsafe"]) == {0.0}, "moved while unsafe"
    assert node.poll() is None
    events = logged_events(event_log)
    names = [e["event"] for e in events]
    assert "stop" in names and "move" in names and "halt" in names
    stop_at = names.index("stop")
    assert events[stop_at]["state"]["automata"]["EmergencyStop"] == "stopped"
    assert events[stop_at]["controllable"] is False


SERVERS = """
import actionlib
from actionlib.msg import TestAction, TestFeedback, TestResult
from std_srvs.srv import SetBool, SetBoolResponse
start()
state = State()
calls, goals, cancelled = [], [], []
FED = None  # a test that waits for the controller to get the feedback sets a threading.Event

def light(request):
    calls.append(request.data)
    if MODE == "never":
        rospy.sleep(3600)
    if MODE == "fail" and len(calls) == 1:
        raise rospy.ServiceException("the bulb is broken")
    return SetBoolResponse(success=True, message="ok")

rospy.Service("/light/set", SetBool, light)

def work(goal):
    goals.append(goal.goal)
    server.publish_feedback(TestFeedback(feedback=3))
    if MODE == "long":
        while not server.is_preempt_requested():
            rospy.sleep(0.01)
        cancelled.append(goal.goal)
        server.set_preempted()
        return
    # the result only once the controller has the feedback: actionlib's feedback and result
    # come on two topics, in either order under load
    if FED is not None:
        FED.wait(10)
    else:  # the controller's state says it has it
        wait_for(lambda: state.value("Arm.progress") == 3, 10)
    server.set_succeeded(TestResult(result=42))

server = actionlib.SimpleActionServer("/arm/work", TestAction, execute_cb=work, auto_start=False)
server.start()
"""


def test_service_and_action_against_real_servers(ros1: Ros1, tmp_path: Path) -> None:
    package = build_package("tests/models/calls_ros1.rscd", 1, "controller", tmp_path)
    node = ros1.node(package, rate=20, seed=3, publish_state=True)
    result = ros1.client(
        'MODE = "fail"\n'
        + SERVERS
        + """
assert wait_for(lambda: len(goals) >= 1, 20), "no goal reached the action server"
assert wait_for(lambda: state.value("Arm.result") == 42, 10)
done({"calls": calls, "goals": goals[:2], "light": state.value("Light"), "progress": state.value("Arm.progress")})
""",
        reports={"": initial_states("tests/models/calls_ros1.rscd")},
    )
    assert result["calls"][:2] == [True, True]  # the first call failed (error event), the light was tried again
    assert result["light"] == "lit"
    assert result["goals"][0] == 7
    assert result["progress"] == 3  # from the action's feedback
    assert node.poll() is None


def test_action_cancelled_when_its_requirement_stops_holding(ros1: Ros1, tmp_path: Path) -> None:
    package = build_package("tests/models/calls_ros1.rscd", 1, "controller", tmp_path)
    ros1.node(package, rate=20, seed=4, publish_state=True)
    result = ros1.client(
        'MODE = "long"\n'
        + SERVERS
        + """
switch = publisher("/switch/off", Empty)
assert wait_for(lambda: len(goals) >= 1 and state.value("Arm") == "working", 20)
switch.publish(Empty())
assert wait_for(lambda: cancelled, 10), "the goal was not cancelled"
assert wait_for(lambda: state.value("Arm") == "idle", 5)
rospy.sleep(0.5)
done({"goals": len(goals), "arm": state.value("Arm"), "switch": state.value("Switch")})
""",
        reports={"": initial_states("tests/models/calls_ros1.rscd")},
    )
    assert result["goals"] == 1  # not started again: the switch is open
    assert result["arm"] == "idle"
    assert result["switch"] == "open"


def test_a_service_that_never_answers_does_not_stop_the_node(ros1: Ros1, tmp_path: Path) -> None:
    package = build_package("tests/models/calls_ros1.rscd", 1, "controller", tmp_path)
    node = ros1.node(package, rate=20, seed=5, publish_state=True)
    result = ros1.client(
        'MODE = "never"\n'
        + SERVERS
        + """
assert wait_for(lambda: calls, 20)
rospy.sleep(0.5)
before = len(state.messages())
rospy.sleep(1.0)
done({"states": len(state.messages()) - before, "light": state.value("Light")})
""",
        reports={"": initial_states("tests/models/calls_ros1.rscd")},
    )
    assert result["states"] >= 10  # the cycle goes on at 20 Hz
    assert result["light"] == "turning_on"
    assert node.poll() is None


def test_a_goal_while_the_server_is_absent_never_hangs_the_node(ros1: Ros1, tmp_path: Path) -> None:
    """The light's service is there, the arm's action server is not: after server_timeout
    the goal fails (the error event), the cycle never stops, and the log says why."""
    package = build_package("tests/models/calls_ros1.rscd", 1, "controller", tmp_path)
    node = ros1.node(package, rate=20, seed=5, publish_state=True, server_timeout=1.0)
    result = ros1.client(
        """
from std_srvs.srv import SetBool, SetBoolResponse
start()
state = State()
rospy.Service("/light/set", SetBool, lambda request: SetBoolResponse(success=True, message="ok"))
assert wait_for(lambda: state.value("Arm") == "working", 20), "the goal was not sent"
started = time.time()
assert wait_for(lambda: state.value("Arm") == "idle", 5), "the goal never failed"
failed_after = time.time() - started
before = len(state.messages())
rospy.sleep(1.0)
done({"failed_after": failed_after, "states": len(state.messages()) - before})
""",
        reports={"": initial_states("tests/models/calls_ros1.rscd")},
    )
    assert 0.5 < result["failed_after"] < 3.0
    assert result["states"] >= 10  # the cycle goes on at 20 Hz
    log = ros1.processes.output()
    assert "action /arm/work: no server after 1.0 s; failed" in log
    assert node.poll() is None


def test_supervision_layer_forwards_allowed_and_blocks_forbidden_commands(ros1: Ros1, tmp_path: Path) -> None:
    package = build_package("examples/maze_solver.rscd", 1, "supervisor", tmp_path)
    node = ros1.node(package, rate=20, publish_state=True)
    result = ros1.client(
        """
start()
robot_moves = Recorder("/cmd_vel", Twist)
robot_lefts = Recorder("/rotate_left", Int16)
blocked = Recorder("/blocked", String)
seen_by_controller = Recorder("/robosc/controller/scan", LaserScan)
state = State()
controller_move = publisher("/robosc/controller/cmd_vel", Twist)
controller_left = publisher("/robosc/controller/rotate_left", Int16)
scan_pub = publisher("/scan", LaserScan)
forward = Twist()
forward.linear.x = 0.3
report = {}
controller_move.publish(forward)  # before any scan: held
assert wait_for(lambda: blocked.messages(), 5), "a command before the first scan was not reported"
report["held"] = json.loads(blocked.messages()[-1].data)["reason"]
blocked.clear()
scan_pub.publish(scan([5.0] * 360))
assert wait_for(lambda: state.value("Distance.front") == "no_wall_front", 5)
assert wait_for(lambda: state.last()["health"]["held"] is False, 5), state.last()  # (no_wall_front is also the start)
assert wait_for(lambda: not state.last()["health"]["unconfirmed"], 10), state.last()  # the platform's driver said where it is
controller_move.publish(forward)  # the way is free: allowed
assert wait_for(lambda: robot_moves.messages(), 5), "an allowed command was not forwarded"
controller_left.publish(Int16(data=90))  # no wall in front: turning left is not allowed
assert wait_for(lambda: blocked.messages(), 5), "a forbidden command was not reported"
report["blocked_left"] = json.loads(blocked.messages()[-1].data)["event"]
scan_pub.publish(scan([0.3] + [5.0] * 359))  # a wall ahead
assert wait_for(lambda: seen_by_controller.messages(), 5), "robot data not passed to the controller"
assert wait_for(lambda: state.value("Distance.front") == "wall_front", 5)
moves_before = len(robot_moves.messages())
controller_move.publish(forward)  # into the wall: blocked
assert wait_for(lambda: len(blocked.messages()) >= 2, 5)
report["blocked_move"] = json.loads(blocked.messages()[-1].data)["event"]
controller_left.publish(Int16(data=90))  # now turning left is allowed
assert wait_for(lambda: robot_lefts.messages(), 5)
rospy.sleep(0.3)
report["moves_into_wall"] = len(robot_moves.messages()) - moves_before
report["left"] = robot_lefts.messages()[0].data
report["platform"] = state.value("Platform")
done(report)
""",
        reports={"": initial_states("examples/maze_solver.rscd")},
    )
    assert result["held"].startswith("held: waiting for the first readable data on")
    assert result["blocked_left"] == "turn_left"
    assert result["blocked_move"] == "movement"
    assert result["moves_into_wall"] == 0
    assert result["left"] == 90
    assert result["platform"] == "turning"
    assert node.poll() is None


def test_supervision_layer_forwards_services_and_actions(ros1: Ros1, tmp_path: Path) -> None:
    package = build_package("tests/models/calls_ros1.rscd", 1, "supervisor", tmp_path)
    node = ros1.node(package, rate=20, publish_state=True)
    result = ros1.client(
        'MODE = "ok"\n'
        + SERVERS
        + """
from actionlib.msg import TestGoal
from actionlib_msgs.msg import GoalStatus
blocked = Recorder("/blocked", String)
controller_light = rospy.ServiceProxy("/robosc/controller/light/set", SetBool)
controller_arm = actionlib.SimpleActionClient("/robosc/controller/arm/work", TestAction)
rospy.wait_for_service("/robosc/controller/light/set", 10)
assert controller_arm.wait_for_server(rospy.Duration(10))
assert wait_for(lambda: ((state.last() or {}).get("health") or {}).get("unconfirmed") == {}, 10)  # reported
report = {}
# the light is dark: work needs Light.lit, so the goal is blocked
controller_arm.send_goal(TestGoal(goal=7))
controller_arm.wait_for_result(rospy.Duration(5))
report["first_goal"] = controller_arm.get_state()
assert wait_for(lambda: blocked.messages(), 5)
report["blocked"] = json.loads(blocked.messages()[-1].data)["event"]
report["goals_before"] = list(goals)
# switching the light on is allowed: forwarded to the real service
answer = controller_light(True)
report["light_answer"] = answer.success
assert wait_for(lambda: state.value("Light") == "lit", 5)
controller_arm.send_goal(TestGoal(goal=6))  # not the goal the model provides (7): blocked
controller_arm.wait_for_result(rospy.Duration(5))
report["other_goal"] = controller_arm.get_state()
feedback = []
FED = threading.Event()
controller_arm.send_goal(TestGoal(goal=7), feedback_cb=lambda f: (feedback.append(f.feedback), FED.set()))
controller_arm.wait_for_result(rospy.Duration(10))
report["second_goal"] = controller_arm.get_state()
report["result"] = controller_arm.get_result().result
report["feedback"] = feedback
report["goals"] = list(goals)
assert wait_for(lambda: state.value("Arm.result") == 42, 5)
report["arm"] = state.value("Arm")
done(report)
""",
        reports={"": initial_states("tests/models/calls_ros1.rscd")},
    )
    assert result["first_goal"] == 4  # GoalStatus.ABORTED: blocked by the supervisor
    assert result["blocked"] == "work.c_trigger"
    assert result["goals_before"] == []
    assert result["light_answer"] is True
    assert result["second_goal"] == 3  # GoalStatus.SUCCEEDED
    assert result["result"] == 42
    assert result["feedback"] == [3]
    assert result["other_goal"] == 4  # ABORTED: only the goal whose data the model provides goes through
    assert result["goals"] == [7]
    assert result["arm"] == "idle"
    assert node.poll() is None


def test_node_serves_the_live_view(ros1: Ros1, tmp_path: Path) -> None:
    import urllib.request

    from ros_support import free_port, wait_until

    package = build_package("examples/maze_solver.rscd", 1, "controller", tmp_path, live=True)
    port = free_port()
    node = ros1.node(package, rate=20, view_port=port)

    def state() -> dict[str, object] | None:
        try:
            with urllib.request.urlopen(f"http://127.0.0.1:{port}/state", timeout=1) as response:
                return json.loads(response.read()) or None
        except OSError:
            return None

    assert wait_until(lambda: state() is not None, 20), ros1.processes.output()
    with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=2) as response:
        assert 'id="Platform::ready"' in response.read().decode()
    # the robot listens while the page is read: once it is gone, the command it was sent is
    # unconfirmed (its topic lost its subscriber), and the page's last record says so
    last = ros1.client(
        """
import urllib.request
start()
lefts = Recorder("/rotate_left", Int16)  # the robot listens: the node sends it commands
scan_pub = publisher("/scan", LaserScan)
scan_pub.publish(scan([0.3] + [5.0] * 359))
assert wait_for(lambda: lefts.messages(), 10), "no turn"

def page_state():
    with urllib.request.urlopen("http://127.0.0.1:PORT/state", timeout=1) as response:
        return json.loads(response.read()) or {}

assert wait_for(lambda: page_state().get("event") == "turn_left", 10)
done(page_state())
""".replace("PORT", str(port)),
        reports={"": initial_states("examples/maze_solver.rscd")},
    )
    assert last["event"] == "turn_left" and last["state"]["automata"]["Platform"] == "turning"
    assert wait_until(lambda: (state() or {}).get("event", "") is None, 10)  # a state record: the robot is gone
    assert (state() or {})["state"]["automata"]["Platform"] is None
    assert node.poll() is None


def test_supervision_layer_fails_closed_on_a_shared_topic(ros1: Ros1, tmp_path: Path) -> None:
    """The line follower's move and halt share /cmd_vel. With the emergency stop pressed, a
    controller's command that is neither (5.0, NaN, (-2, 3)) never reaches the robot; halt
    does; move does not."""
    package = build_package("examples/line_follower.rscd", 1, "supervisor", tmp_path)
    node = ros1.node(package, rate=20, publish_state=True)
    result = ros1.client(
        """
start()
robot = Recorder("/cmd_vel", Twist)
blocked = Recorder("/blocked", String)
state = State()
controller = publisher("/robosc/controller/cmd_vel", Twist)
stop = publisher("/emergency_stop/stop", Empty)
scan_pub = publisher("/scan", LaserScan)
correction = publisher("/line/correction", Float32)
scan_pub.publish(scan([5.0] * 360))
correction.publish(Float32(data=10.0))
stop.publish(Empty())
assert wait_for(lambda: state.value("EmergencyStop") == "stopped", 5)
assert wait_for(lambda: state.value("LineDetector") == "line_found", 5)

def twist(x, z):
    message = Twist()
    message.linear.x, message.angular.z = x, z
    return message

hostile = [twist(5.0, 0.0), twist(float("nan"), 0.0), twist(-2.0, 3.0), twist(0.15, float("inf"))]
for message in hostile:
    controller.publish(message)
    rospy.sleep(0.05)
assert wait_for(lambda: len(blocked.messages()) >= len(hostile), 5), len(blocked.messages())
controller.publish(twist(0.15, -0.1))  # move: not while stopped
assert wait_for(lambda: len(blocked.messages()) > len(hostile), 5)
reports = [json.loads(b.data) for b in blocked.messages()]
before_halt = len(robot.messages())
controller.publish(twist(0.0, 0.0))  # halt: allowed
assert wait_for(lambda: robot.messages(), 5), "halt was not forwarded"
rospy.sleep(0.3)
forwarded = robot.messages()
done({"events": [r["event"] for r in reports], "reasons": sorted({r["reason"] for r in reports}),
      "before_halt": before_halt, "forwarded": [[m.linear.x, m.angular.z] for m in forwarded]})
""",
        reports={"": initial_states("examples/line_follower.rscd")},
    )
    assert result["events"] == [None, None, None, None, "move"]
    assert result["reasons"] == [
        "a number in it is not finite",
        "is the data of no event on it now",
        "the supervisor does not allow it now",
    ]
    assert result["before_halt"] == 0
    assert result["forwarded"] == [[0.0, 0.0]]
    assert node.poll() is None


def test_two_robots_in_namespaces_on_one_rosmaster(ros1: Ros1, tmp_path: Path) -> None:
    """One package generated with relative names, two instances (__ns:=/robot1, /robot2),
    two fake robots: each controller commands only its own robot."""
    from robosc.api import load_model, plan_supervisor, synthesize_model
    from robosc.codegen.ros import generate

    result = synthesize_model(load_model(ROOT / "examples/maze_solver.rscd"))
    package = tmp_path / "maze"
    generate(plan_supervisor(result), 1, "controller", package, relative=True)
    nodes = [ros1.node(package, "__ns:=/" + robot, rate=20, publish_state=True) for robot in ("robot1", "robot2")]
    result = ros1.client(
        """
start()
lefts = {r: Recorder("/%s/rotate_left" % r, Int16) for r in ("robot1", "robot2")}
moves = {r: Recorder("/%s/cmd_vel" % r, Twist) for r in ("robot1", "robot2")}
states = {r: Recorder("/%s/state" % r, String) for r in ("robot1", "robot2")}
scans = {r: publisher("/%s/scan" % r, LaserScan) for r in ("robot1", "robot2")}
global_moves = Recorder("/cmd_vel", Twist)
for r in scans:
    scans[r].publish(scan([5.0] * 360))
assert wait_for(lambda: all(moves[r].messages() for r in moves), 10), "a robot got no movement"
scans["robot1"].publish(scan([0.3] + [5.0] * 359))
scans["robot2"].publish(scan([5.0] * 360))
assert wait_for(lambda: lefts["robot1"].messages(), 5), "robot1 did not turn at its wall"
rospy.sleep(0.5)
platform = {r: json.loads(states[r].messages()[-1].data)["automata"]["Platform"] for r in states}
done({"robot2_lefts": len(lefts["robot2"].messages()), "platform": platform,
      "global": len(global_moves.messages())})
""",
        reports={"/robot1": {"Platform": "ready"}, "/robot2": {"Platform": "ready"}},
    )
    assert result == {"robot2_lefts": 0, "platform": {"robot1": "turning", "robot2": "ready"}, "global": 0}
    assert all(n.poll() is None for n in nodes)


def test_an_action_servers_first_answers_are_kept_even_before_the_goal_is_sent(tmp_path: Path) -> None:
    """An action server may give feedback, and even the result, before actionlib's send_goal has
    returned (the server is quick, the node's thread is not: seen under load). actionlib's
    SimpleActionClient drops what comes in that window, which cost the supervisor an Arm's
    progress; the adapter's Goal passes each answer on. A client whose server answers inside
    send_goal makes the window certain here."""
    import subprocess

    from ros_support import ROS1_PYTHON, ros1_available, unavailable

    if not ros1_available():
        unavailable("ROS 1 (Debian's python3-rospy, python3-actionlib)")
    script = """
import sys
sys.path.insert(0, RUNTIME)
from actionlib import CommState
from onboard.ros1 import SUCCEEDED, Goal

class Handle:
    state = CommState.ACTIVE
    def get_comm_state(self): return self.state
    def get_goal_status(self): return SUCCEEDED
    def get_result(self): return 42

class QuickServer:
    def send_goal(self, goal, transition_cb, feedback_cb):
        handle = Handle()
        transition_cb(handle)  # active
        feedback_cb(handle, goal * 10)
        handle.state = CommState.DONE
        transition_cb(handle)
        transition_cb(handle)  # actionlib may call again in a terminal state: passed on once
        return handle

seen = []
goal = Goal(QuickServer(), 3, on_feedback=lambda f: seen.append(("feedback", f)),
            on_done=lambda status, result: seen.append(("done", status, result)))
print(seen, goal.finished.is_set(), goal.status, goal.result)
"""
    runtime = f"RUNTIME = {str(ROOT / 'src' / 'robosc' / 'runtime')!r}\n"
    done = subprocess.run([ROS1_PYTHON, "-c", runtime + script], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[('feedback', 30), ('done', 3, 42)] True 3 42"


def test_a_driver_whose_report_service_hangs_is_asked_again_and_its_robot_goes_on(ros1: Ros1, tmp_path: Path) -> None:
    """rospy's service calls have no time-out: the Platform's driver takes the first request and
    never answers it. The node gives it up after server_timeout, says so, asks again, and moves
    once the answer comes; before, the component stayed unconfirmed (nothing moved) for ever."""
    package = build_package("examples/maze_solver.rscd", 1, "controller", tmp_path)
    node = ros1.node(package, rate=20, seed=1, server_timeout=1.0)
    result = ros1.client(
        """
from std_srvs.srv import Trigger, TriggerResponse
start()
asked = []
def platform(request):
    asked.append(time.time())
    if len(asked) == 1:
        time.sleep(60)  # the first request is never answered in time
    return TriggerResponse(True, "ready")
rospy.Service("/robosc/report/Distance", Trigger, lambda request: TriggerResponse(True, "sensing"))
rospy.Service("/robosc/report/Platform", Trigger, platform)
moves = Recorder("/cmd_vel", Twist)
scan_pub = rospy.Publisher("/scan", LaserScan, queue_size=10)
assert wait_for(lambda: scan_pub.get_num_connections() > 0, 10)
def clear():
    scan_pub.publish(scan([5.0] * 360))
    return bool(moves.messages())
moved = wait_for(clear, 20)
done({"moved": moved, "asked": len(asked), "first_move_after": moves.items[0][0] - asked[0] if moved else None})
""",
        timeout=120,
    )
    assert result["moved"], result
    assert result["asked"] >= 2 and result["first_move_after"] >= 1.0, result  # the second request was answered
    assert node.poll() is None
    assert "Platform's driver has not answered its report request for" in ros1.processes.output()
