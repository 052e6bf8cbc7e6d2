"""The generated per-robot module and the runtime it runs on: Python 3.8, standard library
only, guards equal to the synthesized supervisor, start values equal to the network's
initial state, names that cannot collide, robust conversion, the tick of SEMANTICS.md 6."""

from __future__ import annotations

import ast
import json
import math
import subprocess
import sys
from collections import Counter
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings

from random_models import robots
from robosc.api import check_text, load_model, plan_supervisor, supervisor_module, synthesize_model
from robosc.codegen.module import runtime_files
from robosc.codegen.plan import plan
from robosc.codegen.pyexpr import GENERATED
from robosc.debug.simulator import load_module
from robosc.language import model as m
from robosc.plant import build_network
from robosc.runtime.onboard import VERSION, RuntimeMismatch, check_version
from robosc.runtime.onboard.supervisor import Supervisor
from robosc.runtime.onboard.values import Data
from robosc.synthesis.evaluate import Undefined, evaluate
from robosc.synthesis.explicit import synthesize_explicit
from robosc.synthesis.methods import synthesize_symbolic

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ["maze_solver", "line_follower", "pick_and_light"]
ADAPTER_IMPORTS = {"rospy", "actionlib", "rclpy", "rcl_interfaces"}  # only in ros1.py / ros2.py


def module_of(name: str) -> Any:
    result = synthesize_model(load_model(ROOT / "examples" / f"{name}.rscd"))
    return load_module(plan_supervisor(result))


def imports_of(text: str) -> set[str]:
    out = set()
    for node in ast.walk(ast.parse(text, feature_version=(3, 8))):
        if isinstance(node, ast.Import):
            out |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            out.add("." * node.level + (node.module or "").split(".")[0])
    return out


@pytest.mark.parametrize("name", EXAMPLES)
def test_module_imports_nothing_but_the_runtime(name: str) -> None:
    text = supervisor_module(synthesize_model(load_model(ROOT / "examples" / f"{name}.rscd")))
    assert imports_of(text) == {".onboard", "onboard"}


def test_runtime_is_standard_library_python_38() -> None:
    assert set(n for n in runtime_files() if not n.endswith(".py")) == {"fastdds.xml"}
    for name, text in runtime_files().items():
        if not name.endswith(".py"):
            continue
        outside = {i for i in imports_of(text) if not i.startswith(".")} - set(sys.stdlib_module_names)
        allowed = ADAPTER_IMPORTS if name in ("ros1.py", "ros2.py") else set()
        assert outside <= allowed, (name, outside)


def test_runtime_version_is_checked_and_matches_robosc() -> None:
    from importlib.metadata import version

    assert version("robosc") == VERSION
    check_version(VERSION)
    with pytest.raises(RuntimeMismatch, match="generate the package again"):
        check_version("0.0.1")


@pytest.mark.skipif(not list(Path("/root/.pyenv/versions").glob("3.8*")), reason="no Python 3.8 here")
def test_module_runs_on_python_38(tmp_path: Path) -> None:
    python = next(Path("/root/.pyenv/versions").glob("3.8*")) / "bin" / "python"
    (tmp_path / "maze_solver_supervisor.py").write_text(
        supervisor_module(synthesize_model(load_model(ROOT / "examples/maze_solver.rscd")))
    )
    (tmp_path / "onboard").mkdir()
    for name, text in runtime_files().items():
        (tmp_path / "onboard" / name).write_text(text)
    script = (
        "import maze_solver_supervisor as m\n"
        "from onboard.values import Data\n"
        "s = m.Robot(seed=1)\n"
        "print(s.tick())\n"  # nothing before the first scan
        "for e in ('scan_front', 'scan_right', 'scan_diag_right'): s.deliver(e, Data({'ranges': [5.0] * 360}))\n"
        "print(s.tick()); s.deliver('scan_front', Data({'ranges': [0.2]})); print(s.tick())\n"
        "import onboard.node, onboard.recording, onboard.messages, onboard.live_server, onboard.delivery\n"
        "s = m.Robot(seed=1, confirmed=False); print(s.allowed(), sorted(s.unsure()))\n"
    )
    done = subprocess.run([str(python), "-c", script], cwd=tmp_path, capture_output=True, text=True, check=True)
    assert done.stdout.split("\n")[:4] == ["None", "movement", "turn_left", "[] ['Distance', 'Platform']"]


def _load(state: Any, plan_: Any, sup: Any, network: Any) -> None:
    for (_, field), location in zip(plan_.automata, state.locations, strict=True):  # network order
        if field is not None:  # None: an automaton of one location
            setattr(sup, field, location.name)
    variable_fields = dict(plan_.variables)
    for variable, value in zip(network.variables, state.values, strict=True):
        setattr(sup, variable_fields[f"{variable.owner}.{variable.name}"], getattr(value, "name", value))
    sup._dirty = True


def _plant_takes(network: Any, event: Any, state: Any) -> bool:
    """The network's plants can take ``event`` in ``state`` (guards evaluated on the model's
    expressions; updates that would leave a range not considered: the runtime takes those
    messages and keeps the variable)."""
    locations = set(state.locations)
    values = dict(zip(network.variables, state.values, strict=True))
    for automaton in network.automata:
        if event not in automaton.alphabet:
            continue
        here = next(loc for loc in automaton.locations if loc in locations)
        ok = False
        for edge in automaton.edges:
            if edge.event is event and edge.source is here:
                try:
                    ok = edge.guard is None or evaluate(edge.guard, locations, values) is True
                except Undefined:
                    ok = False
                if ok:
                    break
        if not ok:
            return False
    return True


def _start_matches_the_network(module: Any, p: Any, network: Any) -> None:
    sup = module.Robot(seed=0)
    for automaton, (name, field) in zip(network.automata, p.automata, strict=True):
        assert name == automaton.name
        assert (field is None and len(automaton.locations) == 1) or getattr(sup, field) == automaton.initial.name
    for variable in network.variables:
        value = network.initial_values[variable]
        assert getattr(sup, dict(p.variables)[f"{variable.owner}.{variable.name}"]) == getattr(value, "name", value)


def _agrees(text: str) -> None:
    model = check_text(text).model
    assert model is not None, check_text(text).render()
    network = build_network(model)
    symbolic = synthesize_symbolic(network)
    if not symbolic.ok:  # nothing to run: planning refuses it
        with pytest.raises(ValueError, match="synthesis failed"):
            plan(symbolic)
        return
    explicit = synthesize_explicit(network)
    p = plan(symbolic)
    module = load_module(p)
    _start_matches_the_network(module, p, network)
    sup = module.Robot(seed=0)
    states = explicit.supervisor.controlled_states()[:400]
    assert states
    for state in states:
        _load(state, p, sup, network)
        allowed = set(sup.allowed())
        for event in network.controllable:
            if event.kind.value == "provide":
                continue
            assert (event.name in allowed) == symbolic.allows(event.name, state), (event.name, state)
        expected = {e.name for e in network.uncontrollable if _plant_takes(network, e, state)}
        assert set(sup.expected()) == expected, state


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(robots())
def test_compiled_guards_equal_the_synthesized_supervisor(text: str) -> None:
    """In every state reachable under the supervisor, the generated module allows exactly
    what the BDDs allow, ``expected()`` lists exactly what the plant can take, and the
    start state is the network's initial state."""
    _agrees(text)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(robots(adversarial=True))
def test_adversarial_names_generate_code_that_behaves(text: str) -> None:
    """Keywords, names of the runtime (timer, tick, lock, send, Robot, rt, ...) and names
    that concatenate to the same text (A.b_c / A_b.c, s.u_response / s_u_response)."""
    _agrees(text)
    model = check_text(text).model
    assert model is not None
    symbolic = synthesize_symbolic(build_network(model))
    if symbolic.ok:
        p = plan(symbolic)
        sup = load_module(p).Robot(seed=0)
        snapshot = sup.snapshot()
        assert sum(len(group) for group in snapshot.values()) == len(p.fields)  # nothing lost in the snapshot
        names = [f.name for f in p.fields] + [e.method for e in p.events]
        assert len(set(names)) == len(names) and all(GENERATED.match(n) for n in names)


def test_runtime_names_cannot_meet_generated_ones() -> None:
    from robosc.runtime.onboard import node

    own = set(dir(Supervisor)) | set(vars(node.NodeCore))
    assert not [n for n in own if GENERATED.match(n)]


START = """
robot Starts {
    datatype enum Level from double to { value < 1.0 -> low default -> high }
    component C {
        outgoing message level with type: Level
        outgoing message raw with type: double
        behaviour {
            variable b: boolean
            variable r: integer(2..5)
            variable z: integer(-3..3)
            variable e: Level
            variable d: double
            variable s: string
            variable i: integer
            variable b2: boolean = true
            variable r2: integer(2..5) = 4
            variable e2: Level = low
            variable d2: double = -1.5
            variable s2: string = "x"
            on response from level do e := value
            on response from raw do d := value
            initial marked state idle {
                transition if b or r = 2 or z = 0 or e = low or b2 or r2 = 4 or e2 = high goto idle
            }
        }
    }
}
"""


def test_start_values_of_every_variable_type() -> None:
    result = check_text(START)
    assert result.model is not None, result.render()
    synthesis = synthesize_model(result.model)
    p = plan(synthesis)
    sup = load_module(p).Robot(seed=0)
    values = sup.snapshot()["variables"]
    assert values == {
        "C.b": False,
        "C.r": 2,
        "C.z": 0,
        "C.e": "low",
        "C.d": 0.0,
        "C.s": "",
        "C.i": 0,
        "C.b2": True,
        "C.r2": 4,
        "C.e2": "low",
        "C.d2": -1.5,
        "C.s2": "x",
    }
    assert type(values["C.d"]) is float and type(values["C.i"]) is int
    _start_matches_the_network(load_module(p), p, synthesis.network)


def test_reset_returns_to_the_start() -> None:
    m_ = module_of("maze_solver")
    sup = m_.Robot(seed=1, wait_for_data=False)
    start = sup.snapshot()
    sup.deliver("scan_front", Data({"ranges": [0.3]}))
    assert sup.tick() == "turn_left"
    assert sup.snapshot() != start
    sup.reset()
    assert sup.snapshot() == start
    assert sup.tick() == "movement"  # the allowed events are computed again after a reset


def test_enum_conversion_refuses_data_it_cannot_read() -> None:
    from robosc.runtime.onboard.supervisor import Unreadable

    m_ = module_of("maze_solver")
    warnings: list[str] = []
    sup = m_.Robot(seed=1, warn=warnings.append)
    convert = sup.EVENT["scan_right"].convert
    wall = Data({"ranges": [5.0] * 240 + [0.5] + [5.0] * 119})
    assert sup.convert(convert, wall) == "wall_right"
    assert sup.convert(convert, Data({"ranges": [math.inf] * 360})) == "no_wall_right"  # REP 117: no return
    assert warnings == []
    for bad in (
        None,
        Data({}),
        Data({"ranges": [0.1]}),
        Data({"ranges": "text"}),
        42,
        Data({"ranges": [math.nan] * 360}),
    ):
        with pytest.raises(Unreadable, match="WallRight"):
            sup.convert(convert, bad)
    # delivered, unreadable data changes nothing and is counted
    assert sup.deliver("scan_right", wall) is True
    for bad in (Data({"ranges": []}), Data({"ranges": [math.nan] * 360}), Data({"ranges": [True] * 360})):
        assert sup.deliver("scan_right", bad) is False
    assert sup.snapshot()["variables"]["Distance.right"] == "wall_right"
    assert sup.health()["unreadable"] == {"scan_right": 3}
    assert len(warnings) == 1 and "scan_right: unreadable data" in warnings[0]  # the rest rate-limited


def test_received_data_stored_as_it_came_must_be_inside_its_variable_type() -> None:
    """``safety := value`` (an enum read from the scan): a value the enum does not have (the
    data of an enum-typed event given by name, ``raw`` False) is not taken; the variable keeps
    what it had."""
    p = plan_supervisor(synthesize_model(load_model(ROOT / "examples/line_follower.rscd")))
    field = {f.label: f.name for f in p.fields}["Lidar.safety"]
    warnings: list[str] = []
    sup = load_module(p).Robot(seed=1, warn=warnings.append)
    sup.warn.interval = 0.0
    assert sup.deliver("scan", "unsafe", raw=False) is True and getattr(sup, field) == "unsafe"
    for bad in ("Unsafe", None, 1, math.nan):
        assert sup.deliver("scan", bad, raw=False) is False
        assert getattr(sup, field) == "unsafe" and "Lidar.safety" in warnings[-1], warnings[-1]


def test_received_data_that_cannot_be_read_does_not_deliver_its_event() -> None:
    p = plan_supervisor(synthesize_model(load_model(ROOT / "examples/pick_and_light.rscd")))
    field = {f.label: f.name for f in p.fields}
    warnings: list[str] = []
    sup = load_module(p).Robot(seed=1, warn=warnings.append)
    sup.warn.interval = 0.0  # every warning, not rate-limited
    setattr(sup, field["Arm"], "picking")
    setattr(sup, field["pick"], "executing")
    assert sup.deliver("pick.u_feedback", Data({"sequence": []})) is False  # value.sequence[0] fails
    assert getattr(sup, field["Arm.progress"]) == 0
    assert sup.deliver("pick.u_feedback", Data({"sequence": ["x"]})) is False  # a string for an integer
    assert getattr(sup, field["Arm.progress"]) == 0
    assert sup.deliver("pick.u_feedback", Data({"sequence": [7]})) is True
    assert getattr(sup, field["Arm.progress"]) == 7
    assert len(warnings) == 2
    setattr(sup, field["Arm.picks"], 3)  # picks: integer(0..3); picks + 1 is outside: not taken, nothing moves
    assert sup.deliver("pick.u_response", Data({"sequence": [1]})) is False
    assert getattr(sup, field["Arm.picks"]) == 3 and "outside its type" in warnings[-1]
    assert (getattr(sup, field["Arm"]), getattr(sup, field["pick"])) == ("picking", "executing")
    assert sup.deliver("pick.u_response", None) is False  # no data at all
    # a response nobody waits for is ignored, not applied
    assert getattr(sup, field["set_light"]) == "idle"
    assert sup.deliver("set_light.u_response", None) is False
    assert getattr(sup, field["Light"]) == "dark"
    with pytest.raises(KeyError):
        sup.deliver("look_at", None)  # controllable: not delivered by the robot


def test_a_double_variable_never_takes_nan_and_nan_data_is_not_sent() -> None:
    p = plan_supervisor(synthesize_model(load_model(ROOT / "examples/line_follower.rscd")))
    sent: list[Any] = []
    warnings: list[str] = []
    sup = load_module(p).Robot(seed=1, warn=warnings.append)
    sup.send = lambda name, data: sent.append((name, data)) or True
    sup.deliver("scan", Data({"ranges": [5.0] * 360}))
    sup.deliver("correction", 10.0)
    assert sup.tick() == "move" and sent[-1] == ("move", {"linear": {"x": 0.15}, "angular": {"z": -0.1}})
    assert sup.deliver("correction", float("nan")) is False  # not a value: kept at 10.0
    assert sup.snapshot()["variables"]["LineDetector.current_correction"] == 10.0
    assert sup.deliver("correction", float("inf")) is False  # a double never takes infinity
    field = {f.label: f.name for f in p.fields}
    setattr(sup, field["LineDetector.current_correction"], 1e308)  # 0 - 1e308/100 is finite; make it overflow
    setattr(sup, field["LineDetector.current_correction"], float("inf"))
    sup._dirty = True
    count = len(sent)
    assert sup.tick() is None  # move's data is not finite: not sent, not performed
    assert len(sent) == count and any("not finite" in w for w in warnings)


def test_tick_is_reproducible_with_a_seed_and_fair() -> None:
    text = """
robot Two {
    component C {
        incoming message a with type: none
        incoming message b with type: none
        incoming message c with type: none
    }
}
"""
    model = check_text(text).model
    assert model is not None
    module = load_module(plan(synthesize_model(model)))
    first = module.Robot(seed=7).tick()
    runs = []
    for _ in range(2):
        sup = module.Robot(seed=7)
        runs.append([sup.tick() for _ in range(300)])
    assert runs[0] == runs[1]
    assert first == runs[0][0]
    counts = Counter(runs[0])
    assert set(counts) == {"a", "b", "c"}
    assert all(70 <= n <= 130 for n in counts.values()), counts  # 100 each expected
    other = module.Robot(seed=8)
    assert [other.tick() for _ in range(300)] != runs[0]


def test_tick_follows_the_supervisor_and_snapshot_is_json() -> None:
    m_ = module_of("maze_solver")
    sent: list[tuple[str, Any]] = []

    class Robot(m_.Robot):  # type: ignore[name-defined,misc]
        def send(self, name: str, data: Any) -> bool:
            sent.append((name, data))
            return True

    sup = Robot(seed=1)
    assert sup.tick() is None and sent == []  # nothing before every scan came once
    clear = Data({"ranges": [5.0] * 360})
    for scan in ("scan_front", "scan_right"):
        sup.deliver(scan, clear)
        assert sup.tick() is None and sup.holds("movement") == "held: waiting for the first readable data on " + (
            "scan_diag_right" if scan == "scan_right" else "scan_diag_right, scan_right"
        )
    sup.deliver("scan_diag_right", clear)
    assert sup.holds("movement") is None
    assert sup.tick() == "movement"
    assert sent[-1] == ("movement", {"linear": {"x": 0.3}})
    sup.deliver("scan_front", Data({"ranges": [0.3]}))
    assert sup.tick() == "turn_left"
    assert sent[-1] == ("turn_left", 90)
    assert sup.tick() is None  # turning: nothing is allowed until rotate_done
    snapshot = json.loads(sup.to_json())
    assert snapshot["automata"]["Platform"] == "turning"
    assert snapshot["variables"]["Distance.front"] == "wall_front"
    sup.deliver("rotate_done")
    sup.deliver("scan_front", Data({"ranges": [2.0]}))
    assert sup.tick() == "movement"


def test_a_refused_send_leaves_the_state_as_it_was() -> None:
    m_ = module_of("maze_solver")
    sup = m_.Robot(seed=1, wait_for_data=False)
    sup.send = lambda name, data: False
    sup.deliver("scan_front", Data({"ranges": [0.3]}))
    assert sup.tick() is None
    assert sup.snapshot()["automata"]["Platform"] == "ready"  # not turning: the command did not go out


def test_every_model_string_is_escaped(tmp_path: Path) -> None:
    nasty = r'/a"b\'c\\d"""e' + "\u00e9"
    literal = '"' + nasty.replace("\\", "\\\\").replace('"', '\\"') + '"'
    text = f"""
robot Nasty {{
    component C {{
        incoming message say with identifier: "/say", type: string
        outgoing message hear with identifier: "/hear", type: string
        behaviour {{
            variable last: string = ""
            initial marked state s {{
                on response from hear do last := {literal}
            }}
        }}
    }}
    provide say with {literal}
}}
"""
    result = check_text(text)
    assert result.ok, result.render()
    assert result.model is not None
    synthesis = synthesize_model(result.model)
    module = load_module(plan(synthesis))
    said: list[Any] = []
    sup = module.Robot(seed=0)
    sup.send = lambda name, data: said.append(data) or True
    sup.tick()
    assert said == [nasty]
    sup.deliver("hear", "anything")
    assert sup.snapshot()["variables"]["C.last"] == nasty
    from robosc.codegen.ros import generate

    for ros in (1, 2):
        for mode in ("controller", "supervisor"):
            out = tmp_path / f"{ros}{mode}"
            for path in generate(plan(synthesis), ros, mode, out):
                if path.suffix == ".py":
                    source = path.read_text()
                    ast.parse(source, feature_version=(3, 8))
                    if path.name.endswith("_supervisor.py"):
                        found = [
                            n.value
                            for n in ast.walk(ast.parse(source))
                            if isinstance(n, ast.Constant) and isinstance(n.value, str) and "\u00e9" in n.value
                        ]
                        assert found and set(found) == {nasty}


def test_keyword_property_names_are_read_with_getattr() -> None:
    text = """
robot K {
    datatype object Odd { ^class: double  ^None: double }
    datatype enum Far from Odd to { value.^class > 1.0 -> far default -> near }
    interface odd use Odd from my_msgs
    component C {
        outgoing message o with type: Far links odd
        behaviour {
            variable f: Far
            on response from o do f := value
            initial marked state s {}
        }
    }
}
"""
    result = check_text(text)
    assert result.model is not None, result.render()
    module = load_module(plan(synthesize_model(result.model)))
    sup = module.Robot(seed=0)
    assert sup.deliver("o", Data({"class": 2.0, "None": 0.0})) is True
    assert sup.snapshot()["variables"]["C.f"] == "far"
    assert m.BasicKind.DOUBLE  # the model module is what the planner reads


def test_a_long_condition_that_reads_received_data_stays_where_it_stands() -> None:
    """A long condition over the state is written once as a method (``self._part0()``); one that
    reads the received data, in every part of a chain, stays in the handler, where the data
    is (whether a part reads data is found once per part: asking again for each part of a long
    chain made the module of 500 robots take minutes)."""
    from robosc.codegen.pyexpr import SHARED_FROM, Names, python
    from robosc.language import model as lm
    from robosc.plant.expressions import NO_SPAN

    def chain(parts: list[lm.Expr]) -> lm.Expr:
        result = parts[0]
        for part in parts[1:]:
            result = lm.Binary("or", result, part, lm.BOOLEAN, NO_SPAN)
        return result

    ints = [lm.Literal(i, lm.INTEGER, NO_SPAN) for i in range(40)]
    flags = [lm.Binary("=", ints[i], ints[i + 1], lm.BOOLEAN, NO_SPAN) for i in range(39)]
    data = lm.Binary(">", lm.DataRef((), lm.INTEGER, NO_SPAN), ints[3], lm.BOOLEAN, NO_SPAN)
    over_state = chain(flags)
    with_data = chain([data, *flags])  # read by every part of the chain
    names = Names({}, {}, shared={})
    assert len(python(over_state, Names({}, {}))) >= SHARED_FROM
    assert "self._part" in python(over_state, names)
    code = python(with_data, names)
    assert "value" in code  # the data read in place
    assert names.shared and not any("value" in body for body in names.shared)  # no method reads it
