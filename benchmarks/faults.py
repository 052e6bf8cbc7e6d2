"""The fault table of issue 29 on real ROS 2 and ROS 1, for this robosc and a baseline revision, side by side:
the warehouse's coordinator (its default parameters) behind stand-ins for the robots and the
door that answer as the model says and report where they are when asked
(tests/warehouse_world.py), every command it sent replayed through the warehouse's rules
against where the robots really were.

* **killed three ways**: ``kill -9`` right after a command went out, while an answer is due
  (it comes while the coordinator is down), and with a robot in the aisle; the same command
  line each time. Forbidden commands, and restarts after which nothing moved for 20 s.
* **killed in the write-ahead window**: ``kill -9`` the instant the coordinator has written
  what a command changes (5fa21e9: its state file replaced, ~8 ms before the command goes out;
  this revision writes no state: its event log recording a decision), five times. Forbidden
  commands, and restarts after which nothing moved for 20 s.
* **a driver killed**: bot2's driver (a process of its own) stopped and killed in the aisle.
  Forbidden commands, and how long bot2 was still commanded.
* **answers twice, and spurious**: every answer sent twice, a ``charged`` every second from a
  robot that is not charging. Forbidden commands, and answers written to the event log as
  events that no robot gave.
* **answers again later**: every answer sent again 0.05 to 1.5 s after it (a flaky bridge, a
  driver's retry), for 60 s. Forbidden commands, and the seconds at the end with no command (a
  fleet that froze).
* **two coordinators**: the same command line twice, 10 s apart, for 60 s; then the first killed.
  Forbidden commands, commands by the second while the first lived, and how long after the
  first's death the second commanded.
* **an event with two outcomes**: docs/models/outcomes.rscd's worker, whose task ends broken,
  done, broken, ... (its driver reports): commands wrong where the arm really was.
* **storage**: the maze solver's node under a read-only ``ROS_HOME``, and with ``ROS_HOME`` and
  its event log on a full disk (tmpfs mounts: root): whether it ran, its exit status after
  SIGINT, tracebacks, Fast DDS profiles left in /dev/shm.
* **the stop held, restarted**: the line follower stopped, killed, started again with its
  state file kept, and with it deleted: move commands in 8 s.

On ROS 1 (rosmaster, Debian's rospy) the coordinator is killed three ways, bot2's driver is
killed, and every answer is given twice, as on ROS 2.

    python benchmarks/faults.py [--baseline 5fa21e9] [--runs 1] [--no-ros1] [--only WORD ...]
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "benchmarks"))

import disks  # noqa: E402
import revision as revisions  # noqa: E402
import warehouse_drivers as drivers  # noqa: E402
from warehouse_world import ANSWERS, ROBOTS, Ros2Wire, World, follow, forbidden, take_driver  # noqa: E402

# the random choice: every command the supervisor allows is sent sooner or later, the hardest test
# of what the coordinator believes (the default policy sends only what given tasks need)
PARAMS = ["-p", "rate:=40.0", "-p", "seed:=3", "-p", "policy:=random"]


def generate(model: str, out: Path, revision: str | None, work: Path) -> tuple[Path, str]:
    """The model's ROS 2 package (this robosc, or ``revision``'s): (folder, module)."""
    revisions.generate(ROOT / model, 2, out, revision, work)
    module = next(p.name for p in out.iterdir() if (p / "node.py").exists())
    return out, module


class Graph:
    """A ROS 2 domain of its own: the test side's node, and the processes started."""

    def __init__(self, work: Path) -> None:
        import rclpy
        from rclpy.executors import SingleThreadedExecutor

        self.work = work
        self.domain = 160 + os.getpid() % 60
        self.env = {
            **os.environ,
            "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
            "ROS_DOMAIN_ID": str(self.domain),
            "ROS_HOME": str(work / "ros_home"),  # each scenario's own (where 5fa21e9 kept its state file)
        }
        self.context = rclpy.Context()
        rclpy.init(context=self.context, domain_id=self.domain)
        self.node = rclpy.create_node("faults", context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.processes: list[subprocess.Popen[bytes]] = []
        self.log = open(work / "faults.log", "ab")  # noqa: SIM115

    def start(
        self, package: tuple[Path, str], *args: str, env: dict[str, str] | None = None
    ) -> subprocess.Popen[bytes]:
        folder, module = package
        process = subprocess.Popen(
            [sys.executable, "-m", f"{module}.node", "--ros-args", *args],
            env={**self.env, "PYTHONPATH": str(folder), **(env or {})},
            stdout=self.log,
            stderr=self.log,
        )
        self.processes.append(process)
        return process

    def spin(self, seconds: float) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.executor.spin_once(timeout_sec=0.01)

    def close(self) -> None:
        for process in self.processes:
            if process.poll() is None:
                process.kill()
                process.wait(10)
        self.executor.shutdown()
        self.node.destroy_node()
        self.context.try_shutdown()
        self.log.close()


def log_of(path: Path) -> list[dict[str, Any]]:
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()] if path.exists() else []


def gos(world: World) -> int:
    return sum(1 for _, e in world.received if e.endswith(".go"))


def killed_three_ways(package: tuple[Path, str], work: Path) -> dict[str, Any]:
    graph = Graph(work)
    log = work / "killed.jsonl"
    world = World(delay=0.3)
    wire = Ros2Wire(graph.node, graph.executor, world)
    try:
        node = graph.start(package, *PARAMS, "-p", f"event_log:={log}")
        frozen = 0
        for moment in ("command", "answer", "aisle"):
            before = len(world.received)
            condition = {
                "command": lambda before=before: len(world.received) > before,
                "answer": lambda: any(not d[2] for d in world.due),
                "aisle": lambda: any(
                    w in ("out2", "out3", "shelf", "back3", "back2") for w in world.rules.where.values()
                ),
            }[moment]
            wire.run(60, condition)
            node.send_signal(signal.SIGKILL)
            node, froze = restarted(graph, package, log, wire, world, node)
            frozen += froze
        return killed(log, world, frozen)
    finally:
        graph.close()


def restarted(
    graph: Graph, package: tuple[Path, str], log: Path, wire: Ros2Wire, world: World, dead: Any
) -> tuple[Any, bool]:
    """The coordinator ``dead`` (killed) down a second (the answers due are sent meanwhile), then
    started again with the same command line: the new process, and whether nothing moved in the
    20 s after."""
    dead.wait(10)
    wire.run(1.0)
    done = gos(world)
    node = graph.start(package, *PARAMS, "-p", f"event_log:={log}")
    return node, not wire.run(20, lambda: gos(world) >= done + 6)


def killed(log: Path, world: World, frozen: int) -> dict[str, Any]:
    found, checked = forbidden(log_of(log), world.received, world.sent)
    return {"forbidden": len(found), "commands": checked, "frozen restarts": frozen}


def signature(folder: Path, pattern: str) -> tuple[Any, ...]:
    """What changes when a file in ``folder`` matching ``pattern`` is written (or replaced)."""
    out = []
    for path in sorted(folder.glob(pattern)) if folder.exists() else []:
        with contextlib.suppress(OSError):
            stat = path.stat()
            out.append((path.name, stat.st_ino, stat.st_mtime_ns, stat.st_size))
    return tuple(out)


def kill_on_change(process: subprocess.Popen[bytes], folder: Path, pattern: str, before: tuple[Any, ...]) -> None:
    """``kill -9`` ``process`` the instant a file in ``folder`` matching ``pattern`` is written
    (looked at every 0.2 ms, for 30 s at most)."""
    end = time.monotonic() + 30
    while process.poll() is None and time.monotonic() < end:
        if signature(folder, pattern) != before:
            process.send_signal(signal.SIGKILL)
            return
        time.sleep(0.0002)


def killed_in_the_window(package: tuple[Path, str], work: Path, kills: int = 5) -> dict[str, Any]:
    """``kill -9`` the instant the coordinator has written what a command changes, before the
    command can have gone out: where a revision persists its state (5fa21e9), when its state file
    is replaced (the write-ahead window); else when its event log records a decision. Started
    again each time with the same command line."""
    graph = Graph(work)
    log = work / "window.jsonl"
    world = World(delay=0.3)
    wire = Ros2Wire(graph.node, graph.executor, world)
    states = work / "ros_home" / "robosc"
    try:
        node = graph.start(package, *PARAMS, "-p", f"event_log:={log}")
        frozen = 0
        for _ in range(kills):
            wire.run(2.0)  # it works a while
            folder, pattern = (states, "*.state.json") if states.exists() else (log.parent, log.name)
            watching = (node, folder, pattern, signature(folder, pattern))
            watcher = threading.Thread(target=kill_on_change, args=watching, daemon=True)
            watcher.start()
            while watcher.is_alive():
                wire.run(0.05)
            if node.poll() is None:  # nothing written in 30 s
                node.kill()
            node, froze = restarted(graph, package, log, wire, world, node)
            frozen += froze
        return killed(log, world, frozen)
    finally:
        graph.close()


def driver_killed(package: tuple[Path, str], work: Path) -> dict[str, Any]:
    graph = Graph(work)
    log = work / "driver.jsonl"
    world = World(delay=0.3, muted=("bot2",))
    wire = Ros2Wire(graph.node, graph.executor, world, robots=("bot1", "bot3"))
    lines: list[dict[str, Any]] = []
    try:
        driver = subprocess.Popen(
            [sys.executable, "-c", drivers.DRIVER_ROS2, str(graph.domain)], env=graph.env, stdout=subprocess.PIPE, text=True
        )
        graph.processes.append(driver)  # type: ignore[arg-type]

        follow(driver.stdout, lines)
        graph.start(package, *PARAMS, "-p", f"event_log:={log}")
        wire.run(60, lambda: bool(lines) and lines[-1]["where"] in drivers.IN_THE_AISLE)
        stopped = drivers.stop_and_kill(driver)
        time.sleep(0.3)
        wire.run(25)
        take_driver(world, lines)
        return dead_driver(log, world, stopped)
    finally:
        graph.close()


def dead_driver(log: Path, world: World, stopped: float) -> dict[str, Any]:
    """Forbidden commands, and how long bot2 was still commanded after its driver stopped."""
    found, checked = forbidden(log_of(log), world.received, world.sent)
    late = [r["time"] - stopped for r in log_of(log) if r["event"].startswith("bot2.") and r["time"] > stopped]
    return {
        "forbidden": len(found),
        "commands": checked,
        "bot2 commanded after its death": len(late),
        "bot2 last commanded (s after its death)": round(max(late), 2) if late else 0.0,
    }


def answers_twice(package: tuple[Path, str], work: Path) -> dict[str, Any]:
    graph = Graph(work)
    log = work / "twice.jsonl"
    world = World(delay=0.2, twice=True, again=0.0)
    wire = Ros2Wire(graph.node, graph.executor, world)
    last = [time.monotonic()]
    try:
        graph.start(package, *PARAMS, "-p", f"event_log:={log}")

        def spurious() -> bool:
            if world.received and time.monotonic() - last[0] > 1.0:
                last[0] = time.monotonic()
                idle = [r for r in ROBOTS if world.rules.where[r] != "charging"]
                if idle:
                    world.spurious(idle[0] + ".charged", wire.publish)
            return False

        wire.run(30, spurious)
        return answered_once(log, world.received, world.sent)
    finally:
        graph.close()


LATER = (0.05, 1.5)  # seconds after an answer that its second copy comes (a flaky bridge, a driver's retry)


def quiet_at_the_end(log: Path, end: float) -> float:
    """Seconds from the last command the coordinator decided to ``end`` (a fleet that froze sends
    nothing more)."""
    times = [r["time"] for r in log_of(log) if r.get("controllable")]
    return round(end - max(times), 1) if times else round(end, 1)


def answers_again(package: tuple[Path, str], work: Path) -> dict[str, Any]:
    """Every answer sent again 0.05 to 1.5 s after it, for 60 s."""
    graph = Graph(work)
    log = work / "again.jsonl"
    world = World(delay=0.2, twice=True, again=LATER)
    wire = Ros2Wire(graph.node, graph.executor, world)
    try:
        graph.start(package, *PARAMS, "-p", f"event_log:={log}")
        wire.run(60)
        end = time.time()
        found, checked = forbidden(log_of(log), world.received, world.sent)
        return {"forbidden": len(found), "commands": checked, "seconds without a command at the end": quiet_at_the_end(log, end)}
    finally:
        graph.close()


def two_coordinators(package: tuple[Path, str], work: Path) -> dict[str, Any]:
    """The same command line twice, the second 10 s after the first, for 60 s; then the first
    killed, for 20 s more."""
    graph = Graph(work)
    logs = [work / "first.jsonl", work / "second.jsonl"]
    world = World(delay=0.2)
    wire = Ros2Wire(graph.node, graph.executor, world)
    try:
        first = graph.start(package, *PARAMS, "-p", f"event_log:={logs[0]}")
        wire.run(10)
        second_started = time.time()
        graph.start(package, *PARAMS, "-p", f"event_log:={logs[1]}")
        wire.run(50)
        both = [r for r in log_of(logs[1]) if r.get("controllable")]
        first.kill()
        killed = time.time()
        wire.run(20)
        records = sorted([r for log in logs for r in log_of(log) if r.get("controllable")], key=lambda r: r["time"])
        found, checked = forbidden(records, world.received, world.sent)
        after = [r["time"] for r in log_of(logs[1]) if r.get("controllable") and r["time"] > killed]
        return {
            "forbidden": len(found),
            "commands": checked,
            "commands by the second while the first lived": len([r for r in both if r["time"] > second_started]),
            "seconds from the first's death to the second's first command": round(after[0] - killed, 1) if after else "none",
        }
    finally:
        graph.close()


WORKER = "docs/models/outcomes.rscd"


def two_outcomes(package: tuple[Path, str], work: Path) -> dict[str, Any]:
    """The worker's task ends broken, done, broken, ... in turn; its driver reports; 60 s."""
    from worker_stand_in import Worker

    graph = Graph(work)
    worker = Worker(graph.node)
    try:
        graph.start(package)
        end = time.monotonic() + 60
        while time.monotonic() < end:
            worker.step()
            graph.executor.spin_once(timeout_sec=0.01)
        return {"commands wrong where the arm was": len(worker.wrong), "tasks ended": worker.ends,
                "repairs": worker.sent.count("repair"), "homes": worker.sent.count("home")}
    finally:
        graph.close()


def storage(package: tuple[Path, str], work: Path, how: str) -> dict[str, Any]:
    """The maze solver's node for 3 s under a read-only ROS_HOME (``how`` "read-only") or with
    ROS_HOME and the event log on a full disk ("full"), then stopped with SIGINT."""
    graph = Graph(work)
    before = disks.profiles()
    place = disks.mounted(work / "disk", "ro") if how == "read-only" else disks.full(work / "disk")
    try:
        with place as disk, open(work / "node.txt", "wb") as out:
            folder, module = package
            env = {**graph.env, "ROS_HOME": str(disk), "PYTHONPATH": str(folder)}
            env.pop("ROS_LOG_DIR", None)
            args = ["-p", f"event_log:={disk / 'events.jsonl'}", "-p", "wait_for_data:=false", "-p", "trust_initial_state:=true"]
            node = subprocess.Popen([sys.executable, "-m", f"{module}.node", "--ros-args", *args], env=env, stdout=out, stderr=out)
            time.sleep(3.0)
            alive = node.poll() is None
            node.send_signal(signal.SIGINT)
            status = node.wait(20)
        text = (work / "node.txt").read_text(errors="replace")
        left = disks.profiles() - before
        return {"ran": alive, "exit status": status, "tracebacks": text.count("Traceback"), "profiles left in /dev/shm": len(left)}
    finally:
        graph.close()


def answered_once(log: Path, received: Any, sent: Any) -> dict[str, Any]:
    """Forbidden commands, and the answers in the event log that no robot gave (duplicates and
    spurious answers taken as events)."""
    found, checked = forbidden(log_of(log), received, sent)
    taken = [r["event"] for r in log_of(log) if not r.get("controllable") and r["event"] in ANSWERS]
    given = [name for _, name, duplicate in sent if not duplicate]
    return {
        "forbidden": len(found),
        "commands": checked,
        "answers logged that no robot gave": max(0, len(taken) - len(given)),
    }


def stop_held(package: tuple[Path, str], work: Path, keep_file: bool) -> dict[str, Any]:
    from geometry_msgs.msg import Twist
    from sensor_msgs.msg import LaserScan
    from std_msgs.msg import Empty, Float32
    from std_srvs.srv import Trigger

    graph = Graph(work)
    home = work / f"ros_home_{keep_file}"
    env = {"ROS_HOME": str(home)}
    stop_state = ["in_service"]

    def report(request: Any, response: Any) -> Any:  # a stop node that reports while it can
        response.success, response.message = stop_state[0] != "gone", stop_state[0]
        return response

    try:
        graph.node.create_service(Trigger, "/robosc/report/EmergencyStop", report)
        cmd: list[Any] = []
        graph.node.create_subscription(Twist, "/cmd_vel", cmd.append, 100)
        scan = graph.node.create_publisher(LaserScan, "/scan", 10)
        correction = graph.node.create_publisher(Float32, "/line/correction", 10)
        stop = graph.node.create_publisher(Empty, "/emergency_stop/stop", 10)
        message = LaserScan()
        message.ranges = [5.0] * 360
        graph.node.create_timer(0.1, lambda: (scan.publish(message), correction.publish(Float32(data=10.0))))
        node = graph.start(package, "-p", "rate:=20.0", "-p", "seed:=3", env=env)
        end = time.monotonic() + 20
        while not any(m.linear.x > 0 for m in cmd) and time.monotonic() < end:
            graph.spin(0.1)
        stop.publish(Empty())
        stop_state[0] = "gone"  # the stop is held; its node no longer answers
        graph.spin(1.0)
        node.send_signal(signal.SIGKILL)
        node.wait(10)
        if not keep_file:
            shutil.rmtree(home / "robosc", ignore_errors=True)
        cmd.clear()
        graph.start(package, "-p", "rate:=20.0", "-p", "seed:=3", env=env)
        graph.spin(8.0)
        return {"moves in 8 s": sum(1 for m in cmd if m.linear.x > 0)}
    finally:
        graph.close()


# ---- ROS 1 ----------------------------------------------------------------------------------------
ROS1_PYTHON = os.environ.get("ROBOSC_ROS1_PYTHON", "/usr/bin/python3")
ROS1_HELPERS = ROOT / "tests" / "ros1_client.py"


class Master:
    """A rosmaster on 127.0.0.1 of its own, and the processes started on it."""

    def __init__(self, work: Path) -> None:
        import socket

        with socket.socket() as probe:
            probe.bind(("127.0.0.1", 0))
            port = probe.getsockname()[1]
        self.env = {
            **{k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "PYTHON"))},
            "ROS_MASTER_URI": f"http://127.0.0.1:{port}",
            "ROS_HOSTNAME": "127.0.0.1",
            "ROS_HOME": str(work / "ros_home"),
        }
        self.log = open(work / "ros1.log", "ab")  # noqa: SIM115
        self.processes: list[subprocess.Popen[Any]] = []
        self.start([ROS1_PYTHON, "/usr/bin/rosmaster", "--core", "-p", str(port)])
        time.sleep(1.5)

    def start(self, command: list[str], **kwargs: Any) -> subprocess.Popen[Any]:
        options: dict[str, Any] = {"stdout": self.log, "stderr": self.log, **kwargs}
        process = subprocess.Popen(command, env=self.env, **options)
        self.processes.append(process)
        return process

    def node(self, package: Path, log: Path) -> subprocess.Popen[Any]:
        script = next((package / "scripts").glob("*_node"))
        return self.start([ROS1_PYTHON, str(script), "_rate:=40.0", "_seed:=3", "_policy:=random", f"_event_log:={log}"])

    def close(self) -> None:
        for process in reversed(self.processes):
            if process.poll() is None:
                process.kill()
                process.wait(10)
        self.log.close()


def ros1_world(
    master: Master, work: Path, twice: bool, body: str, robots: tuple[str, ...] = ROBOTS, again: Any = 0.0
) -> subprocess.Popen[Any]:
    control = work / "control"
    script = (
        f"import sys\nsys.path.insert(0, {str(ROS1_HELPERS.parent)!r})\nfrom ros1_client import *\n"
        + drivers.ROS1_WORLD.format(tests=str(ROOT / "tests"), robots=robots, twice=twice, again=again, control=str(control))
        + body
    )
    return master.start([ROS1_PYTHON, "-c", script], stdout=subprocess.PIPE, text=True)


def ros1_result(world: subprocess.Popen[Any]) -> dict[str, Any]:
    out, _ = world.communicate(timeout=400)
    lines = [line for line in (out or "").splitlines() if line.startswith("{")]
    return json.loads(lines[-1]) if lines else {"received": [], "sent": []}


def ros1_killed_three_ways(package: Path, work: Path) -> dict[str, Any]:
    master = Master(work)
    log = work / "killed.jsonl"
    try:
        node = master.node(package, log)
        world = ros1_world(master, work, False, drivers.ROS1_KILLED_THREE_WAYS.format(wait=20))
        drivers.kill_when_told(work / "control", world, node, lambda: master.node(package, log))
        result = ros1_result(world)
        found, checked = forbidden(log_of(log), result["received"], result["sent"])
        return {"forbidden": len(found), "commands": checked, "frozen restarts": result.get("frozen", "?")}
    finally:
        master.close()


def ros1_driver_killed(package: Path, work: Path) -> dict[str, Any]:
    master = Master(work)
    log = work / "driver.jsonl"
    killed = work / "killed"
    lines: list[dict[str, Any]] = []
    try:
        driver = master.start([ROS1_PYTHON, "-c", drivers.DRIVER_ROS1], stdout=subprocess.PIPE, text=True)
        follow(driver.stdout, lines)
        master.node(package, log)
        body = f"""
run(90, lambda: os.path.exists({str(killed)!r}))
run(25)
with lock:
    done(json.loads(world.dump()))
"""
        world = ros1_world(master, work, False, body, robots=("bot1", "bot3"))
        end = time.monotonic() + 60
        while not (lines and lines[-1]["where"] in drivers.IN_THE_AISLE) and time.monotonic() < end:
            time.sleep(0.01)
        stopped = drivers.stop_and_kill(driver)
        killed.write_text("killed")
        result = ros1_result(world)
        everything = World()
        everything.received, everything.sent = result["received"], result["sent"]
        take_driver(everything, lines)
        return dead_driver(log, everything, stopped)
    finally:
        master.close()


def ros1_answers_twice(package: Path, work: Path) -> dict[str, Any]:
    master = Master(work)
    log = work / "twice.jsonl"
    try:
        master.node(package, log)
        body = """
last = [time.time()]
def spurious():
    if world.received and time.time() - last[0] > 1.0:
        last[0] = time.time()
        idle = [r for r in ROBOTS if world.rules.where[r] != "charging"]
        if idle:
            world.spurious(idle[0] + ".charged", publish)
    return False
run(30, spurious)
with lock:
    done(json.loads(world.dump()))
"""
        result = ros1_result(ros1_world(master, work, True, body))
        return answered_once(log, result["received"], result["sent"])
    finally:
        master.close()


def ros1_answers_again(package: Path, work: Path) -> dict[str, Any]:
    master = Master(work)
    log = work / "again.jsonl"
    try:
        master.node(package, log)
        body = """
run(60)
with lock:
    done(json.loads(world.dump()))
"""
        result = ros1_result(ros1_world(master, work, True, body, again=LATER))
        end = time.time()
        found, checked = forbidden(log_of(log), result["received"], result["sent"])
        return {"forbidden": len(found), "commands": checked, "seconds without a command at the end": quiet_at_the_end(log, end)}
    finally:
        master.close()


def ros1_two_coordinators(package: Path, work: Path) -> dict[str, Any]:
    """The same command line twice, 10 s apart; the robots' 50 s after the second started."""
    master = Master(work)
    logs = [work / "first.jsonl", work / "second.jsonl"]
    try:
        master.node(package, logs[0])
        body = """
run(60)
with lock:
    done(json.loads(world.dump()))
"""
        world = ros1_world(master, work, False, body)
        time.sleep(10)
        second_started = time.time()
        master.node(package, logs[1])
        result = ros1_result(world)
        records = sorted([r for log in logs for r in log_of(log) if r.get("controllable")], key=lambda r: r["time"])
        found, checked = forbidden(records, result["received"], result["sent"])
        later = [t for t, _ in result["received"] if t > second_started + 5]
        return {"forbidden": len(found), "commands": checked, "commands the robots got from 5 s after the second started": len(later)}
    finally:
        master.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", default=None)
    parser.add_argument("--runs", type=int, default=1)
    parser.add_argument("--no-ros1", dest="ros1", action="store_false", help="ROS 2 only")
    parser.add_argument("--only", nargs="*", help="only the scenarios whose names hold one of these words")
    args = parser.parse_args()
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(1))  # so that each scenario's processes are ended
    runs: list[str | None] = [None] + ([args.baseline] if args.baseline else [])
    with tempfile.TemporaryDirectory(prefix="robosc-faults-") as folder:
        work = Path(folder)
        results: dict[str, dict[str, list[Any]]] = {}
        for revision in runs:
            label = "this" if revision is None else revision
            warehouse = generate("docs/models/warehouse_zero_time.rscd", work / f"wh_{label}", revision, work)
            line = generate("examples/line_follower.rscd", work / f"lf_{label}", revision, work)
            worker = generate(WORKER, work / f"wk_{label}", revision, work)
            maze = generate("examples/maze_solver.rscd", work / f"mz_{label}", revision, work)
            warehouse1 = revisions.generate(ROOT / "docs/models/warehouse_zero_time.rscd", 1, work / f"wh1_{label}", revision, work)
            for run in range(args.runs):
                tag = f"{label}{run}"
                scenarios: list[tuple[str, Any, tuple[Any, ...]]] = [
                    ("killed three ways", killed_three_ways, (warehouse, work / f"k{tag}")),
                    ("killed in the write-ahead window", killed_in_the_window, (warehouse, work / f"w{tag}")),
                    ("a driver killed", driver_killed, (warehouse, work / f"d{tag}")),
                    ("answers twice, and spurious", answers_twice, (warehouse, work / f"t{tag}")),
                    ("answers again 0.05-1.5 s later", answers_again, (warehouse, work / f"a{tag}")),
                    ("two coordinators, the same command line", two_coordinators, (warehouse, work / f"c{tag}")),
                    ("an event with two outcomes", two_outcomes, (worker, work / f"o{tag}")),
                    ("ROS_HOME read-only", storage, (maze, work / f"r{tag}", "read-only")),
                    ("ROS_HOME and the event log on a full disk", storage, (maze, work / f"f{tag}", "full")),
                    ("stop held, restarted, state file kept", stop_held, (line, work / f"s{tag}", True)),
                    ("stop held, restarted, state file deleted", stop_held, (line, work / f"m{tag}", False)),
                ]
                if Path(ROS1_PYTHON).exists() and args.ros1:
                    scenarios += [
                        ("ROS 1: killed three ways", ros1_killed_three_ways, (warehouse1, work / f"k1{tag}")),
                        ("ROS 1: a driver killed", ros1_driver_killed, (warehouse1, work / f"d1{tag}")),
                        ("ROS 1: answers twice, and spurious", ros1_answers_twice, (warehouse1, work / f"t1{tag}")),
                        ("ROS 1: answers again 0.05-1.5 s later", ros1_answers_again, (warehouse1, work / f"a1{tag}")),
                        ("ROS 1: two coordinators, the same command line", ros1_two_coordinators, (warehouse1, work / f"c1{tag}")),
                    ]
                if args.only:
                    scenarios = [x for x in scenarios if any(word in x[0] for word in args.only)]
                for name, scenario, arguments in scenarios:
                    arguments[1].mkdir(parents=True, exist_ok=True)
                    outcome = scenario(*arguments)
                    for key, value in outcome.items():
                        results.setdefault(f"{name}: {key}", {}).setdefault(label, []).append(value)
                    print(label, name, outcome, flush=True)
        labels = ["this"] + ([args.baseline] if args.baseline else [])
        print()
        print("| fault | " + " | ".join(f"robosc {label}" for label in labels) + " |")
        print("|---|" + "---|" * len(labels))
        for key, by_label in results.items():
            print(
                f"| {key} | "
                + " | ".join(", ".join(str(v) for v in by_label.get(label, [])) for label in labels)
                + " |"
            )


if __name__ == "__main__":
    main()
