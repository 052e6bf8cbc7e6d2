# -*- coding: utf-8 -*-
"""What a generated ROS node does around its supervisor, middleware aside.

:class:`NodeCore` is shared by the rospy and rclpy adapters (``ros1.py``,
``ros2.py``), which supply publishers, subscriptions, clients and servers. Two
modes (SEMANTICS.md section 6): ``controller`` (the supervisor drives the robot)
and ``supervisor`` (a supervision layer between an existing controller and the
robot: each command is forwarded only as an event the supervisor allows, else
blocked and reported on ``blocked``; data from the robot goes on to the
controller). Names are used as the model gives them: relative ones resolve in
the node's namespace; the node's own topics (``state``, ``blocked``) are relative.
"""

from __future__ import absolute_import, annotations

import json
import math
import re
import sys
import time
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

from .claims import NodeClaims
from .delivery import Delivery
from .layer import BLOCKED_TOPIC, SupervisionLayer
from .messages import Unsendable, fill, received
from .node_base import Call, Topic
from .node_tasks import NodeTasks
from .recording import EventLog, Recorder, writable
from .reports import REPORT_PREFIX, NodeReports
from .supervisor import Warnings
from .tasks import POLICIES
from .viewing import VIEW_EVENTS_TOPIC, VIEW_PAGE_TOPIC, NodeView

# what the adapters read from here
__all__ = [
    "BLOCKED_TOPIC",
    "HEALTH_TOPIC",
    "HOUSEKEEPING",
    "PARAMETERS",
    "REPORT_PREFIX",
    "STATE_TOPIC",
    "VIEW_EVENTS_TOPIC",
    "VIEW_PAGE_TOPIC",
    "Call",
    "NodeCore",
    "Topic",
    "controller_side",
    "default_name",
]

MODES = ("controller", "supervisor")
CONTROLLER_PREFIX = "robosc/controller"  # where a supervision layer meets the controller
STATE_TOPIC = "state"
HEALTH_TOPIC = "health"  # latched: whether the node holds, what it waits for, unreadable data
HOUSEKEEPING = 0.1  # seconds: at least this often, acknowledgements, time-outs and reports are looked at


def default_name(robot_class: Any) -> str:
    """The node's name: ``maze_solver_robosc`` for robot ``MazeSolver``."""
    snake = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", robot_class.ROBOT).lower()
    return re.sub(r"[^a-z0-9_]", "_", snake) + "_robosc"


class Parameter(object):
    """A node parameter: its default, what it means, and the values it takes."""

    def __init__(
        self, name: str, default: Any, description: str, low: Optional[float] = None, high: Optional[float] = None,
        choices: Tuple[str, ...] = (),
    ) -> None:
        self.name = name
        self.default = default
        self.description = description
        self.low = low
        self.high = high
        self.choices = choices  # the texts it may be (none: any)

    def check(self, value: Any) -> tuple[Any, Optional[str]]:
        """``(value, None)`` for a good value (an integer is taken for a float), else
        ``(default, why)``."""
        kind = type(self.default)
        if kind is float and isinstance(value, int) and not isinstance(value, bool):
            value = float(value)
        if type(value) is not kind:
            return self.default, "%s must be a %s, not %r" % (self.name, kind.__name__, value)
        if self.choices and value not in self.choices:
            return self.default, "%s must be one of %s, not %r" % (self.name, ", ".join(self.choices), value)
        if kind in (int, float):
            if kind is float and not math.isfinite(value):
                return self.default, "%s must be a finite number, not %r" % (self.name, value)
            if (self.low is not None and value < self.low) or (self.high is not None and value > self.high):
                return self.default, "%s must be within %s..%s, not %r" % (self.name, self.low, self.high, value)
        return value, None


PARAMETERS = (
    Parameter(
        "rate", 10.0, "controller cycles per second (a supervision layer only publishes its state)", 0.01, 1000.0
    ),
    Parameter("seed", -1, "seed of the controller's random choices (-1: different every run)", -1, 2**31 - 1),
    Parameter("event_log", "", "file to append every event to, as JSON Lines (empty: none)"),
    Parameter("event_log_max_bytes", 10000000, "rotate the event log to FILE.1 at this size (0: no bound)", 0, 2**62),
    Parameter("publish_state", False, "publish the state as JSON on 'state' after each cycle"),
    Parameter("tick_on_message", False, "run a cycle right after each message from the robot"),
    Parameter("view_port", 0, "serve the live view on http://127.0.0.1:PORT/ (0: off)", 0, 65535),
    Parameter(
        "view_topics",
        True,
        "publish the live view's page (latched) on 'live_view/page' and, while someone listens, each event "
        "on 'live_view/events' (for robosc view on another machine)",
    ),
    Parameter("qos_depth", 10, "queue depth of every publisher and subscription", 1, 10000),
    Parameter("server_timeout", 5.0, "seconds to wait for a service or action server before a call fails", 0.0, 3600.0),
    Parameter(
        "trust_initial_state",
        False,
        "take the model's initial state as where the robots are at the start (only where they are known to "
        "start there with the node, e.g. a simulation; never for a node that is started again)",
    ),
    Parameter(
        "report_interval",
        1.0,
        "seconds between two requests for the state of an unconfirmed component (std_srvs/Trigger "
        "robosc/report/<component>, offered by its driver)",
        0.01,
        3600.0,
    ),
    Parameter(
        "ack_timeout",
        1.0,
        "seconds within which every subscriber must acknowledge a command (ROS 2) or stay connected (ROS 1); "
        "else what the command changes is unconfirmed",
        0.01,
        3600.0,
    ),
    Parameter(
        "answer_timeout",
        10.0,
        "seconds a component waits for an answer the model expects before it is unconfirmed and its driver "
        "asked (0: wait for ever)",
        0.0,
        1e9,
    ),
    Parameter(
        "confirm_answers",
        True,
        "an answer a robot publishes (arrived, door_opened) may be a second copy of an earlier one: its "
        "component may be where it was or where the answer leads until its driver reports (false: take "
        "answers as they come, for drivers that send each answer once and offer no report)",
    ),
    Parameter(
        "claim",
        True,
        "a controller claims its robot or fleet on robosc/coordinator and commands only while no older "
        "controller claims it (false: command at once, for a node known to be alone, e.g. a simulation's)",
    ),
    Parameter(
        "clock_skew",
        0.0,
        "seconds a robot's clock may be behind this node's, when an answer's stamp is compared with the command "
        "it answers (an answer stamped earlier than that before it is a late duplicate, ignored)",
        0.0,
        3600.0,
    ),
    Parameter(
        "wait_for_listeners",
        True,
        "send a command on a topic only while something subscribes to it (else hold it and report)",
    ),
    Parameter(
        "wait_for_data",
        True,
        "perform nothing until every communication whose data a condition reads has delivered readable data",
    ),
    Parameter(
        "policy",
        "purpose",
        "a fleet's coordinator: how it chooses among what its supervisor allows: purpose (only what gets the "
        "tasks given on robosc/task done, the robot waiting longest first) or random (any allowed command)",
        choices=POLICIES,
    ),
    Parameter(
        "data_timeout",
        1.0,
        "seconds of unreadable data from a communication before the events that read it are held",
        0.0,
        3600.0,
    ),
)


def controller_side(name: str) -> str:
    """Where a supervision layer offers ``name`` to the controller: ``/cmd_vel`` ->
    ``/robosc/controller/cmd_vel``, ``cmd_vel`` -> ``robosc/controller/cmd_vel``."""
    if name.startswith("/"):
        return "/" + CONTROLLER_PREFIX + name
    if name.startswith("~"):
        return CONTROLLER_PREFIX + "/" + name.lstrip("~/")
    return CONTROLLER_PREFIX + "/" + name


class NodeCore(NodeView, NodeReports, NodeTasks, NodeClaims, SupervisionLayer):
    """The node's work, middleware aside. An adapter calls :meth:`setup`, creates what
    :attr:`inputs`, :attr:`outputs`, :attr:`service_calls` and :attr:`action_calls` need,
    and implements ``publish``, ``publish_text``, ``call_service``, ``start_goal`` and
    ``cancel_goal``. (Attribute names differ from rclpy's Node, which the ROS 2 adapter
    also is.)"""

    def setup(
        self,
        robot_class: Any,
        mode: str,
        parameters: Dict[str, Any],
        log: Callable[[str, str], None],
    ) -> None:
        """``parameters``: name -> value as given (missing: default); bad values are
        refused with a log line and replaced by the default."""
        if mode not in MODES:
            raise ValueError("mode must be controller or supervisor")
        self.mode = mode
        self.log = log
        self.cycles = 0  # timer cycles run so far
        self.beat = 0.0  # when the last heartbeat went out on live_view/events
        self.live_view: Any = None
        self.view_topics = False  # the page and the events on live_view/* (set by view_page)
        self.params: Dict[str, Any] = {}
        for p in PARAMETERS:
            value, why = p.check(parameters.get(p.name, p.default))
            if why is not None:
                log("error", "parameter refused: %s; using %r" % (why, p.default))
            self.params[p.name] = value
        seed = self.params["seed"]
        self.warnings = Warnings(lambda message: self.log("warning", message))
        self.supervisor = robot_class(
            seed=seed if seed >= 0 else None,
            warn=self.warnings,
            wait_for_data=self.params["wait_for_data"],
            data_timeout=self.params["data_timeout"],
            confirmed=self.params["trust_initial_state"],
        )
        self.supervisor.send = self.send  # type: ignore[method-assign]  # what the supervisor sends goes out here
        self.supervisor.watching = True
        self.supervisor.skew = self.params["clock_skew"]
        self.supervisor.confirm_answers = self.params["confirm_answers"]
        self.delivery = Delivery(self)
        self.supervisor.answered = self.delivery.arrived
        self.reported: Optional[Dict[str, Any]] = None  # the health last published
        self.health_seen: Any = None  # (supervisor.health_changes, commands on their way) when last looked
        self.report_clients: Dict[str, Any] = {}  # component -> the adapter's client of its report service
        self.asked: Dict[str, float] = {}  # component -> when its driver was last asked for its state
        # component -> its requests not answered yet, oldest first: (when, on this wall clock, it
        # was asked; how many events had changed it then, supervisor.changes): a report asked for
        # before one may tell where it was before it; an answer stamped later may not be in it
        self.requests: Dict[str, List[Tuple[float, int]]] = {}
        # component -> when its oldest request not answered yet was made
        self.asked_since: Dict[str, float] = self.supervisor.asking  # it counts changes while any
        self.stamps: Dict[str, float] = {}  # topic -> the source stamp of the last message taken from it
        if self.supervisor.unconfirmed:
            log(
                "warning",
                "holding what depends on %s until the robots confirm where they are (a report on %s<component>, "
                "or an event that tells)" % (", ".join(sorted(self.supervisor.unsure())), REPORT_PREFIX),
            )
        self.sinks: List[Callable[[Dict[str, Any]], Any]] = []
        self.clock: Callable[[], float] = time.time  # what records are stamped with (start_outputs sets the node's)
        self.recorder: Optional[Recorder] = None
        self.event_log: Optional[EventLog] = None
        path = self.params["event_log"]
        if path:
            why = writable(path)
            if why is None:
                self.event_log = EventLog(path, self.params["event_log_max_bytes"], lambda text: log("error", text))
                self.sinks.append(self.event_log)
            else:
                log("error", "parameter refused: event_log %r cannot be written (%s); no event log" % (path, why))
        self.blocked_count = self.forwarded_count = 0
        self.refused: Optional[str] = None  # why send() refused the command being forwarded, if it did
        self.text_publishers: Dict[str, Any] = {}  # made by the adapter
        self.text_type: Any = None
        self.still = frozenset(robot_class.STILL)
        self._plan_routes(robot_class)
        self.start_tasks(robot_class, self.params["policy"], lambda: self.clock())
        if mode == "controller" and self.params["claim"]:  # one controller commands (claims.py)
            self.start_claims()
        else:
            self.commanding = mode == "controller"

    # ---- after each callback and cycle -------------------------------------------------------
    def checkpoint(self) -> None:
        """After each callback and cycle: follow the commands sent meanwhile (what each changed
        stays unconfirmed until it is acknowledged), ask at once the drivers of the components an
        answer or an event with several outcomes left unconfirmed, and report on ``health``
        (latched) when what the node holds changed."""
        self.delivery.follow()
        if self.supervisor.doubted:
            self.ask_again(self.supervisor.doubted)
        if self.queue_changed:
            try:
                self.publish_queue()
            except Exception as error:
                self.warnings("cannot publish the task queue: %s" % (error,), "task queue")
        changes = (self.supervisor.health_changes, len(self.delivery.pending))
        if changes == self.health_seen:
            return  # nothing health() shows has changed
        self.health_seen = changes
        if self.recorder is not None and self.supervisor.observer is not None:
            self.recorder.settled()  # a belief changed without an event (a command acknowledged, ...)
        health = self.health()
        if health != self.reported:
            before = self.reported
            self.reported = health
            if health["held"] and (before is None or not before["held"]):
                self.log("warning", "holding every command: waiting for data on %s" % ", ".join(health["waiting_for"]))
            elif before is not None and before["held"] and not health["held"]:
                self.log("info", "every communication delivered data: no longer held")
            try:
                self.publish_text(HEALTH_TOPIC, json.dumps(health, sort_keys=True, default=str))
            except Exception as error:
                self.warnings("cannot report health: %s" % (error,), "health report")

    def health(self) -> Dict[str, Any]:
        """The supervisor's health, without the commands waiting for their acknowledgement (they are
        fleeting: ``in_flight`` counts them)."""
        health: Dict[str, Any] = self.supervisor.health()
        waiting = self.delivery.waiting()
        health["unconfirmed"] = dict((c, v) for c, v in health["unconfirmed"].items() if c not in waiting)
        health["in_flight"] = len(self.delivery.pending)
        claims = self.claim_health()
        if claims is not None:
            health["coordinator"] = claims
        return health

    def _plan_routes(self, robot_class: Any) -> None:
        by_comm: Dict[str, Dict[str, Any]] = {}
        for event in robot_class.EVENTS:
            if event.communication is not None:
                by_comm.setdefault(event.communication, {})[event.kind] = event
        self.inputs: Dict[str, Topic] = {}
        self.outputs: Dict[str, Topic] = {}
        self.service_calls: List[Call] = []
        self.action_calls: List[Call] = []
        self.route: Dict[str, Union[Topic, Call]] = {}  # controllable event name -> what carries it
        for c in robot_class.COMMUNICATIONS:
            events = by_comm.get(c.name, {})
            if c.kind in ("outgoing", "incoming"):
                table = self.inputs if c.kind == "outgoing" else self.outputs
                topic = table.get(c.ros_name)
                if topic is None:
                    topic = table[c.ros_name] = Topic(c.ros_name, [c], [])
                else:
                    topic.communications.append(c)
                if "message" in events:
                    topic.events.append(events["message"])
                    topic.takes.append((events["message"].name, c))
                    self.route[events["message"].name] = topic
                    whole = all(communication.data == "object" for _, communication in topic.takes)
                    topic.whole = tuple(name for name, _ in topic.takes) if whole else None
                continue
            call = Call(c, events)
            (self.service_calls if c.kind == "service" else self.action_calls).append(call)
            for kind in ("trigger", "cancel"):
                if kind in events:
                    self.route[events[kind].name] = call

    def start_outputs(self, robot_class: Any, clock: Callable[[], float], create: Callable[[], None]) -> None:
        """The node's outputs around the adapter's ``create`` (its publishers, subscribers,
        services and actions): the live view and the event log first, before anything can
        deliver an event, the view topics' page and state once their publishers exist."""
        self.clock = clock
        page = self.view_page(robot_class)
        self.live_view = self.open_live_view(page)
        self.start_recording(self.live_view.publish if self.live_view is not None else None)
        create()
        self.start_view_topics(page)
        self.checkpoint()  # the first report on health, now that its publisher exists

    # ---- the cycle -----------------------------------------------------------------------
    def housekeep(self) -> None:
        """The commands on their way, the answers overdue, the reports to ask for: every cycle, and
        at least every HOUSEKEEPING seconds (the adapters add a timer where ``rate`` is slower)."""
        now = time.time()
        self.claims_cycle()
        self.delivery.follow()
        self.overdue(now)
        if self.supervisor.unconfirmed:
            self.ask_reports(now)

    def housekeeping(self) -> None:
        """The timer that keeps up housekeeping where the cycle is slower than HOUSEKEEPING."""
        self.housekeep()
        self.checkpoint()

    def cycle(self) -> None:
        """The timer: housekeeping, a controller's tick, then the state if asked for."""
        self.cycles += 1
        self.housekeep()
        if self.mode == "controller" and self.commanding:  # (else another controller commands)
            try:
                self.supervisor.tick()
            except Exception as error:  # keep the node alive; the state is unchanged
                self.warnings("tick failed: %s: %s" % (type(error).__name__, error), "tick")
        self.checkpoint()
        self.observe()
        if self.params["publish_state"]:
            self.publish_state()
        if self.view_topics:
            self.heartbeat()

    def close(self) -> None:
        """At shutdown: close the live view and the event log, and say how many cycles ran
        (on standard error: the middleware's logger may be gone already)."""
        if self.live_view is not None:
            self.live_view.close()
        if self.event_log is not None:
            self.event_log.close()
        print("[robosc] stopped after %d cycles" % self.cycles, file=sys.stderr)
        sys.stderr.flush()

    def after_message(self) -> None:
        if self.mode == "supervisor":
            self.supervisor.settle()
        elif self.params["tick_on_message"] and self.commanding:
            self.supervisor.tick()

    def publish_state(self) -> None:
        state = dict(self.supervisor.snapshot(), health=self.health())
        self.publish_text(STATE_TOPIC, json.dumps(state, sort_keys=True))

    # ---- data from the robot ---------------------------------------------------------------
    def receive(self, topic: Topic, message: Any, stamp: Optional[float] = None) -> None:
        """A message on a topic the robot publishes: each event on it, then what follows; a
        supervision layer passes it on to the controller. ``stamp``: when the robot sent it (its
        wall clock, seconds), where the middleware or the message tells: a message stamped no later
        than the last one taken from the topic is a duplicate (DDS history given again), ignored."""
        try:
            if stamp is None or self.fresh(topic, stamp):
                supervisor = self.supervisor
                if topic.whole is not None:
                    supervisor.deliver_message(topic.whole, message, stamp)
                else:
                    for name, communication in topic.takes:
                        supervisor.deliver(name, received(communication, message), True, stamp)
                self.after_message()
        except Exception as error:  # a malformed message must not stop the node
            self.warnings("message on %s: %s: %s" % (topic.name, type(error).__name__, error), "receive " + topic.name)
        self.checkpoint()
        if topic.forward is not None:
            topic.forward.publish(message)

    def fresh(self, topic: Topic, stamp: float) -> bool:
        """Whether a message stamped ``stamp`` is later than the last one taken from ``topic``;
        else it is a duplicate (DDS history given again), ignored and reported."""
        last = self.stamps.get(topic.name)
        if last is not None and stamp <= last:
            self.supervisor.ignore(
                topic.name, "stamped %.3f s before the last one taken from it (a duplicate)" % (last - stamp)
            )
            return False
        self.stamps[topic.name] = stamp
        return True

    def answer(self, event: Any, value: Any) -> None:
        """A service's or action's response, error or feedback came back."""
        if event is None:
            return
        try:
            self.supervisor.deliver(event.name, value)
            self.after_message()
        except Exception as error:
            self.warnings("%s: %s: %s" % (event.name, type(error).__name__, error), "answer " + event.name)
        self.checkpoint()

    # ---- commands: the supervisor performs a controllable event ----------------------------
    def send(self, name: str, data: Any) -> bool:
        """Put the controllable event ``name`` on the middleware; False refuses it (not performed)."""
        place = self.route.get(name)
        if place is None:
            return True  # tau, reset, and data events have nothing to send
        if isinstance(place, Topic):
            topic = place
            delivery = self.delivery
            silent = delivery.held(topic) if delivery.silent or delivery.pending else None
            if silent is not None:  # what went before it may not have arrived: its robot is held
                if topic.name in delivery.silent:
                    self.warnings("held: %s: %s" % (name, silent), "silent " + name)
                self.refused = silent
                return False
            # the subscribers as the middleware last told without being asked (where it tells),
            # else asked now: whether the command arrived is told by delivery, which asks
            matched = topic.matched
            if matched is None:
                matched = self.listeners(topic)
            if matched == 0 and self.params["wait_for_listeners"]:
                # a message nobody subscribes to is lost, and the supervisor would believe the
                # robot got it (a robot not up yet, a link down): hold the command instead
                self.warnings("held: %s: nothing subscribes to %s" % (name, topic.name), "unheard " + name)
                self.refused = "nothing subscribes to %s" % topic.name
                return False
            if self.mode == "supervisor":
                message = data  # the controller's own message, already checked
            else:
                made = topic.made
                if made is not None and made[0] is data:  # the same (constant) data as last time
                    message = made[1]
                else:
                    try:
                        message = fill(topic.type(), data, topic.name)
                    except Unsendable as error:
                        self.warnings("not sent: %s: %s" % (name, error), "unsendable " + name)
                        return False
                    topic.made = (data, message)
            if name not in self.still:  # what changes nothing leaves nothing to confirm
                delivery.sent(name, topic)
            self.publish(topic, message)
            return True
        call = place
        event = self.supervisor.EVENT[name]
        if self.mode == "supervisor":
            return self.forward_call(call, event, data)
        if event.kind == "cancel":
            self.cancel_goal(call)
            return True
        try:
            request = fill(call.request(), data, call.name)
        except Unsendable as error:
            self.warnings("not sent: %s: %s" % (name, error), "unsendable " + name)
            return False
        if call.kind == "service":
            self.call_service(call, request)
        else:
            self.start_goal(call, request)
        return True

    def forward_call(self, call: Call, event: Any, data: Any) -> bool:
        """Supervision layer: a call or goal is forwarded by the adapter's server callback."""
        return True


