"""The warehouse's robots and door as a coordinator meets them, without middleware: what each
command does to them, the answers they send after a while (with faults: each answer twice,
a spurious answer), and what their drivers report when asked. The ROS 2 and ROS 1 fault tests
(test_faults_ros.py) put it on the wire; :func:`forbidden` then replays what the coordinator
sent, in the order it decided, with what the world answered, through the warehouse's rules
(written here apart from the model) and counts the commands the rules forbid in the robots'
real situation.

Plain Python 3.8+: Debian's python3 runs it in the ROS 1 client scripts."""

import json
import random
import threading
import time

ROBOTS = ("bot1", "bot2", "bot3")
TASK = ("depot", "out1", "out2", "out3", "shelf", "back3", "back2", "back1")
CELLS = ({"out1", "back1"}, {"out2", "back2"}, {"out3", "back3"}, {"shelf"})
COMMANDS = (*tuple(f"{r}.{c}" for r in ROBOTS for c in ("go", "dock")), "open_door", "close_door")
ANSWERS = (*tuple(f"{r}.charged" for r in ROBOTS), "door_opened", "door_closed")


def topic(event):
    """The ROS name of an event of the warehouse (relative to the coordinator's namespace)."""
    return event.replace(".", "/")


class Rules:
    """Where the robots and the door are, and what the warehouse forbids."""

    def __init__(self):
        self.where = dict((r, "depot") for r in ROBOTS)
        self.door = "closed"

    def report(self, component):
        return self.door if component == "Door" else self.where[component]

    def violations(self, event):
        """What ``event`` (a command) would break, here and now."""
        robot, _, action = event.rpartition(".")
        found = []
        if action == "go":
            here = self.where[robot]
            if here == "charging":
                found.append(f"{robot} told to go while charging")
            elif here in ("depot", "back1") and self.door != "open":
                found.append(f"{robot} through a door that is {self.door}")
            else:
                after = TASK[(TASK.index(here) + 1) % len(TASK)]
                for cell in CELLS:
                    if after in cell and any(self.where[r] in cell for r in ROBOTS if r != robot):
                        found.append(f"{robot} into an occupied cell {after}")
        elif action == "dock":
            if self.where[robot] != "depot":
                found.append(f"{robot} docked from {self.where[robot]}")
            if any(self.where[r] == "charging" for r in ROBOTS):
                found.append(f"{robot} docked at a busy charger")
        elif action == "open_door":
            if self.door != "closed":
                found.append(f"open_door on a door that is {self.door}")
        elif action == "close_door":
            if self.door != "open":
                found.append(f"close_door on a door that is {self.door}")
            if any(self.where[r] in CELLS[0] for r in ROBOTS):
                found.append("door closed on a robot")
        return found

    def apply(self, event):
        """A command the robots got, or an answer they sent: where everything is after it."""
        robot, _, action = event.rpartition(".")
        if action == "go" and self.where[robot] != "charging":
            self.where[robot] = TASK[(TASK.index(self.where[robot]) + 1) % len(TASK)]
        elif action == "dock":
            self.where[robot] = "charging"
        elif action == "charged" and self.where[robot] == "charging":
            self.where[robot] = "depot"
        elif action == "open_door":
            self.door = "opening"
        elif action == "door_opened" and self.door == "opening":
            self.door = "open"
        elif action == "close_door":
            self.door = "closing"
        elif action == "door_closed" and self.door == "closing":
            self.door = "closed"


class World:
    """The robots and the door: commands change them at once, answers follow ``delay`` seconds
    later; with ``twice``, every answer is sent again ``again`` seconds after it (a pair (low,
    high): drawn between them, the same draws every run). Everything it got and sent is kept
    with its time (``received``, ``sent``)."""

    def __init__(self, delay=0.2, twice=False, again=0.4, muted=()):
        self.rules = Rules()
        self.delay = delay
        self.twice = twice
        draw = random.Random(47).uniform
        self.again = (lambda: draw(*again)) if isinstance(again, (tuple, list)) else (lambda: again)
        self.muted = set(muted)  # robots whose drivers are dead: they get nothing
        self.due = []  # (when, answer, duplicate)
        self.received = []  # (time, command)
        self.sent = []  # (time, answer, duplicate)
        self.spurious_sent = 0  # answers nobody asked for

    def command(self, event):
        robot = event.rpartition(".")[0]
        if robot in self.muted:
            return
        now = time.time()
        self.received.append((now, event))
        self.rules.apply(event)
        answer = {"dock": "charged", "open_door": "door_opened", "close_door": "door_closed"}.get(
            event.rpartition(".")[2]
        )
        if answer is not None:
            name = f"{robot}.{answer}" if robot else answer
            self.due.append((now + self.delay, name, False))
            if self.twice:
                self.due.append((now + self.delay + self.again(), name, True))

    def step(self, publish):
        """Send the answers that are due (``publish(answer)``)."""
        now = time.time()
        for item in sorted(d for d in self.due if d[0] <= now):
            self.due.remove(item)
            _, name, duplicate = item
            if name.rpartition(".")[0] in self.muted:
                continue
            if not duplicate:
                self.rules.apply(name)
            self.sent.append((time.time(), name, duplicate))
            publish(name)

    def spurious(self, name, publish):
        """An answer nobody asked for (``charged`` while not charging)."""
        self.spurious_sent += 1
        self.sent.append((time.time(), name, True))
        publish(name)

    def dump(self):
        return json.dumps({"received": self.received, "sent": self.sent, "spurious": self.spurious_sent})


def forbidden(log, received, sent, start=None):
    """The commands the coordinator sent that the rules forbid where the robots really were:
    ``log`` is the coordinator's event log (its decisions, in order, with their times),
    ``received`` what the robots got (time, command), ``sent`` what they answered (time, answer,
    duplicate). A command the log has but no robot received (a dead driver, the last one before
    a kill) changes nothing; one a robot received that the log lacks (sent, then killed before
    logging it) counts where it was received. Returns (violations, commands checked)."""
    decided = [(r["time"], r["event"]) for r in log if r.get("controllable") and r["event"] in COMMANDS]
    got = dict((c, [t for t, e in received if e == c]) for c in COMMANDS)
    timeline = []
    for command in COMMANDS:
        times = [t for t, e in decided if e == command]
        arrived = got[command]
        for index, when in enumerate(times):
            if index < len(arrived):
                timeline.append((min(when, arrived[index]), 0, command))
        for when in arrived[len(times) :]:
            timeline.append((when, 0, command))
    for when, answer, duplicate in sent:
        if not duplicate:
            timeline.append((when, 1, answer))
    rules = Rules()
    found = []
    checked = 0
    for when, kind, event in sorted(timeline):
        if kind == 0:
            checked += 1
            if start is None or when >= start:
                found += [f"{when:.3f} {event}: {v}" for v in rules.violations(event)]
        rules.apply(event)
    return found, checked


class Ros2Wire:
    """The world on a ROS 2 graph, through ``node`` (rclpy, spun by ``executor``): the commands
    subscribed, the answers published, the drivers' reports served (``robots`` and the door)."""

    def __init__(self, node, executor, world, robots=ROBOTS):
        from std_msgs.msg import Empty
        from std_srvs.srv import Trigger

        self.executor, self.world, self.empty = executor, world, Empty
        self.publishers = {}
        for event in COMMANDS:
            if "." not in event or event.partition(".")[0] in robots:
                node.create_subscription(Empty, "/" + topic(event), lambda _, e=event: world.command(e), 100)
        for event in ANSWERS:
            if "." not in event or event.partition(".")[0] in robots:
                self.publishers[event] = node.create_publisher(Empty, "/" + topic(event), 100)
        for component in (*robots, "Door"):

            def serve(request, response, component=component):
                response.success, response.message = True, world.rules.report(component)
                return response

            node.create_service(Trigger, "/robosc/report/" + component, serve)

    def publish(self, event):
        self.publishers[event].publish(self.empty())

    def run(self, seconds, until=None):
        """Send the answers due and spin, for ``seconds`` or until ``until()``; whether it came."""
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.world.step(self.publish)
            self.executor.spin_once(timeout_sec=0.01)
            if until is not None and until():
                return True
        return until is None


def follow(stream, lines):
    """Append each JSON line of ``stream`` (a driver process's output) to ``lines``, on a thread."""

    def read():
        for line in stream:
            if line.startswith("{"):
                lines.append(json.loads(line))

    threading.Thread(target=read, daemon=True).start()


def take_driver(world, lines):
    """What a driver of its own process (its JSON lines) received and answered, into ``world``."""
    for line in lines:
        if "received" in line:
            world.received.append((line["t"], line["received"]))
        if "sent" in line:
            world.sent.append((line["t"], line["sent"], False))
