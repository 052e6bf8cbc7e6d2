"""The fleet's live view in a real browser (Debian's headless Chromium through chromedriver):
`robosc sim --view` on the warehouse, and the page fed by hand where a robot goes stale. What
the page draws is checked against the data it was given: each cell is drawn occupied exactly
when a robot's row says the robot is in it, reserved exactly when one drives into it; the
event list filtered by robot shows that robot's events only; a robot the coordinator has not
confirmed, or whose position stopped coming, is marked stale. The tests save screenshots
(ROBOSC_SCREENSHOT_DIR: copies them there)."""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest

from robosc import children
from robosc.api import synthesize_file
from robosc.cli.main import main
from robosc.debug.live import render_page
from robosc.debug.world_view import render_world_page
from robosc.runtime.onboard.live_server import LiveView
from robosc.sim.view import EventTail, PoseFeed, world_map
from robosc.sim.world import load_world
from ros_support import free_port, new_domain, ros2_available, unavailable, wait_until
from test_live_view import browser  # noqa: F401 (the fixture)

pytest.importorskip("irsim", reason="robosc sim needs IR-SIM (pip install '.[sim]')")

ROOT = Path(__file__).resolve().parent.parent
WORLD = ROOT / "examples/worlds/warehouse.yaml"
MODEL = ROOT / "examples/warehouse.rscd"
ROBOTS = ("bot1", "bot2", "bot3")

# everything the page shows, read in one script (the page does not change while it runs)
PAGE = """
const rows = {};
for (const tr of document.querySelectorAll('tr.robot')) {
  const name = tr.id.slice('robot:'.length);
  const get = (what) => document.getElementById(what + ':' + name).textContent;
  rows[name] = {loc: get('loc'), doing: get('doing'), cell: get('cell'), into: get('into'), why: get('why'),
                stale: tr.classList.contains('stale'),
                body: document.getElementById('body:' + name)?.getAttribute('visibility'),
                bodyStale: document.getElementById('body:' + name)?.classList.contains('stale')};
}
const cells = {};
for (const shape of document.querySelectorAll('#map polygon.cell')) {
  cells[shape.id.slice('cellshape:'.length)] = {
    occupied: shape.classList.contains('occupied'), reserved: shape.classList.contains('reserved'),
    person: shape.classList.contains('person'), stroke: shape.style.stroke,
    said: document.getElementById('occupancy:' + shape.id.slice('cellshape:'.length)).textContent};
}
const person = document.getElementById('person');
return {rows, cells, status: document.getElementById('status').textContent,
        clock: document.getElementById('clock').textContent,
        feed: Array.from(document.querySelectorAll('#feed li')).map((li) => li.textContent),
        person: person ? person.getAttribute('visibility') : null,
        door: document.getElementById('door')?.getAttribute('class'),
        others: {Door: document.getElementById('loc:Door').textContent,
                 cell: document.getElementById('var:Person.cell').textContent}};
"""


def page(driver: Any) -> dict[str, Any]:
    return dict(driver.execute_script(PAGE))


def shoot(driver: Any, tmp_path: Path, name: str) -> None:
    shot = tmp_path / name
    driver.save_screenshot(str(shot))
    assert shot.stat().st_size > 20_000
    if os.environ.get("ROBOSC_SCREENSHOT_DIR"):
        shutil.copy(shot, Path(os.environ["ROBOSC_SCREENSHOT_DIR"]) / name)


def consistent(seen: dict[str, Any]) -> None:
    """Each cell drawn as the robots' rows say: occupied by the robots in it, reserved by those
    driving into it (a robot's colour on the dashed edge), named in its label."""
    rows, cells = seen["rows"], seen["cells"]
    for cell, drawn in cells.items():
        inside = [r for r, row in rows.items() if row["cell"] == cell]
        coming = [r for r, row in rows.items() if row["into"] == cell]
        assert drawn["occupied"] == bool(inside), (cell, drawn, rows)
        assert drawn["reserved"] == bool(coming), (cell, drawn, rows)
        said = " ".join(inside) + ((" " if inside else "") + "→ " + " ".join(coming) if coming else "")
        assert drawn["said"] == said, (cell, drawn, rows)


def test_sim_view_shows_the_fleet_on_its_map_live(browser: Any, tmp_path: Path) -> None:  # noqa: F811
    port = free_port()
    log = tmp_path / "sim.log"
    with open(log, "wb") as out:
        process = children.start(
            [sys.executable, "-m", "robosc", "sim", str(WORLD), str(MODEL), "--ros", "none", "--view",
             "--port", str(port), "--speed", "10"],
            stdout=out, stderr=subprocess.STDOUT,
        )
    try:
        assert wait_until(lambda: "live view: http://127.0.0.1" in log.read_text(), 120), log.read_text()
        browser.get(f"http://127.0.0.1:{port}/")
        assert wait_until(lambda: page(browser)["status"] == "live", 20), log.read_text()
        assert wait_until(lambda: all(r["body"] == "visible" for r in page(browser)["rows"].values()), 10)
        assert sorted(page(browser)["rows"]) == list(ROBOTS)
        assert re.fullmatch(r"\d+\.\d s", page(browser)["clock"]), page(browser)["clock"]  # simulated seconds

        # the cells as the rows say, every time we look; a reservation and the person seen on the way
        reserved = person_cell = False
        end = time.monotonic() + 60
        while time.monotonic() < end and not (reserved and person_cell):
            seen = page(browser)
            consistent(seen)
            for cell, drawn in seen["cells"].items():
                if drawn["reserved"] and not reserved:
                    reserved = True
                    coming = [r for r, row in seen["rows"].items() if row["into"] == cell]
                    colour = browser.execute_script("return colour[arguments[0]];", coming[0])
                    rgb = tuple(int(colour[i : i + 2], 16) for i in (1, 3, 5))
                    assert drawn["stroke"] == "rgb({}, {}, {})".format(*rgb)
                    shoot(browser, tmp_path, "fleet_view_reserved.png")
                if drawn["person"] and seen["person"] == "visible" and not person_cell:
                    person_cell = True  # the person stands in c2 from about 46 s (examples/worlds/warehouse.yaml)
                    assert cell == "c2", cell
                    assert wait_until(lambda: page(browser)["others"]["cell"].startswith("at_c"), 5)
                    shoot(browser, tmp_path, "fleet_view_person.png")
            time.sleep(0.3)
        assert reserved and person_cell, page(browser)
        # the task queue, each robot's task and how long it has waited
        queue, tasks, waited = browser.execute_script(
            "return [document.getElementById('queue').textContent,"
            " Array.from(document.querySelectorAll('[id^=\"task:\"]')).map(e => e.textContent),"
            " Array.from(document.querySelectorAll('[id^=\"waited:\"]')).map(e => e.textContent)];"
        )
        assert re.fullmatch(r"tasks: \d done · \d under way · \d queued", queue), queue
        assert any(re.fullmatch(r"task\d: (\[shelf\] -> depot|shelf -> \[depot\])", t) for t in tasks), tasks
        assert any(re.fullmatch(r"\d+ s", w) for w in waited), waited

        # a robot on demand: its automaton's locations, the current one marked as its row says
        browser.find_element("id", "robot:bot2").click()
        chips = browser.execute_script(
            "const d = document.getElementById('detail:bot2');"
            "return [d.hidden, Array.from(d.querySelectorAll('.chip.current')).map(c => c.textContent),"
            " document.getElementById('loc:bot2').textContent, d.querySelectorAll('.chip').length];"
        )
        from robosc.api import load_model

        bot2 = next(c for c in load_model(ROOT / "examples/warehouse.rscd").components if c.name == "bot2")
        assert chips[0] is False and chips[1] == [chips[2]] and chips[3] == len(bot2.behaviours[0].states), chips

        # the event list by robot
        assert wait_until(lambda: len(page(browser)["feed"]) >= 20, 30)
        select = browser.find_element("id", "filter")
        # (bot1 first: the coordinator gives the first task to bot1, and the others wait their turn)
        for value, wanted in (("bot1", lambda e: e.startswith("bot1.")), ("-", lambda e: not e.startswith("bot"))):
            browser.execute_script("arguments[0].value = arguments[1]; arguments[0].dispatchEvent(new Event('change'));", select, value)
            shown = [line.split(" ")[1] for line in page(browser)["feed"]]
            assert shown and all(wanted(e) for e in shown), (value, shown)
        browser.execute_script("arguments[0].value = ''; arguments[0].dispatchEvent(new Event('change'));", select)
        shown = {line.split(" ")[1].split(".")[0] for line in page(browser)["feed"]}
        assert len(shown) >= 2, shown  # every robot's again
        shoot(browser, tmp_path, "fleet_view.png")

        # the run ends; the page says so and stays
        assert wait_until(lambda: page(browser)["status"].startswith("ended: all 3 tasks given are done"), 240), log.read_text()
        assert not any(r["stale"] for r in page(browser)["rows"].values())
        assert "still serving the fleet's live view" in log.read_text()
    finally:
        children.stop([process])
    assert "ok: all 3 tasks given are done" in log.read_text()


def test_sim_view_on_ros2_shows_the_coordinator_packages_events_and_stays_until_interrupted(
    browser: Any, tmp_path: Path  # noqa: F811
) -> None:
    """On ROS 2 the events are the generated coordinator's (read from its event log as it
    writes it), the frames the simulation's; after the run the page stays until Ctrl-C, and the
    exit code is the run's."""
    if not ros2_available():
        unavailable("ROS 2 (pip install '.[ros2]')")
    port = free_port()
    log = tmp_path / "sim.log"
    with open(log, "wb") as out:
        process = children.start(
            [sys.executable, "-m", "robosc", "sim", str(WORLD), str(MODEL), "--ros", "2", "--view", "--port", str(port),
             "--speed", "10", "--domain", str(new_domain()), "--record", str(tmp_path / "run")],
            stdout=out, stderr=subprocess.STDOUT,
        )
    try:
        assert wait_until(lambda: "live view: http://127.0.0.1" in log.read_text(), 120), log.read_text()
        browser.get(f"http://127.0.0.1:{port}/")
        assert wait_until(lambda: page(browser)["status"] == "live", 60), log.read_text()
        locations = set(page_meta_locations())
        assert wait_until(lambda: sum(e.split(" ")[1].endswith(".arrived") for e in page(browser)["feed"]) >= 2, 120)
        # a robot whose command is on its way is unconfirmed until the command is acknowledged
        # (milliseconds): the coordinator's log says when it is (a state record)
        def placed() -> bool:
            rows = page(browser)["rows"].values()
            return all(row["loc"] in locations and row["body"] == "visible" and not row["stale"] for row in rows)

        assert wait_until(placed, 10), json.dumps(page(browser)["rows"])
        seen = page(browser)
        consistent(seen)
        logged = [json.loads(line)["event"] for line in (tmp_path / "run/events/coordinator.jsonl").read_text().splitlines()]
        shown = [line.split(" ")[1] for line in seen["feed"]]
        assert shown and set(shown) <= set(logged), (shown, logged)  # the coordinator's own events
        shoot(browser, tmp_path, "fleet_view_ros2.png")

        # robosc view --world on the same graph: the coordinator's page, with the map drawn from
        # the poses the robots publish
        graph = dict(item.split("=", 1) for item in re.findall(r"\(watch: (.*?) robosc view", log.read_text())[0].split())
        view_port = free_port()
        view_log = tmp_path / "view.log"
        with open(view_log, "wb") as out:
            viewer = children.start(
                [sys.executable, "-m", "robosc", "view", "--ros", "2", "--world", str(WORLD), "--port", str(view_port)],
                env={**os.environ, **graph}, stdout=out, stderr=subprocess.STDOUT,
            )
        try:
            assert wait_until(lambda: "live view of /fleet on" in view_log.read_text(), 60), view_log.read_text()
            browser.get(f"http://127.0.0.1:{view_port}/")
            assert wait_until(lambda: placed() and all(row["cell"] in ("depot", "c1", "c2", "c3", "shelf")
                                                       for row in page(browser)["rows"].values()), 20), page(browser)
            consistent(page(browser))
            # the coordinator follows the simulation's clock, its first record (before any event) too
            assert re.fullmatch(r"\d+\.\d s", page(browser)["clock"]), page(browser)["clock"]
            # a deployed coordinator's stamps are the wall clock's: shown as the time of day
            wall = 1795710280.25
            shown = browser.execute_script("return [stamp(175.94), stamp(arguments[0])];", wall)
            assert shown == ["175.9 s", time.strftime("%H:%M:%S", time.localtime(wall)) + ".2"], shown
            shoot(browser, tmp_path, "fleet_view_remote.png")
            # the run ends and the graph goes: no pose comes any more, and the page says so per robot
            assert wait_until(lambda: "still serving the fleet's live view" in log.read_text(), 600), log.read_text()
            assert wait_until(lambda: all(r["why"].startswith("no position for") for r in page(browser)["rows"].values()), 20)
            assert all(r["stale"] and r["bodyStale"] for r in page(browser)["rows"].values())
        finally:
            children.stop([viewer])
        browser.get(f"http://127.0.0.1:{port}/")
        assert wait_until(lambda: page(browser)["status"].startswith("ended: all 3 tasks given are done"), 10)
    finally:
        if process.poll() is None:
            process.send_signal(signal.SIGINT)
        code = process.wait(timeout=30)
        children.stop([process])
    assert code == 0, log.read_text()[-3000:]


def page_meta_locations() -> list[str]:
    """The locations of a warehouse robot (bot1's automaton)."""
    result = synthesize_file(MODEL)
    return [loc.name for a in result.network.automata if a.name == "bot1" for loc in a.locations]


def test_a_robot_unconfirmed_or_without_position_is_marked_stale(browser: Any, tmp_path: Path) -> None:  # noqa: F811
    result = synthesize_file(MODEL)
    world = load_world(str(WORLD))
    view = LiveView(render_world_page(result, world_map(world)), port=0)
    try:
        browser.get(view.url)
        assert wait_until(lambda: page(browser)["status"] == "live", 10)
        state = {"automata": {"bot1": "depot", "bot2": "to_out1", "bot3": "depot", "Door": "open", "Person": "watching"},
                 "variables": {"Person.cell": "away"}, "communications": {}, "data": {}}

        def frame(t: float, robots: tuple[str, ...], into: str = "c1") -> dict[str, Any]:
            where = {"bot1": (1.2, 0.6, "depot", ""), "bot2": (3.6, 3.3, "c1", into), "bot3": (1.2, 2.0, "depot", "")}
            return {"time": t, "state": state, "frame": {"t": t, "person": None, "door": "open", "robots": {
                r: {"x": where[r][0], "y": where[r][1], "heading": 0.0, "doing": "driving", "cell": where[r][2],
                    "into": where[r][3], "tasks": 0, "collided": False} for r in robots}}}

        view.publish(frame(1.0, ROBOTS))
        assert wait_until(lambda: page(browser)["rows"]["bot2"]["cell"] == "c1", 10)
        seen = page(browser)
        consistent(seen)
        assert not any(r["stale"] for r in seen["rows"].values()), seen["rows"]
        assert seen["cells"]["c1"]["occupied"] and not seen["cells"]["c2"]["occupied"]
        assert seen["rows"]["bot2"]["loc"] == "to_out1" and seen["others"] == {"Door": "open", "cell": "away"}
        assert seen["door"] == "door open"

        # the coordinator no longer knows where bot2 is (a restart, a lost answer)
        state = {**state, "automata": {**state["automata"], "bot2": None}}
        view.publish({"time": 2.0, "event": "bot1.go", "controllable": True, "data": None, "state": state})
        assert wait_until(lambda: page(browser)["rows"]["bot2"]["why"] == "unconfirmed", 5)
        seen = page(browser)
        assert seen["rows"]["bot2"]["stale"] and seen["rows"]["bot2"]["bodyStale"] and seen["rows"]["bot2"]["loc"] == "–"
        assert [r for r, row in seen["rows"].items() if row["stale"]] == ["bot2"]
        assert seen["feed"] == ["2.0 bot1.go"]

        # confirmed again, but its position stops coming while the others' come
        state = {**state, "automata": {**state["automata"], "bot2": "out1"}}
        started = time.monotonic()
        while time.monotonic() - started < 3.5:
            view.publish(frame(3.0 + time.monotonic() - started, ("bot1", "bot3")))
            time.sleep(0.2)
        seen = page(browser)
        assert seen["rows"]["bot2"]["why"].startswith("no position for "), seen["rows"]
        assert [r for r, row in seen["rows"].items() if row["stale"]] == ["bot2"]
        consistent(seen)  # drawn where it was last seen: c1 held by it
        assert seen["cells"]["c1"]["said"] == "bot2" and seen["rows"]["bot2"]["body"] == "visible"
        shoot(browser, tmp_path, "fleet_view_stale.png")
        view.publish(frame(7.0, ROBOTS, into="c2"))  # and on its way into c2: c2 is reserved for it
        assert wait_until(lambda: not page(browser)["rows"]["bot2"]["stale"], 5)
        seen = page(browser)
        consistent(seen)
        assert seen["cells"]["c2"]["reserved"] and seen["cells"]["c2"]["said"] == "→ bot2"
        assert not seen["cells"]["c1"]["reserved"] and seen["cells"]["c1"]["said"] == "bot2"
    finally:
        view.close()


def test_a_coordinators_page_without_a_world_lists_the_robots_without_a_map(browser: Any) -> None:  # noqa: F811
    result = synthesize_file(MODEL)
    view = LiveView(render_world_page(result), port=0)
    try:
        browser.get(view.url)
        assert wait_until(lambda: page(browser)["status"] == "live", 10)  # connected: what is published now is live
        state = {"automata": {"bot1": "shelf", "bot2": "depot", "bot3": None, "Door": "closed", "Person": "watching"},
                 "variables": {"Person.cell": "at_c2"}}
        view.publish({"time": 5.0, "event": "person_cell", "controllable": False, "data": "c2", "state": state})
        assert wait_until(lambda: page(browser)["rows"]["bot1"]["loc"] == "shelf", 10)
        seen = page(browser)
        assert seen["cells"] == {} and browser.execute_script("return document.getElementById('mapcard').hidden;") is True
        assert [r for r, row in seen["rows"].items() if row["stale"]] == ["bot3"]  # no map: unconfirmed only
        assert seen["feed"] == ['5.0 person_cell c2'] and seen["others"]["cell"] == "at_c2"
    finally:
        view.close()


def test_the_event_log_is_read_as_it_grows_whole_lines_only(tmp_path: Path) -> None:
    log = tmp_path / "events.jsonl"
    tail = EventTail(log)
    assert tail.read() == []  # not there yet
    log.write_text('{"event": "a"}\n{"event": "b"')
    assert tail.read() == [{"event": "a"}]
    with open(log, "a") as handle:
        handle.write('}\nnot json\n[1]\n{"event": "c"}\n')
    assert tail.read() == [{"event": "b"}, {"event": "c"}]
    assert tail.read() == []
    log.write_text('{"event": "d"}\n')  # rotated: a new, shorter file
    assert tail.read() == [{"event": "d"}]


@pytest.mark.parametrize("ros", ["none", "2"])
def test_sim_view_shows_a_world_with_a_goal_and_each_robots_events(browser: Any, tmp_path: Path, ros: str) -> None:  # noqa: F811
    """The same view for robots that each have a controller of their own (the maze): the map with
    the goal, every robot on it, each robot's events named for it (the list filters by robot),
    and the end of the run; in this process, and on ROS 2 (the events read from each controller
    node's event log)."""
    if ros == "2" and not ros2_available():
        unavailable("ROS 2 (rclpy) is not installed")
    port = free_port()
    log = tmp_path / "sim.log"
    domain = ["--domain", str(new_domain())] if ros == "2" else []
    with open(log, "wb") as out:
        process = children.start(
            [sys.executable, "-m", "robosc", "sim", str(ROOT / "examples/worlds/maze.yaml"),
             str(ROOT / "examples/maze_solver.rscd"), "--ros", ros, "--robots", "2", "--view",
             "--port", str(port), "--speed", "10", "--timeout", "120", *domain],
            stdout=out, stderr=subprocess.STDOUT,
        )
    try:
        assert wait_until(lambda: "live view: http://127.0.0.1" in log.read_text(), 120), log.read_text()
        browser.get(f"http://127.0.0.1:{port}/")
        seen = lambda: browser.execute_script(  # noqa: E731
            "return {status: document.getElementById('status').textContent,"
            " clock: document.getElementById('clock').textContent,"
            " rows: Array.from(document.querySelectorAll('tr.robot')).map((tr) => tr.id.slice(6)),"
            " bodies: Array.from(document.querySelectorAll('#map g.robot')).map((g) => g.getAttribute('visibility')),"
            " goal: !!document.getElementById('goal'), cells: document.querySelectorAll('#map polygon.cell').length,"
            " feed: Array.from(document.querySelectorAll('#feed li')).map((li) => li.textContent)};"
        )
        assert wait_until(lambda: seen()["status"] == "live", 20), log.read_text()
        assert wait_until(lambda: seen()["bodies"] == ["visible", "visible"], 20), seen()
        now = seen()
        assert now["rows"] == ["robot1", "robot2"] and now["goal"] and now["cells"] == 0, now
        assert re.fullmatch(r"\d+\.\d s", now["clock"]), now["clock"]  # simulated seconds
        assert wait_until(lambda: {e.split(" ")[1].split(".")[0] for e in seen()["feed"]} == {"robot1", "robot2"}, 30)
        select = browser.find_element("id", "filter")
        browser.execute_script("arguments[0].value = 'robot2'; arguments[0].dispatchEvent(new Event('change'));", select)
        shown = [line.split(" ")[1] for line in seen()["feed"]]
        assert shown and all(e.startswith("robot2.") for e in shown), shown
        shoot(browser, tmp_path, f"world_view_maze_{ros}.png")
        assert wait_until(lambda: seen()["status"].startswith("ended: every robot reached the goal"), 240), log.read_text()
        assert "still serving the live view" in log.read_text()
    finally:
        children.stop([process])
    assert "ok: every robot reached the goal" in log.read_text()


def test_poses_make_frames_of_the_robots_heard_since_the_last(monkeypatch: pytest.MonkeyPatch) -> None:
    result = synthesize_file(MODEL)
    feed = PoseFeed(load_world(str(WORLD)))
    html = feed.page(render_world_page(result))  # the coordinator's page, as it publishes it
    assert '"cells": {"c1"' in html and feed.names == list(ROBOTS)
    assert feed.topics() == [*[[f"{r}.{w}", f"{r}/{w}"] for r in ROBOTS for w in ("pose", "destination")],
                             ["person.pose", "person/pose"]]
    with pytest.raises(ValueError, match="has a map already"):
        feed.page(html)
    with pytest.raises(ValueError, match="not a fleet coordinator's"):
        feed.page(render_page(synthesize_file(ROOT / "examples/maze_solver.rscd")))
    sent: list[dict[str, Any]] = []
    feed.attach(sent.append)
    clock = [100.0]
    monkeypatch.setattr("robosc.sim.view.time.monotonic", lambda: clock[0])
    feed.event({"time": 12.5, "event": "bot2.go", "state": {"automata": {"bot2": "to_out2"}}})
    feed.pose("bot2.destination", [6.4, 3.3, 0.0])  # where its move ends: in c2
    feed.pose("person.pose", [6.4, 4.8, 0.0])
    feed.pose("bot2.pose", [4.5, 3.3, 0.1])
    assert len(sent) == 1 and sent[0]["frame"]["robots"] == {}  # the first: nothing fresh yet
    clock[0] += 0.05
    feed.pose("bot1.pose", [1.2, 0.6, 0.0])  # within PUBLISH_SECONDS: kept for the next frame
    assert len(sent) == 1
    clock[0] += 0.1
    feed.pose("bot3.pose", [float("nan"), 0.0, 0.0])  # no pose: nothing
    assert len(sent) == 1
    feed.pose("bot1.destination", [float("nan"), float("nan"), 0.0])  # bot1 has no move under way
    frame = sent[-1]["frame"]
    assert sorted(frame["robots"]) == ["bot1", "bot2"] and frame["t"] == 12.5 and frame["person"] == [6.4, 4.8]
    assert frame["robots"]["bot2"]["cell"] == "c1" and frame["robots"]["bot2"]["into"] == "c2"
    assert frame["robots"]["bot1"]["cell"] == "depot" and frame["robots"]["bot1"]["into"] == ""
    assert sent[-1]["state"] == {"automata": {"bot2": "to_out2"}}
    clock[0] += 0.2
    feed.pose("person.pose", [float("nan"), float("nan"), 0.0])  # out of sight
    assert sent[-1]["frame"]["robots"] == {} and sent[-1]["frame"]["person"] is None
    feed.pose("bot2.destination", [float("nan"), float("nan"), 0.0])  # arrived: no move under way
    clock[0] += 0.2
    feed.pose("bot2.pose", [5.0, 3.3, 0.0])
    assert sent[-1]["frame"]["robots"]["bot2"]["into"] == ""
    json.dumps(sent, allow_nan=False)  # what the page gets parses in a browser


def test_view_with_a_world_that_is_not_a_fleets_is_refused(capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["view", "--ros", "2", "--world", str(ROOT / "examples/worlds/maze.yaml")])
    err = capsys.readouterr().err
    assert code == 2 and "is not a fleet's world" in err and "Traceback" not in err, err
