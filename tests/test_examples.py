"""The bundled examples load and say what the issue asks of them."""

from __future__ import annotations

from conftest import EXAMPLES
from robosc.api import load_model, restriction
from robosc.language import model as m


def test_line_follower():
    model = load_model(EXAMPLES / "line_follower.rscd")
    assert [c.name for c in model.components] == ["LineDetector", "Lidar", "Platform", "EmergencyStop"]
    assert model.component("EmergencyStop").library == "EmergencyStopLibrary"
    move = model.communication("move")
    assert isinstance(move, m.Message) and move.direction is m.Direction.INCOMING
    assert move.interface.ros_type == "Twist" and move.interface.package == "geometry_msgs"
    scan = model.communication("scan")
    assert isinstance(scan.type, m.EnumType) and scan.type.source.name == "LaserScan"
    correction = model.component("LineDetector").automaton.variable("current_correction")
    assert correction.type == m.DOUBLE and correction not in m.synthesis_variables(model)


def test_maze_solver():
    model = load_model(EXAMPLES / "maze_solver.rscd")
    enums = {e.name for e in model.enums}
    assert enums == {"WallFront", "WallRight", "WallDiagRight"}
    assert {c.name for c in model.requirements[0].communications} == {"movement"}
    assert {v.name for v in m.synthesis_variables(model)} == {"front", "right", "diag_right"}


def test_pick_and_light_uses_every_construct():
    model = load_model(EXAMPLES / "pick_and_light.rscd")
    kinds = {type(c) for c in model.communications}
    assert kinds == {m.Message, m.Service, m.Action}
    arm = model.component("Arm").automaton
    results = {t.result for t in arm.transitions if isinstance(t, m.ResultTransition)}
    assert {
        m.ResultKind.REQUEST,
        m.ResultKind.RESPONSE,
        m.ResultKind.FEEDBACK,
        m.ResultKind.ERROR,
        m.ResultKind.CANCEL,
    } <= results
    assert any(t.source is None for t in arm.transitions)  # a global transition
    assert any(isinstance(t, m.TauTransition) and t.guard is not None for t in arm.transitions)
    assert arm.variable("picks").type.is_ranged_integer
    pose = next(t for t in model.data_types if t.name == "Pose")
    assert isinstance(pose.properties[0].type, m.ObjectType)  # nested properties
    assert {p.condition is None for p in model.provides} == {True, False}
    assert {r.kind for r in model.requirements} == {m.RequirementKind.NEEDS, m.RequirementKind.DISABLES}
    assert any(len(r.communications) > 1 for r in model.requirements)


def test_shelf_picker_shows_what_the_supervisor_buys():
    """The example of README's "What synthesis adds": no requirement mentions when to pick;
    synthesis forbids a pick with a full tray and says why."""
    from robosc.api import synthesize_file
    from robosc.language.render import render

    result = synthesize_file(EXAMPLES / "shelf_picker.rscd")
    assert result.ok
    assert [(g.event.name, render(g.added)) for g in result.added_guards] == [
        ("pick.c_trigger", "Tray.empty or Tray.one")
    ]
    why = restriction(result, "pick.c_trigger")
    assert why is not None and not why.never
    assert why.state.endswith("Base.at_shelf, Arm.stowed, Tray.two")
    assert [s.event.name for s in why.consequence.path] == ["pick.u_response"]
    reason = why.consequence.reason
    assert "Arm stays in holding (drop.c_trigger is forbidden here by requirement drop needs" in reason
    assert "Base stays in at_shelf (dock.c_trigger is forbidden here by requirement dock needs Arm.stowed)" in reason


def test_shelf_picker_without_unload_recovery_points_at_the_unhandled_error():
    """The mistake made while writing the example: no transition on a failed unload. Synthesis
    then never allows a pick, and the explanation names the error that traps the tray."""
    from robosc.api import check_text, synthesize_model

    text = (EXAMPLES / "shelf_picker.rscd").read_text()
    broken = text.replace("on error from unload goto two", "")
    assert broken != text
    result = synthesize_model(check_text(broken).model)
    why = restriction(result, "pick.c_trigger")
    assert why is not None and why.never
    assert (
        "after drop.c_trigger, drop.u_response, dock.c_trigger, dock.u_response, unload.c_trigger the uncontrollable "
        "event unload.u_error can happen" in why.consequence.reason
    )
    assert why.consequence.reason.endswith(
        "(Tray stays in emptying (waits for unload.u_response, which cannot happen here))"
    )


def test_warehouse_fleet_is_set_in_one_line_and_synthesis_lets_one_robot_into_the_aisle():
    """examples/warehouse.rscd: the fleet's size is the count of one component; two robots in
    the narrow aisle can block each other in front of the shelf, so synthesis lets a robot in
    from beside the doorway only while no other robot is deeper in the aisle, whatever the size."""
    from robosc.api import check_text, synthesize_model
    from robosc.synthesis.options import SynthesisOptions

    text = (EXAMPLES / "warehouse.rscd").read_text()
    assert text.count("component bot[3]") == 1
    for n in (3, 4):
        model = check_text(text.replace("component bot[3]", f"component bot[{n}]")).model
        assert [c.name for c in model.groups["bot"]] == [f"bot{i}" for i in range(1, n + 1)]
        counted = synthesize_model(model)
        mono = synthesize_model(model, options=SynthesisOptions(fleet="monolithic"))
        assert counted.ok and mono.ok and counted.method == "symmetric"
        assert [g.event.name for g in counted.added_guards] == [f"bot{i}.go" for i in range(1, n + 1)]
        assert [g.event.name for g in mono.added_guards] == [f"bot{i}.go" for i in range(1, n + 1)]
        # the door alone is never restricted further; bot1 beside the doorway may enter only when
        # no other robot is deeper in the aisle; to the place beside the doorway it may always go
        for result in (counted, mono):
            assert result.allows("bot1.go", result.state({"Door": "open", "bot1": "out0"}))
            assert not result.allows("bot1.go", result.state({"Door": "open", "bot1": "out0", "bot2": "out2"}))
            assert not result.allows("bot1.go", result.state({"Door": "open", "bot1": "out0", "bot2": "back3"}))
            assert result.allows("bot1.go", result.state({"Door": "open", "bot1": "out0", "bot2": "charging"}))
            assert result.allows("bot1.go", result.state({"Door": "open", "bot1": "out0", "bot2": "back0"}))
            assert not result.allows("bot1.go", result.state({"Door": "closed", "bot1": "out0"}))
            assert result.allows("bot1.go", result.state({"Door": "closed", "bot2": "out2"}))
