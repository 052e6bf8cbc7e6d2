"""The generated stand-alone supervisor module: self-contained, Python 3.8, guards equal to
the synthesized supervisor, robust enum conversion, the tick of SEMANTICS.md section 6."""

from __future__ import annotations

import ast
import json
import math
import subprocess
from collections import Counter
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings

from random_models import robots
from robosc.api import check_text, load_model, plan_supervisor, supervisor_module, synthesize_model
from robosc.plant import build_network
from robosc.runtime.plan import plan
from robosc.runtime.simulator import load_module
from robosc.synthesis.explicit import synthesize_explicit
from robosc.synthesis.symbolic import synthesize_symbolic

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ["maze_solver", "line_follower", "pick_and_light"]
STDLIB = {"__future__", "json", "math", "random", "sys", "threading"}


def module_of(name: str) -> Any:
    result = synthesize_model(load_model(ROOT / "examples" / f"{name}.rscd"))
    return load_module(plan_supervisor(result))


@pytest.mark.parametrize("name", EXAMPLES)
def test_module_is_self_contained_python_38(name: str) -> None:
    text = supervisor_module(synthesize_model(load_model(ROOT / "examples" / f"{name}.rscd")))
    tree = ast.parse(text, feature_version=(3, 8))
    imported = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            imported |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            imported.add((node.module or "").split(".")[0])
    assert imported <= STDLIB, imported - STDLIB


@pytest.mark.skipif(not list(Path("/root/.pyenv/versions").glob("3.8*")), reason="no Python 3.8 here")
def test_module_runs_on_python_38(tmp_path: Path) -> None:
    python = next(Path("/root/.pyenv/versions").glob("3.8*")) / "bin" / "python"
    path = tmp_path / "maze_solver_supervisor.py"
    path.write_text(supervisor_module(synthesize_model(load_model(ROOT / "examples/maze_solver.rscd"))))
    script = (
        "import maze_solver_supervisor as m\n"
        "s = m.Supervisor(seed=1)\n"
        "print(s.tick()); s.on_scan_front(m.Data({'ranges': [0.2]})); print(s.tick())\n"
    )
    done = subprocess.run([str(python), "-c", script], cwd=tmp_path, capture_output=True, text=True, check=True)
    assert done.stdout.split() == ["movement", "turn_left"]


def _load(state: Any, plan_: Any, sup: Any, network: Any) -> None:
    fields = dict(plan_.automata)
    for automaton, location in zip(network.automata, state.locations, strict=True):
        setattr(sup, fields[automaton.name], location.name)
    variable_fields = dict(plan_.variables)
    for variable, value in zip(network.variables, state.values, strict=True):
        setattr(sup, variable_fields[f"{variable.owner}.{variable.name}"], getattr(value, "name", value))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(robots())
def test_compiled_guards_equal_the_synthesized_supervisor(text: str) -> None:
    """In every state reachable under the supervisor, each generated ``can_<event>`` says
    exactly what the BDDs say, and ``expected()`` lists every uncontrollable event the
    plant can take."""
    model = check_text(text).model
    assert model is not None
    network = build_network(model)
    symbolic = synthesize_symbolic(network)
    if not symbolic.ok:
        return
    explicit = synthesize_explicit(network)
    p = plan(symbolic)
    module = load_module(p)
    sup = module.Supervisor(seed=0)
    fixpoint = symbolic.details["fixpoint"]
    for state in explicit.details["supervisor"].controlled_states()[:400]:
        _load(state, p, sup, network)
        for event in p.controllable:
            expected = symbolic.allows(event.name, state)
            assert getattr(sup, f"can_{event.method}")() == expected, (event.name, state)
        plant_enabled = {
            e.name
            for e in network.uncontrollable
            if fixpoint.enc.state(
                dict(zip(network.automata, state.locations, strict=True)),
                dict(zip(network.variables, state.values, strict=True)),
            )
            & fixpoint.enabled[e]
            != fixpoint.enc.false
        }
        # the plant's own: the generated code also takes an event whose update would leave
        # a variable's range (synthesis treats that edge as impossible; a robot can still
        # send the message, and the variable then keeps its value)
        assert plant_enabled <= set(sup.expected())


def test_enum_conversion_falls_back_to_the_default_on_malformed_data() -> None:
    m = module_of("maze_solver")
    warnings: list[str] = []
    convert = m.enum_WallRight
    wall = m.Data({"ranges": [5.0] * 240 + [0.5] + [5.0] * 119})
    assert convert(wall, warnings.append) == "wall_right"
    assert warnings == []
    assert convert(m.Data({"ranges": [math.nan] * 360}), warnings.append) == "no_wall_right"  # NaN: no rule holds
    assert warnings == []
    for bad in (None, m.Data({}), m.Data({"ranges": [0.1]}), m.Data({"ranges": "text"}), 42):
        assert convert(bad, warnings.append) == "no_wall_right"
    assert len(warnings) == 5
    assert "WallRight: unreadable data" in warnings[0]


def test_handlers_never_raise_and_keep_variables_in_their_type() -> None:
    m = module_of("pick_and_light")
    warnings: list[str] = []
    sup = m.Supervisor(seed=1, warn=warnings.append)
    sup.c_Arm, sup.p_pick = "picking", "executing"
    assert sup.on_pick_u_feedback(m.Data({"sequence": []})) is True  # value.sequence[0] fails: kept
    assert sup.v_Arm_progress == 0
    assert sup.on_pick_u_feedback(m.Data({"sequence": ["x"]})) is True  # a string for an integer: kept
    assert sup.v_Arm_progress == 0
    assert sup.on_pick_u_feedback(m.Data({"sequence": [7]})) is True
    assert sup.v_Arm_progress == 7
    assert len(warnings) == 2
    sup.v_Arm_picks = 3  # picks: integer(0..3); picks + 1 is outside: kept
    assert sup.on_pick_u_response(None) is True
    assert sup.v_Arm_picks == 3 and "outside its type" in warnings[-1]
    # a response nobody waits for is ignored, not applied
    assert sup.p_set_light == "idle"
    assert sup.on_set_light_u_response(None) is False
    assert sup.c_Light == "dark"


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
    first = [module.Supervisor(seed=7).tick() for _ in range(1)]
    runs = []
    for _ in range(2):
        sup = module.Supervisor(seed=7)
        runs.append([sup.tick() for _ in range(300)])
    assert runs[0] == runs[1]
    assert first[0] == runs[0][0]
    counts = Counter(runs[0])
    assert set(counts) == {"a", "b", "c"}
    assert all(70 <= n <= 130 for n in counts.values()), counts  # 100 each expected
    other = module.Supervisor(seed=8)
    assert [other.tick() for _ in range(300)] != runs[0]


def test_tick_follows_the_supervisor_and_snapshot_is_json() -> None:
    m = module_of("maze_solver")
    sent: list[tuple[str, Any]] = []

    class Robot(m.Supervisor):  # type: ignore[name-defined,misc]
        def send_movement(self, data: Any) -> None:
            sent.append(("movement", data))

        def send_turn_left(self, data: Any) -> None:
            sent.append(("turn_left", data))

    sup = Robot(seed=1)
    assert sup.tick() == "movement"
    assert sent[-1] == ("movement", {"linear": {"x": 0.3}})
    sup.on_scan_front(m.Data({"ranges": [0.3]}))
    assert sup.tick() == "turn_left"
    assert sent[-1] == ("turn_left", 90)
    assert sup.tick() is None  # turning: nothing is allowed until rotate_done
    snapshot = json.loads(sup.to_json())
    assert snapshot["automata"]["Platform"] == "turning"
    assert snapshot["variables"]["Distance.front"] == "wall_front"
    sup.on_rotate_done()
    sup.on_scan_front(m.Data({"ranges": [2.0]}))
    assert sup.tick() == "movement"


def test_every_model_string_is_escaped(tmp_path: Path) -> None:
    nasty = r'/a"b\'c\\d"""e' + "\u00e9"
    literal = '"' + nasty.replace("\\", "\\\\").replace('"', '\\"') + '"'
    text = f"""
robot Nasty {{
    datatype object Twist {{
        x: double
    }}
    interface twist use Twist from geometry_msgs
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

    class Sayer(module.Supervisor):  # type: ignore[name-defined,misc]
        def send_say(self, data: Any) -> None:
            said.append(data)

    sup = Sayer(seed=0)
    sup.tick()
    assert said == [nasty]
    sup.on_hear("anything")
    assert sup.v_C_last == nasty
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
