"""Where the proof meets the robot, in-process (issue 21): the hold until data comes, unreadable data, and a supervision layer that
forwards a command only when it is exactly the data of an event the supervisor allows now
(a property test over random messages of several types). The same on real ROS:
test_boundary_ros.py."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from hypothesis import given, settings
from hypothesis import strategies as st

from robosc.api import load_model, plan_supervisor, synthesize_model
from robosc.debug.simulator import load_module
from robosc.runtime.onboard.values import Data
from test_onboard import FakeNode, Float32, Int16, Twist

ROOT = Path(__file__).resolve().parent.parent
CLEAR = Data({"ranges": [5.0] * 360})
OBSTACLE = Data({"ranges": [0.2] + [5.0] * 359})


class Clock:
    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


def line_follower(**params: Any) -> FakeNode:
    return FakeNode("examples/line_follower.rscd", "controller", **params)


def commands(node: FakeNode, cycles: int = 20) -> list[float]:
    node.published.clear()
    for _ in range(cycles):
        node.cycle()
    return [m.linear.x for _, m in node.published]


def feed(node: FakeNode, scan: Any = CLEAR) -> None:
    node.receive(node.inputs["/scan"], scan)
    node.receive(node.inputs["/line/correction"], Float32Data(10.0))


def Float32Data(value: float) -> Float32:
    message = Float32()
    message.data = value
    return message


MOVE = 0.15


# ---- data ------------------------------------------------------------------------------------
def test_unreadable_scans_after_an_obstacle_leave_halt_the_only_command() -> None:
    clock = Clock()
    node = line_follower(data_timeout=0.5)
    node.supervisor.clock = clock
    feed(node)
    assert MOVE in commands(node)
    feed(node, OBSTACLE)
    assert set(commands(node)) == {0.0}
    for bad in (Data({"ranges": []}), Data({"ranges": [math.nan] * 360}), Data({}), None):
        feed(node, bad)
        assert set(commands(node)) == {0.0}, f"moved on {bad!r}"
    assert node.supervisor.health()["unreadable"] == {"scan": 4}
    assert node.supervisor.health()["stale"] == []
    clock.now += 0.6  # NaN scans only, for longer than data_timeout: whatever reads the scan is held
    feed(node, Data({"ranges": [math.nan] * 360}))
    assert commands(node) == []
    assert node.supervisor.health()["stale"] == ["scan"]
    assert node.supervisor.holds("move") == "held: no readable data on scan for 0.5 s"
    health = [json.loads(text) for name, text in node.texts if name == "health"]
    assert health[-1]["stale"] == ["scan"] and health[-1]["unreadable"] == {"scan": 5}
    feed(node)  # readable again
    assert MOVE in commands(node)
    assert node.supervisor.health()["stale"] == []


def test_a_fresh_maze_solver_allows_nothing_before_its_first_scan() -> None:
    node = FakeNode("examples/maze_solver.rscd", "controller")
    assert node.supervisor.allowed() == []
    assert commands(node) == []
    assert node.supervisor.health()["waiting_for"] == ["scan_diag_right", "scan_front", "scan_right"]
    node.receive(node.inputs["/scan"], Data({"ranges": [math.nan] * 360}))  # unreadable: still waiting
    assert node.supervisor.allowed() == [] and node.supervisor.held
    node.receive(node.inputs["/scan"], CLEAR)
    assert node.supervisor.allowed() == ["movement"]
    waived = FakeNode("examples/maze_solver.rscd", "controller", wait_for_data=False)
    assert waived.supervisor.allowed() == ["movement"]


# ---- the supervision layer: forwarded if and only if exactly an allowed event's data ------------
def _events(node: FakeNode) -> dict[str, Any]:
    return {e.name: e for e in node.outputs["/cmd_vel"].events}


finite_or_not = st.one_of(
    st.sampled_from([0.0, -0.0, 0.15, 0.1500000059604645, 1e-7, -1e-300, 5.0]),
    st.floats(allow_nan=True, allow_infinity=True, width=64),
)


@settings(max_examples=300, deadline=None)
@given(
    stopped=st.booleans(),
    correction=st.sampled_from([None, 10.0, -3.0]),
    values=st.fixed_dictionaries(
        {name: finite_or_not for name in ("lx", "ly", "lz", "ax", "ay", "az")},
    ),
    kind=st.sampled_from(["twist", "float", "int", "data"]),
)
def test_the_layer_forwards_exactly_what_an_allowed_event_sends(
    stopped: bool, correction: float | None, values: dict[str, float], kind: str
) -> None:
    node = FakeNode("examples/line_follower.rscd", "supervisor", wait_for_data=False)
    node.receive(node.inputs["/scan"], CLEAR)
    if correction is not None:
        node.receive(node.inputs["/line/correction"], Float32Data(correction))
    if stopped:
        node.receive(node.inputs["/emergency_stop/stop"], None)
    message: Any
    if kind == "twist":
        message = Twist(values["lx"], values["az"])
        message.linear.y, message.linear.z = values["ly"], values["lz"]
        message.angular.x, message.angular.y = values["ax"], values["ay"]
    elif kind == "float":
        message = Float32Data(values["lx"])
    elif kind == "int":
        message = Int16()
        message.data = 7
    else:
        message = Data({"linear": {"x": values["lx"]}})
    allowed = set(node.supervisor.allowed())
    # the oracle: the event's data, written out; computed fields finite, the rest exact
    exact = None
    if kind == "twist" and all(math.isfinite(v) for v in values.values()):
        still = values["ly"] == values["lz"] == values["ax"] == values["ay"] == 0.0
        if still and values["lx"] == 0.0 and values["az"] == 0.0 and "halt" in allowed:
            exact = "halt"
        elif still and values["lx"] == 0.15 and "move" in allowed:
            exact = "move"
    forwarded = node.request(node.outputs["/cmd_vel"], message)
    assert forwarded == (exact is not None), (values, kind, allowed)
    assert node.published == ([("/cmd_vel", message)] if exact else [])
    if exact is None:
        assert node.blocked_count == 1


def test_the_five_almost_halts_are_blocked() -> None:
    node = FakeNode("examples/line_follower.rscd", "supervisor", wait_for_data=False)
    node.receive(node.inputs["/scan"], CLEAR)
    node.receive(node.inputs["/line/correction"], Float32Data(10.0))
    node.receive(node.inputs["/emergency_stop/stop"], None)
    assert node.supervisor.allowed() == ["halt"]
    for part, axis, value in (("linear", "y", 2.0), ("angular", "x", 1.5), ("linear", "x", 1e-7),
                              ("linear", "z", -0.5), ("angular", "y", 0.3)):
        message = Twist()
        setattr(getattr(message, part), axis, value)
        assert node.request(node.outputs["/cmd_vel"], message) is False
    assert node.published == [] and node.blocked_count == 5
    assert {r["reason"] for r in node.blocked_reports()} == {"is the data of no event on it now"}
    assert node.request(node.outputs["/cmd_vel"], Twist()) is True


def test_a_held_layer_says_why_it_blocks() -> None:
    node = FakeNode("examples/line_follower.rscd", "supervisor")
    node.receive(node.inputs["/emergency_stop/stop"], None)
    assert node.request(node.outputs["/cmd_vel"], Twist()) is False
    assert node.blocked_reports()[-1] == {
        **node.blocked_reports()[-1],
        "event": "halt",
        "reason": "held: waiting for the first readable data on correction, scan",
    }


def test_every_example_module_loads_with_its_reads_and_domains() -> None:
    for model in ("line_follower", "maze_solver", "pick_and_light", "shelf_picker"):
        module = load_module(plan_supervisor(synthesize_model(load_model(ROOT / "examples" / f"{model}.rscd"))))
        robot = module.Robot(seed=0)
        assert len(robot.PLAN) == 16
        assert all(len(f) == 5 for f in robot.FIELDS)
        assert {c.name for c in robot.COMMUNICATIONS} >= robot.WAITED
    line = load_module(plan_supervisor(synthesize_model(load_model(ROOT / "examples/line_follower.rscd"))))
    assert line.Robot.EVENT["move"].reads == {"scan", "correction"} and line.Robot.EVENT["halt"].reads == {"scan"}
