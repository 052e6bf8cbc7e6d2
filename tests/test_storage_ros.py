"""Storage that fails under a node (issue 47, part 4), on real ROS 2 and ROS 1: ``ROS_HOME``
read-only, and a full disk under ROS's log files and the event log. The node starts and runs
where it can, says once what it cannot write, leaves nothing in ``/dev/shm`` and ends without a
traceback. The folders are tmpfs mounts the test makes and removes (it needs root)."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

import disks
from ros_support import ROS1_PYTHON, Ros1, Ros2, build_package, unavailable, wait_until

MODEL = "examples/maze_solver.rscd"
RUNNING = "robosc supervisor of MazeSolver running"


@contextlib.contextmanager
def mounted(folder: Path, options: str) -> Iterator[Path]:
    try:
        with disks.mounted(folder, options) as disk:
            yield disk
    except disks.CannotMount as error:
        unavailable(f"a tmpfs mount ({error})")


@contextlib.contextmanager
def full(folder: Path) -> Iterator[Path]:
    try:
        with disks.full(folder) as disk:
            yield disk
    except disks.CannotMount as error:
        unavailable(f"a tmpfs mount ({error})")


def ended(process: subprocess.Popen[bytes], log: Path) -> str:
    """Stop the node as a launch file does (SIGINT), wait for it to end; its output."""
    process.send_signal(signal.SIGINT)
    try:
        process.wait(20)
    except subprocess.TimeoutExpired:
        process.kill()
        raise
    return log.read_text(errors="replace")


def started(ros: Ros1 | Ros2, command: list[str], env: dict[str, str], name: str) -> tuple[subprocess.Popen[bytes], Path]:
    process = ros.processes.start(name, command, env)
    log = ros.processes.logs / f"{name}.log"
    assert wait_until(lambda: RUNNING in log.read_text(errors="replace") or process.poll() is not None, 30, 0.05)
    return process, log


def ros2_node(package: Path, *params: str) -> list[str]:
    module = next(p.name for p in package.iterdir() if (p / "node.py").exists())
    return [sys.executable, "-m", f"{module}.node", "--ros-args", *(x for p in params for x in ("-p", p))]


def test_ros2_a_read_only_ros_home_starts_the_node_logging_to_the_console(ros2: Ros2, tmp_path: Path) -> None:
    """Before: rclpy's raw traceback at start (failed to initialize logging), and the node's Fast
    DDS profile left in /dev/shm."""
    package = build_package(MODEL, 2, "controller", tmp_path)
    before = disks.profiles()
    with mounted(tmp_path / "home", "ro") as home:
        env = {**ros2.env, "ROS_HOME": str(home), "PYTHONPATH": str(package)}
        env.pop("ROS_LOG_DIR", None)
        process, log = started(ros2, ros2_node(package), env, "read_only")
        assert process.poll() is None, log.read_text()
        output = ended(process, log)
    assert process.returncode == 0, output
    assert output.count("ROS cannot write its log files") == 1, output
    assert "Traceback" not in output
    assert disks.profiles() <= before


def test_ros2_a_full_disk_is_said_once_and_the_node_ends_cleanly(ros2: Ros2, tmp_path: Path) -> None:
    """ROS's log files and the event log on a full disk: each said once; no OSError at the end."""
    package = build_package(MODEL, 2, "controller", tmp_path)
    with full(tmp_path / "disk") as disk:
        env = {**ros2.env, "ROS_HOME": str(disk), "ROS_LOG_DIR": str(disk / "log"), "PYTHONPATH": str(package)}
        params = (f"event_log:={disk / 'events.jsonl'}", "wait_for_data:=false", "trust_initial_state:=true", "rate:=50.0")
        process, log = started(ros2, ros2_node(package, *params), env, "full")
        ros2.spin(1.0)  # cycles, each with its state to log
        assert process.poll() is None, log.read_text()
        output = ended(process, log)
    assert process.returncode == 0, output
    assert output.count("the disk of ROS's log files") == 1, output
    assert output.count("cannot write the event log") == 1, output
    assert "Traceback" not in output and "OSError" not in output.replace("(OSError: [Errno 28]", ""), output


def test_ros1_a_read_only_ros_home_leaves_the_node_running(ros1: Ros1, tmp_path: Path) -> None:
    """rospy says it cannot make its log folder; the node runs and ends cleanly."""
    package = build_package(MODEL, 1, "controller", tmp_path)
    script = str(next((package / "scripts").glob("*_node")))
    with mounted(tmp_path / "home", "ro") as home:
        env = {**ros1.env, "ROS_HOME": str(home), "ROS_LOG_DIR": str(home / "log")}
        process, log = started(ros1, [ROS1_PYTHON, script, "_wait_for_data:=false"], env, "read_only1")
        assert process.poll() is None, log.read_text()
        output = ended(process, log)
    assert process.returncode == 0, output
    assert RUNNING in output and "Traceback" not in output and "Logging error" not in output, output


def test_ros1_a_full_disk_is_said_once_and_the_node_ends_cleanly(ros1: Ros1, tmp_path: Path) -> None:
    """rospy's log file on a full disk printed a traceback for each line it could not write (and
    at the end); now one line says so. (A read-only ROS_HOME: rospy warns, and the node runs.)"""
    package = build_package(MODEL, 1, "controller", tmp_path)
    script = str(next((package / "scripts").glob("*_node")))
    with full(tmp_path / "disk") as disk:
        env = {**ros1.env, "ROS_HOME": str(disk), "ROS_LOG_DIR": str(disk / "log")}
        params = [f"_event_log:={disk / 'events.jsonl'}", "_wait_for_data:=false", "_trust_initial_state:=true"]
        process, log = started(ros1, [ROS1_PYTHON, script, *params], env, "full1")
        assert wait_until(lambda: "held: movement" in log.read_text(errors="replace"), 10, 0.05)
        assert process.poll() is None, log.read_text()
        output = ended(process, log)
    assert process.returncode == 0, output
    assert output.count("cannot write ROS's log file") == 1, output
    assert output.count("cannot write the event log") == 1, output
    assert "Traceback" not in output and "Logging error" not in output, output


pytestmark = pytest.mark.skipif(os.geteuid() != 0 and not os.environ.get("CI"), reason="mounts need root")
