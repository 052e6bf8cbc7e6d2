"""Rule 15: topic, service and action names are valid ROS graph resource names.

Valid in both ROS 1 and ROS 2: an optional leading ``/`` or ``~/``, then
``/``-separated tokens that start with a letter and hold letters, digits and
``_`` (no ``__``); no empty token, no trailing ``/``.
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Model

_TOKEN = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")


def problem(name: str) -> str | None:
    """Why ``name`` is not a valid ROS name, or None when it is."""
    if not name:
        return "it is empty"
    body = name[2:] if name.startswith("~/") else name[1:] if name[0] in "/~" else name
    if not body:
        return "it names no topic"
    if body.endswith("/"):
        return "it ends with '/'"
    for token in body.split("/"):
        if not token:
            return "it has an empty part ('//')"
        if not _TOKEN.match(token):
            return f"part '{token}' must start with a letter and hold only letters, digits and '_'"
        if "__" in token:
            return f"part '{token}' contains '__'"
    return None


def check(model: Model) -> Iterator[Diagnostic]:
    for communication in model.communications:
        reason = problem(communication.ros_name)
        if reason is not None:
            yield error(
                communication.span,
                f"'{communication.ros_name}' is not a valid ROS name for '{communication.name}': {reason}",
                Code.TOPIC_NAMES,
            )
