"""The ROS packages' files: package.xml, CMakeLists.txt / setup.py, launch files (ROS 1's
loaded by roslaunch itself), and the CLI commands that write them."""

from __future__ import annotations

import ast
import json
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from ros_support import ROS1_PYTHON, build_package, ros1_available, unavailable

ROOT = Path(__file__).resolve().parent.parent


def run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "robosc", *args], capture_output=True, text=True, timeout=120, check=False
    )


def depends(package: Path) -> set[str]:
    root = ET.parse(package / "package.xml").getroot()
    assert root.get("format") == "3"
    return {e.text or "" for e in root if e.tag.endswith("depend")}


RUNTIME = {
    "__init__.py",
    "answers.py",
    "claims.py",
    "belief.py",
    "delivery.py",
    "effects.py",
    "fastdds.xml",
    "health.py",
    "layer.py",
    "live_server.py",
    "messages.py",
    "node.py",
    "node_base.py",
    "node_tasks.py",
    "outcomes.py",
    "profiles.py",
    "reading.py",
    "recording.py",
    "reports.py",
    "ros1.py",
    "ros2.py",
    "routes.py",
    "supervisor.py",
    "tables.py",
    "tasks.py",
    "unknown.py",
    "values.py",
    "viewing.py",
}


def test_ros1_catkin_package(tmp_path: Path) -> None:
    package = build_package("examples/pick_and_light.rscd", 1, "controller", tmp_path)
    files = {p.relative_to(package).as_posix() for p in package.rglob("*") if p.is_file()}
    python = "src/pick_and_light_robosc"
    assert files == {
        "package.xml",
        "CMakeLists.txt",
        "README.md",
        "setup.py",
        "scripts/pick_and_light_robosc_node",
        "launch/pick_and_light_robosc.launch",
        f"{python}/__init__.py",
        f"{python}/pick_and_light_supervisor.py",
        *(f"{python}/onboard/{name}" for name in RUNTIME),
    }
    assert {
        "catkin",
        "rospy",
        "std_msgs",
        "geometry_msgs",
        "std_srvs",
        "test_msgs",
        "actionlib",
        "actionlib_msgs",
    } <= depends(package)
    cmake = (package / "CMakeLists.txt").read_text()
    assert "project(pick_and_light_robosc)" in cmake and "catkin_python_setup()" in cmake
    assert "catkin_install_python(PROGRAMS scripts/${PROJECT_NAME}_node" in cmake
    node = (package / "scripts/pick_and_light_robosc_node").read_text()
    assert node.startswith("#!/usr/bin/env python3")
    assert (package / "scripts/pick_and_light_robosc_node").stat().st_mode & 0o111
    for path in [package / "scripts/pick_and_light_robosc_node", *package.rglob("*.py")]:
        ast.parse(path.read_text(), feature_version=(3, 8))
    # ROS types are found by module at run time, never imported by a bare class name
    module = (package / python / "pick_and_light_supervisor.py").read_text()
    assert "Comm('pick', 'action', '/arm/pick', 'test_msgs/Fibonacci', 'none')" in module
    assert "Comm('set_light', 'service', '/light/set', 'std_srvs/SetBool', 'none')" in module


def test_the_runtime_is_copied_verbatim(tmp_path: Path) -> None:
    from robosc.codegen.module import runtime_files

    package = build_package("examples/maze_solver.rscd", 2, "controller", tmp_path)
    copied = {p.name: p.read_text() for p in (package / "maze_solver_robosc/onboard").iterdir()}
    assert copied == runtime_files()
    assert set(copied) == RUNTIME


def test_ros2_ament_python_package(tmp_path: Path) -> None:
    package = build_package("examples/pick_and_light.rscd", 2, "controller", tmp_path)
    files = {p.relative_to(package).as_posix() for p in package.rglob("*") if p.is_file()}
    assert files == {
        "package.xml",
        "setup.py",
        "setup.cfg",
        "README.md",
        "resource/pick_and_light_robosc",
        "pick_and_light_robosc/__init__.py",
        "pick_and_light_robosc/node.py",
        "pick_and_light_robosc/pick_and_light_supervisor.py",
        "launch/pick_and_light_robosc.launch.py",
        *(f"pick_and_light_robosc/onboard/{name}" for name in RUNTIME),
    }
    assert {"rclpy", "std_msgs", "geometry_msgs", "std_srvs", "test_msgs", "action_msgs"} <= depends(package)
    root = ET.parse(package / "package.xml").getroot()
    assert root.find("export/build_type").text == "ament_python"  # type: ignore[union-attr]
    setup = (package / "setup.py").read_text()
    assert "'pick_and_light_robosc_node = pick_and_light_robosc.node:main'" in setup
    assert 'package_name + ".onboard"' in setup
    assert "script_dir=$base/lib/pick_and_light_robosc" in (package / "setup.cfg").read_text()
    for path in package.rglob("*.py"):
        ast.parse(path.read_text(), feature_version=(3, 8))


def test_relative_names_option(tmp_path: Path) -> None:
    from robosc.api import load_model, plan_supervisor, synthesize_model
    from robosc.codegen.ros import generate

    plan = plan_supervisor(synthesize_model(load_model(ROOT / "examples/maze_solver.rscd")))
    generate(plan, 2, "supervisor", tmp_path / "rel", relative=True)
    module = (tmp_path / "rel/maze_solver_robosc/maze_solver_supervisor.py").read_text()
    assert "Comm('movement', 'incoming', 'cmd_vel', 'geometry_msgs/Twist', 'object')" in module
    launch = (tmp_path / "rel/launch/maze_solver_robosc.launch.py").read_text()
    assert "('cmd_vel', 'robosc/controller/cmd_vel')" in launch
    generate(plan, 2, "supervisor", tmp_path / "abs")
    module = (tmp_path / "abs/maze_solver_robosc/maze_solver_supervisor.py").read_text()
    assert "Comm('movement', 'incoming', '/cmd_vel', 'geometry_msgs/Twist', 'object')" in module


LOAD_LAUNCH = """
import json, sys
import roslaunch.config, roslaunch.xmlloader
config = roslaunch.config.ROSLaunchConfig()
roslaunch.xmlloader.XmlLoader().load(sys.argv[1], config, argv=sys.argv[2:], verbose=False)
print(json.dumps({
    "nodes": [[n.package, n.type, n.name, [list(r) for r in n.remap_args]] for n in config.nodes],
    "params": {k: p.value for k, p in config.params.items()},
}))
"""


@pytest.mark.parametrize("mode", ["controller", "supervisor"])
def test_ros1_launch_file_loads_in_roslaunch(tmp_path: Path, mode: str) -> None:
    if not ros1_available():
        unavailable("ROS 1 (Debian's python3-roslaunch)")
    package = build_package("examples/maze_solver.rscd", 1, mode, tmp_path)
    launch = package / "launch/maze_solver_robosc.launch"
    extra = ["controller_package:=my_robot", "controller_type:=wall_follower.py"] if mode == "supervisor" else []
    done = subprocess.run(
        [ROS1_PYTHON, "-c", LOAD_LAUNCH, str(launch), "rate:=25.0", *extra],
        capture_output=True,
        text=True,
        timeout=60,
        env={"ROS_HOME": str(tmp_path), "PATH": "/usr/bin:/bin"},
    )
    assert done.returncode == 0, done.stderr
    loaded = json.loads(done.stdout.strip().splitlines()[-1])
    assert loaded["params"]["/maze_solver_robosc/rate"] == 25.0
    assert loaded["params"]["/maze_solver_robosc/tick_on_message"] is False
    assert loaded["params"]["/maze_solver_robosc/server_timeout"] == 5.0
    nodes = {n[2]: n for n in loaded["nodes"]}
    assert nodes["maze_solver_robosc"][:2] == ["maze_solver_robosc", "maze_solver_robosc_node"]
    if mode == "supervisor":
        controller = nodes["controller"]
        assert controller[:2] == ["my_robot", "wall_follower.py"]
        assert ["/cmd_vel", "/robosc/controller/cmd_vel"] in controller[3]
        assert ["/scan", "/robosc/controller/scan"] in controller[3]
    else:
        assert set(nodes) == {"maze_solver_robosc"}


def test_generate_and_build_commands(tmp_path: Path) -> None:
    result = run(
        "generate",
        str(ROOT / "examples/line_follower.rscd"),
        "--ros",
        "2",
        "--mode",
        "supervisor",
        "-o",
        str(tmp_path / "lf"),
    )
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "lf/line_follower_robosc/node.py").exists()
    result = run("build", str(ROOT / "examples/maze_solver.rscd"), "-o", str(tmp_path / "out"))
    assert result.returncode == 0, result.stderr
    for relative in (
        "ros1/maze_solver_robosc/package.xml",  # the folder has the package's name (catkin_lint --strict)
        "ros1/maze_solver_robosc/README.md",
        "ros1/maze_solver_robosc/src/maze_solver_robosc/live_view.html",
        "ros2/maze_solver_robosc/setup.py",
        "ros2/maze_solver_robosc/README.md",
        "ros2/maze_solver_robosc/maze_solver_robosc/live_view.html",
        "maze_solver_supervisor.py",
        "onboard/supervisor.py",
        "MazeSolver.cif",
    ):
        assert (tmp_path / "out" / relative).exists(), relative
    assert "128 reachable states" in result.stdout


def test_generate_refuses_what_ros_cannot_run(tmp_path: Path) -> None:
    model = tmp_path / "clash.rscd"
    model.write_text(
        "robot K {\n  component C {\n    incoming message a with identifier: '/x', type: double\n"
        "    incoming message b with identifier: '/x', type: boolean\n  }\n}\n"
    )
    result = run("generate", str(model), "--ros", "1", "-o", str(tmp_path / "x"))
    assert result.returncode == 1
    assert (
        f"{model}:4:5: error: 'b' uses topic /x with type std_msgs/Bool, but another communication uses it with std_msgs/Float32"
        in result.stderr
    )
    model = tmp_path / "untyped.rscd"
    model.write_text("robot U {\n  component C {\n    service s with request: none, response: none\n  }\n}\n")
    result = run("generate", str(model), "--ros", "2", "-o", str(tmp_path / "y"))
    assert result.returncode == 1
    assert f"{model}:3:5: error: service 's' must link the ROS service type it calls" in result.stderr
    assert "Traceback" not in result.stderr
