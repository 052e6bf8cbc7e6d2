# -*- coding: utf-8 -*-
"""The rclpy adapter (ROS 2): :class:`SupervisorNode` is an ``rclpy.node.Node`` that runs a
generated robot class. A generated package's node module is only::

    from .onboard.ros2 import main
    from .my_robot_supervisor import Robot
    main(Robot, "controller")

Parameters are declared with descriptors (read only; see ``node.PARAMETERS``) and
checked: a bad value is refused with a log line and the default is used. QoS:
sensor data (``sensor_msgs`` types) is subscribed best effort, so that it reaches the
node from sensor-data publishers (best effort) and reliable ones alike; other data
is subscribed reliably (no first message lost while the connection is made), and
commands are published reliably. Each can be changed per topic with ROS 2's
``qos_overrides.<topic>.<publisher|subscription>.<policy>`` parameters. A controller runs on the single-threaded executor (no lock needed); a
supervision layer on a multi-threaded one when it forwards service calls or action goals (they wait for the robot
on threads of their own), every callback holding the supervisor's lock; otherwise single-threaded too.
"""

from __future__ import absolute_import, annotations

import contextlib
import os
import sys
import time
from typing import Any, Callable, Dict, List, Optional

import rclpy
from rcl_interfaces.msg import ParameterDescriptor
from rclpy.action.client import ActionClient
from rclpy.action.server import ActionServer, CancelResponse
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.duration import Duration
from rclpy.event_handler import PublisherEventCallbacks
from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor, SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSPolicyKind, QoSProfile, ReliabilityPolicy
from rclpy.qos_overriding_options import QoSOverridingOptions
from rclpy.utilities import ok, try_shutdown

from . import profiles
from .claims import CLAIM_TOPIC
from .messages import SENSOR_PACKAGE, MissingType, load
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

SUCCEEDED = 4  # action_msgs/GoalStatus.STATUS_SUCCEEDED
POLL_SECONDS = 0.05  # how often a call waiting for its server looks again


class SupervisorNode(Node, NodeCore):
    """The node of a robot's supervisor (``mode`` controller or supervisor)."""

    acknowledges = True  # reliable DDS: every subscriber acknowledges what it received
    NOW = Duration(seconds=0)

    def __init__(
        self, robot_class: Any, mode: str = "controller", node_name: Optional[str] = None, **kwargs: Any
    ) -> None:
        Node.__init__(self, node_name or default_name(robot_class), **kwargs)
        given = {}
        for p in PARAMETERS:
            descriptor = ParameterDescriptor(description=p.description, read_only=True, dynamic_typing=True)
            given[p.name] = self.declare_parameter(p.name, p.default, descriptor).value
        self.setup(robot_class, mode, given, self._log)
        self.lock = self.supervisor.lock
        self.spent: List[Any] = []  # timers of finished waits, destroyed at the next cycle
        self._load_types()
        self.start_outputs(robot_class, self._now, self._create)
        self.cycle_timer = self.create_timer(1.0 / self.params["rate"], self.callback(self.cycle))
        if 1.0 / self.params["rate"] > HOUSEKEEPING:
            self.housekeeping_timer = self.create_timer(HOUSEKEEPING, self.callback(self.housekeeping))

    # ---- set-up ----------------------------------------------------------------------------
    def _now(self) -> float:
        """Seconds on the node's clock (the simulation's under ``use_sim_time``)."""
        return float(self.get_clock().now().nanoseconds) / 1e9

    def _log(self, level: str, message: str) -> None:
        logger = self.get_logger()  # rclpy wants one severity per line of code that logs
        if level == "error":
            logger.error(message)
        elif level == "warning":
            logger.warning(message)
        else:
            logger.info(message)

    def _load_types(self) -> None:
        for topic in list(self.inputs.values()) + list(self.outputs.values()):
            topic.type = load(topic.package, "msg", topic.type_name)
        for call in self.service_calls:
            call.type = load(call.package, "srv", call.type_name)
            call.request = call.type.Request
        for call in self.action_calls:
            call.type = load(call.package, "action", call.type_name)
            call.request = call.type.Goal
        self.text_type = load("std_msgs", "msg", "String")

    def _create(self) -> None:
        depth = self.params["qos_depth"]
        reliable = QoSProfile(depth=depth, reliability=ReliabilityPolicy.RELIABLE)
        best_effort = QoSProfile(depth=depth, reliability=ReliabilityPolicy.BEST_EFFORT)
        # history, depth, reliability and durability can be set per topic (a robot that publishes its
        # emergency stop transient local is read so: qos_overrides./stop.subscription.durability)
        overrides = QoSOverridingOptions(
            [QoSPolicyKind.HISTORY, QoSPolicyKind.DEPTH, QoSPolicyKind.RELIABILITY, QoSPolicyKind.DURABILITY]
        )
        supervising = self.mode == "supervisor"
        latched = QoSProfile(
            depth=depth, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL
        )
        self.text_publishers = {
            STATE_TOPIC: self.create_publisher(self.text_type, STATE_TOPIC, 10),
            HEALTH_TOPIC: self.create_publisher(self.text_type, HEALTH_TOPIC, latched),
        }
        if self.view_topics:  # transient local: a viewer that comes later gets the page and last events
            for name in (VIEW_PAGE_TOPIC, VIEW_EVENTS_TOPIC):
                self.text_publishers[name] = self.create_publisher(self.text_type, name, latched)
        if supervising:
            self.text_publishers[BLOCKED_TOPIC] = self.create_publisher(self.text_type, BLOCKED_TOPIC, reliable)
        for topic in self.outputs.values():  # commands to the robot
            topic.publisher = self.create_publisher(
                topic.type,
                topic.name,
                reliable,
                qos_overriding_options=overrides,
                event_callbacks=PublisherEventCallbacks(matched=self.matching(topic)),
            )
            topic.matched = topic.publisher.get_subscription_count()
            if supervising:  # ... as the controller sends them
                self.create_subscription(
                    topic.type, controller_side(topic.name), self.callback(self.request, topic), reliable
                )
        for topic in self.inputs.values():  # data from the robot
            if supervising:
                topic.forward = self.create_publisher(topic.type, controller_side(topic.name), reliable)
            qos = best_effort if topic.package == SENSOR_PACKAGE else reliable
            self.create_subscription(topic.type, topic.name, self.stamped(topic), qos, qos_overriding_options=overrides)
        trigger = load("std_srvs", "srv", "Trigger")
        self.trigger_request = trigger.Request
        if self.claim is not None:  # one controller commands (claims.py)
            claims = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE)
            self.text_publishers[CLAIM_TOPIC] = self.create_publisher(self.text_type, CLAIM_TOPIC, claims)
            self.create_subscription(self.text_type, CLAIM_TOPIC, self.callback(self.claim_heard), claims)
        if self.dispatcher is not None:  # a fleet's coordinator: tasks at run time (node_tasks.py)
            self.text_publishers[TASKS_TOPIC] = self.create_publisher(self.text_type, TASKS_TOPIC, latched)
            tasks = QoSProfile(depth=TASK_DEPTH, reliability=ReliabilityPolicy.RELIABLE)  # none lost in a burst
            self.create_subscription(self.text_type, TASK_TOPIC, self.callback(self.task_given), tasks)
            self.create_service(trigger, QUEUE_SERVICE, self.callback(self.serve_queue))
        for component in self.supervisor.COMPONENTS:
            self.report_clients[component] = self.create_client(trigger, REPORT_PREFIX + component)
        forwarding = ReentrantCallbackGroup()
        for call in self.service_calls:
            call.client = self.create_client(call.type, call.name)
            if supervising:
                self.create_service(
                    call.type, controller_side(call.name), self.serve_call(call), callback_group=forwarding
                )
        for call in self.action_calls:
            call.client = ActionClient(self, call.type, call.name)
            if supervising:
                call.server = ActionServer(
                    self,
                    call.type,
                    controller_side(call.name),
                    self.serve_goal(call),
                    cancel_callback=self.serve_cancel(call),
                    callback_group=forwarding,
                )

    @staticmethod
    def matching(topic: Any) -> Callable[[Any], None]:
        """The publisher's matched event: how many subscribers ``topic`` has now (``Topic.matched``)."""

        def matched(status: Any) -> None:
            topic.matched = int(status.current_count)

        return matched

    def callback(self, function: Callable[..., Any], *first: Any) -> Callable[..., Any]:
        """``function(*first, *args)`` for rclpy: under the lock in a supervision layer (a
        multi-threaded executor), never raising into the executor."""
        locked = self.mode == "supervisor"

        def run(*args: Any) -> Any:
            try:
                if locked:
                    with self.lock:
                        return function(*(first + args))
                return function(*(first + args))
            except Exception as error:  # keep the node alive
                self.warnings("%s: %s: %s" % (getattr(function, "__name__", "callback"), type(error).__name__, error))
                return None

        return run

    def stamped(self, topic: Any) -> Any:
        """The subscription callback of ``topic``: two parameters, so that rclpy passes the message
        with its info, which tells when its publisher sent it (DDS's source timestamp)."""
        receive = self.callback(self.receive, topic)

        def take(message: Any, info: Any) -> None:
            stamp = None
            try:
                nanoseconds = int(info["source_timestamp"])
                stamp = nanoseconds / 1e9 if nanoseconds > 0 else None
            except Exception:
                pass
            receive(message, stamp)

        return take

    def acknowledged(self, topic: Any) -> bool:
        """Whether every subscriber of a command topic acknowledged all it was sent."""
        return bool(topic.publisher.wait_for_all_acked(self.NOW))

    def claimers(self) -> int:
        return max(0, self.count_publishers(self.resolve_topic_name(CLAIM_TOPIC)) - 1)

    def ask_report(self, component: str, client: Any) -> bool:
        if not client.service_is_ready():
            return False
        future = client.call_async(self.trigger_request())
        future.add_done_callback(self.callback(self.reported_by, component))
        return True

    # ---- the cycle and data ---------------------------------------------------------------------
    def cycle(self) -> None:
        for timer in self.spent:
            self.destroy_timer(timer)
        self.spent = []
        NodeCore.cycle(self)

    # ---- services and actions of a controller ------------------------------------------------------
    def when_ready(self, call: Call, ready: Callable[[], bool], go: Callable[[], None]) -> None:
        """``go()`` once the server is there; the error event after ``server_timeout``
        seconds without it. Never blocks the executor."""
        if ready():
            go()
            return
        timeout = self.params["server_timeout"]
        self.warnings(
            "%s %s is not available; waiting up to %.1f s" % (call.kind, call.name, timeout), "wait " + call.name
        )
        deadline = time.monotonic() + timeout
        number = call.goal
        state: Dict[str, Any] = {}

        def poll() -> None:
            if number != call.goal:  # cancelled meanwhile
                state["timer"].cancel()
                self.spent.append(state["timer"])
            elif ready():
                state["timer"].cancel()
                self.spent.append(state["timer"])
                go()
            elif time.monotonic() >= deadline:
                state["timer"].cancel()
                self.spent.append(state["timer"])
                self.warnings(
                    "%s %s: no server after %.1f s; failed" % (call.kind, call.name, timeout), "gone " + call.name
                )
                self.answer(call.error, None)

        state["timer"] = self.create_timer(POLL_SECONDS, self.callback(poll))

    def subscribers(self, publisher: Any) -> int:
        return int(publisher.get_subscription_count())

    def call_service(self, call: Call, request: Any) -> bool:
        call.goal += 1
        number = call.goal

        def go() -> None:
            future = call.client.call_async(request)
            future.add_done_callback(self.callback(self.answered, call, number))

        self.when_ready(call, call.client.service_is_ready, go)
        return True

    def answered(self, call: Call, number: int, future: Any) -> None:
        if number != call.goal:
            return
        try:
            response = future.result()
        except Exception as error:
            self.warnings("service %s failed: %s" % (call.name, error), "failed " + call.name)
            response = None
        self.answer(call.error if response is None else call.response, response)

    def start_goal(self, call: Call, goal: Any) -> bool:
        call.goal += 1
        number = call.goal

        def go() -> None:
            future = call.client.send_goal_async(goal, feedback_callback=self.callback(self.feedback, call, number))
            future.add_done_callback(self.callback(self.accepted, call, number))

        self.when_ready(call, call.client.server_is_ready, go)
        return True

    def feedback(self, call: Call, number: int, message: Any) -> None:
        if number == call.goal:
            self.answer(call.feedback, message.feedback)

    def accepted(self, call: Call, number: int, future: Any) -> None:
        try:
            handle = future.result()
        except Exception as error:
            self.warnings("action %s: %s" % (call.name, error), "failed " + call.name)
            handle = None
        if number != call.goal:
            if handle is not None and handle.accepted:
                handle.cancel_goal_async()  # cancelled before the server accepted it
            return
        if handle is None or not handle.accepted:
            self.answer(call.error, None)
            return
        call.handle = handle
        handle.get_result_async().add_done_callback(self.callback(self.done, call, number))

    def done(self, call: Call, number: int, future: Any) -> None:
        if number != call.goal:
            return  # a goal this node cancelled, or an older one
        try:
            answer = future.result()
        except Exception as error:
            self.warnings("action %s: %s" % (call.name, error), "failed " + call.name)
            answer = None
        if answer is not None and answer.status == SUCCEEDED:
            self.answer(call.response, answer.result)
        else:
            self.answer(call.error, None)

    def cancel_goal(self, call: Call) -> bool:
        call.goal += 1  # results of the cancelled goal are ignored
        handle, call.handle = call.handle, None
        if handle is not None:
            handle.cancel_goal_async()
        return True

    # ---- supervision layer: calls and goals from the controller ---------------------------------------
    def wait_for(self, future: Any, stop: Callable[[], bool] = lambda: False) -> Any:
        """The result of a future that other executor threads complete (None if it failed)."""
        while not future.done():
            if stop() or not ok():
                return None
            time.sleep(0.001)
        try:
            return future.result()
        except Exception as error:
            self.warnings("call failed: %s" % (error,), "call failed")
            return None

    def serve_call(self, call: Call) -> Callable[..., Any]:
        def serve(request: Any, response: Any) -> Any:
            """The controller calls the service (on a thread of its own): forwarded if the
            supervisor allows it; a blocked call is answered with an empty response."""
            with self.lock:
                allowed = self.admit(call, request)
            if not allowed:
                return response
            answer = None
            if call.client.wait_for_service(timeout_sec=self.params["server_timeout"]):
                answer = self.wait_for(call.client.call_async(request))
            with self.lock:
                self.answer(call.error if answer is None else call.response, answer)
            return answer if answer is not None else response

        return serve

    def serve_goal(self, call: Call) -> Callable[..., Any]:
        def serve(goal_handle: Any) -> Any:
            """The controller sends a goal (on a thread of its own): forwarded if the supervisor
            allows it, feedback and result passed back; a blocked goal is aborted."""
            with self.lock:
                allowed = self.admit(call, goal_handle.request)
                if allowed:
                    call.goal += 1
                    number = call.goal
            if not allowed:
                goal_handle.abort()
                return call.type.Result()
            handle = None
            if call.client.wait_for_server(timeout_sec=self.params["server_timeout"]):
                handle = self.wait_for(
                    call.client.send_goal_async(
                        goal_handle.request,
                        feedback_callback=lambda message: self.pass_feedback(
                            call, number, message.feedback, goal_handle
                        ),
                    )
                )
            if handle is None or not handle.accepted:
                with self.lock:
                    if number == call.goal:
                        self.answer(call.error, None)
                goal_handle.abort()
                return call.type.Result()
            with self.lock:
                call.handle = handle
            answer = self.wait_for(handle.get_result_async(), lambda: number != call.goal)
            with self.lock:
                if number != call.goal:  # cancelled, by the controller or by the supervisor
                    ok = None
                elif answer is not None and answer.status == SUCCEEDED:
                    self.answer(call.response, answer.result)
                    ok = True
                else:
                    self.answer(call.error, None)
                    ok = False
            if ok is None and goal_handle.is_cancel_requested:
                goal_handle.canceled()
            elif ok:
                goal_handle.succeed()
            else:
                goal_handle.abort()
            return answer.result if answer is not None else call.type.Result()

        return serve

    def pass_feedback(self, call: Call, number: int, feedback: Any, goal_handle: Any) -> None:
        with self.lock:
            if number != call.goal:
                return
            self.answer(call.feedback, feedback)
        goal_handle.publish_feedback(feedback)

    def serve_cancel(self, call: Call) -> Callable[[Any], Any]:
        def cancel(goal_handle: Any) -> Any:
            """The controller cancels its goal: forwarded if the supervisor allows the cancel."""
            with self.lock:
                if call.cancel is not None and self.supervisor.perform(call.cancel.name):
                    self.supervisor.settle()
                    self.checkpoint()
                    return CancelResponse.ACCEPT
                self.blocked(
                    call.cancel.name if call.cancel else None, call.name, "the supervisor does not allow it now"
                )
                return CancelResponse.REJECT

        return cancel

    def forward_call(self, call: Call, event: Any, data: Any) -> bool:
        if event.kind == "cancel":  # the supervisor itself cancels: the forwarding thread ends the goal
            return self.cancel_goal(call)
        return True


def describe(error: BaseException) -> str:
    return "%s: %s" % (type(error).__name__, error)


def start(arguments: List[str]) -> None:
    """``rclpy.init``; where ROS cannot write its log files (``ROS_HOME`` or ``ROS_LOG_DIR`` read-only
    or full), said once, and started again logging to the console only."""
    try:
        rclpy.init(args=arguments)
    except Exception as error:
        if "logging" not in str(error):
            raise
        print(
            "[robosc] ROS cannot write its log files (%s): the node logs to the console only (set ROS_LOG_DIR "
            "to a folder it may write)" % (describe(error),),
            file=sys.stderr,
        )
        try_shutdown()
        rclpy.init(args=[*arguments, "--ros-args", "--disable-external-lib-logs"])
        return
    folder = os.environ.get("ROS_LOG_DIR") or os.path.join(
        os.environ.get("ROS_HOME") or os.path.join(os.path.expanduser("~"), ".ros"), "log"
    )
    with contextlib.suppress(OSError):  # ROS's logger says nothing when its file cannot grow
        if os.statvfs(folder).f_bavail == 0:
            print("[robosc] the disk of ROS's log files (%s) is full: log lines go to the console only" % folder,
                  file=sys.stderr)


def main(
    robot_class: Any, mode: str = "controller", args: Optional[List[str]] = None, node_name: Optional[str] = None
) -> int:
    """Run the node until shut down; returns the exit status."""
    arguments = args if args is not None else sys.argv
    # acknowledgements within milliseconds (see profiles.py), unless the user has a profile of their own
    written = None
    if not (os.environ.get("FASTRTPS_DEFAULT_PROFILES_FILE") or os.environ.get("FASTDDS_DEFAULT_PROFILES_FILE")):
        try:
            written = profiles.write(robot_class, arguments)
            os.environ["FASTRTPS_DEFAULT_PROFILES_FILE"] = written
        except OSError as error:  # no temporary file: the profile as it comes, for every writer
            print("[robosc] %s: every command topic gets the 10 ms heartbeat" % (error,), file=sys.stderr)
            os.environ["FASTRTPS_DEFAULT_PROFILES_FILE"] = os.path.join(os.path.dirname(__file__), profiles.DEFAULT)
    try:
        start(arguments)
        node = SupervisorNode(robot_class, mode, node_name)
    except Exception as error:  # a message type missing, or ROS itself cannot start: said, no traceback
        print("[robosc] cannot start: %s" % (error if isinstance(error, MissingType) else describe(error)), file=sys.stderr)
        try_shutdown()
        return 1
    finally:  # Fast DDS has read it when the node's participant was made (or will not)
        if written is not None:
            with contextlib.suppress(OSError):
                os.remove(written)
    node.log("info", "robosc supervisor of %s running (%s, %s Hz)" % (robot_class.ROBOT, mode, node.params["rate"]))
    # a supervision layer forwarding calls or goals waits for the robot on threads of its own
    waits = mode == "supervisor" and bool(node.service_calls or node.action_calls)
    executor = MultiThreadedExecutor(num_threads=4) if waits else SingleThreadedExecutor()
    executor.add_node(node)
    status = 0
    try:
        executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    except Exception as error:  # a shutdown (SIGTERM) can end the wait set under the executor
        if ok():
            node.log("error", "the node stopped: %s: %s" % (type(error).__name__, error))
            status = 1
    finally:
        node.close()
        with contextlib.suppress(Exception):  # already gone with its context
            node.destroy_node()
        try_shutdown()
    return status
