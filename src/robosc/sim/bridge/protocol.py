"""The lines between the simulation (robosc) and the simulator's ROS node, one JSON object
each, ``op`` saying what it is.

simulation -> node:
  {"op": "setup", "robots": ["robot1", ...], "topics": {role: name}, "roles": [role, ...],
   "scan": {LaserScan fields but ranges}}
  {"op": "clock", "t": seconds}
  {"op": "publish", "robot": i, "role": role, "value": ...}   (scan: ranges; line_correction: a number)
  {"op": "quit"}
  a fleet's world (the coordinator's topics, every message std_msgs/Empty):
  {"op": "setup", "robots": [], "topics": {}, "roles": [], "scan": {},
   "fleet": {"commands": [[name, topic, kind], ...], "answers": [[name, topic, kind], ...]}}
   (kind "none": std_msgs/Empty; "string": std_msgs/String; "poses": [[name, topic], ...], each a
   geometry_msgs/Pose2D topic: a robot's pose, where its move ends, the person's position;
   "reports": {component: {"service": name, "at": location, "moves": {name: [[from, to], ...]}}}:
   the std_srvs/Trigger service each driver offers to say where its component is, which it
   knows from the commands it obeyed and the answers it gave, moved as the model moves it;
   "tasks": {"give": topic, "queue": topic}: the simulator's node gives the coordinator its
   tasks (std_msgs/String) and reads the queue it publishes)
  {"op": "answer", "name": name, "data": text or null}   (an answer: publish it on its topic)
  {"op": "poses", "poses": {name: [x, y, theta], ...}}   (x NaN: none, e.g. no move under way)
  {"op": "task", "text": text}          (give the coordinator a task: std_msgs/String on fleet.tasks.give)
node -> simulation:
  {"op": "ready"}
  {"op": "peers", "robots": [connected roles of robot 0, ...]}
  {"op": "command", "robot": i, "role": "cmd_vel", "value": {"linear": {"x": x}, "angular": {"z": z}}}
  {"op": "command", "robot": i, "role": "rotate_left" | "rotate_right", "value": degrees}
  {"op": "refused", "robot": i}        (the controller reported a refused command on 'blocked')
  {"op": "press", "robot": i, "pressed": true | false}   (the emergency stop button service)
  a fleet's world:
  {"op": "order", "name": name}         (the coordinator sent a command: bot1.go, open_door)
  {"op": "queue", "text": json}         (the coordinator's task queue, as it published it)
  {"op": "peers", "robots": [[topics with the coordinator on the other end]]}
"""

import json
import math
import os
import sys
import threading
from typing import Any, Callable, Dict, List, Tuple

# the roles whose topics the node publishes; the others it subscribes to
PUBLISHED = ("scan", "rotate_done", "line_correction", "line_lost", "stop", "continue")
SUBSCRIBED = ("cmd_vel", "rotate_left", "rotate_right")
BUTTON = "emergency_stop_button"  # the service (std_srvs/SetBool) that presses the button


def node_name() -> str:
    """The node's name: ROBOSC_SIM_NODE, or robosc_sim (a fleet's world starts one per robot's
    driver beside the simulator's)."""
    return os.environ.get("ROBOSC_SIM_NODE") or "robosc_sim"


def topic(robot: str, name: str) -> str:
    """A world topic name inside a robot's namespace: ("robot1", "/scan") -> "/robot1/scan"."""
    return "/%s/%s" % (robot, name.lstrip("/"))


def sec_nanosec(t: float) -> Tuple[int, int]:
    """Seconds as a ROS 2 time's (sec, nanosec)."""
    nanoseconds = int(round(t * 1e9))
    return nanoseconds // 1000000000, nanoseconds % 1000000000


def finite(value: Any) -> float:
    """A number from a message; NaN for anything else (the simulation then stops the robot)."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        return math.nan
    return number


class Channel(object):
    """Lines in from standard input (on a thread of their own), lines out on standard output."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        # the lines go to the real standard output; whatever else prints goes to the log
        self._out = sys.stdout
        sys.stdout = sys.stderr

    def send(self, op: str, **fields: Any) -> None:
        fields["op"] = op
        line = json.dumps(fields, allow_nan=True)
        with self._lock:
            self._out.write(line + "\n")
            self._out.flush()

    def on_twist(self, i: int) -> Callable[[Any], None]:
        """The callback of robot ``i``'s velocity command topic (geometry_msgs/Twist)."""
        return lambda m: self.send("command", robot=i, role="cmd_vel", value=twist_value(m.linear.x, m.angular.z))

    def on_number(self, i: int, role: str) -> Callable[[Any], None]:
        """The callback of robot ``i``'s ``role`` topic (a number: degrees to rotate)."""
        return lambda m: self.send("command", robot=i, role=role, value=finite(m.data))

    def on_refused(self, i: int) -> Callable[[Any], None]:
        """The callback of robot ``i``'s controller's ``blocked`` topic."""
        return lambda m: self.send("refused", robot=i)

    def serve(self, handle: Callable[[Dict[str, Any]], None], stop: Callable[[], None]) -> threading.Thread:
        def read() -> None:
            for line in sys.stdin:
                try:
                    message = json.loads(line)
                except ValueError:
                    continue
                if message.get("op") == "quit":
                    break
                handle(message)
            stop()

        thread = threading.Thread(target=read, name="simulation", daemon=True)
        thread.start()
        return thread


def twist_value(linear_x: Any, angular_z: Any) -> Dict[str, Dict[str, float]]:
    return {"linear": {"x": finite(linear_x)}, "angular": {"z": finite(angular_z)}}


def peer_counts(robots: List[str], connected: Callable[[int, str], bool], roles: List[str]) -> List[List[str]]:
    return [[role for role in roles if connected(i, role)] for i in range(len(robots))]


class Setup(object):
    """The first line: the robots' names, the world's topics by role, the roles the model
    uses, and the LaserScan's fields but its ranges."""

    def __init__(self, message: Dict[str, Any]) -> None:
        self.robots = [str(r) for r in message["robots"]]  # type: List[str]
        self.topics = dict(message["topics"])  # type: Dict[str, str]
        self.roles = [str(r) for r in message["roles"]]  # type: List[str]
        self.scan = dict(message["scan"])  # type: Dict[str, Any]
        fleet = message.get("fleet") or {}
        self.commands = [(str(n), str(t), str(k)) for n, t, k in fleet.get("commands", [])]  # type: List[Tuple[str, str, str]]
        self.answers = [(str(n), str(t), str(k)) for n, t, k in fleet.get("answers", [])]  # type: List[Tuple[str, str, str]]
        self.poses = [(str(n), str(t)) for n, t in fleet.get("poses", [])]  # type: List[Tuple[str, str]]
        self.reports = dict(fleet.get("reports") or {})  # type: Dict[str, Dict[str, Any]]
        # the operator's side of the coordinator's tasks: {"give": topic, "queue": topic} or {}
        self.tasks = dict(fleet.get("tasks") or {})  # type: Dict[str, str]
        self.fleet = "fleet" in message


def read_setup() -> Setup:
    """The setup line from the simulation; the node ends without one."""
    line = sys.stdin.readline()
    message = json.loads(line) if line.strip() else None
    if not isinstance(message, dict) or message.get("op") != "setup":
        sys.exit("robosc sim bridge: no setup line")
    return Setup(message)


def published_kinds() -> Dict[str, Any]:
    """The message type of each role the node publishes (the same in ROS 1 and ROS 2)."""
    from sensor_msgs.msg import LaserScan
    from std_msgs.msg import Empty, Float32

    kinds = {"scan": LaserScan, "rotate_done": Empty, "line_correction": Float32, "line_lost": Empty}
    kinds.update({"stop": Empty, "continue": Empty})
    return kinds


def message_for(kinds: Dict[str, Any], setup: Setup, message: Dict[str, Any], stamp: Callable[[Any], None]) -> Any:
    """The ROS message of a ``publish`` line; ``stamp(header)`` sets a scan's time."""
    role = message["role"]
    out = kinds[role]()
    if role == "scan":
        stamp(out.header)
        out.header.frame_id = "%s/base_scan" % setup.robots[int(message["robot"])]
        for key, value in setup.scan.items():
            setattr(out, key, float(value))
        out.ranges = [float(r) for r in message["value"]]
    elif role == "line_correction":
        out.data = float(message["value"])
    return out


class Wiring(object):
    """Each robot's publishers and subscriptions, made by the middleware's functions:
    ``publisher(name, kind)``, ``subscriber(name, kind, callback)`` and ``button(name,
    press)``, where ``press(pressed)`` is what the button service does."""

    def __init__(
        self,
        setup: Setup,
        channel: Channel,
        publisher: Callable[[str, Any], Any],
        subscriber: Callable[[str, Any, Callable[[Any], None]], Any],
        button: Callable[[str, Callable[[bool], None]], Any],
    ) -> None:
        from geometry_msgs.msg import Twist
        from std_msgs.msg import Int16, String

        self.setup = setup
        self.kinds = published_kinds()
        self.publishers = []  # type: List[Dict[str, Any]]
        self.subscriptions = []  # type: List[Dict[str, Any]]
        self.keep = []  # type: List[Any]
        for i, robot in enumerate(setup.robots):
            names = dict((role, topic(robot, setup.topics[role])) for role in setup.roles)
            self.publishers.append(
                dict((role, publisher(names[role], self.kinds[role])) for role in setup.roles if role in PUBLISHED)
            )
            subs = {}  # type: Dict[str, Any]
            for role in setup.roles:
                if role == "cmd_vel":
                    subs[role] = subscriber(names[role], Twist, channel.on_twist(i))
                elif role in SUBSCRIBED:
                    subs[role] = subscriber(names[role], Int16, channel.on_number(i, role))
            self.subscriptions.append(subs)
            self.keep.append(subscriber(topic(robot, "blocked"), String, channel.on_refused(i)))
            self.keep.append(button(topic(robot, BUTTON), self._press(channel, i)))

    @staticmethod
    def _press(channel: Channel, i: int) -> Callable[[bool], None]:
        return lambda pressed: channel.send("press", robot=i, pressed=pressed)

    def handler(self, clock: Callable[[float], None], stamp: Callable[[Any, float], None]) -> Callable[[Dict[str, Any]], None]:
        """What the node does with a line: ``clock(t)`` publishes /clock, ``stamp(header, t)``
        sets a header's time."""
        now = [0.0]

        def handle(message: Dict[str, Any]) -> None:
            op = message.get("op")
            if op == "clock":
                now[0] = float(message["t"])
                clock(now[0])
            elif op == "publish":
                publisher = self.publishers[int(message["robot"])].get(message["role"])
                if publisher is not None:
                    publisher.publish(message_for(self.kinds, self.setup, message, lambda h: stamp(h, now[0])))

        return handle

    def peers(self, publisher_count: Callable[[Any], int], subscriber_count: Callable[[Any], int]) -> List[List[str]]:
        """For each robot, the roles whose topic has the controller on the other end."""

        def connected(i: int, role: str) -> bool:
            if role in self.publishers[i]:
                return publisher_count(self.publishers[i][role]) > 0
            return subscriber_count(self.subscriptions[i][role]) > 0

        return peer_counts(self.setup.robots, connected, self.setup.roles)


class Whereabouts(object):
    """Where each driver's component is, as the driver knows it: moved by each command it
    obeys and each answer it gives (before the answer goes out, so that a report asked for
    after the answer came has it). Thread-safe: commands come on the middleware's threads."""

    def __init__(self, reports: Dict[str, Dict[str, Any]]) -> None:
        self.lock = threading.Lock()
        self.at = dict((c, str(r["at"])) for c, r in reports.items())  # type: Dict[str, str]
        self.moves = {}  # type: Dict[str, List[Tuple[str, Any, str]]]
        for component, report in reports.items():
            for name, pairs in dict(report.get("moves") or {}).items():
                for source, target in pairs:
                    self.moves.setdefault(str(name), []).append((component, source, str(target)))

    def went(self, name: str) -> None:
        """The command or answer ``name`` went by: its component moves as the model says."""
        with self.lock:
            for component, source, target in self.moves.get(name, ()):
                if source is None or self.at.get(component) == source:
                    self.at[component] = target
                    break

    def where(self, component: str) -> str:
        with self.lock:
            return self.at[component]


class FleetWiring(object):
    """A fleet's world: the robots' drivers and the door, as the coordinator meets them under
    its namespace; a subscription per command and a publisher per answer (std_msgs/Empty), and
    the report service of each (``service(name, answer)``, ``answer()`` giving the location)."""

    def __init__(
        self,
        setup: Setup,
        channel: Channel,
        publisher: Callable[..., Any],
        subscriber: Callable[[str, Any, Callable[[Any], None]], Any],
        service: Callable[[str, Callable[[], str]], Any],
    ) -> None:
        from geometry_msgs.msg import Pose2D
        from std_msgs.msg import Empty, String

        self.whereabouts = Whereabouts(setup.reports)
        self.services = [
            service(str(report["service"]), self._where(component)) for component, report in setup.reports.items()
        ]
        self.kinds = {"none": Empty, "string": String}
        self.publishers = dict(
            (name, (topic, publisher(topic, self.kinds[kind]), kind)) for name, topic, kind in setup.answers
        )
        self.pose_kind = Pose2D
        self.poses = dict((name, publisher(topic, Pose2D)) for name, topic in setup.poses)
        self.subscriptions = dict(
            (name, (topic, subscriber(topic, self.kinds[kind], self._order(channel, name))))
            for name, topic, kind in setup.commands
        )
        self.give = None  # type: Any
        if setup.tasks:  # as an operator gives tasks and watches the queue
            self.give = (setup.tasks["give"], publisher(setup.tasks["give"], String, 1000))  # a burst of tasks: none lost
            self.subscriptions["queue"] = (setup.tasks["queue"], subscriber(setup.tasks["queue"], String, self._queue(channel)))

    @staticmethod
    def _queue(channel: Channel) -> Callable[[Any], None]:
        def queue(message: Any) -> None:
            channel.send("queue", text=str(message.data))

        return queue

    def _where(self, component: str) -> Callable[[], str]:
        return lambda: self.whereabouts.where(component)

    def _order(self, channel: Channel, name: str) -> Callable[[Any], None]:
        def order(message: Any) -> None:
            self.whereabouts.went(name)
            channel.send("order", name=name)

        return order

    def handler(self, clock: Callable[[float], None], stamp: Callable[[Any, float], None]) -> Callable[[Dict[str, Any]], None]:
        def handle(message: Dict[str, Any]) -> None:
            op = message.get("op")
            if op == "clock":
                clock(float(message["t"]))
            elif op == "answer":
                found = self.publishers.get(str(message.get("name")))
                if found is not None:
                    self.whereabouts.went(str(message.get("name")))
                    out = self.kinds[found[2]]()
                    if found[2] == "string":
                        out.data = str(message.get("data") or "")
                    found[1].publish(out)
            elif op == "task" and self.give is not None:
                from std_msgs.msg import String

                self.give[1].publish(String(data=str(message.get("text"))))
            elif op == "poses":
                for name, value in dict(message.get("poses") or {}).items():
                    pose = self.poses.get(str(name))
                    if pose is not None and isinstance(value, list) and len(value) == 3:
                        pose.publish(self.pose_kind(x=finite(value[0]), y=finite(value[1]), theta=finite(value[2])))

        return handle

    def peers(self, publisher_count: Callable[[Any], int], subscriber_count: Callable[[Any], int]) -> List[List[str]]:
        """The topics that have the coordinator on the other end (as one robot's list)."""
        connected = [topic for topic, p, _ in self.publishers.values() if publisher_count(p) > 0]
        if self.give is not None and publisher_count(self.give[1]) > 0:
            connected.append(self.give[0])
        connected += [topic for topic, s in self.subscriptions.values() if subscriber_count(s) > 0]
        return [connected]
