"""The live view in a real browser: Debian's headless Chromium, driven through chromedriver
(selenium), opens the page while the simulator runs a script; the highlighted state
and the variables must change as the script says. The test saves a screenshot."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from robosc import children
from ros_support import free_port, unavailable, wait_until

ROOT = Path(__file__).resolve().parent.parent
CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"


@pytest.fixture
def browser(tmp_path: Path) -> Iterator[Any]:
    if not (os.path.exists(CHROMIUM) and os.path.exists(CHROMEDRIVER)):
        unavailable("Chromium (Debian's chromium and chromium-driver)")
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in (
        "--headless=new",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-dev-shm-usage",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--window-size=1500,1100",
        f"--user-data-dir={tmp_path / 'chromium'}",
    ):
        options.add_argument(flag)
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    try:
        yield driver
    finally:
        driver.quit()


def simulate(tmp_path: Path, port: int, *args: str) -> subprocess.Popen[bytes]:
    log = open(tmp_path / "simulate.log", "wb")  # noqa: SIM115 (closed with the process)
    process = children.start(
        [sys.executable, "-m", "robosc", "simulate", *args, "--view", "--port", str(port)],
        stdout=log,
        stderr=subprocess.STDOUT,
    )
    assert wait_until(lambda: _serving(port), 30), (tmp_path / "simulate.log").read_text()
    return process


def _serving(port: int) -> bool:
    import urllib.request

    try:
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=1) as response:
            return bool(response.status == 200)
    except OSError:
        return False


def current(driver: Any, automaton: str) -> list[str]:
    """The locations the page highlights for one automaton."""
    return list(
        driver.execute_script(
            "return Array.from(document.querySelectorAll('#card\\\\:' + CSS.escape(arguments[0]) + ' g.node.current'))"
            ".map(g => g.id.split('::')[1]);",
            automaton,
        )
    )


def text(driver: Any, element_id: str) -> str:
    return str(driver.execute_script("return document.getElementById(arguments[0]).textContent;", element_id))


def test_live_view_follows_a_scripted_run(browser: Any, tmp_path: Path) -> None:
    script = tmp_path / "maze.txt"
    script.write_text(
        "sleep 4\n"  # the browser connects
        "tick\n"
        "sleep 2\n"
        'scan_front {"ranges": [0.3]}\n'
        "sleep 2\n"
        "tick\n"  # turn left
        "sleep 2\n"
        "rotate_done\n"
        'scan_front {"ranges": [3.0]}\n'
        "sleep 2\n"
    )
    port = free_port()
    process = simulate(tmp_path, port, str(ROOT / "examples/maze_solver.rscd"), "--script", str(script), "--seed", "1")
    try:
        browser.get(f"http://127.0.0.1:{port}/")
        assert wait_until(lambda: text(browser, "status") == "live", 10)
        assert wait_until(lambda: current(browser, "Platform") == ["ready"], 5)
        assert current(browser, "Distance") == ["sensing"]
        assert wait_until(lambda: text(browser, "var:Distance.front") == "wall_front", 12), "the scan did not show"
        assert current(browser, "Platform") == ["ready"]
        assert wait_until(lambda: current(browser, "Platform") == ["turning"], 6), "the turn did not show"
        assert text(browser, "where:Platform") == "turning"
        assert text(browser, "last") == "turn_left"
        shot = tmp_path / "live_view.png"
        browser.save_screenshot(str(shot))
        assert shot.stat().st_size > 10_000
        if os.environ.get("ROBOSC_SCREENSHOT"):
            shutil.copy(shot, os.environ["ROBOSC_SCREENSHOT"])
        assert wait_until(lambda: current(browser, "Platform") == ["ready"], 6)
        assert wait_until(lambda: text(browser, "var:Distance.front") == "no_wall_front", 6)
        feed = browser.execute_script(
            "return Array.from(document.querySelectorAll('#feed li')).map(li => li.textContent);"
        )
        assert feed[:3] == ["scan_front no_wall_front", "rotate_done", "turn_left 90"]  # enum data, converted
        # the script is over; the page stays, and says the data will not change any more
        assert wait_until(lambda: text(browser, "status") == "ended: the simulation is over", 10)
    finally:
        children.stop([process])


def test_live_view_keeps_up_with_100_events_per_second(browser: Any, tmp_path: Path) -> None:
    port = free_port()
    log = tmp_path / "events.jsonl"
    process = simulate(
        tmp_path,
        port,
        str(ROOT / "examples/pick_and_light.rscd"),
        "--random",
        "1500",
        "--rate",
        "100",
        "--seed",
        "3",
        "--quiet",
        "--log",
        str(log),
    )
    try:
        browser.get(f"http://127.0.0.1:{port}/")
        assert wait_until(lambda: text(browser, "status") == "live", 10)
        time.sleep(3)
        # the simulator writes each event to its log as it happens (one line each, flushed): the
        # page has every one of them a moment later, however fast the machine runs the simulator
        def caught_up(written: int) -> bool:
            return wait_until(lambda: int(text(browser, "count")) >= written, 2)

        for _ in range(3):
            written = len(log.read_text().splitlines())
            assert caught_up(written), (written, text(browser, "count"))
            time.sleep(1)
        assert len(log.read_text().splitlines()) > written  # the simulator was still going
        # the page stays responsive: a script round trip and a screenshot are quick
        begin = time.monotonic()
        for _ in range(10):
            browser.execute_script("return document.getElementById('count').textContent;")
        assert (time.monotonic() - begin) / 10 < 0.25
        lag = browser.execute_script("return pending.length;")
        assert lag < 50  # events are drawn as they come, not piling up
        components = ["Camera", "Arm", "Light", "Speaker", "Stop"]
        assert all(len(current(browser, c)) == 1 for c in components)
        # the busy services and actions: their cells show a location of their plant
        seen = set()
        for _ in range(100):
            seen.add(browser.execute_script("return document.getElementById('plant:pick').textContent;"))
            time.sleep(0.02)
        assert seen & {"executing", "ready", "error"}, seen
    finally:
        children.stop([process])


def test_live_view_says_a_component_is_unconfirmed_and_highlights_none_of_its_locations(
    browser: Any, tmp_path: Path
) -> None:
    # a node sends null for what it has not confirmed (after a restart, an answer that may be a
    # copy, a command whose delivery is uncertain): the page says so, and shows no location
    from robosc.api import synthesize_file
    from robosc.debug.live import render_page

    page = tmp_path / "live.html"
    page.write_text(render_page(synthesize_file(ROOT / "examples/maze_solver.rscd")))
    browser.get(page.as_uri())  # no server: the page is fed by hand
    feed = "apply({state: {automata: arguments[0], variables: arguments[1]}}, false);"
    browser.execute_script(feed, {"Platform": "turning"}, {"Distance.front": "wall_front"})
    assert current(browser, "Platform") == ["turning"] and text(browser, "where:Platform") == "turning"
    browser.execute_script(feed, {"Platform": None}, {"Distance.front": None})
    assert current(browser, "Platform") == []
    assert text(browser, "where:Platform") == "unconfirmed"
    assert text(browser, "var:Distance.front") == "unconfirmed"
    browser.execute_script(feed, {"Platform": "ready"}, {"Distance.front": "no_wall_front"})
    assert current(browser, "Platform") == ["ready"] and text(browser, "where:Platform") == "ready"
