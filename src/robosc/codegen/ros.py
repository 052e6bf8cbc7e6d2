"""ROS 1 (catkin) and ROS 2 (ament_python) packages around the generated supervisor.

:func:`ros_plan` groups a run-time plan by what ROS sees: one publisher per
topic the controller writes, one subscription per topic it reads (several
events may share a topic, e.g. three views of one ``/scan``), a client per
service and action. :func:`generate` renders the package files from templates.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from robosc.codegen.templating import environment
from robosc.language.source import Span
from robosc.runtime.module import module_name, render_module, source_name
from robosc.runtime.plan import Communication, EventPlan, Plan

# basic data without an interface: std_msgs (SEMANTICS.md section 7)
STD_MSGS = {"string": "String", "boolean": "Bool", "integer": "Int64", "double": "Float64", "none": "Empty"}
MODES = ("controller", "supervisor")
# topics of a supervision layer: the controller's side of each remapped topic
CONTROLLER_PREFIX = "/robosc/controller"


class RosError(Exception):
    """The model cannot run on ROS as it is (a service without an interface, one topic with
    two types); ``span`` is the model text to point at."""

    def __init__(self, message: str, span: Span) -> None:
        super().__init__(message)
        self.span = span


def controller_side(name: str) -> str:
    """Where a supervision layer meets the controller: ``/cmd_vel`` -> ``/robosc/controller/cmd_vel``."""
    return CONTROLLER_PREFIX + (name if name.startswith("/") else "/" + name)


@dataclass(frozen=True)
class Import:
    module: str  # "geometry_msgs.msg"
    name: str  # "Twist"


class _Remapped:
    """Something a supervision layer offers the controller under a remapped name."""

    name: str

    @property
    def controller_side(self) -> str:
        return controller_side(self.name)


@dataclass(frozen=True)
class Topic(_Remapped):
    name: str  # the ROS name, e.g. "/cmd_vel"
    attribute: str  # Python attribute suffix for the publisher / subscription
    type: str  # the message class, e.g. "Twist"
    basic: bool  # a std_msgs wrapper: the data is in ``.data``
    empty: bool  # std_msgs/Empty: no data
    events: tuple[EventPlan, ...]  # the events carried on this topic


@dataclass(frozen=True)
class Call(_Remapped):
    """A service or action client."""

    communication: Communication
    name: str
    attribute: str
    type: str  # ROS 1: "SetBool" / "FibonacciAction"; ROS 2: "SetBool" / "Fibonacci"
    request: str  # the request / goal class expression for generation ``ros``
    trigger: EventPlan
    response: EventPlan
    error: EventPlan
    feedback: EventPlan | None = None
    cancel: EventPlan | None = None


@dataclass(frozen=True)
class RosPlan:
    plan: Plan
    ros: int  # 1 or 2
    mode: str
    package: str
    module: str  # the supervisor module's name
    imports: tuple[Import, ...]
    publishers: tuple[Topic, ...]  # topics the controller writes (incoming messages)
    subscriptions: tuple[Topic, ...]  # topics the controller reads (outgoing messages)
    services: tuple[Call, ...]
    actions: tuple[Call, ...]
    dependencies: tuple[str, ...]  # ROS packages for package.xml


def package_name(plan: Plan) -> str:
    """``maze_solver_robosc`` for robot ``MazeSolver`` (a valid ROS package name)."""
    snake = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", plan.robot).lower()
    snake = re.sub(r"[^a-z0-9_]", "_", snake)
    return f"{snake}_robosc"


def _attribute(name: str, taken: set[str]) -> str:
    base = re.sub(r"\W", "_", name.strip("/"), flags=re.ASCII) or "root"
    candidate, n = base, 1
    while candidate in taken:
        n += 1
        candidate = f"{base}_{n}"
    taken.add(candidate)
    return candidate


def _check_interface(c: Communication) -> None:
    """ROS needs a type for everything but basic data on a topic (which goes in std_msgs)."""
    if c.package is not None and c.ros_type is not None:
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


def ros_plan(plan: Plan, ros: int, mode: str = "controller") -> RosPlan:
    if ros not in (1, 2):
        raise ValueError("ROS generation must be 1 or 2")
    if mode not in MODES:
        raise ValueError(f"mode must be one of {', '.join(MODES)}")
    imports: dict[tuple[str, str], Import] = {}
    dependencies = {"std_msgs"}
    dependencies.add("rospy" if ros == 1 else "rclpy")

    def need(module: str, name: str) -> str:
        imports.setdefault((module, name), Import(module, name))
        dependencies.add(module.split(".")[0])
        return name

    need("std_msgs.msg", "String")  # /state and /blocked
    events_by_comm: dict[str, dict[str, EventPlan]] = {}
    for e in plan.events:
        if e.communication is not None:
            events_by_comm.setdefault(e.communication.name, {})[e.kind] = e

    topics: dict[tuple[str, str], list[EventPlan]] = {}
    topic_types: dict[tuple[str, str], tuple[str, bool, bool]] = {}
    services: list[Call] = []
    actions: list[Call] = []
    taken: set[str] = set()
    for c in plan.communications:
        events = events_by_comm.get(c.name, {})
        _check_interface(c)
        if c.kind in ("incoming", "outgoing"):
            if c.package is not None and c.ros_type is not None:
                type_name, basic, empty = need(f"{c.package}.msg", c.ros_type), False, False
            else:
                type_name = need("std_msgs.msg", STD_MSGS[c.data_kind])
                basic, empty = True, c.data_kind == "none"
            key = (c.kind, c.ros_name)
            previous = topic_types.setdefault(key, (type_name, basic, empty))
            if previous[0] != type_name:
                raise RosError(
                    f"'{c.name}' uses topic {c.ros_name} with type {type_name}, "
                    f"but another communication uses it with {previous[0]}",
                    c.span,
                )
            topics.setdefault(key, []).append(events["message"])
            continue
        assert c.package is not None and c.ros_type is not None
        if c.kind == "service":
            type_name = need(f"{c.package}.srv", c.ros_type)
            request = f"{type_name}.Request"
            if ros == 1:  # the request class, which only the controller builds itself
                request = need(f"{c.package}.srv", f"{c.ros_type}Request") if mode == "controller" else request
        elif ros == 1:
            type_name = need(f"{c.package}.msg", f"{c.ros_type}Action")
            request = need(f"{c.package}.msg", f"{c.ros_type}Goal") if mode == "controller" else ""
            dependencies.update({"actionlib", "actionlib_msgs"})
        else:
            type_name = need(f"{c.package}.action", c.ros_type)
            request = f"{type_name}.Goal"
        call = Call(
            c,
            c.ros_name,
            _attribute(c.name, taken),
            type_name,
            request,
            events["trigger"],
            events["response"],
            events["error"],
            events.get("feedback"),
            events.get("cancel"),
        )
        (services if c.kind == "service" else actions).append(call)

    def make(kind: str) -> tuple[Topic, ...]:
        out = []
        for (k, name), events in topics.items():
            if k != kind:
                continue
            type_name, basic, empty = topic_types[(k, name)]
            out.append(Topic(name, _attribute(name, taken), type_name, basic, empty, tuple(events)))
        return tuple(out)

    return RosPlan(
        plan,
        ros,
        mode,
        package_name(plan),
        module_name(plan),
        tuple(sorted(imports.values(), key=lambda i: (i.module, i.name))),
        make("incoming"),
        make("outgoing"),
        tuple(services),
        tuple(actions),
        tuple(sorted(dependencies)),
    )


def generate(plan: Plan, ros: int, mode: str, output: Path, live_page: str | None = None) -> list[Path]:
    """Write the ROS ``ros`` package for ``plan`` under ``output``; returns the files written.
    ``live_page`` is the live view's page (laid out at generation time), served by the node
    when its ``view_port`` parameter is set."""
    rp = ros_plan(plan, ros, mode)
    env = environment()
    context = {"rp": rp, "plan": plan, "source_name": source_name(plan)}
    files: dict[str, str] = {}
    module_text = render_module(plan)
    node = f"{rp.package}_node"
    from importlib.resources import files as package_files

    live_server = package_files("robosc.debug").joinpath("live_server.py").read_text(encoding="utf-8")
    where = "scripts" if ros == 1 else rp.package
    files[f"{where}/robosc_live.py"] = live_server
    if live_page is not None:
        files[f"{where}/live_view.html"] = live_page
    if ros == 1:
        files[f"scripts/{node}.py"] = env.get_template("ros1/node.py.j2").render(**context)
        files[f"scripts/{rp.module}.py"] = module_text
        files["package.xml"] = env.get_template("ros1/package.xml.j2").render(**context)
        files["CMakeLists.txt"] = env.get_template("ros1/CMakeLists.txt.j2").render(node=node, **context)
        files[f"launch/{rp.package}.launch"] = env.get_template("ros1/launch.xml.j2").render(node=node, **context)
    else:
        files[f"{rp.package}/__init__.py"] = ""
        files[f"{rp.package}/node.py"] = env.get_template("ros2/node.py.j2").render(**context)
        files[f"{rp.package}/{rp.module}.py"] = module_text
        files["package.xml"] = env.get_template("ros2/package.xml.j2").render(**context)
        files["setup.py"] = env.get_template("ros2/setup.py.j2").render(node=node, **context)
        files["setup.cfg"] = env.get_template("ros2/setup.cfg.j2").render(**context)
        files[f"resource/{rp.package}"] = ""
        files[f"launch/{rp.package}.launch.py"] = env.get_template("ros2/launch.py.j2").render(node=node, **context)
    written = []
    for relative, text in files.items():
        path = output / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        if relative.startswith("scripts/") and relative.endswith("_node.py"):
            path.chmod(0o755)
        written.append(path)
    return written
