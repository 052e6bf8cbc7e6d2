"""``robosc view``: the live view of a controller running in a simulation, fetched over ROS
(the page latched on live_view/page, the events on live_view/events) and served on
127.0.0.1 by another process, as on an engineer's laptop; in headless Chromium for ROS 2,
over HTTP for ROS 1."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from robosc import children
from ros_support import free_port, new_domain, ros1_available, ros2_available, stop_all, unavailable, wait_until
from test_live_view import browser  # noqa: F401 (the fixture)

pytest.importorskip("irsim", reason="robosc sim needs IR-SIM (pip install '.[sim]')")

ROOT = Path(__file__).resolve().parent.parent


class Run:
    def __init__(self, tmp_path: Path) -> None:
        self.tmp_path = tmp_path
        self.processes: list[tuple[str, subprocess.Popen[bytes]]] = []

    def start(self, name: str, args: list[str], env: dict[str, str]) -> subprocess.Popen[bytes]:
        log = open(self.tmp_path / f"{name}.log", "wb")  # noqa: SIM115 (closed with the process)
        process = children.start([sys.executable, "-m", "robosc", *args], env=env, stdout=log, stderr=subprocess.STDOUT)
        self.processes.append((name, process))
        return process

    def log(self, name: str) -> str:
        return (self.tmp_path / f"{name}.log").read_text(errors="replace")

    def output(self) -> str:
        return "\n".join(f"--- {name}\n{self.log(name)[-3000:]}" for name, _ in self.processes)


@pytest.fixture
def run(tmp_path: Path) -> Iterator[Run]:
    r = Run(tmp_path)
    try:
        yield r
    finally:
        stop_all([p for _, p in r.processes])


def start_sim(run: Run, ros: int, robots: int, domain: int | None = None, name: str = "sim") -> dict[str, str]:
    """A maze run in real time (long enough to watch); returns the environment of its graph."""
    args = ["sim", str(ROOT / "examples/worlds/maze.yaml"), str(ROOT / "examples/maze_solver.rscd")]
    args += ["--ros", str(ros), "--robots", str(robots), "--speed", "1", "--timeout", "200"]
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    if ros == 2:
        domain = domain if domain is not None else new_domain()
        args += ["--domain", str(domain)]
    run.start(name, args, env)
    found: list[str] = []

    def announced() -> bool:
        found[:] = re.findall(r"the robots run on (.*?) \(watch", run.log(name))
        return bool(found)

    assert wait_until(announced, 90), run.output()
    graph = dict(item.split("=", 1) for item in found[0].split())
    return {**env, **graph}


def start_view(run: Run, env: dict[str, str], ros: int, *args: str) -> str:
    port = free_port()
    run.start("view", ["view", "--ros", str(ros), "--port", str(port), *args], env)
    url = f"http://127.0.0.1:{port}/"
    assert wait_until(lambda: "live view of" in run.log("view"), 90, 0.2), run.output()
    return url


def test_robosc_view_lists_and_chooses_among_the_robots_on_a_ros2_graph(run: Run, browser: Any) -> None:  # noqa: F811
    if not ros2_available():
        unavailable("ROS 2 (pip install '.[ros2]')")
    env = start_sim(run, 2, robots=2)
    import time

    time.sleep(3)  # the controllers start
    # the first call lists both: it looks until what it finds has settled (before: 1 of 2)
    done = subprocess.run(
        [sys.executable, "-m", "robosc", "view", "--ros", "2", "--list"], env=env, capture_output=True, text=True, timeout=60
    )
    assert done.stdout.split() == ["/robot1", "/robot2"], (done.stdout, done.stderr, run.output())
    # several robots, no --namespace, no terminal to ask on: the choice is the user's
    done = subprocess.run(
        [sys.executable, "-m", "robosc", "view", "--ros", "2"], env=env, capture_output=True, text=True, timeout=60,
        stdin=subprocess.DEVNULL,
    )
    assert done.returncode == 2
    assert "2 controllers found (/robot1, /robot2): choose one with --namespace" in done.stderr
    url = start_view(run, env, 2, "--namespace", "robot2")
    assert "live view of /robot2 on " + url in run.log("view")

    browser.get(url)
    assert browser.title == "MazeSolver: robosc live view"
    assert wait_until(lambda: browser.find_element("id", "status").text == "live", 20)
    count = lambda: int(browser.find_element("id", "count").text)  # noqa: E731
    assert wait_until(lambda: count() > 20, 30), run.output()  # the robot's events, as they happen
    where = lambda: browser.find_element("id", "where:Platform").text  # noqa: E731
    assert where() in ("ready", "turning", "unconfirmed")
    # unconfirmed for a moment where a busy machine makes an answer late: then known again
    assert wait_until(lambda: where() in ("ready", "turning"), 20), where()
    front = browser.find_element("id", "var:Distance.front").text
    assert front in ("wall_front", "no_wall_front")
    # zoom and pan: the wheel zooms the diagram in around the pointer, a drag moves it, a
    # double-click fits it again
    svg = browser.find_element("css selector", ".card svg")
    view_box = lambda: [  # noqa: E731
        float(x) for x in browser.execute_script("return arguments[0].getAttribute('viewBox')", svg).split()
    ]
    fit = view_box()
    browser.execute_script(
        "const r = arguments[0].getBoundingClientRect();"
        "arguments[0].dispatchEvent(new WheelEvent('wheel', {deltaY: -100, clientX: r.left + r.width / 2,"
        " clientY: r.top + r.height / 2, bubbles: true, cancelable: true}));",
        svg,
    )
    zoomed = view_box()
    assert zoomed[2] == pytest.approx(fit[2] / 1.2, rel=1e-3) and zoomed[3] == pytest.approx(fit[3] / 1.2, rel=1e-3)
    centre = fit[0] + fit[2] / 2
    assert zoomed[0] + zoomed[2] / 2 == pytest.approx(centre, abs=fit[2] * 0.01)  # around the pointer
    from selenium.webdriver.common.action_chains import ActionChains

    ActionChains(browser).move_to_element(svg).click_and_hold().move_by_offset(60, 0).release().perform()
    panned = view_box()
    assert panned[0] < zoomed[0] and panned[2] == pytest.approx(zoomed[2])  # dragged right: the view moves left
    ActionChains(browser).double_click(svg).perform()
    assert view_box() == pytest.approx(fit)
    browser.save_screenshot(str(run.tmp_path / "view.png"))
    # the robots go away (the simulation is ended): within 2 s of their last data the page no
    # longer says live (before: a green "live" over the old state, for ever)
    status = lambda: browser.find_element("id", "status").text  # noqa: E731
    sim = next(p for name, p in run.processes if name == "sim")
    children.stop([sim])
    assert wait_until(lambda: status().startswith("no data for "), 4), status()
    # and they come back on the same graph: live again
    start_sim(run, 2, robots=2, domain=int(env["ROS_DOMAIN_ID"]), name="sim again")
    assert wait_until(lambda: status() == "live", 60), (status(), run.output())


def test_robosc_view_on_ros1(run: Run) -> None:
    if not ros1_available():
        unavailable("ROS 1 (Debian's python3-rospy, python3-rosmaster)")
    env = start_sim(run, 1, robots=1)
    url = start_view(run, env, 1)  # one robot: no need to choose
    assert "live view of /robot1" in run.log("view")
    with urllib.request.urlopen(url, timeout=10) as page:
        assert b"<title>MazeSolver: robosc live view</title>" in page.read()
    records: list[dict[str, Any]] = []

    def moving() -> bool:
        with urllib.request.urlopen(url + "state", timeout=10) as answer:
            records.append(json.loads(answer.read()))
        return len({r["event"] for r in records if r}) >= 2

    assert wait_until(moving, 30, 0.3), run.output()
    assert {"Distance", "Platform"} <= set(records[-1]["state"]["automata"])
