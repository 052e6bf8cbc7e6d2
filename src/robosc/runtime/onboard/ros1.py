# -*- coding: utf-8 -*-
"""The rospy adapter (ROS 1): :class:`SupervisorNode` runs a generated robot class. A
generated package's node script is only::

    from my_robot_robosc.onboard.ros1 import main
    from my_robot_robosc.my_robot_supervisor import Robot
    main(Robot, "controller")

rospy runs every callback on a thread of its own, so each one holds the
supervisor's lock. Services are called on a thread (rospy calls are synchronous)
and come back as response / error events; actions use actionlib's
ActionClient (:class:`Goal`). Both wait for their server at most ``~server_timeout``
seconds, on their thread, so the node keeps running meanwhile. Parameters are
private (``~rate``, ...) and checked: a bad value is refused with a log line.
"""

from __future__ import absolute_import, annotations, print_function

import logging
import sys
import threading
import time
from typing import Any, Callable, Dict, List, Optional

import rospy

from .claims import CLAIM_TOPIC
from .messages import MissingType, load
from .node import (
    BLOCKED_TOPIC,
    HEALTH_TOPIC,
    HOUSEKEEPING,
    PARAMETERS,
    REPORT_PREFIX,
    STATE_TOPIC,
    VIEW_EVENTS_TOPIC,
    VIEW_PAGE_TOPIC,
    Call,
    NodeCore,
    controller_side,
    default_name,
)
from .node_tasks import QUEUE_SERVICE, TASK_DEPTH, TASK_TOPIC, TASKS_TOPIC

SUCCEEDED = 3  # actionlib_msgs/GoalStatus.SUCCEEDED
LOST = 9  # actionlib_msgs/GoalStatus.LOST


class Goal(object):
    """One goal sent with actionlib's ActionClient, its feedback and its end passed on.
    actionlib's callbacks come with their goal handle, so none is lost when the server answers
    before ``send_goal`` has returned (SimpleActionClient drops what comes in that window: the
    goal's early feedback and its becoming active, seen under load)."""

    def __init__(
        self,
        client: Any,
        goal: Any,
        on_feedback: Callable[[Any], None],
        on_done: Optional[Callable[[int, Any], None]] = None,
    ) -> None:
        from actionlib import CommState

        self.comm = CommState
        self.on_feedback = on_feedback
        self.on_done = on_done
        self.finished = threading.Event()
        self.status = LOST
        self.result: Any = None
        self.handle = client.send_goal(goal, transition_cb=self.transition, feedback_cb=self.feedback)

    def feedback(self, handle: Any, feedback: Any) -> None:
        if not self.finished.is_set():
            self.on_feedback(feedback)

    def transition(self, handle: Any, *_: Any) -> None:
        state = handle.get_comm_state()
        if self.finished.is_set() or state not in (self.comm.DONE, self.comm.LOST):
            return
        if state == self.comm.DONE:
            self.status, self.result = handle.get_goal_status(), handle.get_result()
        self.finished.set()
        if self.on_done is not None:
            self.on_done(self.status, self.result)

    def cancel(self) -> None:
        self.handle.cancel()


_CONSOLE: List[bool] = []  # [True]: rospy could not set up its console output: lines go to stderr


def _log(level: str, message: str) -> None:
    if _CONSOLE:
        print("[robosc] %s: %s" % (level, message), file=sys.stderr)
    if rospy.core.is_shutdown_requested():
        # shutting down, maybe for a node of the same name the master has taken instead: rospy's
        # logger would ask the master for a parameter as this node, and the master would shut the
        # other node down in turn; said on standard error instead
        print("[robosc] %s: %s" % (level, message), file=sys.stderr)
        return
    {"error": rospy.logerr, "warning": rospy.logwarn}.get(level, rospy.loginfo)(message)


class Matching(rospy.SubscribeListener):  # type: ignore[misc]
    """A command topic's subscribers come and go: how many it has now (``Topic.matched``)."""

    def __init__(self, topic: Any) -> None:
        self.topic = topic

    def peer_subscribe(self, topic_name: str, topic_publish: Any, peer_publish: Any) -> None:
        publisher = self.topic.publisher  # None while rospy is still making it: asked then
        self.topic.matched = publisher.get_num_connections() if publisher is not None else None

    def peer_unsubscribe(self, topic_name: str, num_peers: int) -> None:
        self.topic.matched = int(num_peers)


def quiet_log_files() -> None:
    """rospy's log files (``ROS_HOME``/``ROS_LOG_DIR``) on a full disk: Python's logging would print
    a traceback for every line that cannot be written, and at the end; said once instead."""
    said: List[bool] = []  # once said, not again

    def failed(record: Any) -> None:
        if not said:
            said.append(True)
            error = sys.exc_info()[1]
            print("[robosc] cannot write ROS's log file (%s: %s): log lines go to the console only"
                  % (type(error).__name__, error), file=sys.stderr)

    loggers = [logging.getLogger()] + [
        logger for logger in logging.Logger.manager.loggerDict.values() if isinstance(logger, logging.Logger)
    ]
    for logger in loggers:
        for handler in logger.handlers:
            if isinstance(handler, logging.FileHandler):
                handler.handleError = failed  # type: ignore[method-assign]
    console = [h for h in logging.getLogger("rosout").handlers if type(h).__name__ == "RosStreamHandler"]
    if not console and not _CONSOLE:  # its log configuration could not be read or written (ROS_HOME read-only)
        _CONSOLE.append(True)
        print("[robosc] rospy could not set up its logging: the node's log lines go to standard error", file=sys.stderr)


class SupervisorNode(NodeCore):
    def __init__(self, robot_class: Any, mode: str = "controller", node_name: Optional[str] = None) -> None:
        logging.raiseExceptions = False  # (rospy logs while it starts, before its handlers can be told)
        rospy.init_node(node_name or default_name(robot_class))
        quiet_log_files()
        given = {}
        for p in PARAMETERS:
            try:
                given[p.name] = rospy.get_param("~" + p.name, p.default)
            except Exception as error:  # an unreadable parameter server entry
                _log("error", "parameter %s unreadable: %s" % (p.name, error))
        self.setup(robot_class, mode, given, _log)
        self.lock = self.supervisor.lock
        self._load_types()
        self.start_outputs(robot_class, rospy.get_time, self._create)
        self.cycle_timer = rospy.Timer(rospy.Duration(1.0 / self.params["rate"]), self.locked(self.cycle))
        if 1.0 / self.params["rate"] > HOUSEKEEPING:
            self.housekeeping_timer = rospy.Timer(rospy.Duration(HOUSEKEEPING), self.locked(self.housekept))

    def _load_types(self) -> None:
        for topic in list(self.inputs.values()) + list(self.outputs.values()):
            topic.type = load(topic.package, "msg", topic.type_name)
        for call in self.service_calls:
            call.type = load(call.package, "srv", call.type_name)
            call.request = load(call.package, "srv", call.type_name + "Request")
        for call in self.action_calls:
            call.type = load(call.package, "msg", call.type_name + "Action")
            call.request = load(call.package, "msg", call.type_name + "Goal")
        self.text_type = load("std_msgs", "msg", "String")

    def _create(self) -> None:
        depth = self.params["qos_depth"]
        supervising = self.mode == "supervisor"
        self.text_publishers = {
            STATE_TOPIC: rospy.Publisher(STATE_TOPIC, self.text_type, queue_size=10),
            HEALTH_TOPIC: rospy.Publisher(HEALTH_TOPIC, self.text_type, queue_size=10, latch=True),
        }
        if self.view_topics:  # latched: a viewer that comes later gets the page and the last event
            for name in (VIEW_PAGE_TOPIC, VIEW_EVENTS_TOPIC):
                self.text_publishers[name] = rospy.Publisher(name, self.text_type, queue_size=100, latch=True)
        if supervising:
            self.text_publishers[BLOCKED_TOPIC] = rospy.Publisher(BLOCKED_TOPIC, self.text_type, queue_size=depth)
        for topic in self.outputs.values():
            topic.publisher = rospy.Publisher(
                topic.name, topic.type, subscriber_listener=Matching(topic), queue_size=depth
            )
            topic.matched = topic.publisher.get_num_connections()
        for topic in self.inputs.values():
            if supervising:
                topic.forward = rospy.Publisher(controller_side(topic.name), topic.type, queue_size=depth)
        import actionlib

        for call in self.service_calls:
            call.client = rospy.ServiceProxy(call.name, call.type)
        for call in self.action_calls:
            call.client = actionlib.ActionClient(call.name, call.type)
        self.trigger = load("std_srvs", "srv", "Trigger")
        self.asking: Dict[str, float] = {}  # components whose driver is being asked now, since when
        for component in self.supervisor.COMPONENTS:
            self.report_clients[component] = rospy.ServiceProxy(REPORT_PREFIX + component, self.trigger)
        if self.dispatcher is not None:  # a fleet's coordinator: tasks at run time (node_tasks.py)
            self.text_publishers[TASKS_TOPIC] = rospy.Publisher(TASKS_TOPIC, self.text_type, queue_size=10, latch=True)
        if self.claim is not None:  # one controller commands (claims.py)
            self.text_publishers[CLAIM_TOPIC] = rospy.Publisher(CLAIM_TOPIC, self.text_type, queue_size=10)
        # subscriptions and servers last: their callbacks need everything above
        if self.claim is not None:
            rospy.Subscriber(CLAIM_TOPIC, self.text_type, self.locked(self.claim_heard), queue_size=10)
        if self.dispatcher is not None:
            rospy.Subscriber(TASK_TOPIC, self.text_type, self.locked(self.task_given), queue_size=TASK_DEPTH)
            rospy.Service(QUEUE_SERVICE, self.trigger, self.locked(self.serve_queue_ros1))
        for topic in self.inputs.values():
            rospy.Subscriber(topic.name, topic.type, self.locked(self.stamped, topic), queue_size=depth)
        if supervising:
            for topic in self.outputs.values():
                rospy.Subscriber(
                    controller_side(topic.name), topic.type, self.locked(self.request, topic), queue_size=depth
                )
            for call in self.service_calls:
                rospy.Service(controller_side(call.name), call.type, self.serve_call(call))
            for call in self.action_calls:
                call.server = actionlib.SimpleActionServer(
                    controller_side(call.name), call.type, execute_cb=self.serve_goal(call), auto_start=False
                )
                call.server.start()

    def serve_queue_ros1(self, _request: Any) -> Any:
        return self.trigger._response_class(success=True, message=self.queue_text())

    def locked(self, function: Callable[..., Any], *first: Any) -> Callable[..., Any]:
        """``function(*first, *args)`` holding the lock, never raising into rospy."""

        def run(*args: Any) -> Any:
            try:
                with self.lock:
                    return function(*(first + args))
            except Exception as error:
                self.warnings("%s: %s: %s" % (getattr(function, "__name__", "callback"), type(error).__name__, error))
                return None

        return run

    def cycle(self, _event: Any = None) -> None:
        NodeCore.cycle(self)

    def housekept(self, _event: Any = None) -> None:
        NodeCore.housekeeping(self)

    def stamped(self, topic: Any, message: Any) -> None:
        """A message from the robot, with its header's stamp when it has one (ROS 1 gives no
        other: a message without a header cannot be told from a duplicate)."""
        stamp = None
        header = getattr(message, "header", None)
        if header is not None and getattr(header, "stamp", None) is not None:
            seconds = header.stamp.to_sec()
            stamp = seconds if seconds > 0 else None
        self.receive(topic, message, stamp)

    # ---- asking a driver where its component is ------------------------------------------------
    def ask_report(self, component: str, client: Any) -> bool:
        """Call the driver's report service on a thread (rospy calls are synchronous), one at a time
        per component; the answer comes back under the lock. Where no server is there yet, the
        thread says so, and the next look asks again. A request not answered within
        ``server_timeout`` is given up (rospy's calls have no time-out of their own: a driver that
        hangs would keep its component unconfirmed for ever): reported, asked again, and its answer,
        should it come, is not taken."""
        now = time.monotonic()
        since = self.asking.get(component)
        if since is not None:
            if now - since < self.params["server_timeout"]:
                return False
            self.warnings(
                "%s's driver has not answered its report request for %.1f s: asked again" % (component, now - since),
                "report " + component,
            )
            self.not_answered(component)  # its answer, should it come, is not taken
        self.asking[component] = now

        def ask() -> None:
            response = None
            try:
                client.wait_for_service(timeout=0.2)
                response = client()
            except Exception:  # no driver offers it (yet), or it failed
                pass
            with self.lock:
                if self.asking.get(component) != now:
                    return  # given up on: a later request is out
                del self.asking[component]
                if response is None:
                    self.not_answered(component)
                    self.asked.pop(component, None)  # not asked: the next look tries again
                else:
                    self.report(component, bool(response.success), str(response.message))

        thread = threading.Thread(target=ask)
        thread.daemon = True
        thread.start()
        return True

    # ---- services and actions of a controller --------------------------------------------------------
    def subscribers(self, publisher: Any) -> int:
        return int(publisher.get_num_connections())

    def call_service(self, call: Call, request: Any) -> bool:
        return self.on_a_thread(self.call_now, call, request)

    @staticmethod
    def on_a_thread(work: Callable[[Call, int, Any], None], call: Call, request: Any) -> bool:
        """A new call or goal (older ones are ignored from now on), done on a thread: rospy's
        calls are synchronous and a server may take its time."""
        call.goal += 1
        thread = threading.Thread(target=work, args=(call, call.goal, request))
        thread.daemon = True
        thread.start()
        return True

    def call_now(self, call: Call, number: int, request: Any) -> None:
        """On a thread: wait for the server, call, and report the answer as an event."""
        response = None
        try:
            call.client.wait_for_service(timeout=max(self.params["server_timeout"], 0.001))
            response = call.client(request)
        except rospy.ROSException as error:  # no server in time
            self.warnings("service %s: %s" % (call.name, error), "gone " + call.name)
        except Exception as error:  # failed on the server
            self.warnings("service %s failed: %s" % (call.name, error), "failed " + call.name)
        with self.lock:
            if number == call.goal:
                self.answer(call.error if response is None else call.response, response)

    def start_goal(self, call: Call, goal: Any) -> bool:
        return self.on_a_thread(self.send_goal_now, call, goal)

    def send_goal_now(self, call: Call, number: int, goal: Any) -> None:
        if not call.client.wait_for_server(rospy.Duration(max(self.params["server_timeout"], 0.001))):
            self.warnings(
                "action %s: no server after %.1f s; failed" % (call.name, self.params["server_timeout"]),
                "gone " + call.name,
            )
            with self.lock:
                if number == call.goal:
                    self.answer(call.error, None)
            return
        with self.lock:
            if number != call.goal:
                return  # cancelled while waiting for the server
            call.handle = Goal(
                call.client,
                goal,
                on_feedback=lambda feedback: self.locked(self.feedback, call, number, feedback)(),
                on_done=lambda status, result: self.locked(self.done, call, number, status, result)(),
            )

    def feedback(self, call: Call, number: int, feedback: Any) -> None:
        if number == call.goal:
            self.answer(call.feedback, feedback)

    def done(self, call: Call, number: int, status: int, result: Any) -> None:
        if number != call.goal:
            return  # a goal this node cancelled, or an older one
        self.answer(call.response if status == SUCCEEDED else call.error, result if status == SUCCEEDED else None)

    def cancel_goal(self, call: Call) -> bool:
        call.goal += 1  # results of the cancelled goal are ignored
        try:
            if call.handle is not None:
                call.handle.cancel()
        except Exception as error:
            self.warnings("action %s: cancel failed: %s" % (call.name, error), "cancel " + call.name)
        return True

    # ---- supervision layer: calls and goals from the controller -------------------------------------------
    def serve_call(self, call: Call) -> Callable[..., Any]:
        def serve(request: Any) -> Any:
            """The controller calls the service: forwarded if the supervisor allows it."""
            with self.lock:
                allowed = self.admit(call, request)
            if not allowed:
                raise rospy.ServiceException("blocked by the supervisor")
            try:
                call.client.wait_for_service(timeout=max(self.params["server_timeout"], 0.001))
                response = call.client(request)
            except Exception as error:
                with self.lock:
                    self.answer(call.error, None)
                raise rospy.ServiceException(str(error)) from None
            with self.lock:
                self.answer(call.response, response)
            return response

        return serve

    def serve_goal(self, call: Call) -> Callable[..., Any]:
        def serve(goal: Any) -> None:
            """The controller sends a goal (on the action server's thread): forwarded if the
            supervisor allows it, feedback and result passed back."""
            server = call.server
            with self.lock:
                allowed = self.admit(call, goal)
                if allowed:
                    call.goal += 1
                    number = call.goal
            if not allowed:
                server.set_aborted(text="blocked by the supervisor")
                return
            client = call.client
            if not client.wait_for_server(rospy.Duration(max(self.params["server_timeout"], 0.001))):
                with self.lock:
                    if number == call.goal:
                        self.answer(call.error, None)
                server.set_aborted(text="no action server")
                return
            sent = Goal(client, goal, on_feedback=lambda feedback: self.pass_feedback(call, number, feedback))
            while not sent.finished.wait(0.02):
                if rospy.is_shutdown():
                    return
                if number != call.goal:  # the supervisor cancelled it
                    sent.cancel()
                    server.set_preempted(text="cancelled by the supervisor")
                    return
                if server.is_preempt_requested():
                    with self.lock:
                        cancelled = call.cancel is not None and self.supervisor.perform(call.cancel.name)
                        if cancelled:
                            self.supervisor.settle()
                            self.checkpoint()
                        else:
                            self.blocked(
                                call.cancel.name if call.cancel else None,
                                call.name,
                                "the supervisor does not allow it now",
                            )
                    if cancelled:
                        sent.cancel()
                        server.set_preempted()
                        return
            with self.lock:
                if number != call.goal:
                    server.set_preempted(text="cancelled by the supervisor")
                    return
                succeeded = sent.status == SUCCEEDED
                result = sent.result
                self.answer(call.response if succeeded else call.error, result if succeeded else None)
            if succeeded:
                server.set_succeeded(result)
            else:
                server.set_aborted(result)

        return serve

    def pass_feedback(self, call: Call, number: int, feedback: Any) -> None:
        with self.lock:
            if number != call.goal:
                return
            self.answer(call.feedback, feedback)
        call.server.publish_feedback(feedback)

    def forward_call(self, call: Call, event: Any, data: Any) -> bool:
        if event.kind == "cancel":  # the forwarding loop cancels the robot's goal
            call.goal += 1
        return True


def main(robot_class: Any, mode: str = "controller", node_name: Optional[str] = None) -> int:
    """Run the node until shut down; returns the exit status."""
    try:
        node = SupervisorNode(robot_class, mode, node_name)
    except MissingType as error:
        print("[robosc] %s" % (error,), file=sys.stderr)
        return 1
    node.log("info", "robosc supervisor of %s running (%s, %s Hz)" % (robot_class.ROBOT, mode, node.params["rate"]))
    rospy.spin()
    node.close()
    return 0
