"""The generated per-robot module (Python 3.8+, standard library only) and the runtime it
runs on: :func:`render_module` writes the module from a plan, :func:`runtime_files` gives
the verbatim copy of :mod:`robosc.runtime.onboard` that goes next to it."""

from __future__ import annotations

import hashlib
import re
from importlib.resources import files
from pathlib import Path

from robosc.codegen.plan import Plan
from robosc.codegen.templating import environment
from robosc.runtime.onboard import VERSION

RUNTIME_PACKAGE = "onboard"  # the runtime's directory next to a generated module
PLAN_PLACEHOLDER = "<plan>"  # replaced by the hash of the module's text


def module_name(plan: Plan) -> str:
    """The generated module's name: ``maze_solver_supervisor`` for robot ``MazeSolver``."""
    snake = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", plan.robot).lower()
    return f"{snake}_supervisor"


def render_module(plan: Plan, relative_names: bool = False) -> str:
    """The module's text; with ``relative_names``, the model's absolute ROS names are made
    relative (``/scan`` -> ``scan``), so that a namespace moves the whole robot."""
    template = environment().get_template("supervisor.py.j2")
    names = {c.name: c.ros_name for c in plan.communications}
    if relative_names:
        names = {k: v.lstrip("/") if v.startswith("/") else v for k, v in names.items()}
    text = template.render(
        plan=plan, version=VERSION, source_name=source_name(plan), ros_names=names, plan_id=PLAN_PLACEHOLDER
    )
    digest = hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]
    return text.replace(repr(PLAN_PLACEHOLDER), repr(digest), 1)


def runtime_files() -> dict[str, str]:
    """The runtime's modules, by file name (``supervisor.py``, ``ros2.py``, ...), as they are, with
    the Fast DDS profile the ROS 2 adapter loads (``fastdds.xml``)."""
    folder = files("robosc.runtime").joinpath(RUNTIME_PACKAGE)
    return {
        entry.name: entry.read_text(encoding="utf-8")
        for entry in sorted(folder.iterdir(), key=lambda e: e.name)
        if entry.name.endswith((".py", ".xml"))
    }


def source_name(plan: Plan) -> str:
    """The model's file name, reduced to characters that are safe in any generated file."""
    return re.sub(r"[^\w.\- ]", "_", Path(plan.source).name).replace("--", "-_")
