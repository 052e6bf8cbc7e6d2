"""A child process that talks in JSON objects, one a line: how robosc speaks with the parts
that run under a middleware's own interpreter (the simulator's ROS node, ``robosc view``'s
listener)."""

from __future__ import annotations

import json
import queue
import subprocess
import threading
import time
from collections.abc import Callable
from typing import IO, Any


class PeerGone(Exception):
    """The child process no longer reads its standard input."""


class LinePeer:
    """Lines to the process's standard input; the JSON objects of its standard output on
    ``lines`` (None once it ended), each stamped ``received`` (time.perf_counter()) when it came."""

    def __init__(self, process: subprocess.Popen[bytes]) -> None:
        assert process.stdin is not None and process.stdout is not None
        self.process = process
        self._in: IO[bytes] = process.stdin
        self.lines: queue.Queue[dict[str, Any] | None] = queue.Queue()
        threading.Thread(target=self._read, args=(process.stdout,), daemon=True).start()

    def _read(self, stream: IO[bytes]) -> None:
        for raw in stream:
            try:
                message = json.loads(raw)
            except ValueError:
                continue
            if isinstance(message, dict):
                message["received"] = time.perf_counter()
                self.lines.put(message)
        self.lines.put(None)

    def send(self, op: str, **fields: Any) -> None:
        fields["op"] = op
        try:
            self._in.write((json.dumps(fields) + "\n").encode())
            self._in.flush()
        except (BrokenPipeError, ValueError, OSError):
            raise PeerGone(op) from None

    def wait_for(self, condition: Callable[[dict[str, Any]], bool], timeout: float) -> dict[str, Any] | None:
        """The first line from the process that meets ``condition`` (the lines before it are
        used up), or None after ``timeout`` seconds; PeerGone if the process ended first."""
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            try:
                message = self.lines.get(timeout=0.1)
            except queue.Empty:
                continue
            if message is None:
                raise PeerGone("ended")
            if condition(message):
                return message
        return None

    def quit(self) -> None:
        """Ask the process to end, and close its standard input."""
        try:
            self.send("quit")
            self._in.close()
        except (PeerGone, OSError):
            pass
