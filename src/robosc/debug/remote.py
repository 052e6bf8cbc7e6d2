"""``robosc view``: the live view of a controller running elsewhere on the ROS graph. The
controller publishes its page (latched) and its events on ``live_view/*``; a listener under
the middleware's interpreter (``remote_listener.py``) passes them here, and the page is served
on this machine's 127.0.0.1, fed as if the node served it itself.
"""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any, Protocol

from robosc import children
from robosc.jsonlines import LinePeer, PeerGone

LISTENER = Path(__file__).resolve().parent / "remote_listener.py"


class RemoteError(Exception):
    """No controller found, or the middleware could not be reached."""


class Listener:
    """The listener process; its lines on a queue (None: it ended)."""

    def __init__(self, ros: int, discover: float = 2.0) -> None:
        if ros == 1:
            python = os.environ.get("ROBOSC_ROS1_PYTHON", "/usr/bin/python3")
            env = {k: v for k, v in os.environ.items() if not k.startswith("PYTHON")}
        else:
            python = sys.executable
            env = dict(os.environ)
        env["PYTHONUNBUFFERED"] = "1"
        try:
            self.process = children.start(
                [python, str(LISTENER), str(ros), str(discover)],
                env=env,
                stdin=subprocess.PIPE,
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
            )
        except OSError as exc:
            raise RemoteError(f"cannot start {python}: {exc.strerror or exc}") from None
        self.peer = LinePeer(self.process)
        self.lines = self.peer.lines
        self.errors: list[str] = []
        assert self.process.stderr is not None
        threading.Thread(target=self._errors, args=(self.process.stderr,), daemon=True).start()

    def _errors(self, stream: IO[bytes]) -> None:
        for raw in stream:
            self.errors = [*self.errors[-19:], raw.decode("utf-8", "replace").rstrip()]

    def send(self, op: str, **fields: Any) -> None:
        try:
            self.peer.send(op, **fields)
        except PeerGone:
            raise RemoteError("the ROS listener ended" + self.why()) from None

    def expect(
        self, op: str, timeout: float, nothing: str = "", also: Callable[[dict[str, Any]], None] | None = None
    ) -> dict[str, Any]:
        """The next line of ``op``; ``also`` sees each line before it. RemoteError (saying
        ``nothing``) when none comes in ``timeout`` seconds, or when the listener ended."""

        def wanted(message: dict[str, Any]) -> bool:
            if message.get("op") == op:
                return True
            if also is not None:
                also(message)
            return False

        try:
            found = self.peer.wait_for(wanted, timeout)
        except PeerGone:
            raise RemoteError("the ROS listener ended" + self.why()) from None
        if found is None:
            raise RemoteError(nothing or f"nothing came from ROS in {timeout:g} s")
        return found

    def why(self) -> str:
        time.sleep(0.2)  # its last words
        return (":\n" + "\n".join(self.errors[-8:])) if self.errors else ""

    def close(self) -> None:
        self.peer.quit()
        with contextlib.suppress(subprocess.TimeoutExpired):
            self.process.wait(timeout=5)
        children.stop([self.process], grace=5)


def find_robots(listener: Listener, timeout: float = 60.0) -> list[str]:
    """The namespaces of the controllers that publish their live view."""
    robots = listener.expect("robots", timeout).get("robots")
    return [str(r) for r in robots] if isinstance(robots, list) else []


class Poses(Protocol):
    """What a view adds from pose topics (a fleet's map: robosc.sim.view.PoseFeed)."""

    def page(self, html: str) -> str:
        """The page to serve instead of ``html`` (raises RemoteError where it cannot)."""

    def topics(self) -> list[list[str]]:
        """[name, topic relative to the namespace] of each geometry_msgs/Pose2D topic to follow."""

    def attach(self, publish: Callable[[dict[str, Any]], None]) -> None:
        """Where the records it makes go (the served view's publish)."""

    def event(self, record: dict[str, Any]) -> None:
        """Each event record of the controller's, after the page has it."""

    def pose(self, name: str, pose: list[float]) -> None:
        """A pose that came on the topic named ``name``."""


def watch(listener: Listener, namespace: str, port: int = 8765, timeout: float = 20.0, poses: Poses | None = None) -> Any:
    """Serve the live view of the controller in ``namespace`` on 127.0.0.1:``port``; its
    events follow on a thread of their own, and with ``poses``, what the pose topics it names
    say. Returns the LiveView (``.url``, ``.close()``)."""
    from robosc.runtime.onboard.live_server import LiveView

    listener.send("watch", namespace=namespace)
    early: list[dict[str, Any]] = []  # events that came before the page

    def keep(message: dict[str, Any]) -> None:
        if message.get("op") == "event" and isinstance(message.get("record"), dict):
            early.append(message["record"])

    nothing = f"no live view page came from {namespace} in {timeout:g} s"
    page = str(listener.expect("page", timeout, nothing, keep).get("html", ""))
    if poses is not None:
        page = poses.page(page)
    try:
        view = LiveView(page, port=port, watched=True)  # the page says when the robot goes silent
    except OSError as exc:
        raise RemoteError(f"cannot serve on 127.0.0.1:{port}: {exc.strerror or exc}") from None
    if poses is not None:
        poses.attach(view.publish)
        listener.send("poses", poses=poses.topics())

    def forward() -> None:
        while True:
            message = listener.lines.get()
            if message is None:
                return
            record = message.get("record")
            if message.get("op") == "event" and isinstance(record, dict):
                show(record)
            elif message.get("op") == "pose" and poses is not None and isinstance(message.get("pose"), list):
                poses.pose(str(message.get("name")), message["pose"])

    def show(record: dict[str, Any]) -> None:
        if record.get("heartbeat") is True:  # the node is there, though nothing happened
            view.alive()
        else:
            view.publish(record)
            if poses is not None:
                poses.event(record)

    for record in early:
        show(record)
    threading.Thread(target=forward, name="robosc-view", daemon=True).start()
    return view
