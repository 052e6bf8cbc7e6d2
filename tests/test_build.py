"""The generated packages built for real: the ROS 2 package with colcon, the ROS 1 package
in a catkin workspace (catkin_make, catkin_lint), every package.xml read by catkin_pkg,
and the nodes started from the install spaces (ROS 1 through roslaunch of the generated
launch file)."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from robosc.api import load_model, plan_supervisor, synthesize_model
from robosc.codegen.ros import generate, package_name
from ros_support import ROOT, Ros1, Ros2, build_package, unavailable, wait_until

COLCON = Path(sys.executable).parent / "colcon"
DEBIAN = {**os.environ, "PATH": "/usr/bin:/bin:" + os.environ.get("PATH", "")}


def in_workspace(model: str, ros: int, workspace: Path) -> Path:
    """The controller package of ``model`` (relative names) in ``workspace/src/<package name>``."""
    plan = plan_supervisor(synthesize_model(load_model(ROOT / model)))
    target = workspace / "src" / package_name(plan)
    generate(plan, ros, "controller", target, relative=True)
    return target


def run(command: list[str] | str, cwd: Path, env: dict[str, str] | None = None, timeout: float = 300) -> str:
    done = subprocess.run(
        command,
        cwd=cwd,
        env=env or DEBIAN,
        capture_output=True,
        text=True,
        timeout=timeout,
        shell=isinstance(command, str),
        executable="/bin/bash" if isinstance(command, str) else None,
    )
    assert done.returncode == 0, f"{command} failed:\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
    return done.stdout + done.stderr


@pytest.mark.parametrize("ros", [1, 2])
@pytest.mark.parametrize("mode", ["controller", "supervisor"])
def test_catkin_pkg_reads_every_package_xml(tmp_path: Path, ros: int, mode: str) -> None:
    from catkin_pkg.package import parse_package

    package = build_package("examples/pick_and_light.rscd", ros, mode, tmp_path)
    parsed = parse_package(str(package / "package.xml"))
    parsed.validate()
    assert parsed.name == "pick_and_light_robosc"
    assert parsed.maintainers[0].email == "robosc@example.com"
    assert {"std_srvs", "test_msgs"} <= {d.name for d in parsed.exec_depends}


def test_ros1_package_builds_in_a_catkin_workspace_and_runs_through_roslaunch(ros1: Ros1, tmp_path: Path) -> None:
    if not shutil.which("catkin_make", path="/usr/bin") or not shutil.which("catkin_lint", path="/usr/bin"):
        unavailable("catkin and catkin_lint (Debian's catkin, catkin-lint)")
    workspace = tmp_path / "ws"
    package = in_workspace("examples/maze_solver.rscd", 1, workspace)
    lint = run(["catkin_lint", "-W2", "--strict", str(package)], workspace)
    assert "found 0 problems" in lint or "0 problems" in lint, lint
    built = run(["catkin_make", "-C", str(workspace), "install"], workspace)
    installed = workspace / "install"
    assert (installed / "lib/maze_solver_robosc/maze_solver_robosc_node").exists(), built[-3000:]
    assert list(installed.glob("lib/python3*/dist-packages/maze_solver_robosc/onboard/supervisor.py"))
    shutil.rmtree(workspace / "src")  # the installed package must not need its sources
    shutil.rmtree(workspace / "devel")
    launch = (
        f". {installed}/setup.bash && exec roslaunch maze_solver_robosc maze_solver_robosc.launch"
        " namespace:=/robot7 rate:=20.0 publish_state:=true"
    )
    env = {**ros1.env, "PATH": "/usr/bin:/bin"}
    ros1.processes.start("roslaunch", ["/bin/bash", "-c", launch], env)
    result = ros1.client(
        """
start()
moves = Recorder("/robot7/cmd_vel", Twist)
lefts = Recorder("/robot7/rotate_left", Int16)
scan_pub = publisher("/robot7/scan", LaserScan, timeout=30)
scan_pub.publish(scan([5.0] * 360))
assert wait_for(lambda: moves.messages(), 10), "no movement"
scan_pub.publish(scan([0.3] + [5.0] * 359))
assert wait_for(lambda: lefts.messages(), 5), "no turn at the wall"
done({"left": lefts.messages()[0].data, "move": moves.messages()[0].linear.x})
""",
        timeout=90,
        reports={"/robot7": {"Platform": "ready"}},  # the robot's driver says where it is
    )
    assert result == {"left": 90, "move": pytest.approx(0.3)}
    # roslaunch starts the node again when it dies; it does not take on what the dead one
    # believed: it holds what depends on the platform until the robot's driver reports
    node = str(installed / "lib/maze_solver_robosc/maze_solver_robosc_node")

    def pids() -> list[str]:
        return subprocess.run(["pgrep", "-f", node], capture_output=True, text=True).stdout.split()

    found = pids()
    assert len(found) == 1, found
    os.kill(int(found[0]), signal.SIGKILL)
    assert wait_until(lambda: pids() not in ([], found), 30), "not respawned"
    unconfirmed = health(ros1, "/robot7/health", 20)["unconfirmed"]
    assert unconfirmed["Platform"] == {"why": "not confirmed since the start", "may_be": {"Platform": ["ready", "turning"]}}


def health(ros1: Ros1, topic: str, wait: float) -> Any:
    """The latest report a node put on its latched health topic (within ``wait`` seconds)."""
    return ros1.client(
        f"""
start()
state = Recorder({topic!r}, String)
assert wait_for(lambda: state.messages(), {wait}), "no health from the node"
done(json.loads(state.messages()[-1].data))
""",
        timeout=wait + 60,
    )


def test_ros2_package_builds_with_colcon_and_runs_from_the_install_space(ros2: Ros2, tmp_path: Path) -> None:
    from geometry_msgs.msg import Twist
    from std_msgs.msg import Int16

    if not COLCON.exists():
        unavailable("colcon (pip install colcon-common-extensions)")
    workspace = tmp_path / "ws"
    in_workspace("examples/maze_solver.rscd", 2, workspace)
    env = {**os.environ, "PATH": f"{COLCON.parent}:{os.environ['PATH']}"}
    out = run([str(COLCON), "build", "--event-handlers", "console_cohesion-"], workspace, env)
    assert "1 package finished" in out
    shutil.rmtree(workspace / "src")  # the installed package must not need its sources
    executable = workspace / "install/maze_solver_robosc/lib/maze_solver_robosc/maze_solver_robosc_node"
    assert executable.exists()
    assert list(workspace.glob("install/maze_solver_robosc/lib/python3*/site-packages/maze_solver_robosc/onboard/fastdds.xml"))
    ros2.reports({"Platform": "ready"}, "/robot3")  # the robot's driver says where it is
    start = f". {workspace}/install/setup.bash && exec {executable} --ros-args -r __ns:=/robot3 -p rate:=20.0"
    ros2.processes.start("installed", ["/bin/bash", "-c", start], ros2.env)
    moves = ros2.record(Twist, "/robot3/cmd_vel")
    lefts = ros2.record(Int16, "/robot3/rotate_left")
    from sensor_msgs.msg import LaserScan

    scan = ros2.node.create_publisher(LaserScan, "/robot3/scan", 10)

    def clear() -> bool:
        message: Any = LaserScan()
        message.ranges = [5.0] * 360
        scan.publish(message)
        return bool(moves)

    assert ros2.spin_until(clear, 20), "no movement:\n" + ros2.processes.output()

    def wall() -> bool:
        message: Any = LaserScan()
        message.ranges = [0.3] + [5.0] * 359
        scan.publish(message)
        return bool(lefts)

    assert ros2.spin_until(wall, 10)
    assert lefts[0].data == 90 and moves[0].linear.x == pytest.approx(0.3)


def robosc_build(model: str, out: Path) -> None:
    """`robosc build MODEL -o OUT`, as a user runs it."""
    done = subprocess.run(
        [sys.executable, "-m", "robosc", "build", str(ROOT / model), "-o", str(out)],
        capture_output=True, text=True, timeout=120,
    )
    assert done.returncode == 0, done.stderr


def readme_steps(package: Path, workspace: Path) -> list[str]:
    """The commands of the package README's 'Build and run' block, with the workspace here."""
    text = (package / "README.md").read_text()
    block = text.split("```sh\n", 1)[1].split("```", 1)[0]
    home = {"~/catkin_ws": str(workspace), "~/ros2_ws": str(workspace)}
    lines = []
    for line in block.splitlines():
        for written, here in home.items():
            line = line.replace(written, here)
        if line.strip():
            lines.append(line)
    return lines


def test_the_ros1_package_readme_builds_and_launches_as_written(ros1: Ros1, tmp_path: Path) -> None:
    """`robosc build`, then the generated README's commands one by one, with a Python that
    has no catkin_pkg first on PATH (as pyenv or a virtual environment puts it): before, the
    README said nothing and catkin_make failed with "No module named 'catkin_pkg'"."""
    if not shutil.which("catkin_make", path="/usr/bin"):
        unavailable("catkin (Debian's catkin)")
    robosc_build("examples/maze_solver.rscd", tmp_path / "out")
    package = tmp_path / "out/ros1/maze_solver_robosc"  # the folder has the package's name
    lint = run(["catkin_lint", "-W2", "--strict", str(package)], package)
    assert "0 problems" in lint, lint
    steps = readme_steps(package, tmp_path / "catkin_ws")
    assert steps[-1] == "roslaunch maze_solver_robosc maze_solver_robosc.launch"
    other = tmp_path / "pyenv"  # a python3 without ROS's packages, first on PATH (as pyenv puts its own)
    other.mkdir()
    (other / "python3").write_text(f'#!/bin/sh\nexec {sys.executable} -S "$@"\n')
    (other / "python3").chmod(0o755)
    env = {**ros1.env, "PATH": f"{other}:/usr/bin:/bin"}
    assert subprocess.run(["python3", "-c", "import catkin_pkg"], env=env, capture_output=True).returncode != 0
    script = "set -e\n" + "\n".join(steps[:-1]) + "\nexec " + steps[-1] + "\n"
    ros1.processes.start("readme", ["/bin/bash", "-c", script], env, cwd=package)
    report = health(ros1, "/health", 240)  # catkin_make first, then roslaunch
    assert report["waiting_for"] == ["scan_diag_right", "scan_front", "scan_right"], ros1.processes.output()


def test_the_ros2_package_readme_builds_as_written(ros2: Ros2, tmp_path: Path) -> None:
    """The generated README's colcon steps, then its node without the ros2 command (which has
    no wheels here: 'ros2 launch' is not run, see README's limitations)."""
    if not COLCON.exists():
        unavailable("colcon (pip install colcon-common-extensions)")
    robosc_build("examples/maze_solver.rscd", tmp_path / "out")
    package = tmp_path / "out/ros2/maze_solver_robosc"
    workspace = tmp_path / "ros2_ws"
    steps = readme_steps(package, workspace)
    assert steps[-1] == "ros2 launch maze_solver_robosc maze_solver_robosc.launch.py"
    env = {**ros2.env, "PATH": f"{COLCON.parent}:{os.environ['PATH']}"}
    run("set -e\n" + "\n".join(steps[:-1]) + "\n", package, env)
    readme = (package / "README.md").read_text()
    alone = "install/maze_solver_robosc/lib/maze_solver_robosc/maze_solver_robosc_node"
    assert f"`{alone}` does the same" in readme.replace("\n", " ")
    from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
    from std_msgs.msg import String

    reports: list[Any] = []
    latched = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    ros2.node.create_subscription(String, "/health", reports.append, latched)
    start = f"cd {workspace} && source install/setup.bash && exec {alone}"
    ros2.processes.start("readme", ["/bin/bash", "-c", start], env)
    assert ros2.spin_until(lambda: bool(reports), 30), ros2.processes.output()
