"""A stand-in for docs/models/outcomes.rscd's worker on ROS 2, for test_outcomes.py and
benchmarks/faults.py: its task ends broken, done, broken, ... in turn (``status`` 0.2 s after
``start``), its driver reports where the arm is, and every command is checked against where the
arm really is."""

from __future__ import annotations

import time
from typing import Any

READY = {"start": "idle", "home": "done", "repair": "broken"}  # where each command is right


class Worker:
    """The worker's side, on the rclpy ``node``: ``wrong`` lists the commands sent where the arm
    was not where they are right, ``sent`` all, in order."""

    def __init__(self, node: Any) -> None:
        from std_msgs.msg import Empty
        from std_srvs.srv import Trigger

        self.empty = Empty
        self.at, self.ends = "idle", 0
        self.wrong: list[str] = []
        self.sent: list[str] = []
        self.due: list[float] = []
        self.status = node.create_publisher(Empty, "/status", 10)
        for command in READY:
            node.create_subscription(Empty, f"/{command}", self.heard(command), 10)
        node.create_service(Trigger, "/robosc/report/arm", self.report)

    def heard(self, command: str) -> Any:
        def take(_: Any) -> None:
            self.sent.append(command)
            if self.at != READY[command]:
                self.wrong.append(f"{command} while the arm is {self.at}")
            self.at = "working" if command == "start" else "idle"
            if command == "start":
                self.due.append(time.monotonic() + 0.2)

        return take

    def report(self, _: Any, response: Any) -> Any:
        response.success, response.message = True, self.at
        return response

    def step(self) -> None:
        """The task's end, once due: broken and done in turn, said with ``status``."""
        if self.due and self.due[0] <= time.monotonic():
            self.due.pop(0)
            self.ends += 1
            self.at = "broken" if self.ends % 2 else "done"
            self.status.publish(self.empty())
