"""Render the stand-alone supervisor module (Python 3.8+, standard library only) from a plan."""

from __future__ import annotations

from pathlib import Path

from robosc.codegen.templating import environment
from robosc.runtime.plan import Plan


def module_name(plan: Plan) -> str:
    """The generated module's name: ``maze_solver_supervisor`` for robot ``MazeSolver``."""
    import re

    snake = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", plan.robot).lower()
    return f"{snake}_supervisor"


def render_module(plan: Plan) -> str:
    from importlib.metadata import version

    template = environment("robosc.runtime").get_template("supervisor.py.j2")
    return template.render(plan=plan, version=version("robosc"), source_name=source_name(plan))


def source_name(plan: Plan) -> str:
    """The model's file name, reduced to characters that are safe in any generated file."""
    import re

    return re.sub(r"[^\w.\- ]", "_", Path(plan.source).name)
