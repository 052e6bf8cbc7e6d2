"""Each grammar construct of LANGUAGE.md sections 1-2 parses into the syntax node it means."""

from __future__ import annotations

import pytest

from robosc.language import syntax as s
from robosc.language.parser import parse_text


def parse(text: str) -> s.FileSyntax:
    result = parse_text(text)
    assert result.syntax is not None, result.diagnostics
    return result.syntax


def only(text: str):
    return parse(f"robot R {{ {text} }}").definitions[0]


def expr_of(text: str) -> s.Expr:
    requirement = only(f"requirement x needs {text}")
    return requirement.condition


def test_robot_and_library_headers():
    assert parse("robot R {}").kind == "robot"
    lib = parse("library L { component C {} }")
    assert lib.kind == "library" and lib.name.text == "L"
    assert isinstance(lib.definitions[0], s.LocalComponentSyntax)


def test_messages_with_and_without_identifier_and_links():
    comp = only(
        'component C { outgoing message a with identifier: "/a", type: T links i incoming message b with type: none }'
    )
    a, b = comp.items
    assert (a.direction, a.name.text, a.identifier.value, a.type.name.text, a.links.text) == (
        "outgoing",
        "a",
        "/a",
        "T",
        "i",
    )
    assert (b.direction, b.identifier, b.type.kind, b.links) == ("incoming", None, "none", None)


def test_service_and_action():
    comp = only(
        "component C { service s with request: integer(0..5), response: string "
        "action a with identifier: 'x', request: A, response: array(double), feedback: boolean links l }"
    )
    service, action = comp.items
    assert isinstance(service, s.ServiceSyntax)
    assert (service.request.low, service.request.high, service.response.kind) == (0, 5, "string")
    assert isinstance(action, s.ActionSyntax)
    assert action.identifier.value == "x"
    assert isinstance(action.response, s.ArrayTypeSyntax) and action.response.element.kind == "double"
    assert action.feedback.kind == "boolean" and action.links.text == "l"


def test_negative_integer_range():
    comp = only("component C { incoming message m with type: integer(-5..-1) }")
    assert (comp.items[0].type.low, comp.items[0].type.high) == (-5, -1)


def test_behaviour_states_variables_and_transitions():
    comp = only("""component C { behaviour {
        variable v: integer(0..3) = 2
        variable d: double
        on error from a goto s
        initial marked state s {
            on response from a do v := value, d := 1.5 goto t
            on request to b
            transition if v > 1 goto s
        }
        marked state t { transition }
        state u { on cancel to a on feedback from a }
    } }""")
    behaviour = comp.items[0]
    v, d, global_transition, st, t, u = behaviour.items
    assert isinstance(v, s.VariableSyntax) and v.initial == s.IntLit(2)
    assert d.initial is None and d.type.kind == "double"
    assert isinstance(global_transition, s.ResultTransitionSyntax) and global_transition.result == "error"
    assert (st.initial, st.marked, t.initial, t.marked, u.marked) == (True, True, False, True, False)
    on_response, on_request, tau = st.transitions
    assert [a.target.head.text for a in on_response.assignments] == ["v", "d"]
    assert on_response.assignments[0].value == s.Access(None, ())
    assert on_response.target.text == "t" and on_request.preposition == "to"
    assert isinstance(tau, s.TauTransitionSyntax) and tau.target.text == "s"
    assert t.transitions[0] == s.TauTransitionSyntax(None, None)
    assert [x.result for x in u.transitions] == ["cancel", "feedback"]


def test_imported_component():
    comp = only("component Local from Lib import Remote")
    assert isinstance(comp, s.ImportedComponentSyntax)
    assert (comp.name.text, comp.library.text, comp.component.text) == ("Local", "Lib", "Remote")


def test_datatypes_and_interface():
    robot = parse("""robot R {
        datatype object P { x: double nested: Q list: array(integer) }
        datatype enum E from P to { value.x > 1.0 -> big  default -> small }
        interface i use Twist from geometry_msgs
    }""")
    obj, enum, interface = robot.definitions
    assert [p.name.text for p in obj.properties] == ["x", "nested", "list"]
    assert enum.source == s.NamedTypeSyntax(s.Name("P"))
    assert enum.rules[1] == s.EnumRuleSyntax(None, s.Name("small"))
    assert (interface.ros_type.text, interface.package.text) == ("Twist", "geometry_msgs")


def test_requirements_single_and_set():
    robot = parse(
        "robot R { requirement a needs true requirement {a, b} needs x "
        "requirement y disables a requirement z disables {} }"
    )
    needs, needs_set, disables, disables_empty = robot.definitions
    assert (needs.kind, needs.events.is_set, [n.text for n in needs.events.names]) == ("needs", False, ["a"])
    assert [n.text for n in needs_set.events.names] == ["a", "b"] and needs_set.events.is_set
    assert disables.kind == "disables" and disables.condition == s.Access(s.Name("y"), ())
    assert disables_empty.events.names == ()


def test_provide_with_object_value_expression_and_condition():
    robot = parse(
        "robot R { provide m with { linear: { x: 0.3 }, angular: { z: 1 - 2 } } if A.s "
        "provide n with 90 provide o with {} }"
    )
    first, second, third = robot.definitions
    linear = first.data.fields[0]
    assert linear.name.text == "linear" and isinstance(linear.value, s.ObjectValueSyntax)
    assert linear.value.fields[0].value == s.DoubleLit("0.3")
    assert first.condition == s.Access(s.Name("A"), (s.MemberStep(s.Name("s")),))
    assert second.data == s.IntLit(90) and second.condition is None
    assert third.data == s.ObjectValueSyntax(())


def test_literals_and_access_paths():
    assert expr_of("value.ranges[270]") == s.Access(None, (s.MemberStep(s.Name("ranges")), s.IndexStep(270)))
    assert expr_of("0.25") == s.DoubleLit("0.25")
    assert expr_of("100.0").value == 100.0
    assert expr_of('"a\\"b"').value == 'a"b'
    assert expr_of("'it\\'s'").value == "it's"
    assert expr_of("true") == s.BoolLit(True) and expr_of("false") == s.BoolLit(False)


def test_escaped_identifiers_drop_the_caret():
    comp = only("component ^state { outgoing message ^message with type: none }")
    assert comp.name.text == "state" and comp.items[0].name.text == "message"


@pytest.mark.parametrize("comment", ["// line comment\n", "/* block\n comment */"])
def test_comments_are_ignored_and_kept(comment: str):
    result = parse(f"{comment}robot R {{ {comment} requirement a needs true {comment} }}")
    assert len(result.definitions) == 1
    assert [c.text for c in result.comments] == [comment.strip()] * 3


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("robot R { component C { state s {} } }", "unexpected 'state'"),
        ("robot R { requirement a needs }", "expected an expression"),
        ("robot R {", "unexpected end of file"),
        ("robot R { component C { outgoing message m with type: none } } extra", "unexpected 'extra'"),
        ('robot R { component C { outgoing message m with identifier: "x, type: none } }', "unterminated string"),
        ("robot R { /* open", "unterminated comment"),
        ("robot R { requirement a needs 1 # 2 }", "unexpected character '#'"),
        ("robot R { component state {} }", "'state' is a keyword"),
        ("robot R { requirement a needs .5 }", "unexpected"),
    ],
)
def test_syntax_errors_are_one_clear_diagnostic(text: str, fragment: str):
    result = parse_text(text, "m.rscd")
    assert result.syntax is None
    assert len(result.diagnostics) == 1
    diagnostic = result.diagnostics[0]
    assert fragment in f"{diagnostic.message}; {diagnostic.hint}"
    assert diagnostic.code == "syntax" and diagnostic.span.line >= 1 and diagnostic.span.column >= 1


def test_syntax_error_position_is_the_failing_token():
    result = parse_text("robot R {\n  component C {\n    bogus\n  }\n}", "m.rscd")
    span = result.diagnostics[0].span
    assert (span.line, span.column) == (3, 5)


def test_deep_nesting_is_a_diagnostic_not_a_crash():
    deep = "(" * 5000 + "true" + ")" * 5000
    result = parse_text(f"robot R {{ requirement a needs {deep} }}")
    assert result.syntax is None and "nested" in result.diagnostics[0].message
    # a run of one associative operator is a balanced tree: 3,000 operands parse, a few levels deep
    long_chain = " or ".join(["true"] * 3000)
    result = parse_text(f"robot R {{ requirement a needs {long_chain} }}")
    assert result.syntax is not None and not result.diagnostics
    # a run of one that is not associative counts a level per operand
    long_chain = " - ".join(["1"] * 3000)
    result = parse_text(f"robot R {{ requirement a needs {long_chain} > 0 }}")
    [found] = result.diagnostics
    assert result.syntax is None and found.code == "limit"
    assert found.message == "expression more than 100 levels deep (102 operands joined by '-' in a row)"
    result = parse_text(f"robot R {{ requirement a needs {' - '.join(['1'] * 100)} > 0 }}")
    assert result.syntax is not None  # 100 operands and the comparison: 100 levels, the most
