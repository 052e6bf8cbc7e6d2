"""ROS 1 (catkin) and ROS 2 (ament_python) packages around the generated supervisor.

A package holds the per-robot module (:func:`robosc.codegen.module.render_module`),
a verbatim copy of the runtime (:mod:`robosc.runtime.onboard`, as ``onboard/``), a
node entry of a few lines, the package files and a launch file. :func:`ros_plan`
checks that the model can run on ROS (interfaces, one type per topic) and works
out the dependencies and the supervision layer's remappings; :func:`generate`
writes the files.
"""

from __future__ import annotations

import re
from pathlib import Path

from robosc.codegen.module import RUNTIME_PACKAGE, module_name, render_module, runtime_files, source_name
from robosc.codegen.plan import Communication, Plan
from robosc.codegen.templating import environment, markdown_cell
from robosc.language.source import Span
from robosc.record import record
from robosc.runtime.onboard import VERSION
from robosc.runtime.onboard.messages import SENSOR_PACKAGE, wire_type
from robosc.runtime.onboard.node import PARAMETERS, controller_side
from robosc.runtime.onboard.supervisor import Communication as OnBoard

MODES = ("controller", "supervisor")
ROS_TYPE = re.compile(r"^[A-Z][A-Za-z0-9]*$")  # a ROS message / service / action type name
ROS_PACKAGE = re.compile(r"^[a-z][a-z0-9_]*$")  # REP 144


class RosError(Exception):
    """The model cannot run on ROS as it is (a service without an interface, one topic with
    two types); ``span`` is the model text to point at."""

    def __init__(self, message: str, span: Span) -> None:
        super().__init__(message)
        self.span = span


@record
class RosPlan:
    plan: Plan
    ros: int  # 1 or 2
    mode: str
    package: str
    module: str  # the per-robot module's name
    node: str  # the node's executable
    dependencies: tuple[str, ...]  # ROS packages for package.xml
    remaps: tuple[tuple[str, str], ...]  # supervision layer: (robot side, controller side)
    relative: bool  # the model's absolute names made relative to the node's namespace
    parameters: tuple[tuple[str, str, str], ...]  # (name, default as text, type) for launch files


@record
class Duty:
    """One line of the generated README's table of what a driver provides: a topic, service or
    action of the node's, as the driver meets it."""

    name: str  # as the node uses it (relative to its namespace where it is relative)
    type: str  # the ROS type, as `ros2 interface show` / `rosmsg show` name it
    way: str  # "node -> driver" or "driver -> node"
    qos: str
    does: str  # what the driver does with it


@record
class DriverDuties:
    component: str
    duties: tuple[Duty, ...]


def _type(ros: int, package: str, kind: str, name: str) -> str:
    return f"{package}/{name}" if ros == 1 else f"{package}/{kind}/{name}"


def driver_duties(rp: RosPlan) -> tuple[DriverDuties, ...]:
    """What each component's driver must provide for the node (the generated README's tables):
    every topic, service and action with its type, its QoS and who answers what."""
    depth = next(p.default for p in PARAMETERS if p.name == "qos_depth")
    reliable = f"reliable, volatile, keep last {depth}" if rp.ros == 2 else f"TCPROS, queue_size {depth}"
    names = {c.name: markdown_cell(ros_name(c, rp.relative)) for c in rp.plan.communications}
    out = []
    for driver in rp.plan.drivers:
        answers = dict(driver.answers)
        duties = []
        for c in rp.plan.communications:
            if c.component != driver.component:
                continue
            name = names[c.name]
            if c.kind in ("incoming", "outgoing"):
                package, type_name = wire_type(OnBoard(c.name, c.kind, name, c.interface, c.data_kind))
                ros_type = _type(rp.ros, package, "msg", type_name)
                if c.kind == "incoming":
                    replies = [f"`{names[r]}`" for r in answers.get(c.name, ())]
                    does = "subscribe; each message is one command"
                    if replies:
                        does += f"; after it, publish {' or '.join(replies)}, once, when that happens"
                    duties.append(Duty(name, ros_type, "node -> driver", reliable, does))
                else:
                    best_effort = rp.ros == 2 and package == SENSOR_PACKAGE
                    qos = f"best effort, volatile, keep last {depth}" if best_effort else reliable
                    if any(c.name in replies for replies in answers.values()):
                        does = "publish it once each time it happens, never again for the same"
                    elif c.data_kind != "none":
                        does = "publish as it has new data"
                    else:
                        does = "publish it each time it happens"
                    duties.append(Duty(name, ros_type, "driver -> node", qos, does))
                continue
            assert c.package is not None and c.ros_type is not None
            kind = "srv" if c.kind == "service" else "action"
            does = "serve it; the response is the answer" if c.kind == "service" else (
                "serve it: accept or reject each goal, send feedback, finish with a result"
            )
            duties.append(Duty(name, _type(rp.ros, c.package, kind, c.ros_type), "node -> driver", c.kind, does))
        locations = ", ".join(f"`{markdown_cell(location)}`" for location in driver.locations)
        duties.append(
            Duty(
                markdown_cell(f"robosc/report/{driver.component}"),
                _type(rp.ros, "std_srvs", "srv", "Trigger"),
                "node -> driver",
                "service",
                f"answer `success: true` and, as `message`, where it is now: one of {locations}",
            )
        )
        once = {(d.name, d.way): d for d in reversed(duties)}  # a topic several communications share: once
        kept = [d for d in duties if once[d.name, d.way] is d]
        out.append(DriverDuties(markdown_cell(driver.component), tuple(kept)))
    return tuple(out)


def package_name(plan: Plan) -> str:
    """``maze_solver_robosc`` for robot ``MazeSolver`` (a valid ROS package name)."""
    snake = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", plan.robot).lower()
    snake = re.sub(r"[^a-z0-9_]", "_", snake)
    return f"{snake}_robosc"


def ros_name(c: Communication, relative: bool) -> str:
    """The name the node uses: as the model gives it, or made relative (``/scan`` -> ``scan``)."""
    return c.ros_name.lstrip("/") if relative and c.ros_name.startswith("/") else c.ros_name


def _check_interface(c: Communication) -> None:
    """ROS needs a type for everything but basic data on a topic (which goes in std_msgs)."""
    if c.package is not None and c.ros_type is not None:
        span = c.interface_span or c.span
        if not ROS_TYPE.match(c.ros_type):
            raise RosError(f"'{c.ros_type}' is not a ROS type name (a capital letter, then letters and digits)", span)
        if not ROS_PACKAGE.match(c.package):
            raise RosError(f"'{c.package}' is not a ROS package name (lower case letters, digits, '_')", span)
        return
    if c.kind in ("service", "action"):
        raise RosError(
            f"{c.kind} '{c.name}' needs an interface ('links ...') to run on ROS: "
            f"robosc cannot tell which ROS {'srv' if c.kind == 'service' else 'action'} type to use",
            c.span,
        )
    if c.data_kind == "object":
        raise RosError(
            f"message '{c.name}' carries an object but links no interface: "
            "robosc cannot tell which ROS message type to use",
            c.span,
        )


def _launch_value(default: object) -> tuple[str, str]:
    if isinstance(default, bool):
        return ("true" if default else "false"), "bool"
    return str(default), type(default).__name__


def ros_plan(plan: Plan, ros: int, mode: str = "controller", relative: bool = False) -> RosPlan:
    if ros not in (1, 2):
        raise ValueError("ROS generation must be 1 or 2")
    if mode not in MODES:
        raise ValueError(f"mode must be one of {', '.join(MODES)}")
    dependencies = {"std_msgs", "rospy" if ros == 1 else "rclpy"}
    topic_types: dict[tuple[str, str], tuple[str, str]] = {}
    remaps: dict[str, str] = {}
    for c in plan.communications:
        _check_interface(c)
        name = ros_name(c, relative)
        remaps[name] = controller_side(name)
        if c.kind in ("incoming", "outgoing"):
            package, type_name = wire_type(OnBoard(c.name, c.kind, name, c.interface, c.data_kind))
            dependencies.add(package)
            previous = topic_types.setdefault((c.kind, name), (package, type_name))
            if previous != (package, type_name):
                raise RosError(
                    f"'{c.name}' uses topic {name} with type {package}/{type_name}, "
                    f"but another communication uses it with {previous[0]}/{previous[1]}",
                    c.span,
                )
            continue
        assert c.package is not None
        dependencies.add(c.package)
        if c.kind == "action":
            dependencies.update({"actionlib", "actionlib_msgs"} if ros == 1 else {"action_msgs"})
    package = package_name(plan)
    return RosPlan(
        plan,
        ros,
        mode,
        package,
        module_name(plan),
        f"{package}_node",
        tuple(sorted(dependencies)),
        tuple(remaps.items()),
        relative,
        tuple((p.name, *_launch_value(p.default)) for p in PARAMETERS),
    )


def generate(
    plan: Plan, ros: int, mode: str, output: Path, live_page: str | None = None, relative: bool = False
) -> list[Path]:
    """Write the ROS ``ros`` package for ``plan`` under ``output``; returns the files written.
    ``live_page`` is the live view's page (laid out at generation time), served by the node
    when its ``view_port`` parameter is set. With ``relative``, the model's absolute names
    are made relative, so that a namespace moves the whole robot."""
    rp = ros_plan(plan, ros, mode, relative)
    env = environment()
    context = {
        "rp": rp, "plan": plan, "source_name": source_name(plan), "version": VERSION, "drivers": driver_duties(rp)
    }
    python = f"src/{rp.package}" if ros == 1 else rp.package  # where the Python package goes
    files: dict[str, str] = {
        f"{python}/__init__.py": "",
        f"{python}/{rp.module}.py": render_module(plan, relative),
    }
    for name, text in runtime_files().items():
        files[f"{python}/{RUNTIME_PACKAGE}/{name}"] = text
    if live_page is not None:
        files[f"{python}/live_view.html"] = live_page
    folder = f"ros{ros}"
    files["package.xml"] = env.get_template(f"{folder}/package.xml.j2").render(**context)
    files["setup.py"] = env.get_template(f"{folder}/setup.py.j2").render(**context)
    files["README.md"] = env.get_template(f"{folder}/README.md.j2").render(**context)
    if ros == 1:
        files[f"scripts/{rp.node}"] = env.get_template("ros1/node.py.j2").render(**context)
        files["CMakeLists.txt"] = env.get_template("ros1/CMakeLists.txt.j2").render(**context)
        files[f"launch/{rp.package}.launch"] = env.get_template("ros1/launch.xml.j2").render(**context)
    else:
        files[f"{rp.package}/node.py"] = env.get_template("ros2/node.py.j2").render(**context)
        files["setup.cfg"] = env.get_template("ros2/setup.cfg.j2").render(**context)
        files[f"resource/{rp.package}"] = ""
        files[f"launch/{rp.package}.launch.py"] = env.get_template("ros2/launch.py.j2").render(**context)
    written = []
    for relative_path, text in files.items():
        path = output / relative_path
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        if relative_path.startswith("scripts/"):
            path.chmod(0o755)
        written.append(path)
    return written


__all__ = ["DriverDuties", "Duty", "RosError", "RosPlan", "driver_duties", "generate", "package_name", "ros_name", "ros_plan"]
