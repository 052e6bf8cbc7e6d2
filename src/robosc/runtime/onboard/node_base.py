# -*- coding: utf-8 -*-
"""The base of a generated node's parts (``node.py``'s :class:`~.node.NodeCore`, the live view
and recording, the drivers' reports, the supervision layer): what carries each event
(:class:`Topic`, :class:`Call`), the state they share, set by ``NodeCore.setup``, and what the
rospy and rclpy adapters implement (publishers, subscriber counts, calls, goals, reports)."""

from __future__ import absolute_import, annotations

from typing import Any, Callable, Dict, List, Optional, Tuple

from .delivery import Delivery
from .messages import wire_type
from .recording import EventLog, Recorder
from .supervisor import Supervisor, Warnings


class Topic(object):
    """A topic the node reads (``events`` the robot reports) or writes (commands)."""

    def __init__(self, name: str, communications: List[Any], events: List[Any]) -> None:
        self.name = name
        self.communications = communications  # the model's communications on it (one type)
        self.events = events
        self.takes: List[Tuple[str, Any]] = []  # (event, its communication) of a topic the robot publishes
        # the events of takes when each takes the whole message as its data (object), else None
        self.whole: Optional[Tuple[str, ...]] = None
        self.package, self.type_name = wire_type(communications[0])
        self.type: Any = None  # the message class, loaded by the adapter
        self.publisher: Any = None
        self.forward: Any = None  # supervision layer: the other side of the topic
        # the data last sent and the message made of it, used again while the data is the very same
        # object (a model's constant data is): a message is never changed once made
        self.made: Any = None
        # how many subscribers it has, as the middleware last told (ROS 2's matched events); None: ask
        self.matched: Optional[int] = None


class Call(object):
    """A service or action the node calls, with its events."""

    def __init__(self, communication: Any, events: Dict[str, Any]) -> None:
        self.communication = communication
        self.name = communication.ros_name
        self.kind = communication.kind
        interface: str = communication.interface or "/"
        self.package, _, self.type_name = interface.partition("/")
        self.trigger: Any = events.get("trigger")  # a service and an action always have these three
        self.response: Any = events.get("response")
        self.error: Any = events.get("error")
        self.feedback: Any = events.get("feedback")  # actions only
        self.cancel: Any = events.get("cancel")
        self.type: Any = None  # classes, loaded by the adapter
        self.request: Any = None
        self.client: Any = None
        self.server: Any = None  # supervision layer: what the controller calls
        self.goal = 0  # which goal is current; callbacks of older ones are ignored
        self.handle: Any = None


class NodeBase(object):
    """What the node's parts share (set by ``NodeCore.setup``) and the adapters' part."""

    mode: str
    params: Dict[str, Any]
    log: Callable[[str, str], None]
    warnings: Warnings
    supervisor: Supervisor
    delivery: Delivery
    clock: Callable[[], float]  # what records are stamped with
    sinks: List[Callable[[Dict[str, Any]], Any]]
    recorder: Optional[Recorder]
    event_log: Optional[EventLog]
    live_view: Any
    view_topics: bool  # the page and the events on live_view/*
    beat: float  # when the last heartbeat went out on live_view/events
    report_clients: Dict[str, Any]  # component -> the adapter's client of its report service
    asked: Dict[str, float]  # component -> when its driver was last asked for its state
    # component -> its report requests not answered yet, oldest first: (when it was asked, how many
    # events had changed it then); a driver answers its requests in order
    requests: Dict[str, List[Tuple[float, int]]]
    asked_since: Dict[str, float]  # component -> when its oldest request not answered yet was made
    refused: Optional[str]  # why send() refused the command being forwarded, if it did
    blocked_count: int
    forwarded_count: int
    text_publishers: Dict[str, Any]  # made by the adapter
    text_type: Any

    def checkpoint(self) -> None:
        """After each callback and cycle (``NodeCore``'s)."""
        raise NotImplementedError

    # ---- implemented by the adapters -------------------------------------------------------
    acknowledges = False  # whether the middleware tells when a subscriber received a command

    def publish(self, topic: Topic, message: Any) -> bool:
        """Put a message on a topic (publishers of rospy and rclpy alike)."""
        topic.publisher.publish(message)
        return True

    def publish_text(self, topic_name: str, text: str) -> None:
        """``state`` or ``blocked``, as std_msgs/String (``text_type``), where the adapter made it."""
        publisher = self.text_publishers.get(topic_name)
        if publisher is not None:
            publisher.publish(self.text_type(data=text))

    def listeners(self, topic: Topic) -> int:
        """How many subscribers ``topic`` (a command topic of the robot) has now."""
        return self.subscribers(topic.publisher)

    def text_subscribers(self, topic_name: str) -> int:
        """How many subscribers a text topic of ``text_publishers`` has (0 when it has none)."""
        publisher = self.text_publishers.get(topic_name)
        return self.subscribers(publisher) if publisher is not None else 0

    def acknowledged(self, topic: Topic) -> bool:
        """Whether every subscriber of ``topic`` acknowledged all it was sent (where ``acknowledges``)."""
        return True

    def ask_report(self, component: str, client: Any) -> bool:
        """Ask the driver of ``component`` (through ``client``) for its state; its answer comes back
        through :meth:`report`. False when the request could not go out (no server yet)."""
        return False

    def subscribers(self, publisher: Any) -> int:
        """How many subscribers ``publisher`` (one the adapter made) has now."""
        raise NotImplementedError

    def call_service(self, call: Call, request: Any) -> bool:
        raise NotImplementedError

    def start_goal(self, call: Call, goal: Any) -> bool:
        raise NotImplementedError

    def cancel_goal(self, call: Call) -> bool:
        raise NotImplementedError
