# -*- coding: utf-8 -*-
"""A fleet coordinator node's tasks on the middleware (the queue itself: ``tasks.py``).

* ``robosc/task`` (std_msgs/String, subscribed): a task given, as JSON
  ``{"stops": ["shelf", "depot"], "robot": "bot2", "id": "order-17"}`` (``robot`` and ``id``
  optional) or as text: ``shelf depot`` or ``bot2: shelf depot``.
* ``robosc/tasks`` (std_msgs/String, latched): the queue as JSON after each change:
  ``{"tasks": [{"id", "stops", "robot", "state", "why", "by", "reached", "queued_at",
  "assigned_at", "done_at"}, ...], "counts": {state: n}, "waiting": {robot: seconds since it
  last got on with its task}, "t": the node's time}``.
* ``robosc/queue`` (std_srvs/Trigger): the same JSON, on request.

A task that cannot be read or that no robot can do is in the queue as failed, with why, and in
the node's log."""

from __future__ import absolute_import, annotations

import json
from typing import Any, Callable, Dict, List, Optional, Tuple

from .node_base import NodeBase
from .tasks import FAILED, Dispatcher

TASK_TOPIC = "robosc/task"
TASKS_TOPIC = "robosc/tasks"
QUEUE_SERVICE = "robosc/queue"
MAX_TASK_TEXT = 10000  # characters of one task message read at most
TASK_DEPTH = 1000  # task messages queued for the node at most: an operator may give many at once


def read_task(text: Any) -> Tuple[List[str], Optional[str], Optional[str]]:
    """(stops, robot or None, id or None) from a task message's text; ValueError says why not."""
    if not isinstance(text, str) or not text.strip():
        raise ValueError("a task is JSON {\"stops\": [...]} or text 'stop stop ...' (it was empty)")
    if len(text) > MAX_TASK_TEXT:
        raise ValueError("a task message is at most %d characters" % MAX_TASK_TEXT)
    text = text.strip()
    if text.startswith("{"):
        try:
            given = json.loads(text)
        except ValueError as error:
            raise ValueError("a task in JSON could not be read: %s" % error) from None
        if not isinstance(given, dict):
            raise ValueError("a task in JSON is an object")
        unknown = sorted(set(given) - set(("stops", "robot", "id")))
        if unknown:
            raise ValueError("a task has stops, robot and id, not %s" % ", ".join(unknown))
        stops, robot, name = given.get("stops"), given.get("robot"), given.get("id")
        if not isinstance(stops, list) or not all(isinstance(s, str) for s in stops):
            raise ValueError("a task's stops are a list of location names")
        for what, value in (("robot", robot), ("id", name)):
            if value is not None and not isinstance(value, str):
                raise ValueError("a task's %s is a text" % what)
        return stops, robot, name
    robot = None
    if ":" in text:
        robot, _, text = text.partition(":")
        robot = robot.strip()
    return text.split(), robot or None, None


class NodeTasks(NodeBase):
    """The tasks part of a node: made when the model has a group of robots."""

    dispatcher: Optional[Dispatcher] = None
    queue_changed = False

    def start_tasks(self, robot_class: Any, policy: str, clock: Callable[[], float]) -> None:
        """Give the supervisor a dispatcher if its model has a fleet (a group of instances)."""
        self.dispatcher = None
        self.queue_changed = False
        if not any(route[1] is not None for route in getattr(robot_class, "ROUTES", ())):
            return
        self.dispatcher = Dispatcher(self.supervisor, policy, on_change=self.task_changed, clock=clock)
        self.supervisor.tasks = self.dispatcher
        self.queue_changed = True  # the empty queue, for its readers

    def task_given(self, message: Any) -> None:
        """A message on ``robosc/task`` (std_msgs/String)."""
        if self.dispatcher is None:
            return
        try:
            stops, robot, name = read_task(getattr(message, "data", None))
        except ValueError as error:
            self.dispatcher.refuse(str(error))
        else:
            self.dispatcher.submit(stops, robot, name)
        self.checkpoint()

    def task_changed(self, task: Dict[str, Any]) -> None:
        self.queue_changed = True
        if task["state"] == FAILED:
            self.log("error", "task %s refused: %s" % (task["id"], task["why"]))
        else:
            self.log("info", "task %s %s%s" % (task["id"], task["state"], " (%s)" % task["by"] if task["by"] else ""))

    def queue_text(self) -> str:
        """The queue as the ``robosc/tasks`` topic and the ``robosc/queue`` service give it."""
        if self.dispatcher is None:
            return json.dumps({"tasks": [], "counts": {}, "waiting": {}})
        d = self.dispatcher
        return json.dumps({"tasks": d.queue(), "counts": d.counts(), "waiting": d.waiting(), "t": d.clock()},
                          sort_keys=True)

    def serve_queue(self, _request: Any, response: Any) -> Any:
        """The ``robosc/queue`` service (std_srvs/Trigger), as rclpy calls it."""
        response.success, response.message = True, self.queue_text()
        return response

    def publish_queue(self) -> None:
        if self.queue_changed:
            self.queue_changed = False
            self.publish_text(TASKS_TOPIC, self.queue_text())
