"""The runtime's node core, messages, recording and warnings, in-process with fake
middleware: what a generated node does, without ROS."""

from __future__ import annotations

import json
import math
import time
from pathlib import Path
from typing import Any

import pytest

from robosc.api import load_model, plan_supervisor, synthesize_model
from robosc.debug.simulator import load_module
from robosc.runtime.onboard.claims import CLAIM_WAIT
from robosc.runtime.onboard.messages import Unsendable, conforms, fill, wire_type
from robosc.runtime.onboard.node import PARAMETERS, NodeCore, controller_side
from robosc.runtime.onboard.recording import EventLog
from robosc.runtime.onboard.supervisor import Communication, Warnings
from robosc.runtime.onboard.values import Data, finite

ROOT = Path(__file__).resolve().parent.parent


# ---- messages like ROS's: ROS 2 style (get_fields_and_field_types) and ROS 1 style (slots) ----
class Vector3:
    def __init__(self) -> None:
        self.x = self.y = self.z = 0.0

    @staticmethod
    def get_fields_and_field_types() -> dict[str, str]:
        return {"x": "double", "y": "double", "z": "double"}


class Twist:
    def __init__(self, x: float = 0.0, z: float = 0.0) -> None:
        self.linear, self.angular = Vector3(), Vector3()
        self.linear.x, self.angular.z = x, z

    @staticmethod
    def get_fields_and_field_types() -> dict[str, str]:
        return {"linear": "geometry_msgs/Vector3", "angular": "geometry_msgs/Vector3"}

    def __repr__(self) -> str:  # the test ids: the same in every pytest-xdist worker
        return f"Twist({self.linear.x!r}, {self.angular.z!r})"


class Int16:  # ROS 1 style: slots and slot types
    __slots__ = ("data",)
    _slot_types = ("int16",)
    _type = "std_msgs/Int16"

    def __init__(self) -> None:
        self.data = 0


class Float32:
    __slots__ = ("data",)
    _slot_types = ("float32",)
    _type = "std_msgs/Float32"

    def __init__(self) -> None:
        self.data = 0.0


class FakeNode(NodeCore):
    """Middleware that records what the node would put on the wire."""

    def __init__(self, model: str, mode: str, **params: Any) -> None:
        """A node of ``model``, which takes the model's initial state as confirmed unless
        ``trust_initial_state`` is given (the node's default is not to)."""
        params.setdefault("trust_initial_state", True)
        self.published: list[tuple[str, Any]] = []
        self.texts: list[tuple[str, str]] = []
        self.logs: list[tuple[str, str]] = []
        module = load_module(plan_supervisor(synthesize_model(load_model(ROOT / model))))
        self.setup(module.Robot, mode, params, lambda level, text: self.logs.append((level, text)))
        if self.claim is not None:  # a fake graph: no other controller to listen for (test_claims.py)
            self.listening_since -= CLAIM_WAIT
            self.decide()
        self.warnings.interval = 0.0  # every warning, for the tests
        for topic in list(self.inputs.values()) + list(self.outputs.values()):
            topic.type = {"Twist": Twist, "Int16": Int16, "Float32": Float32}.get(topic.type_name, Data)

    listening = True  # whether the robot subscribes to the node's command topics

    def subscribers(self, publisher: Any) -> int:
        return int(self.listening)

    def publish(self, topic: Any, message: Any) -> bool:
        self.published.append((topic.name, message))
        return True

    def publish_text(self, topic_name: str, text: str) -> None:
        self.texts.append((topic_name, text))

    def blocked_reports(self) -> list[dict[str, Any]]:
        return [json.loads(text) for name, text in self.texts if name == "blocked"]


def line_follower(mode: str, **params: Any) -> FakeNode:
    """The line follower with a clear scan, its start's wait for data waived (correction)."""
    node = FakeNode("examples/line_follower.rscd", mode, **{"wait_for_data": False, **params})
    node.receive(node.inputs["/scan"], Data({"ranges": [5.0] * 360}))
    return node


# ---- supervision layer: fail closed ---------------------------------------------------------
HOSTILE = [
    Twist(5.0, 0.0),  # a speed no event sends
    Twist(float("nan"), 0.0),
    Twist(0.15, float("nan")),  # move's constant part, but not finite
    Twist(0.0, float("inf")),
    Twist(-2.0, 3.0),
    Data({}),  # no fields at all
    Data({"linear": "fast"}),
    None,
    "move",
    42,
]


@pytest.mark.parametrize("message", HOSTILE, ids=repr)
def test_a_message_that_matches_no_event_is_blocked_and_reported(message: Any) -> None:
    node = line_follower("supervisor")
    node.receive(node.inputs["/emergency_stop/stop"], None)  # the emergency stop is pressed
    assert node.request(node.outputs["/cmd_vel"], message) is False
    assert node.published == []  # nothing reached the robot
    report = node.blocked_reports()[-1]
    assert report["topic"] == "/cmd_vel" and report["event"] is None
    assert report["reason"] in ("is the data of no event on it now", "a number in it is not finite")
    assert node.blocked_count == 1 and node.forwarded_count == 0


def test_the_layer_forwards_an_allowed_event_as_itself_and_blocks_a_forbidden_one() -> None:
    node = line_follower("supervisor")
    node.receive(node.inputs["/emergency_stop/stop"], None)
    halt = Twist(0.0, 0.0)
    assert node.request(node.outputs["/cmd_vel"], halt) is True
    assert node.published == [("/cmd_vel", halt)]  # the controller's own message
    move = Twist(0.15, -0.1)
    assert node.request(node.outputs["/cmd_vel"], move) is False  # stopped: move is not allowed
    assert node.blocked_reports()[-1]["event"] == "move"
    assert node.blocked_reports()[-1]["reason"] == "the supervisor does not allow it now"
    node.receive(node.inputs["/emergency_stop/continue"], None)
    node.receive(node.inputs["/line/correction"], 10.0)
    assert node.request(node.outputs["/cmd_vel"], move) is True
    assert node.published[-1] == ("/cmd_vel", move)
    assert node.request(node.outputs["/cmd_vel"], halt) is False  # not stopped, line found, safe: no halt


def test_a_message_is_an_event_only_when_it_is_exactly_its_data() -> None:
    from robosc.runtime.onboard.supervisor import ANY

    move = {"linear": {"x": 0.15}, "angular": {"z": ANY}}
    halt = {"linear": {"x": 0.0}, "angular": {"z": 0.0}}
    assert conforms(Twist(0.15, 0.3), move) and not conforms(Twist(0.15, 0.3), halt)
    assert conforms(Twist(0.0, 0.0), halt) and not conforms(Twist(0.0, 0.0), move)
    assert not conforms(Twist(0.1500001, 0.0), move)  # a float64 field: exactly, no tolerance
    assert not conforms(Twist(1e-7, 0.0), halt)  # a nonzero velocity is not zero
    assert not conforms(Twist(0.15, math.nan), move) and not conforms(Twist(0.15, math.inf), move)
    sideways = Twist(0.0, 0.0)
    sideways.linear.y = 2.0  # a field the model does not provide must hold its default
    assert not conforms(sideways, halt)
    assert conforms(Twist(), None) and not conforms(Twist(0.1, 0.0), None)  # no data: all defaults
    wire = Float32()
    wire.data = 0.15000000596046448  # 0.15 as a float32 field carries it
    assert conforms(wire, 0.15) and not conforms(wire, 0.16)
    assert not conforms(True, 1) and not conforms(1, True)  # booleans are not numbers
    deep: Any = Data({})
    for _ in range(100):
        deep = Data({"inner": deep})
    assert not finite(deep)  # too deep to be a message: refused, not a RecursionError


# ---- controller: what goes on the wire -----------------------------------------------------
def test_the_controller_never_publishes_what_its_message_cannot_carry() -> None:
    node = FakeNode("examples/maze_solver.rscd", "controller")
    assert node.send("turn_left", 90) is True
    assert node.published[-1][0] == "/rotate_left" and node.published[-1][1].data == 90
    assert node.send("turn_left", 40000) is False  # outside Int16
    assert node.send("turn_left", 1.5) is False
    assert node.send("turn_left", True) is False
    assert node.send("movement", {"linear": {"x": float("nan")}}) is False
    assert node.send("movement", {"linear": {"w": 1.0}}) is False  # no such field
    node.checkpoint()
    assert len(node.published) == 1
    assert any("outside int16" in text for _, text in node.logs)


def test_a_command_nobody_subscribes_to_is_held_not_performed() -> None:
    """A message on a topic without subscribers is lost: the supervisor must not believe it
    sent it (a robot of the fleet not up yet, a link down). It is held and reported."""
    node = FakeNode("examples/maze_solver.rscd", "controller", tick_on_message=True)
    node.listening = False
    node.receive(node.inputs["/scan"], Data({"ranges": [0.3] + [5.0] * 359}))
    node.cycle()
    assert node.published == []
    assert "turn_left" in node.supervisor.allowed()  # not performed: the turn is still to be made
    assert any("held: turn_left: nothing subscribes to /rotate_left" in text for _, text in node.logs)
    node.listening = True  # the robot subscribes
    node.cycle()
    assert [name for name, _ in node.published] == ["/rotate_left"]
    layer = line_follower("supervisor")  # a supervision layer forwards only to a robot that listens
    layer.receive(layer.inputs["/emergency_stop/stop"], None)
    layer.listening = False
    assert layer.request(layer.outputs["/cmd_vel"], Twist(0.0, 0.0)) is False
    assert layer.published == [] and layer.blocked_reports()[-1]["reason"] == "nothing subscribes to /cmd_vel"
    layer.listening = True  # the next refusal is the supervisor's own, and says so
    assert layer.request(layer.outputs["/cmd_vel"], Twist(0.15, -0.1)) is False
    assert layer.blocked_reports()[-1]["reason"] == "the supervisor does not allow it now"
    waived = FakeNode("examples/maze_solver.rscd", "controller", wait_for_listeners=False, tick_on_message=True)
    waived.listening = False
    waived.receive(waived.inputs["/scan"], Data({"ranges": [0.3] + [5.0] * 359}))
    assert [name for name, _ in waived.published] == ["/rotate_left"]


def test_fill_checks_ranges_and_types() -> None:
    assert fill(Float32(), 0.5).data == 0.5
    with pytest.raises(Unsendable, match="outside float32"):
        fill(Float32(), 1e39)
    with pytest.raises(Unsendable, match="not finite"):
        fill(Float32(), math.inf)
    message = fill(Twist(), {"linear": {"x": 1}, "angular": {"z": -0.5}})
    assert (message.linear.x, message.angular.z) == (1.0, -0.5) and type(message.linear.x) is float


def test_wire_types_follow_the_original_unless_an_interface_is_linked() -> None:
    def comm(data: str, interface: str | None = None) -> Communication:
        return Communication("c", "incoming", "/c", interface, data)

    assert wire_type(comm("double")) == ("std_msgs", "Float32")
    assert wire_type(comm("integer")) == ("std_msgs", "Int16")
    assert wire_type(comm("boolean")) == ("std_msgs", "Bool")
    assert wire_type(comm("string")) == ("std_msgs", "String")
    assert wire_type(comm("none")) == ("std_msgs", "Empty")
    assert wire_type(comm("double", "std_msgs/Float64")) == ("std_msgs", "Float64")


def test_tick_on_message_runs_a_cycle_after_each_message() -> None:
    node = FakeNode("examples/maze_solver.rscd", "controller", tick_on_message=True)
    node.receive(node.inputs["/scan"], Data({"ranges": [0.3] + [5.0] * 359}))
    assert [name for name, _ in node.published] == ["/rotate_left"]  # no timer needed
    node.receive(node.inputs["/rotate_done"], None)
    assert node.published[-1][0] == "/rotate_left"  # ready again, the wall still in front
    quiet = FakeNode("examples/maze_solver.rscd", "controller")
    quiet.receive(quiet.inputs["/scan"], Data({"ranges": [0.3] + [5.0] * 359}))
    assert quiet.published == []  # default: commands come with the timer's cycle
    quiet.cycle()
    assert [name for name, _ in quiet.published] == ["/rotate_left"]


def test_a_malformed_message_never_stops_the_node() -> None:
    node = FakeNode("examples/maze_solver.rscd", "controller", tick_on_message=True)
    for bad in (None, 42, Data({"ranges": "x"}), Data({"ranges": [math.nan] * 360}), object()):
        node.receive(node.inputs["/scan"], bad)
    assert not [name for name, _ in node.published if name == "/rotate_left"]


# ---- parameters -------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("name", "value"),
    [
        ("rate", 0.0),
        ("rate", float("nan")),
        ("rate", -5.0),
        ("rate", "fast"),
        ("view_port", 70000),
        ("seed", -7),
        ("qos_depth", 0),
        ("server_timeout", float("inf")),
        ("publish_state", "yes"),
    ],
)
def test_a_bad_parameter_is_refused_with_a_log_line(name: str, value: Any) -> None:
    node = FakeNode("examples/maze_solver.rscd", "controller", **{name: value})
    default = next(p.default for p in PARAMETERS if p.name == name)
    assert node.params[name] == default
    assert [level for level, text in node.logs if name in text] == ["error"]


def test_good_parameters_are_taken() -> None:
    node = FakeNode("examples/maze_solver.rscd", "controller", rate=20, seed=3, qos_depth=5)
    assert node.params["rate"] == 20.0 and type(node.params["rate"]) is float
    assert (node.params["seed"], node.params["qos_depth"]) == (3, 5)
    assert node.logs == []


def test_an_unwritable_event_log_is_refused(tmp_path: Path) -> None:
    node = FakeNode("examples/maze_solver.rscd", "controller", event_log=str(tmp_path / "missing/dir/log.jsonl"))
    assert node.event_log is None and node.logs[0][0] == "error"


def test_names_of_a_supervision_layer() -> None:
    assert controller_side("/cmd_vel") == "/robosc/controller/cmd_vel"
    assert controller_side("cmd_vel") == "robosc/controller/cmd_vel"  # relative stays relative


# ---- bounded: the event log and the warnings ---------------------------------------------------
def test_event_log_rotates_at_its_size(tmp_path: Path) -> None:
    path = tmp_path / "events.jsonl"
    node = FakeNode(
        "examples/maze_solver.rscd", "controller", event_log=str(path), event_log_max_bytes=4000, tick_on_message=True
    )
    node.start_recording()
    for i in range(300):
        node.receive(node.inputs["/scan"], Data({"ranges": [0.3 if i % 2 else 5.0] + [5.0] * 359}))
        node.receive(node.inputs["/rotate_done"], None)
    assert node.event_log is not None and node.event_log.rotations > 3
    assert path.stat().st_size <= 4000 and (tmp_path / "events.jsonl.1").stat().st_size <= 4000
    assert not (tmp_path / "events.jsonl.2").exists()
    lines = path.read_text().splitlines()
    assert lines and all(json.loads(line)["state"] for line in lines)  # whole records only
    unbounded = EventLog(str(tmp_path / "all.jsonl"), 0)
    for _ in range(100):
        unbounded({"event": "x" * 100})
    assert unbounded.rotations == 0


class Failing:
    """A file whose writes fail while ``full``, the first failing write torn half-way."""

    def __init__(self, handle: Any) -> None:
        self.handle, self.full, self.tore, self.closed = handle, False, False, False

    def write(self, data: bytes) -> int:
        if self.full:
            if not self.tore:
                self.tore = True
                self.handle.write(data[: len(data) // 2])
            raise OSError(28, "No space left on device")
        return int(self.handle.write(data))

    def tell(self) -> int:
        return int(self.handle.tell())

    def close(self) -> None:
        self.handle.close()
        raise OSError(28, "No space left on device")


def test_an_event_log_that_cannot_be_written_says_so_once_and_goes_on_when_it_can(tmp_path: Path) -> None:
    """A full disk (issue 47): each record is one unbuffered write; a failing one is said once and
    lost, the line it tore ended; when records are written again that is said, with how many
    were lost; closing never fails."""
    said: list[str] = []
    path = tmp_path / "events.jsonl"
    log = EventLog(str(path), 0, said.append)
    log({"event": "a"})
    log.handle = failing = Failing(log.handle)  # type: ignore[assignment]
    failing.full = True
    for name in "bcd":
        log({"event": name})
    assert said == [f"cannot write the event log {path} (OSError: [Errno 28] No space left on device): events are not logged until it can be"]
    failing.full = False
    log({"event": "e"})
    assert said[1:] == [f"the event log {path} is written again (3 events were not)"]
    log.close()
    lines = path.read_text().splitlines()
    assert [json.loads(line)["event"] for line in (lines[0], lines[2])] == ["a", "e"] and len(lines) == 3


def test_view_topics_carry_events_only_while_someone_listens() -> None:
    node = FakeNode("examples/maze_solver.rscd", "controller", tick_on_message=True)
    listeners = [0]
    node.text_subscribers = lambda name: listeners[0] if name == "live_view/events" else 0  # type: ignore[method-assign]
    snapshots = [0]
    snapshot = node.supervisor.snapshot

    def counted() -> Any:
        snapshots[0] += 1
        return snapshot()

    node.supervisor.snapshot = counted
    node.view_topics = True
    node.start_recording()
    scan = Data({"ranges": [0.3] + [5.0] * 359})
    node.receive(node.inputs["/scan"], scan)
    views = [name for name, _ in node.texts if name.startswith("live_view")]
    assert views == [] and snapshots[0] == 0  # nobody listens: no record is even made
    listeners[0] = 1  # looked at by the next cycle, at most every 0.1 s (it is a middleware call)
    node.receive(node.inputs["/scan"], scan)
    assert [name for name, _ in node.texts if name.startswith("live_view")] == []
    time.sleep(0.11)
    node.cycle()
    node.texts.clear()
    node.receive(node.inputs["/scan"], scan)
    events = [json.loads(text) for name, text in node.texts if name == "live_view/events"]
    assert [e["event"] for e in events][:3] == ["scan_front", "scan_right", "scan_diag_right"]
    assert events[0]["state"]["variables"]["Distance.front"] == "wall_front"
    node.texts.clear()
    node.start_view_topics(b"<html>page</html>")
    assert node.texts[0] == ("live_view/page", "<html>page</html>")
    assert node.texts[1][0] == "live_view/events" and json.loads(node.texts[1][1])["event"] is None


def test_the_state_record_a_view_starts_from_is_stamped_by_the_nodes_clock_as_its_events_are() -> None:
    """Under use_sim_time the node's clock is the simulation's: a page must not start from the
    wall clock and then go on in simulated seconds."""
    node = FakeNode("examples/maze_solver.rscd", "controller", tick_on_message=True)
    records: list[dict[str, Any]] = []
    node.sinks.append(records.append)
    node.start_outputs(type(node.supervisor), lambda: 175.94, lambda: None)
    node.receive(node.inputs["/scan"], Data({"ranges": [0.3] + [5.0] * 359}))
    assert records and {r["time"] for r in records} == {175.94}
    assert node.state_record()["time"] == 175.94


def test_view_page_is_read_only_when_asked_for() -> None:
    off = FakeNode("examples/maze_solver.rscd", "controller", view_topics=False)
    assert off.view_page(type(off.supervisor)) is None and off.logs == [] and not off.view_topics
    on = FakeNode("examples/maze_solver.rscd", "controller")  # view_topics by default; this package has no page
    assert on.view_page(type(on.supervisor)) is None and not on.view_topics
    assert on.logs[-1][0] == "warning" and "no live view page for robosc view" in on.logs[-1][1]
    served = FakeNode("examples/maze_solver.rscd", "controller", view_port=8765)
    assert served.view_page(type(served.supervisor)) is None
    assert served.logs[-1][0] == "error" and "live view not started on port 8765" in served.logs[-1][1]


def test_warnings_are_rate_limited() -> None:
    now = [0.0]
    out: list[str] = []
    warn = Warnings(out.append, interval=5.0, clock=lambda: now[0])
    for _ in range(1000):
        warn("scan: unreadable", "scan")
    assert out == ["scan: unreadable"]
    warn("other", "other")
    now[0] = 6.0
    warn("scan: unreadable", "scan")
    assert out == ["scan: unreadable", "other", "scan: unreadable (and 999 more like it)"]
