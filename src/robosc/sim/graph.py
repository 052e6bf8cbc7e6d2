"""A private ROS graph on this machine for one simulation: a rosmaster of its own on
127.0.0.1 (ROS 1) or a domain id of its own with discovery on localhost (ROS 2), the
simulator's node, and one controller node per robot in its namespace (``/robot1`` ...), all
from one generated package.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import socket
import subprocess
import sys
import time
from pathlib import Path

from robosc import children
from robosc.sim.session import Bridge, SessionError

BRIDGE_PACKAGE = "robosc_sim_bridge"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _port_open(port: int) -> bool:
    with contextlib.suppress(OSError), socket.create_connection(("127.0.0.1", port), timeout=0.2):
        return True
    return False


def copy_bridge(folder: Path) -> Path:
    """The simulator's node, copied where the middleware's interpreter can import it."""
    target = folder / BRIDGE_PACKAGE
    if target.exists():
        shutil.rmtree(target)
    source = Path(__file__).resolve().parent / "bridge"
    target.mkdir(parents=True)
    for file in source.glob("*.py"):
        shutil.copyfile(file, target / file.name)
    return folder


class Graph:
    """The processes of one simulation; ``stop()`` ends them all, the last started first."""

    def __init__(self, ros: int, folder: Path, domain: int | None = None, ros1_python: str | None = None) -> None:
        self.ros = ros
        self.folder = folder
        self.logs = folder / "logs"
        self.logs.mkdir(parents=True, exist_ok=True)
        self.processes: list[tuple[str, subprocess.Popen[bytes]]] = []
        self.bridge_copied = False
        self.ros1_python = ros1_python or os.environ.get("ROBOSC_ROS1_PYTHON", "/usr/bin/python3")
        base = {k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "PYTHON", "AMENT_", "RMW_"))}
        base["PYTHONUNBUFFERED"] = "1"
        if ros == 1:
            port = free_port()
            self.env = {
                **base,
                "ROS_MASTER_URI": f"http://127.0.0.1:{port}",
                "ROS_HOSTNAME": "127.0.0.1",
                "ROS_IP": "127.0.0.1",
                "ROS_HOME": str(folder / "ros_home"),
                "ROS_LOG_DIR": str(folder / "ros_home" / "log"),
            }
            self._start("rosmaster", [self.ros1_python, "/usr/bin/rosmaster", "--core", "-p", str(port)], self.env)
            end = time.monotonic() + 20
            while not _port_open(port):
                if time.monotonic() > end or self.processes[-1][1].poll() is not None:
                    self.stop()
                    raise SessionError("the rosmaster did not start:\n" + self.output())
                time.sleep(0.05)
        else:
            self.domain = domain if domain is not None else 100 + os.getpid() % 100
            self.env = {
                **os.environ,
                "ROS_DOMAIN_ID": str(self.domain),
                "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
                "ROS_HOME": str(folder / "ros_home"),  # the controllers' logs: this run's own
                "PYTHONUNBUFFERED": "1",
            }

    def _start(self, name: str, command: list[str], env: dict[str, str], pipe: bool = False) -> subprocess.Popen[bytes]:
        log = open(self.logs / f"{name}.log", "wb")  # noqa: SIM115 (kept open by the process)
        process = children.start(
            command,
            env=env,
            stdout=subprocess.PIPE if pipe else log,
            stderr=log,
            stdin=subprocess.PIPE if pipe else subprocess.DEVNULL,
        )
        log.close()
        self.processes.append((name, process))
        return process

    def bridge_folder(self) -> Path:
        """Where the simulator's node is copied for this graph's nodes to import: once per graph,
        so that a folder kept from an earlier run gets this run's, and a node still starting is
        never left without it while the next one is started."""
        folder = self.folder / "bridge"
        if not self.bridge_copied:
            copy_bridge(folder)
            self.bridge_copied = True
        return folder

    def bridge(self, process: str = "simulator", node: str = "robosc_sim") -> Bridge:
        """The simulator's node (or, in a fleet's world, a robot's driver: ``process`` names it
        in the logs and in ``failed()``, ``node`` on the graph)."""
        folder = self.bridge_folder()
        python = self.ros1_python if self.ros == 1 else sys.executable
        env = {**self.env, "PYTHONPATH": str(folder), "ROBOSC_SIM_NODE": node}
        return Bridge(self._start(process, [python, "-m", f"{BRIDGE_PACKAGE}.ros{self.ros}"], env, pipe=True))

    def controller(
        self, package: Path, robot: str, params: dict[str, object], process: str | None = None
    ) -> subprocess.Popen[bytes]:
        """One instance of the generated controller package, in namespace ``/robot``; its
        process is named ``process`` (default: ``robot``) in the logs and in ``failed()``."""
        process = process or robot
        if self.ros == 1:
            script = next((package / "scripts").glob("*_node"))
            args = [f"__ns:=/{robot}", *(f"_{k}:={_text(v)}" for k, v in params.items())]
            return self._start(process, [self.ros1_python, str(script), *args], self.env)
        module = next(p.name for p in package.iterdir() if (p / "node.py").exists())
        args = ["--ros-args", "-r", f"__ns:=/{robot}", "-p", "use_sim_time:=true"]
        for key, value in params.items():
            args += ["-p", f"{key}:={_text(value)}"]
        env = {**self.env, "PYTHONPATH": str(package)}
        return self._start(process, [sys.executable, "-m", f"{module}.node", *args], env)

    def failed(self, sim: object) -> str | None:
        """Why the run cannot go on: a process of the graph that ended (a controller killed or
        crashed, the rosmaster), with its exit status and the simulated time; None if all run."""
        for name, process in self.processes:
            status = process.poll()
            if status is not None and name != "simulator":
                what = "the controller of " + name if name.startswith("robot") else "the " + name.replace("_", " of ", 1)
                how = f"killed by signal {-status}" if status < 0 else f"exit status {status}"
                return f"{what} died at {getattr(sim, 'time', 0.0):.1f} s simulated ({how})"
        return None

    def output(self, lines: int = 15) -> str:
        parts = []
        for name, _ in self.processes:
            text = (self.logs / f"{name}.log").read_text(errors="replace").splitlines()[-lines:]
            if text:
                parts.append(f"--- {name}\n" + "\n".join(text))
        return "\n".join(parts)

    def stop(self) -> None:
        children.stop([process for _, process in self.processes])


def _text(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)
