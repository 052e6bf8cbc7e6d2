"""A fleet in one world on real middleware, as it would be deployed: `robosc sim` on the
warehouse's world starts the generated coordinator package (one node, namespace /fleet), a
driver node per robot and the simulator's node (the door, the person's detector), each offering
its topics under that namespace; the coordinator runs on the simulation's /clock. Every robot
does its task, none touches another, a wall or the door, and every command the coordinator
logged was obeyed and answered over ROS."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import time
import urllib.request
import xmlrpc.client
from pathlib import Path

import pytest

from robosc import children
from ros_support import free_port, logged_events, new_domain, ros1_available, ros2_available, unavailable

pytest.importorskip("irsim", reason="robosc sim needs IR-SIM (pip install '.[sim]')")

from robosc.api import plan_supervisor, synthesize_file
from robosc.cli.main import main
from robosc.debug.simulator import load_module
from robosc.debug.world_view import render_world_page
from robosc.sim.bridge.protocol import Whereabouts
from robosc.sim.fleet_ros import reports, run_fleet_ros, wiring
from robosc.sim.graph import BRIDGE_PACKAGE, Graph
from robosc.sim.world import load_world

ROOT = Path(__file__).resolve().parent.parent
WORLD = ROOT / "examples/worlds/warehouse.yaml"
MODEL = ROOT / "examples/warehouse.rscd"
LEGS = 10  # the warehouse task's moves


def logged(folder: Path) -> list[dict[str, object]]:
    return logged_events(folder / "events" / "coordinator.jsonl")


def check_answered(events: list[dict[str, object]], robots: tuple[str, ...], simulated: float) -> None:
    """Each robot was told to go and answered over ROS: a go, then its arrived (or stopped),
    before the next go; the legs of at least one task arrived (the run may end before the
    coordinator took the last robot's last answer); the log is stamped in simulated seconds."""
    names = [str(e["event"]) for e in events]
    arrived = 0
    for robot in robots:
        mine = [n.rpartition(".")[2] for n in names if n.startswith(robot + ".") and not n.endswith(("dock", "charged"))]
        assert mine.count("arrived") >= LEGS - 1, (robot, mine)
        arrived += min(LEGS, mine.count("arrived"))
        moving = False
        for what in mine:
            if what == "go":
                assert not moving, (robot, mine)
                moving = True
            elif what in ("arrived", "stopped"):
                assert moving, (robot, mine)
                moving = False
    assert arrived >= LEGS * len(robots) - 1
    times = [float(e["time"]) for e in events]  # type: ignore[arg-type]
    assert times == sorted(times) and times[0] >= 0 and times[-1] <= simulated + 0.5


def test_wiring_is_the_coordinators_topics_under_its_namespace() -> None:
    plan = plan_supervisor(synthesize_file(MODEL))
    commands, answers = wiring(plan, ["bot1", "bot2", "bot3"])
    assert ["bot2.go", "/fleet/bot2/go", "none"] in commands and ["open_door", "/fleet/open_door", "none"] in commands
    assert ["bot3.arrived", "/fleet/bot3/arrived", "none"] in answers
    assert ["door_closed", "/fleet/door_closed", "none"] in answers
    assert ["person_cell", "/fleet/person_cell", "string"] in answers  # the detector: the cell's name
    assert len(commands) == 3 * 2 + 2 and len(answers) == 3 * 3 + 2 + 1


def test_each_driver_of_the_world_knows_where_its_component_is_from_what_went_by() -> None:
    """The report each simulated driver gives (std_srvs/Trigger robosc/report/<component>)
    follows the model's moves over the commands it obeyed and the answers it gave."""
    plan = plan_supervisor(synthesize_file(MODEL))
    commands, answers = wiring(plan, ["bot1", "bot2", "bot3"])
    table = reports(plan, commands, answers)
    assert sorted(table) == ["Door", "bot1", "bot2", "bot3"]  # the person is told by its detector
    assert table["bot2"]["service"] == "/fleet/robosc/report/bot2" and table["Door"]["at"] == "closed"
    where = Whereabouts(json.loads(json.dumps(table)))  # as the bridge gets it, one JSON line
    assert where.where("bot1") == "depot"
    for name, expected in (("bot1.go", "to_out0"), ("bot1.stopped", "stopped_out0"), ("bot1.go", "to_out0"),
                           ("bot1.arrived", "out0"), ("bot1.go", "to_out1"), ("bot1.charged", "to_out1"),
                           ("bot1.arrived", "out1")):
        where.went(name)
        assert where.where("bot1") == expected, name  # an answer it cannot give from there moves nothing
    where.went("bot2.dock")
    where.went("open_door")
    assert (where.where("bot2"), where.where("bot3"), where.where("Door")) == ("charging", "depot", "opening")
    where.went("bot2.charged")
    where.went("door_opened")
    assert (where.where("bot2"), where.where("Door")) == ("ready", "open")  # charged: a task is next
    where.went("bot2.go")
    assert where.where("bot2") == "to_out0"


def test_the_simulators_node_is_copied_once_per_run_over_an_earlier_runs(tmp_path: Path) -> None:
    """A --record folder kept from an earlier run gets this run's simulator's node (an older one
    offers no report services: the coordinator would wait for ever), copied once for every node
    of the run."""
    package = tmp_path / "bridge" / BRIDGE_PACKAGE
    package.mkdir(parents=True)
    (package / "protocol.py").write_text("# an earlier robosc's\n")
    graph = Graph(2, tmp_path)
    assert graph.bridge_folder() == tmp_path / "bridge"
    assert (package / "protocol.py").read_text() == (ROOT / "src/robosc/sim/bridge/protocol.py").read_text()
    (package / "starting.txt").write_text("a driver node is importing from here")
    graph.bridge_folder()  # the next robot's driver
    assert (package / "starting.txt").exists()


def test_robosc_sim_runs_the_warehouse_fleet_on_ros2_as_deployed(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    if not ros2_available():
        unavailable("ROS 2 (pip install '.[ros2]')")
    folder = tmp_path / "run"
    args = ["sim", str(WORLD), str(MODEL), "--ros", "2", "--speed", "10", "--domain", str(new_domain()), "--timeout", "2400"]
    code = main([*args, "--record", str(folder)])
    out = capsys.readouterr().out
    assert code == 0, out + "\n" + "\n".join(p.read_text()[-3000:] for p in (folder / "logs").glob("*.log"))
    assert "3 robot(s) in warehouse, ROS 2" in out and "ok: all 3 tasks given are done" in out
    rows = re.findall(r"│ (bot\d) +│ +(\d+) │ +\d+ s │ +[\d.]+ m │ +([\d.]+) m │ +([\d.]+) m │ +\d+ │ +- │", out)
    assert [r[0] for r in rows] == ["bot1", "bot2", "bot3"], out  # with the closest approach to the person
    simulated = float(re.search(r"\(([\d.]+) s simulated", out).group(1))  # type: ignore[union-attr]
    check_answered(logged(folder), ("bot1", "bot2", "bot3"), simulated)
    # as deployed: the coordinator trusts no initial state; each driver says where it is
    coordinator = (folder / "logs" / "coordinator.log").read_text()
    for component in ("bot1", "bot2", "bot3", "Door"):
        assert f"{component} confirmed by its driver: {'closed' if component == 'Door' else 'depot'}" in coordinator
    from PIL import Image

    with Image.open(folder / "fleet.gif") as gif:  # the run's animation: a frame per 2 s simulated
        assert gif.n_frames == int(simulated / 2.0) + 1


def test_the_warehouse_fleet_runs_on_ros1_and_robosc_view_draws_it(tmp_path: Path) -> None:
    """The fleet on ROS 1, watched meanwhile by `robosc view --ros 1 --world` (the coordinator's
    page and events, the robots' Pose2D topics): every robot shows up on the view's map, in the
    world's cells, with the coordinator's belief beside it."""
    if not ros1_available():
        unavailable("ROS 1 (Debian's python3-rospy, python3-rosmaster)")
    result = synthesize_file(MODEL)
    plan = plan_supervisor(result)
    port = free_port()
    viewers: list[subprocess.Popen[bytes]] = []
    seen: dict[str, set[str]] = {}
    beliefs: set[str] = set()
    asked = [0.0]

    offered: dict[str, list[str]] = {}

    def on_start(graph: object) -> None:
        master = xmlrpc.client.ServerProxy(getattr(graph, "env", {})["ROS_MASTER_URI"])
        publishers, subscribers, services = master.getSystemState("/test")[2]
        offered.update({f"pub {t}": sorted(n) for t, n in publishers if t.startswith("/fleet/")})
        offered.update({f"sub {t}": sorted(n) for t, n in subscribers if t.startswith("/fleet/")})
        offered.update({f"srv {t}": sorted(n) for t, n in services if t.startswith("/fleet/")})
        env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
        log = open(tmp_path / "view.log", "wb")  # noqa: SIM115 (closed with the process)
        viewers.append(children.start(
            [sys.executable, "-m", "robosc", "view", "--ros", "1", "--world", str(WORLD), "--port", str(port)],
            env={**env, **getattr(graph, "env", {})}, stdout=log, stderr=subprocess.STDOUT,
        ))

    def on_step(world: object) -> None:  # what the view serves, once a second
        if time.monotonic() - asked[0] < 1.0:
            return
        asked[0] = time.monotonic()
        try:
            with urllib.request.urlopen(f"http://127.0.0.1:{port}/state", timeout=0.5) as response:
                last = json.loads(response.read())
        except (OSError, ValueError):
            return
        for name, robot in ((last or {}).get("frame") or {}).get("robots", {}).items():
            seen.setdefault(name, set()).add(robot["cell"])
        automata = ((last or {}).get("state") or {}).get("automata") or {}
        beliefs.update(str(v) for k, v in automata.items() if k == "bot1" and v is not None)  # null: unconfirmed

    try:
        report = run_fleet_ros(
            load_world(WORLD), plan, load_module(plan), 1, 3, timeout=2400.0, speed=10.0, folder=tmp_path,
            on_start=on_start, on_step=on_step, page=render_world_page(result),
            # answers overdue on long moves and charges (1 s wall): the coordinator asks the robots'
            # drivers, who say where they are from the commands they obeyed and answers they gave
            settings={"answer_timeout": 1.0},
        )
    finally:
        children.stop(viewers)
    assert report.ok, report.why + "\n" + "\n".join(p.read_text()[-3000:] for p in (tmp_path / "logs").glob("*.log"))
    assert report.collisions == 0 and report.ignored == 0
    assert all(s.tasks >= 1 for s in report.robots)
    check_answered(logged(tmp_path), ("bot1", "bot2", "bot3"), report.simulated)
    coordinator = (tmp_path / "logs" / "coordinator.log").read_text()
    overdue = re.findall(r"(bot\d): no answer \((bot\d)\.(?:arrived|charged)", coordinator)
    confirmed = re.findall(r"(bot\d) confirmed by its driver: (\w+)", coordinator)
    assert len(overdue) >= 3, coordinator[-3000:]
    # (an answer that comes after all confirms too: one only the command's target gives)
    assert {c for _, c in confirmed} - {"depot"}, confirmed  # reports from mid-move, from the charger
    # each robot's topics are its own driver node's; the door's and the detector's the simulator's
    assert offered["pub /fleet/bot2/arrived"] == ["/bot2_driver"] and offered["pub /fleet/bot2/pose"] == ["/bot2_driver"]
    assert "/bot3_driver" in offered["sub /fleet/bot3/go"] and "/bot1_driver" not in offered["sub /fleet/bot3/go"]
    assert offered["pub /fleet/door_opened"] == ["/robosc_sim"] and offered["pub /fleet/person_cell"] == ["/robosc_sim"]
    assert offered["srv /fleet/robosc/report/bot2"] == ["/bot2_driver"]  # each driver says where its robot is
    assert offered["srv /fleet/robosc/report/Door"] == ["/robosc_sim"]
    view_log = (tmp_path / "view.log").read_text()
    assert sorted(seen) == ["bot1", "bot2", "bot3"], (seen, view_log[-2000:])
    assert set().union(*seen.values()) <= {"depot", "c1", "c2", "c3", "shelf"} and "depot" in set().union(*seen.values())
    assert beliefs and beliefs <= {loc.name for a in result.network.automata if a.name == "bot1" for loc in a.locations}
