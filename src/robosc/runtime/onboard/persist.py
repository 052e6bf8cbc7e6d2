# -*- coding: utf-8 -*-
"""The supervisor's state on disk, so that a node started again (after a crash, ``kill -9``
or a power loss) resumes where it stopped instead of starting from the initial state.

The file is written at every change of the state, atomically: the new text goes to a
temporary file next to it, is flushed and synced, renamed over the old one, and the
directory is synced, so that after any stop the file holds either the old or the new
state, whole. It is refused (and the node starts from the initial state, held until its
data arrives) when it cannot be read, is not whole (its checksum), belongs to another
supervisor (``PLAN``, the hash of the generated module), or is older than ``max_age``.
"""

from __future__ import absolute_import, annotations

import hashlib
import json
import os
import time
from typing import Any, Callable, Dict, Optional, Tuple

FORMAT = 1
MAX_BYTES = 16 * 1024 * 1024  # a state file larger than this is not read
FUTURE_SLACK = 60.0  # seconds a state may seem to come from the future (clocks of a restarted machine)


def default_path(node_name: str) -> str:
    """Where the node called ``node_name`` (its full name, ``/robot1/line_follower_robosc``)
    keeps its state: ``$ROS_HOME/robosc/robot1.line_follower_robosc.state.json`` (ROS_HOME
    defaults to ``~/.ros``). ROS names have no dots, so different nodes get different files."""
    home = os.environ.get("ROS_HOME") or os.path.join(os.path.expanduser("~"), ".ros")
    name = node_name.strip("/").replace("/", ".") or "robosc"
    return os.path.join(home, "robosc", name + ".state.json")


def _checksum(body: Dict[str, Any]) -> str:
    return hashlib.sha256(json.dumps(body, sort_keys=True).encode("utf-8")).hexdigest()


class StateFile(object):
    """The persisted state of one node's supervisor ``robot`` with plan ``plan``."""

    def __init__(
        self, path: str, robot: str, plan: str, max_age: float, clock: Callable[[], float] = time.time
    ) -> None:
        self.path = path
        self.robot = robot
        self.plan = plan
        self.max_age = max_age
        self.clock = clock
        self.last: Optional[Dict[str, Any]] = None  # the fields written last
        self.writes = 0
        self.age = 0.0  # how old the state was when it was loaded

    def load(self) -> Tuple[Optional[Dict[str, Any]], Optional[str]]:
        """``(fields, None)`` for a state to resume, ``(None, None)`` when there is no file,
        ``(None, why)`` when there is one that must not be resumed."""
        try:
            size = os.path.getsize(self.path)
        except OSError:
            if not os.path.lexists(self.path):
                return None, None
            return None, "cannot be read"
        if size > MAX_BYTES:
            return None, "too large (%d bytes)" % size
        try:
            with open(self.path, "rb") as handle:
                text = handle.read(MAX_BYTES + 1).decode("utf-8")
            document = json.loads(text)
        except (OSError, UnicodeDecodeError) as error:
            return None, "cannot be read (%s)" % (error,)
        except ValueError as error:
            return None, "corrupt (%s)" % (error,)
        if not isinstance(document, dict) or not isinstance(document.get("body"), dict):
            return None, "corrupt (not a robosc state)"
        body = document["body"]
        if document.get("sha256") != _checksum(body):
            return None, "corrupt (its checksum does not match)"
        if body.get("format") != FORMAT:
            return None, "of another format (%r)" % (body.get("format"),)
        if body.get("robot") != self.robot or body.get("plan") != self.plan:
            return None, "of another supervisor (%s, plan %s; this node runs %s, plan %s)" % (
                body.get("robot"),
                body.get("plan"),
                self.robot,
                self.plan,
            )
        saved = body.get("saved")
        if isinstance(saved, bool) or not isinstance(saved, (int, float)) or saved != saved:
            return None, "corrupt (no time)"
        age = self.clock() - saved
        if age > self.max_age:
            return None, "stale (saved %.0f s ago; state_max_age is %.0f s)" % (age, self.max_age)
        if age < -FUTURE_SLACK:
            return None, "saved %.0f s in the future" % (-age,)
        fields = body.get("fields")
        if not isinstance(fields, dict):
            return None, "corrupt (no state)"
        self.last = fields
        self.age = age
        return fields, None

    def save(self, fields: Dict[str, Any]) -> bool:
        """Write ``fields`` if they differ from what was written last; True when written."""
        if fields == self.last:
            return False
        body = {"format": FORMAT, "robot": self.robot, "plan": self.plan, "saved": self.clock(), "fields": fields}
        text = json.dumps({"body": body, "sha256": _checksum(body)}, sort_keys=True)
        folder = os.path.dirname(self.path) or "."
        if not os.path.isdir(folder):
            os.makedirs(folder)
        temporary = self.path + ".tmp"
        with open(temporary, "w") as handle:
            handle.write(text)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(temporary, self.path)
        try:  # the rename itself survives a power loss once the directory is synced
            descriptor = os.open(folder, os.O_RDONLY)
            try:
                os.fsync(descriptor)
            finally:
                os.close(descriptor)
        except OSError:
            pass
        self.last = fields
        self.writes += 1
        return True
