"""Each static rule of LANGUAGE.md section 5: a model that breaks it, and one that keeps it."""

from __future__ import annotations

import pytest

from conftest import codes, messages, robot

COMPONENT = """
  component C {{
    {comms}
    behaviour {{
      {body}
    }}
  }}"""


def component(body: str, comms: str = "outgoing message m with type: boolean") -> str:
    return COMPONENT.format(comms=comms, body=body)


OK_STATES = "initial marked state a {}"
BOT = "component bot[{count} {{ incoming message go with type: none behaviour {{ initial marked state a {{ on request to go }} }} }}"

CASES = {
    "rule-1": [
        (robot(component(OK_STATES), component(OK_STATES).replace("m with", "m2 with")), "component 'C'"),
        (robot(component(OK_STATES, "outgoing message sense with type: none")), "communication 'sense'"),
        (robot(component("initial marked state a {} state a {}")), "state 'a' of 'C'"),
        (robot(component("variable v: boolean variable v: boolean " + OK_STATES)), "variable 'v' of 'C'"),
        (robot("datatype object P { x: double x: double }"), "property 'x' of P"),
        (robot(component(OK_STATES).replace("component C", "component s")), "component 's' differs from 'S'"),
        (robot(component("initial marked state a {} state A {}")), "state 'A' of 'C' differs from 'a' ("),
        (robot(component(OK_STATES, "outgoing message Sense with type: none")), "communication 'Sense' differs"),
        (robot("datatype enum E from double to { value > 1.0 -> Idle default -> small }"), "has the name of state"),
        (robot("datatype object P {} datatype object P {}"), "data type 'P'"),
        (robot("interface i use A from b interface i use A from b"), "interface 'i'"),
        (robot("datatype enum E from double to { default -> idle }"), "name of state 'S.idle'"),
        (
            robot("datatype enum E from double to { default -> v }", "datatype enum F from double to { default -> v }"),
            "enum value 'v'",
        ),
    ],
    "rule-2": [
        (robot(component("marked state a {}")), "no initial state"),
        (robot(component("initial marked state a {} initial state b { transition goto a }")), "more than one initial"),
    ],
    "rule-3": [
        (robot(component("initial state a {}")), "no state of 'C' is marked"),
        (robot(component("initial marked state a { transition goto b } state b {}")), "'C.b' is reachable"),
    ],
    "rule-4": [
        (
            robot("component C { behaviour { initial marked state a {} } behaviour { initial marked state b {} } }"),
            "more than one behaviour",
        ),
    ],
    "rule-5": [
        (robot(component("initial marked state a { on request to m }")), "'request' does not fit 'm'"),
        (
            robot(component("initial marked state a { on response from m }", "incoming message m with type: none")),
            "'response' does not fit 'm'",
        ),
        (
            robot(
                component(
                    "initial marked state a { on feedback from m }", "service m with request: none, response: none"
                )
            ),
            "a service has",
        ),
        (
            robot(
                component("initial marked state a { on cancel to m }", "service m with request: none, response: none")
            ),
            "a service has",
        ),
    ],
    "rule-6": [
        (
            robot(
                component(
                    "variable n: integer initial marked state a { on request to m do n := 1 }",
                    "incoming message m with type: integer",
                )
            ),
            "no assignment on a request to 'm'",
        ),
    ],
    "rule-7": [
        (
            robot(component("initial marked state a { on response from m do S.active := value }")),
            "cannot assign 'S.active'",
        ),
    ],
    "rule-8": [
        (robot(component(OK_STATES), "provide m with true"), "cannot provide data for 'm'"),
    ],
    "rule-9": [
        (robot(component("variable n: integer initial marked state a { transition if n > 1 }")), "needs a range"),
        (robot(component("variable n: integer " + OK_STATES), "requirement act needs C.n = 2"), "needs a range"),
    ],
    "rule-10": [
        (
            robot(component("variable d: double initial marked state a { transition if d > 1.0 }")),
            "only booleans, ranged integers and enums",
        ),
        (
            robot(
                component("variable t: string " + OK_STATES, "incoming message m with type: integer"),
                "provide m with 1 if C.t = 'x'",
            ),
            "type string",
        ),
    ],
    "enum-values": [
        (
            robot("datatype enum E from double to { value > 1.0 -> big value < -1.0 -> big default -> small }"),
            "names value 'big' in more than one rule",
        ),
        (robot("datatype enum E from double to { value > 1.0 -> big default -> big }"), "value 'big' in more"),
    ],
    "no-array": [
        (
            robot(
                component(
                    "variable n: integer(0..3) initial marked state a { on response from m do n := value[0] }",
                    "outgoing message m with type: array(integer(0..3))",
                ),
                "requirement act needs C.n > 1",
            ),
            "the data of 'm' is array(integer(0..3)); a communication's data is an object",
        ),
        (
            robot(component("variable xs: array(boolean) initial marked state a {}")),
            "variable 'xs' has the array type array(boolean)",
        ),
        (
            robot(component(OK_STATES, "service s with request: boolean, response: array(double) links trigger")),
            "the data of 's' is array(double)",
        ),
        (
            robot(
                "datatype object P { xs: array(integer(0..3)) }",
                "interface p use P from q",
                component(
                    "variable n: integer(0..3) initial marked state a { on response from m do n := value.xs[1] }",
                    "outgoing message m with type: P links p",
                ),
                "requirement act needs C.n > 1",
            ),
            "property 'xs' is an array",
        ),
    ],
    "no-object-variable": [
        (
            robot(
                "datatype object P { x: double }",
                component("variable v: P " + OK_STATES),
            ),
            "variable 'v' has the object type P",
        ),
    ],
    "range": [
        (
            robot(component("variable n: integer(0..3) = 7 initial marked state a { transition if n > 1 }")),
            "7 is outside the range of 'n' (integer(0..3))",
        ),
        (
            robot(
                component("variable n: integer(0..3) initial marked state a { on response from m do n := -1 }"),
                "requirement act needs C.n > 1",
            ),
            "-1 is outside the range of 'n'",
        ),
    ],
    "precedence": [
        (robot("requirement act needs S.active => S.active and !S.active"), "'=>' binds tighter than 'and'"),
        (robot("requirement act needs !S.active or S.active => S.active"), "this reads as !S.active or (S.active => S.active)"),
    ],
    "implicit-start": [
        (
            robot(
                "datatype enum E from double to { value > 1.0 -> big default -> small }",
                component("variable e: E initial marked state a { transition if e = small }"),
            ),
            "has no initial value: it starts as 'big'",
        ),
    ],
    "rule-11": [
        (
            robot(
                "datatype enum E from double to { default -> e1 }",
                "datatype enum F from E to { value = e1 -> f1 default -> f2 }",
            ),
            "converted from enum 'E'",
        ),
    ],
    "rule-12": [
        (robot(component(OK_STATES, "service s with request: none, response: none")), "service 's' must link"),
        (
            robot(component(OK_STATES, "action x with request: none, response: none, feedback: none")),
            "action 'x' must link",
        ),
        (
            robot("datatype object P { x: double }", component(OK_STATES, "outgoing message m with type: P")),
            "must link the ROS interface",
        ),
        (
            robot(
                "datatype object P { x: double }",
                "datatype enum E from P to { value.x > 1.0 -> big default -> small }",
                component(OK_STATES, "outgoing message m with type: E"),
            ),
            "must link the ROS interface",
        ),
    ],
    "rule-13": [
        (
            robot(
                component(OK_STATES, 'outgoing message m with identifier: "/topic", type: none'),
                'component D { outgoing message n with identifier: "/topic", type: none }',
            ),
            "both publish to topic '/topic'",
        ),
    ],
    "rule-14": [
        (robot("requirement act needs S.idel"), "unknown state or variable 'idel'"),
        (robot("requirement acts needs true"), "unknown communication 'acts'"),
        (robot(component("initial marked state a { transition goto b }")), "unknown state 'b'"),
        (robot(component("variable v: Missing " + OK_STATES)), "unknown data type 'Missing'"),
        (robot(component(OK_STATES, "outgoing message m with type: none links nothing")), "unknown interface"),
        (robot("requirement act needs Sx.idle"), "unknown name 'Sx'"),
        (robot("component I from Nowhere import C"), "unknown library 'Nowhere'"),
    ],
    "rule-15": [
        (robot(component(OK_STATES, 'outgoing message m with identifier: "/a//b", type: none')), "empty part"),
        (
            robot(component(OK_STATES, 'outgoing message m with identifier: "/9lives", type: none')),
            "start with a letter",
        ),
        (robot(component(OK_STATES, 'outgoing message m with identifier: "/a/", type: none')), "ends with '/'"),
        (robot(component(OK_STATES, 'outgoing message m with identifier: "/a b", type: none')), "only letters"),
        (robot(component(OK_STATES, 'outgoing message m with identifier: "", type: none')), "empty"),
    ],
    "package-name": [(robot().replace("robot R", "robot _R"), "a ROS package name begins with a letter")],
    "text": [
        (robot(component(OK_STATES, 'incoming message m with type: string'), 'provide m with "a\\0"'), "U+0000"),
        (robot(component(OK_STATES, 'incoming message m with type: string'), 'provide m with "\x1b[2J"'), "U+001B"),
    ],
    "uncontrollable-requirement": [(robot("requirement sense needs S.idle"), "'sense' is a message the robot sends")],
    "several-outcomes": [
        (
            robot(component(
                "initial marked state a { on response from m goto b on response from m goto c } marked state b {} "
                "marked state c {}", "outgoing message m with type: none")),
            "'on response from m' in C's state 'a' has 2 outcomes (b, c)",
        ),
    ],
    "enum-default": [
        (robot("datatype enum E from double to { value > 1.0 -> big }"), "has no default rule"),
        (robot("datatype enum E from double to { default -> a default -> b }"), "more than one default"),
    ],
    "instances": [
        (robot(BOT.format(count="0]")), "0 instances of 'bot': a component has from 1 to 1000 instances"),
        (robot(BOT.format(count="3] initial a, a")), "2 initial states for 3 instances of 'bot'"),
        (robot(BOT.format(count="2]"), "requirement act needs all(q in S: q.idle)"), "'all' ranges over nothing: 'S'"),
        (robot(BOT.format(count="2]"), "for r in S { requirement r.go needs true }"), "'for' ranges over nothing"),
        (robot(BOT.format(count="2]"), "requirement bot.go needs true"), "'bot' is a group of instances"),
        (robot(BOT.format(count="2]"), "for r in bot { requirement r.go needs r }"), "'r' stands for an instance"),
        (
            robot(BOT.format(count="2]"), "for r in bot { for r in bot { requirement r.go needs true } }"),
            "'r' already names an instance here",
        ),
        (robot(BOT.format(count="2]"), component(OK_STATES).replace("component C", "component bot2")), "'bot2' names both"),
        (robot(BOT.format(count="2]"), component(OK_STATES).replace("component C", "component Bot")), "group 'bot' has"),
        (robot(BOT.format(count='2] namespace "9x"')), "'9x' is not a valid ROS namespace"),
        (robot(BOT.format(count="2]").replace("message go with", 'message go with identifier: "/go",')), "absolute"),
    ],
    "constant": [
        (
            robot(component(OK_STATES, "incoming message d with type: double"), "provide d with 1.0 / 0.0"),
            "division by zero",
        ),
        (
            robot(
                component(
                    "variable x: double initial marked state a { on response from m do x := 2.0 / (1 - 1) }",
                    "outgoing message m with type: double",
                )
            ),
            "division by zero",
        ),
        (robot("datatype enum E from double to { value / -0.0 > 1.0 -> big default -> small }"), "division by zero"),
    ],
}

VALID = {
    "instances": robot(
        BOT.format(count='3] namespace "/fleet" initial a, a, a'),
        "for r in bot { requirement r.go needs count(q in bot: q != r and q.a) <= 2 and any(q in bot: q = r) }",
    ),
    "rule-1": robot(component(OK_STATES), "datatype enum E from double to { value > 1.0 -> big default -> small }"),
    "rule-2": robot(component("initial marked state a { transition goto b } state b { transition goto a }")),
    "rule-3": robot(component("initial state a { transition goto b } marked state b { transition goto a }")),
    "rule-4": robot(component(OK_STATES)),
    "rule-5": robot(
        component(
            "initial marked state a { on request to s on response from s on error from s "
            "on request to x on response from x on feedback from x on error from x on cancel to x }",
            "service s with request: none, response: none links t "
            "action x with request: none, response: none, feedback: none links f",
        ),
        "interface t use Trigger from std_srvs interface f use Fibonacci from action_tutorials_interfaces",
    ),
    "rule-6": robot(component("variable n: integer initial marked state a { on response from m do n := 1 }")),
    "rule-7": robot(component("variable v: boolean initial marked state a { on response from m do v := value }")),
    "rule-8": robot(component(OK_STATES, "incoming message m with type: integer"), "provide m with 3 if S.idle"),
    "rule-9": robot(component("variable n: integer(0..3) initial marked state a { transition if n > 1 }")),
    "rule-10": robot(
        component("variable d: double initial marked state a { on response from m do d := 1.0 }"),
        "requirement act needs C.a",
    ),
    "rule-11": robot("datatype enum E from double to { value > 1.0 -> big default -> small }"),
    "rule-12": robot(
        "datatype object P { x: double }",
        "interface p use Point from geometry_msgs",
        component(OK_STATES, "outgoing message m with type: P links p"),
    ),
    "rule-13": robot(
        component(OK_STATES, 'outgoing message m with identifier: "/topic", type: none'),
        'component D { incoming message n with identifier: "/topic", type: none }',
    ),
    "rule-14": robot("requirement act needs S.idle and S.active"),
    "rule-15": robot(component(OK_STATES, 'outgoing message m with identifier: "~/private/a_b1", type: none')),
    "package-name": robot().replace("robot R", "robot R_"),
    "text": robot(component(OK_STATES, "incoming message m with type: string"), 'provide m with "a\\tb\\n\\r\tc"'),
    "uncontrollable-requirement": robot("requirement act needs S.idle"),
    "several-outcomes": robot(component(
        "initial marked state a { on response from m goto b on response from m goto b } marked state b {}",
        "outgoing message m with type: none")),
    "enum-default": robot("datatype enum E from double to { value > 1.0 -> big default -> small }"),
    "enum-values": robot("datatype enum E from double to { value > 1.0 or value < -1.0 -> big default -> small }"),
    "no-array": robot(
        "datatype object Scan { ranges: array(double) }",
        "interface scan use LaserScan from sensor_msgs",
        component(
            "variable d: double = 0.0 initial marked state a { on response from m do d := value.ranges[0] }",
            "outgoing message m with type: Scan links scan",
        ),
    ),
    "no-object-variable": robot(
        "datatype object P { x: double }",
        "interface p use Point from geometry_msgs",
        component(
            "variable x: double initial marked state a { on response from m do x := value.x }",
            "outgoing message m with type: P links p",
        ),
    ),
    "implicit-start": robot(
        "datatype enum E from double to { value > 1.0 -> big default -> small }",
        component("variable e: E = small initial marked state a { transition if e = small }"),
    ),
    "precedence": robot("requirement act needs (S.active => S.active) and !S.active"),
    "range": robot(component("variable n: integer(0..3) = 3 initial marked state a { transition if n > 1 }")),
    "constant": robot(component(OK_STATES, "incoming message d with type: double"), "provide d with 1.0 / (2 - 1.5)"),
}


@pytest.mark.parametrize(
    ("code", "text", "fragment"),
    [(code, text, fragment) for code, cases in CASES.items() for text, fragment in cases],
)
def test_rule_violation_is_reported(check, code: str, text: str, fragment: str):
    result = check(text)
    assert code in codes(result), result.render()
    relevant = [d for d in result.diagnostics if d.code == code]
    assert any(fragment in d.message for d in relevant), result.render()
    assert all(d.span.line >= 1 and d.span.path.endswith("model.rscd") for d in relevant)


@pytest.mark.parametrize("code", sorted(VALID))
def test_model_that_keeps_the_rule_passes(check, code: str):
    result = check(VALID[code])
    assert result.diagnostics == (), result.render()
    assert result.ok and result.model is not None


def test_every_rule_has_a_test():
    from robosc.language.codes import Code

    not_rules = {Code.IO, Code.SYNTAX, Code.LIMIT, Code.TYPES, Code.ROS}
    synthesis = {Code.NEVER_ALLOWED, Code.NEVER_HOLDS, Code.UNREACHED_STATE}
    rules = {code.value for code in Code} - {c.value for c in not_rules | synthesis}
    assert rules <= set(CASES) and rules <= set(VALID)


def test_implicit_enum_start_says_where_it_starts(check):
    result = check(CASES["implicit-start"][0][0])
    assert result.ok
    [found] = result.diagnostics
    assert found.severity.value == "warning"
    assert "it starts as 'big', the first value of E (the original tool's start value was unspecified)" in found.message
    assert found.hint == "say where it starts, as in 'variable e: E = big'"


def test_shared_topic_is_only_a_warning(check):
    result = check(CASES["rule-13"][0][0])
    assert result.ok and result.model is not None
    assert [d.severity.value for d in result.diagnostics] == ["warning"]


def test_all_semantic_errors_of_a_file_are_reported_in_one_run(check):
    result = check(
        robot(
            component("variable n: integer initial state a { transition if n > 1 goto zz }"),
            "requirement nope needs S.idle",
            "provide sense with true",
        )
    )
    assert {"rule-3", "rule-9", "rule-14", "rule-8"} <= set(codes(result)), result.render()


TYPE_ERRORS = [
    ("requirement act needs 1 + 2", "a requirement must be a boolean expression"),
    ("requirement act needs S.active and 3", "'and' needs boolean operands"),
    ("requirement act needs S.active > 1", "'>' needs numeric operands"),
    ("requirement act needs S.active = 1", "cannot compare boolean with integer"),
    ("requirement act needs !3", "'!' needs a boolean operand"),
    ("requirement act needs -S.active", "'-' needs a numeric operand"),
    ("requirement act needs value", "'value' means nothing at robot level"),
    ("requirement act needs S", "'S' is a component"),
    ("requirement act needs S.idle.x", "state 'S.idle' has no properties"),
    ("datatype enum E from double to { value.x > 1.0 -> a default -> b }", "double has no property 'x'"),
    ("datatype enum E from double to { value[0] > 1.0 -> a default -> b }", "cannot index [0] into double"),
    ("datatype enum E from integer to { value -> a default -> b }", "an enum rule must be a boolean expression"),
    (
        "datatype enum E from double to { default -> a } datatype enum F from double to { default -> b } "
        "requirement act needs a = b",
        "cannot compare E with F",
    ),
]


@pytest.mark.parametrize(("statement", "fragment"), TYPE_ERRORS)
def test_type_rules(check, statement: str, fragment: str):
    result = check(robot(statement))
    assert fragment in messages(result), result.render()
    assert "types" in codes(result)


def test_assignment_value_must_fit_variable(check):
    text = robot(component("variable n: integer(0..3) = 7 initial marked state a { on response from m do n := value }"))
    result = check(text)
    assert "a value of type boolean does not fit 'n' of type integer(0..3)" in messages(result)
    # no guard reads n: out of range is a warning (the original accepts it), not an error
    [out_of_range] = [d for d in result.diagnostics if d.code == "range"]
    assert out_of_range.severity.value == "warning"
    assert out_of_range.message.startswith("7 is outside the range of 'n' (integer(0..3)); no guard")


def test_out_of_range_constant_is_an_error_only_for_synthesis_variables(check):
    body = "variable n: integer(0..20) initial marked state a { on response from m do n := -5 }"
    alone = check(robot(component(body)))
    assert alone.ok and [d.severity.value for d in alone.diagnostics] == ["warning"]
    read = check(robot(component(body), "requirement act needs C.n > 1"))
    assert not read.ok and [d.code for d in read.errors] == ["range"]


def test_arithmetic_result_types(check):
    result = check(
        robot(
            component(
                "variable i: integer(0..9) variable d: double "
                "initial marked state a { on response from m do i := 1 + 2 * 3, d := 1 / 2, d := 1 - 0.5, i := 4 / 2 }"
            )
        )
    )
    assert messages(result).count("does not fit") == 1  # only 4 / 2 (a double) into an integer
    assert "a value of type double does not fit 'i'" in messages(result)


def test_synthesis_variable_hint_says_use_an_enum(check):
    result = check(robot(component("variable d: double initial marked state a { transition if d > 1.0 }")))
    assert [d.hint for d in result.diagnostics if d.code == "rule-10"] == [
        "use an enum that turns the data into a few named values"
    ]
