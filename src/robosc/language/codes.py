"""Every diagnostic code robosc reports, in one place.

A code names the rule a diagnostic enforces. ``rule-N`` is static rule N of
LANGUAGE.md section 5; the other codes are named for what they catch. Editors
and CI match on the code (it is in ``robosc check --format json``), so a code,
once published, keeps its meaning. Each member's description says what the
rule is; ``robosc check --list-codes`` prints them.
"""

from __future__ import annotations

from enum import Enum


class Code(str, Enum):
    """A diagnostic code. Compares equal to its text (``Code.TYPES == "types"``)."""

    description: str

    def __new__(cls, value: str, description: str) -> Code:
        member = str.__new__(cls, value)
        member._value_ = value
        member.description = description
        return member

    def __str__(self) -> str:
        return str(self.value)

    # reading
    IO = "io", "a file cannot be read (missing, a directory, a special file, too large, not text)"
    SYNTAX = "syntax", "the text does not follow the grammar"
    LIMIT = "limit", "the model is beyond what robosc can represent (a number, a range, nesting, size)"
    TYPES = "types", "an expression's or value's type does not fit where it is used"
    # the static rules of LANGUAGE.md section 5
    UNIQUE_NAMES = "rule-1", "names are unique per kind, compared without case, as the original does"
    INITIAL_STATE = "rule-2", "an automaton has exactly one initial state"
    MARKED_REACHABLE = "rule-3", "every reachable state can reach a marked state"
    ONE_BEHAVIOUR = "rule-4", "a component has at most one behaviour"
    RESULT_TYPES = "rule-5", "a transition's result fits its communication"
    NO_DATA_TO_REQUEST = "rule-6", "no assignment on a transition that sends data to a node"
    OWN_VARIABLES = "rule-7", "a transition assigns only variables of its own automaton"
    PROVIDE_DIRECTION = "rule-8", "provide statements only for what the controller sends"
    INTEGER_RANGE = "rule-9", "an integer whose value takes part in synthesis needs a range"
    SYNTHESIS_TYPES = "rule-10", "a variable in synthesis is a boolean, a ranged integer or an enum"
    ENUM_SOURCE = "rule-11", "an enum is not converted from another enum"
    INTERFACE_LINKS = "rule-12", "a service, an action, or a communication carrying an object links an interface"
    SHARED_TOPICS = "rule-13", "warning: two components publish to the same topic"
    UNKNOWN_NAME = "rule-14", "every reference resolves"
    TOPIC_NAMES = "rule-15", "topic identifiers are valid ROS graph resource names"
    # further rules the original enforces
    ENUM_DEFAULT = "enum-default", "an enum has exactly one default rule"
    ENUM_VALUES = "enum-values", "an enum value is named by one rule only"
    NO_ARRAY = "no-array", "arrays only inside objects: no array variable or array message, none reaching synthesis"
    NO_OBJECT_VARIABLE = "no-object-variable", "a variable cannot have an object type"
    CONSTANT = "constant", "a constant part of an expression cannot be computed (division by zero)"
    ROS = "ros", "the model cannot be generated for ROS as it is (code generation)"
    RANGE = "range", "a constant is outside the range of the integer it is assigned to"
    # what the build turns into names and text outside the model
    PACKAGE_NAME = "package-name", "a robot's name begins with a letter (it names a ROS package, node and files)"
    TEXT = "text", "a string holds no NUL or other control character but tab, newline and carriage return"
    INSTANCES = (
        "instances",
        "instances of a component: a count from 1 to 1000, one initial state per instance, names and ROS "
        "names that no two instances share; quantifiers and 'for' over a group of instances",
    )
    # warnings that catch modelling mistakes
    IMPLICIT_START = "implicit-start", "warning: a guard or requirement reads an enum variable with no initial value"
    PRECEDENCE = (
        "precedence",
        "warning: '=>' stands beside 'and', 'or' or a comparison without parentheses; it binds tighter than "
        "they do (as in the original tool), which is rarely what is meant",
    )
    UNCONTROLLABLE_REQUIREMENT = (
        "uncontrollable-requirement",
        "warning: a requirement on a message the robot sends, which the supervisor cannot forbid",
    )
    SEVERAL_OUTCOMES = (
        "several-outcomes",
        "warning: an event has several outcomes (transitions from one state on one event to different states): "
        "the controller is unconfirmed among them until the robot tells which",
    )
    NEVER_ALLOWED = "never-allowed", "warning: synthesis disables a controllable event everywhere"
    NEVER_HOLDS = "never-holds", "warning: a requirement's condition holds in no reachable state"
    UNREACHED_STATE = "unreached-state", "warning: no controlled run reaches a state"
