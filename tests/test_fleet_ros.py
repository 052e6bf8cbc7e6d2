"""The fleet's coordinator on real middleware: the warehouse example (three robots, a door, a
charger) built as one package, by colcon for ROS 2 and by catkin for ROS 1, started from its
install space in a namespace, and commanding each robot under that namespace while stand-ins
for the robots and the door answer. What the coordinator sent (as the robots received it,
checked against the node's own event log) is replayed through the warehouse's rules, written
here apart from the model: never two robots in an aisle cell or on the shelf, the door passed
only while open and closed only with its doorway empty, one robot charging at a time; and
every robot gets past the shelf (no deadlock)."""

from __future__ import annotations

import json
import os
import shutil
import time
from pathlib import Path
from typing import Any

from ros_support import Ros1, Ros2, initial_states, logged_events, unavailable
from test_build import COLCON, in_workspace, run
from warehouse_world import Rules

MODEL = "docs/models/warehouse_zero_time.rscd"
ROBOTS = ("bot1", "bot2", "bot3")
TASK = ("depot", "out1", "out2", "out3", "shelf", "back3", "back2", "back1")
CELLS = ({"out1", "back1"}, {"out2", "back2"}, {"out3", "back3"}, {"shelf"})
ANSWERS = {"open_door": "door_opened", "close_door": "door_closed"}  # the door's answer to each command
TRIPS = 6  # gos per robot: past the shelf, on the way back
BURST = 40  # tasks given at once (beyond any default queue depth)


def replay(events: list[str]) -> dict[str, int]:
    """Runs the events through the warehouse's rules (asserting them at every step); returns
    how many times each robot was told to go."""
    where = dict.fromkeys(ROBOTS, "depot")
    door = "closed"
    gos = dict.fromkeys(ROBOTS, 0)
    for step, event in enumerate(events):
        context = f"step {step} ({event}) of {events[max(0, step - 5) : step + 1]}"
        robot, _, action = event.rpartition(".")
        if action == "go":
            here = where[robot]
            if here in ("depot", "back1"):
                assert door == "open", f"through a door that is {door}: {context}"
            where[robot] = TASK[(TASK.index(here) + 1) % len(TASK)]
            gos[robot] += 1
        elif action == "dock":
            assert where[robot] == "depot", context
            where[robot] = "charging"
        elif action == "charged":
            assert where[robot] == "charging", context
            where[robot] = "depot"
        elif action == "open_door":
            assert door == "closed", context
            door = "opening"
        elif action == "door_opened":
            door = "open"
        elif action == "close_door":
            assert door == "open", context
            assert not any(where[r] in CELLS[0] for r in ROBOTS), f"door closed on a robot: {context}"
            door = "closing"
        elif action == "door_closed":
            door = "closed"
        else:
            raise AssertionError(f"unexpected event {event}")
        for cell in CELLS:
            inside = [r for r in ROBOTS if where[r] in cell]
            assert len(inside) <= 1, f"{inside} in {sorted(cell)}: {context}"
        assert sum(where[r] == "charging" for r in ROBOTS) <= 1, context
    return gos


def test_replay_catches_what_the_warehouse_forbids() -> None:
    """The checker itself: sound runs pass, each broken rule fails."""
    assert replay(["open_door", "door_opened", "bot1.go", "bot1.go", "bot2.go"]) == {"bot1": 2, "bot2": 1, "bot3": 0}
    for bad in (
        ["bot1.go"],  # the door is closed
        ["open_door", "door_opened", "bot1.go", "bot2.go"],  # two in the first cell
        ["open_door", "door_opened", "bot1.go", "close_door"],  # closed on a robot
        ["bot1.dock", "bot2.dock"],  # two charging
    ):
        try:
            replay(bad)
        except AssertionError:
            continue
        raise AssertionError(f"{bad} passed")


def logged(path: Path) -> list[str]:
    return [r["event"] for r in logged_events(path)]


def check_run(log: Path, received: dict[str, list[str]]) -> None:
    """The node's log obeys the rules and every robot got past the shelf; what each topic
    carried is what the log says the node sent on it, in order."""
    events = logged(log)
    gos = replay(events)
    assert all(n >= TRIPS for n in gos.values()), gos
    for name, got in received.items():
        sent = [e for e in events if e == name]
        assert got == sent[: len(got)] and len(sent) - len(got) <= 1, (name, len(got), len(sent))


def test_ros2_coordinator_built_by_colcon_commands_each_robot_in_its_namespace(ros2: Ros2, tmp_path: Path) -> None:
    from std_msgs.msg import Empty

    if not COLCON.exists():
        unavailable("colcon (pip install colcon-common-extensions)")
    workspace = tmp_path / "ws"
    in_workspace(MODEL, 2, workspace)
    env = {**os.environ, "PATH": f"{COLCON.parent}:{os.environ['PATH']}"}
    out = run([str(COLCON), "build", "--event-handlers", "console_cohesion-"], workspace, env)
    assert "1 package finished" in out
    shutil.rmtree(workspace / "src")
    node = workspace / "install/warehouse_robosc/lib/warehouse_robosc/warehouse_robosc_node"
    log = tmp_path / "events.jsonl"
    received: dict[str, list[str]] = {}
    publishers: dict[str, Any] = {}
    answers: list[tuple[float, str]] = []  # (when, event): the robots and the door answer after a while

    def listen(name: str, topic: str, answer: str | None) -> None:
        got = received.setdefault(name, [])

        def heard(_: Any) -> None:
            got.append(name)
            happened(name)
            if answer is not None:
                answers.append((time.monotonic() + 0.05, answer))

        ros2.node.create_subscription(Empty, topic, heard, 100)

    for robot in ROBOTS:
        listen(f"{robot}.go", f"/depot/{robot}/go", None)
        listen(f"{robot}.dock", f"/depot/{robot}/dock", f"{robot}.charged")
        publishers[f"{robot}.charged"] = ros2.node.create_publisher(Empty, f"/depot/{robot}/charged", 10)
    for command, answer in ANSWERS.items():
        listen(command, f"/depot/{command}", answer)
        publishers[answer] = ros2.node.create_publisher(Empty, f"/depot/{answer}", 10)
    # the operator: a task per robot on the coordinator's task topic, the queue read back
    from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
    from std_msgs.msg import String

    # (a writer keeps its last `depth` samples until they are delivered: a burst needs a deep one)
    give = ros2.node.create_publisher(
        String, "/depot/robosc/task", QoSProfile(depth=BURST + 10, reliability=ReliabilityPolicy.RELIABLE)
    )
    queues: list[dict[str, Any]] = []
    latched = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    ros2.node.create_subscription(String, "/depot/robosc/tasks", lambda m: queues.append(json.loads(m.data)), latched)
    start = (
        f". {workspace}/install/setup.bash && exec {node} --ros-args -r __ns:=/depot"
        f" -p rate:=40.0 -p seed:=3 -p event_log:={log}"
    )
    states = ros2.reports(initial_states(MODEL), "/depot")  # the robots and the door report where they are
    truth = Rules()

    def happened(event: str) -> None:  # a command the stand-ins got, or an answer they sent
        truth.apply(event)
        states.update((c, truth.report(c)) for c in states)

    ros2.processes.start("coordinator", ["/bin/bash", "-c", start], ros2.env)
    for publisher in [*publishers.values(), give]:
        ros2.wait_subscribed(publisher, 30)
    for _ in range(BURST):  # a burst of tasks no robot can do: each is in the queue, refused
        give.publish(String(data="nowhere"))
    for robot in ROBOTS:
        give.publish(String(data=f"{robot}: shelf depot"))

    def progress() -> bool:
        now = time.monotonic()
        for due in [a for a in answers if a[0] <= now]:
            answers.remove(due)
            happened(due[1])
            publishers[due[1]].publish(Empty())
        return bool(queues) and queues[-1]["counts"].get("done") == len(ROBOTS) and len(queues[-1]["tasks"]) > BURST

    assert ros2.spin_until(progress, 60), f"{ {k: len(v) for k, v in received.items()} }\n{queues[-1:]}\n{ros2.processes.output()}"
    ros2.processes.stop()
    check_run(log, received)
    assert [(t["robot"], t["by"], t["state"]) for t in queues[-1]["tasks"][BURST:]] == [(r, r, "done") for r in ROBOTS]
    assert queues[-1]["counts"]["failed"] == BURST  # none lost on the way
    assert not any(received[f"{r}.dock"] for r in ROBOTS)  # nobody asked for a charge: none sent


ROS1_ROBOTS = """
sys.path.insert(0, {tests!r})
from warehouse_world import Rules
start()
states = REPORTED["/depot"]  # the robots and the door report where they are
truth = Rules()
def happened(event):  # a command the stand-ins got, or an answer they sent
    truth.apply(event)
    states.update((c, truth.report(c)) for c in states)
robots = {robots!r}
answers = {answers!r}
received = {{}}
publishers = {{}}
pending = []
lock = threading.Lock()

def listen(name, topic, answer):
    received[name] = []
    def heard(_):
        with lock:
            received[name].append(name)
            happened(name)
            if answer is not None:
                pending.append((time.time() + 0.05, answer))
    rospy.Subscriber(topic, Empty, heard, queue_size=100)

for robot in robots:
    listen(robot + ".go", "/depot/%s/go" % robot, None)
    listen(robot + ".dock", "/depot/%s/dock" % robot, robot + ".charged")
    publishers[robot + ".charged"] = publisher("/depot/%s/charged" % robot, Empty, timeout=60)
for command, answer in answers.items():
    listen(command, "/depot/" + command, answer)
    publishers[answer] = publisher("/depot/" + answer, Empty, timeout=60)
queues = []
rospy.Subscriber("/depot/robosc/tasks", String, lambda m: queues.append(json.loads(m.data)), queue_size=100)
give = publisher("/depot/robosc/task", String, timeout=60, queue_size={burst} + 10)  # a burst: a deep queue
for _ in range({burst}):  # a burst of tasks no robot can do: each is in the queue, refused
    give.publish(String(data="nowhere"))
for robot in robots:  # the operator: a task per robot on the coordinator's task topic
    give.publish(String(data=robot + ": shelf depot"))

def progress():
    with lock:
        due = [p for p in pending if p[0] <= time.time()]
        for p in due:
            pending.remove(p)
            happened(p[1])
    for _, answer in due:
        publishers[answer].publish(Empty())
    return bool(queues) and queues[-1]["counts"].get("done") == len(robots)

assert wait_for(progress, 60), ({{k: len(v) for k, v in received.items()}}, queues[-1:])
assert [(t["robot"], t["by"], t["state"]) for t in queues[-1]["tasks"][{burst}:]] == [(r, r, "done") for r in robots]
assert queues[-1]["counts"]["failed"] == {burst}, queues[-1]["counts"]  # none lost on the way
time.sleep(0.5)
with lock:
    done(received)
"""


def test_ros1_coordinator_built_by_catkin_commands_each_robot_in_its_namespace(ros1: Ros1, tmp_path: Path) -> None:
    if not shutil.which("catkin_make", path="/usr/bin"):
        unavailable("catkin (Debian's catkin)")
    workspace = tmp_path / "ws"
    in_workspace(MODEL, 1, workspace)
    run(["catkin_make", "-C", str(workspace), "install"], workspace)
    installed = workspace / "install"
    shutil.rmtree(workspace / "src")
    shutil.rmtree(workspace / "devel")
    log = tmp_path / "events.jsonl"
    launch = (
        f". {installed}/setup.bash && exec roslaunch warehouse_robosc warehouse_robosc.launch"
        f" namespace:=/depot rate:=40.0 seed:=3 event_log:={log}"
    )
    ros1.processes.start("roslaunch", ["/bin/bash", "-c", launch], {**ros1.env, "PATH": "/usr/bin:/bin"})
    script = ROS1_ROBOTS.format(robots=list(ROBOTS), answers=ANSWERS, trips=TRIPS, burst=BURST, tests=str(Path(__file__).parent))
    received = ros1.client(script, timeout=150, reports={"/depot": initial_states(MODEL)})
    ros1.processes.stop()
    check_run(log, received)
