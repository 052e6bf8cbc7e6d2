"""A robot's name names its ROS package (``MazeSolver`` -> ``maze_solver_robosc``), its node
and its files; ROS package names begin with a lower-case letter (REP 144; catkin_pkg refuses
``_hidden_robosc``), so a robot's name begins with a letter. (Every name has at most
``transformer.MAX_NAME`` characters, so that file names stay within the file system's limit.)"""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Model


def check(model: Model) -> Iterator[Diagnostic]:
    if model.kind == "robot" and model.name_span is not None and not model.name[:1].isalpha():
        yield error(
            model.name_span,
            f"robot '{model.name}' names its ROS package, node and files, and a ROS package name begins "
            "with a letter",
            Code.PACKAGE_NAME,
            f"rename the robot, e.g. '{model.name.lstrip('_') or 'Robot'}'",
        )
