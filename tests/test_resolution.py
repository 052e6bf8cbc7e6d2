"""References resolve to the objects they name; libraries are found and imported."""

from __future__ import annotations

from pathlib import Path

from conftest import EXAMPLES, codes, messages, robot
from robosc.api import check_file, check_text
from robosc.language import model as m

LIBRARY = """library Lib {
  datatype enum Level from integer to { value > 5 -> high default -> low }
  component Sensor {
    outgoing message level with identifier: "/level", type: Level
    behaviour {
      variable current: Level = low
      on response from level do current := value
      initial marked state watching {}
    }
  }
}
"""


def test_expressions_hold_objects(check):
    result = check(
        robot(
            "datatype enum E from double to { value > 1.0 -> big default -> small }",
            "component C { outgoing message m with type: E behaviour { variable e: E = small "
            "on response from m do e := value initial marked state a {} } }",
            "requirement act needs S.idle and C.e = big",
        )
    )
    model = result.model
    assert model is not None, result.render()
    requirement = model.requirements[0]
    assert requirement.communications == (model.communication("act"),)
    condition = requirement.condition
    assert isinstance(condition, m.Binary) and condition.op == "and"
    state_ref, equality = condition.left, condition.right
    assert isinstance(state_ref, m.StateRef)
    assert state_ref.state is model.component("S").automaton.state("idle")
    assert isinstance(equality.left, m.VariableRef) and equality.left.variable is model.component(
        "C"
    ).automaton.variable("e")
    enum = next(t for t in model.data_types if t.name == "E")
    assert isinstance(equality.right, m.EnumLiteral) and equality.right.enum is enum
    assert equality.right.value is enum.value("big")
    assert enum.rules[0].condition.left.type == m.DOUBLE


def test_transitions_hold_states_and_communications(check):
    result = check(robot())
    automaton = result.model.component("S").automaton
    idle, busy = automaton.states
    request, tau = [t for t in automaton.transitions if t.source is not None]
    assert request.source is idle and request.target is busy
    assert request.communication is result.model.communication("act")
    assert isinstance(tau, m.TauTransition) and tau.source is busy and tau.target is idle
    global_transition = next(t for t in automaton.transitions if t.source is None)
    assert global_transition.assignments[0].variable is automaton.variable("active")
    assert isinstance(global_transition.assignments[0].value, m.DataRef)


def test_value_steps_resolve_to_properties(check):
    result = check(
        robot(
            "datatype object Scan { ranges: array(double) }",
            "datatype enum Near from Scan to { value.ranges[3] < 0.5 -> near default -> far }",
        )
    )
    enum = next(t for t in result.model.data_types if t.name == "Near")
    scan = next(t for t in result.model.data_types if t.name == "Scan")
    data = enum.rules[0].condition.left
    assert isinstance(data, m.DataRef)
    assert data.steps == (m.FieldStep(scan.properties[0]), m.IndexStep(3))
    assert data.type == m.DOUBLE


def test_types_may_be_used_before_they_are_defined(check):
    result = check(robot("datatype object A { b: B }", "datatype object B { x: double }"))
    a = result.model.data_types[0]
    assert a.properties[0].type is result.model.data_types[1]


def test_recursive_type_is_an_error_not_a_hang(check):
    result = check(robot("datatype object A { b: B }", "datatype object B { a: A }"))
    assert "contains itself" in messages(result)


def test_import_from_library_next_to_the_model(check):
    result = check(
        robot("component Tank from Lib import Sensor", "requirement act needs Tank.current = high and Tank.watching"),
        lib=LIBRARY,
    )
    assert result.ok, result.render()
    tank = result.model.component("Tank")
    assert (tank.library, tank.library_component) == ("Lib", "Sensor")
    assert tank.automaton.states[0].owner == "Tank"
    assert tank.communications[0].owner == "Tank"
    assert any(isinstance(t, m.EnumType) and t.name == "Level" for t in result.model.data_types)
    assert any(path.endswith("lib.rscd") for path in result.sources)


def test_the_same_library_component_imported_twice_is_two_components(check):
    lib = LIBRARY.replace('identifier: "/level", ', "")
    result = check(robot("component A from Lib import Sensor", "component B from Lib import Sensor"), lib=lib)
    assert "communication 'level' is defined more than once" in messages(result)


def test_library_found_on_search_path(tmp_path: Path):
    (tmp_path / "libs").mkdir()
    (tmp_path / "libs" / "whatever_name.rscd").write_text(LIBRARY)
    (tmp_path / "model").mkdir()
    model = tmp_path / "model" / "r.rscd"
    model.write_text(robot("component Tank from Lib import Sensor"))
    assert "unknown library 'Lib'" in messages(check_file(model))
    assert check_file(model, [tmp_path / "libs"]).ok


def test_missing_library_hint_names_search_path(check):
    result = check(robot("component T from Libb import Sensor"), lib=LIBRARY)
    diagnostic = next(d for d in result.diagnostics if "unknown library" in d.message)
    assert "did you mean 'Lib'?" in diagnostic.hint and "-I DIR" in diagnostic.hint


def test_errors_inside_a_library_point_into_the_library(check):
    broken = LIBRARY.replace("goto", "").replace(
        "initial marked state watching {}", "initial marked state watching { transition goto nowhere }"
    )
    result = check(robot("component Tank from Lib import Sensor"), lib=broken)
    diagnostic = next(d for d in result.diagnostics if "nowhere" in d.message)
    assert diagnostic.span.path.endswith("lib.rscd") and diagnostic.span.line == 8


def test_syntax_error_in_library_is_reported_in_library(check):
    result = check(robot("component Tank from Lib import Sensor"), lib="library Lib { component }")
    assert codes(result) == ["syntax"]
    assert result.diagnostics[0].span.path.endswith("lib.rscd")


def test_unknown_library_component_suggests(check):
    result = check(robot("component T from Lib import Sensr"), lib=LIBRARY)
    assert "did you mean 'Sensor'?" in [d.hint for d in result.diagnostics]


def test_did_you_mean_only_when_close(check):
    result = check(robot("requirement act needs S.zzzzzz"))
    assert result.diagnostics[0].hint is None


def test_checking_a_library_file_on_its_own():
    result = check_file(EXAMPLES / "emergency_stop.rscd")
    assert result.ok and result.model.kind == "library"
    assert [c.name for c in result.model.components] == ["EmergencyStop"]


def test_check_text_never_needs_a_file():
    assert check_text(robot()).ok


def test_other_languages_spellings_of_the_basic_types_get_the_robosc_word(check):
    for written, word in (("bool", "boolean"), ("int", "integer"), ("float", "double"), ("str", "string"),
                          ("Float32", "double"), ("String", "string"), ("void", "none")):
        result = check(robot().replace("outgoing message sense with type: boolean",
                                       f"outgoing message sense with type: {written}"))
        [d] = result.diagnostics
        assert d.message == f"unknown data type '{written}'" and d.hint == f"RoboSC writes '{word}'"
    # a data type of the model with such a name is the model's own
    own = check(robot("datatype object Float32 { data: double }").replace("type: boolean", "type: Float32"))
    assert "unknown data type" not in messages(own)


def test_a_did_you_mean_proposes_only_what_may_be_assigned(check):
    """Assigning another component's variable (before: "did you mean 'Battery.charges'?",
    which the next check refuses): the hint says why it cannot be, and what to do."""
    text = robot(
        "component Battery { behaviour { variable charges: integer(0..3) = 0 initial marked state ok {} } }",
        "component Dock { outgoing message docked with type: none behaviour { "
        "initial marked state idle { on response from docked do charges := 1 } } }",
    )
    [d] = check(text).diagnostics
    assert d.message == "unknown variable 'charges' in component 'Dock'"
    assert d.hint is not None and d.hint.startswith(
        "'charges' is a variable of Battery, and a transition assigns only its own component's variables (rule 7)"
    )
    assert "Battery.charges" not in d.hint
    close = text.replace("variable charges", "variable charge").replace("do charges", "do chargs")
    close = close.replace("initial marked state idle", "variable charges: integer(0..3) = 0 initial marked state idle")
    [d] = check(close).diagnostics
    assert d.hint == "did you mean 'charges'?"  # Dock's own, not Battery's 'charge'
