"""The checked model: what the language stage hands to every later stage.

Every reference is resolved to the object it names (a transition holds the
:class:`State` it goes to, an expression holds the :class:`Variable` it reads),
and every expression carries its type. Entities (components, states, variables,
communications, data types) compare by identity; nothing here points back to
the parse tree. Entities that need to know their component carry its name in
``owner`` (a label for display, not a reference).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from enum import Enum

from robosc.language.source import Span
from robosc.record import field, record

# ---- data types ----------------------------------------------------------


class BasicKind(str, Enum):
    STRING = "string"
    BOOLEAN = "boolean"
    INTEGER = "integer"
    DOUBLE = "double"
    NONE = "none"


@record
class BasicType:
    kind: BasicKind
    low: int | None = None  # inclusive range, integers only
    high: int | None = None

    @property
    def is_ranged_integer(self) -> bool:
        return self.kind is BasicKind.INTEGER and self.low is not None

    def __str__(self) -> str:
        if self.is_ranged_integer:
            return f"integer({self.low}..{self.high})"
        return self.kind.value


@record
class ArrayType:
    element: DataType

    def __str__(self) -> str:
        return f"array({self.element})"


@record(eq=False)
class Property:
    name: str
    type: DataType
    span: Span = field(repr=False)


@record(eq=False)
class ObjectType:
    name: str
    properties: tuple[Property, ...]
    span: Span = field(repr=False)

    def property(self, name: str) -> Property | None:
        return next((p for p in self.properties if p.name == name), None)

    def __str__(self) -> str:
        return self.name


@record(eq=False)
class EnumValue:
    name: str
    span: Span = field(repr=False)


@record(eq=False)
class EnumRule:
    condition: Expr | None  # None: the default rule
    value: EnumValue
    span: Span = field(repr=False)


@record(eq=False)
class EnumType:
    """``enum E from T to { rules }``. ``values`` in order of first mention; the first is the default start value."""

    name: str
    source: DataType
    values: tuple[EnumValue, ...]
    rules: tuple[EnumRule, ...]
    span: Span = field(repr=False)

    @property
    def default(self) -> EnumValue | None:
        return next((r.value for r in self.rules if r.condition is None), None)

    def value(self, name: str) -> EnumValue | None:
        return next((v for v in self.values if v.name == name), None)

    def __str__(self) -> str:
        return self.name


@record
class ErrorType:
    """The type of something that did not resolve; suppresses follow-up errors."""

    def __str__(self) -> str:
        return "<error>"


DataType = BasicType | ArrayType | ObjectType | EnumType | ErrorType

BOOLEAN = BasicType(BasicKind.BOOLEAN)
INTEGER = BasicType(BasicKind.INTEGER)
DOUBLE = BasicType(BasicKind.DOUBLE)
STRING = BasicType(BasicKind.STRING)
NONE = BasicType(BasicKind.NONE)
ERROR = ErrorType()


@record(eq=False)
class Interface:
    """``interface name use RosType from ros_package``."""

    name: str
    ros_type: str
    package: str
    span: Span = field(repr=False)


# ---- expressions -----------------------------------------------------------


@record
class FieldStep:
    property: Property


@record
class IndexStep:
    index: int


Step = FieldStep | IndexStep


@record(eq=False)
class Literal:
    value: bool | int | float | str
    type: DataType
    span: Span = field(repr=False)


@record(eq=False)
class EnumLiteral:
    enum: EnumType
    value: EnumValue
    span: Span = field(repr=False)

    @property
    def type(self) -> DataType:
        return self.enum


@record(eq=False)
class StateRef:
    """``Component.state``: true while the component's automaton is in ``state``."""

    state: State
    span: Span = field(repr=False)
    type: DataType = BOOLEAN


@record(eq=False)
class VariableRef:
    """A variable, optionally followed by property / index steps into its data."""

    variable: Variable
    steps: tuple[Step, ...]
    type: DataType
    span: Span = field(repr=False)


@record(eq=False)
class DataRef:
    """``value...``: the data the middleware delivered (or the enum's raw input)."""

    steps: tuple[Step, ...]
    type: DataType
    span: Span = field(repr=False)


@record(eq=False)
class Unary:
    op: str  # "!" or "-"
    operand: Expr
    type: DataType
    span: Span = field(repr=False)


@record(eq=False)
class Binary:
    op: str  # or and = != > >= < <= => + - * /
    left: Expr
    right: Expr
    type: DataType
    span: Span = field(repr=False)
    # an ``any`` / ``all`` over a whole array (group, its size), as the resolver joined its
    # terms (one per instance, in order: see simplify.join); only shown so, never read
    over: tuple[str, int] | None = field(default=None, compare=False, repr=False)


@record(eq=False)
class Invalid:
    """An expression that did not resolve (already reported)."""

    span: Span = field(repr=False)
    type: DataType = ERROR


@record(eq=False)
class Count:
    """``count(q in group: ...)``: how many of ``terms`` (one per instance of ``group``, in
    instance order) hold; an integer from 0 to their number."""

    group: str
    terms: tuple[Expr, ...]
    type: DataType
    span: Span = field(repr=False)


Expr = Literal | EnumLiteral | StateRef | VariableRef | DataRef | Unary | Binary | Count | Invalid


def walk(expr: Expr, seen: set[int] | None = None) -> Iterator[Expr]:
    """``expr`` and every expression inside it; with ``seen``, an operation (a part of several
    expressions, shared) whose id is in it is skipped, and each one walked is added."""
    stack = [expr]
    while stack:
        node = stack.pop()
        if seen is not None and isinstance(node, Binary | Unary | Count):
            if id(node) in seen:
                continue
            seen.add(id(node))
        yield node
        if isinstance(node, Binary):
            stack += [node.right, node.left]
        elif isinstance(node, Unary):
            stack.append(node.operand)
        elif isinstance(node, Count):
            stack += reversed(node.terms)


def walk_all(exprs: Iterable[Expr]) -> Iterator[Expr]:
    """Every expression inside each of ``exprs`` (parts of one model, alive while it is), each
    object once: a part several of them share (a quantifier inside a ``for`` block that does
    not read its variable, resolved once for every instance) is walked once, so that a fleet
    costs linear time, not quadratic."""
    seen: set[int] = set()
    for root in exprs:
        yield from walk(root, seen)


# ---- communication ----------------------------------------------------------


class Direction(str, Enum):
    INCOMING = "incoming"  # the controller publishes to the node
    OUTGOING = "outgoing"  # the node publishes, the controller receives


@record(eq=False)
class Message:
    name: str
    owner: str
    direction: Direction
    identifier: str | None
    type: DataType
    interface: Interface | None
    span: Span = field(repr=False)

    @property
    def ros_name(self) -> str:
        return self.identifier if self.identifier is not None else self.name

    @property
    def request_type(self) -> DataType:
        return self.type

    @property
    def response_type(self) -> DataType:
        return self.type


@record(eq=False)
class Service:
    name: str
    owner: str
    identifier: str | None
    request_type: DataType
    response_type: DataType
    interface: Interface | None
    span: Span = field(repr=False)

    @property
    def ros_name(self) -> str:
        return self.identifier if self.identifier is not None else self.name


@record(eq=False)
class Action:
    name: str
    owner: str
    identifier: str | None
    request_type: DataType
    response_type: DataType
    feedback_type: DataType
    interface: Interface | None
    span: Span = field(repr=False)

    @property
    def ros_name(self) -> str:
        return self.identifier if self.identifier is not None else self.name


Communication = Message | Service | Action


def data_types_of(communication: Communication) -> tuple[DataType, ...]:
    if isinstance(communication, Message):
        return (communication.type,)
    if isinstance(communication, Service):
        return (communication.request_type, communication.response_type)
    return (communication.request_type, communication.response_type, communication.feedback_type)


# ---- behaviour --------------------------------------------------------------


@record(eq=False)
class State:
    name: str
    owner: str
    initial: bool
    marked: bool
    span: Span = field(repr=False)


@record(eq=False)
class Variable:
    name: str
    owner: str
    type: DataType
    initial: Expr | None
    span: Span = field(repr=False)


class ResultKind(str, Enum):
    REQUEST = "request"
    RESPONSE = "response"
    FEEDBACK = "feedback"
    ERROR = "error"
    CANCEL = "cancel"


@record(eq=False)
class Assignment:
    variable: Variable
    steps: tuple[Step, ...]
    value: Expr
    span: Span = field(repr=False)


@record(eq=False)
class ResultTransition:
    """``on RESULT from/to COMM do ... goto S``; ``source`` None means every state."""

    source: State | None
    result: ResultKind
    communication: Communication
    assignments: tuple[Assignment, ...]
    target: State | None  # None: stays where it is
    span: Span = field(repr=False)


@record(eq=False)
class TauTransition:
    """``transition if G goto S``: a controllable event of its own."""

    source: State | None
    guard: Expr | None
    target: State | None
    span: Span = field(repr=False)


Transition = ResultTransition | TauTransition


@record(eq=False)
class Automaton:
    states: tuple[State, ...]
    variables: tuple[Variable, ...]
    transitions: tuple[Transition, ...]
    span: Span = field(repr=False)

    @property
    def initial_states(self) -> tuple[State, ...]:
        return tuple(s for s in self.states if s.initial)

    def state(self, name: str) -> State | None:
        return next((s for s in self.states if s.name == name), None)

    def variable(self, name: str) -> Variable | None:
        return next((v for v in self.variables if v.name == name), None)

    def transitions_from(self, state: State) -> Iterator[Transition]:
        """What ``state`` can do: its own transitions and the automaton-wide ones."""
        return (t for t in self.transitions if t.source is None or t.source is state)


@record(eq=False)
class Component:
    """A component (a ROS node). ``library`` is set for an imported one. An instance
    (``component bot[4] ...`` makes bot1 .. bot4) names its ``group`` and its ``index`` (from 1);
    its communications are named ``bot1.go`` and live in its ROS ``namespace``."""

    name: str
    communications: tuple[Communication, ...]
    behaviours: tuple[Automaton, ...]  # the language allows at most one (rule 4)
    span: Span = field(repr=False)
    library: str | None = None
    library_component: str | None = None
    group: str | None = None
    index: int | None = None
    namespace: str | None = None

    @property
    def automaton(self) -> Automaton | None:
        return self.behaviours[0] if self.behaviours else None


# ---- robot-level statements -------------------------------------------------


class RequirementKind(str, Enum):
    NEEDS = "needs"
    DISABLES = "disables"


@record(eq=False)
class Requirement:
    """``E needs C`` or ``C disables E``, for each communication in ``communications``."""

    kind: RequirementKind
    communications: tuple[Communication, ...]
    condition: Expr
    span: Span = field(repr=False)


@record(eq=False)
class FieldValue:
    property: Property
    value: Expr | ObjectValue
    span: Span = field(repr=False)


@record(eq=False)
class ObjectValue:
    type: DataType
    fields: tuple[FieldValue, ...]
    span: Span = field(repr=False)


@record(eq=False)
class Provide:
    communication: Communication
    data: Expr | ObjectValue
    condition: Expr | None
    span: Span = field(repr=False)


# ---- the whole model --------------------------------------------------------


@record(eq=False)
class Model:
    """A checked robot (or library): components with everything they use resolved."""

    kind: str  # "robot" or "library"
    name: str
    path: str
    components: tuple[Component, ...]
    data_types: tuple[ObjectType | EnumType, ...]
    interfaces: tuple[Interface, ...]
    requirements: tuple[Requirement, ...] = ()
    provides: tuple[Provide, ...] = ()
    name_span: Span | None = None  # where the robot or library is named

    @property
    def communications(self) -> tuple[Communication, ...]:
        return tuple(c for comp in self.components for c in comp.communications)

    @property
    def variables(self) -> tuple[Variable, ...]:
        return tuple(v for comp in self.components for a in comp.behaviours for v in a.variables)

    def component(self, name: str) -> Component | None:
        return next((c for c in self.components if c.name == name), None)

    @property
    def groups(self) -> dict[str, tuple[Component, ...]]:
        """Each group of instances (``component bot[4] ...``) and its instances, in order."""
        found: dict[str, list[Component]] = {}
        for component in self.components:
            if component.group is not None:
                found.setdefault(component.group, []).append(component)
        return {name: tuple(instances) for name, instances in found.items()}

    def communication(self, name: str) -> Communication | None:
        return next((c for c in self.communications if c.name == name), None)

    @property
    def enums(self) -> tuple[EnumType, ...]:
        return tuple(t for t in self.data_types if isinstance(t, EnumType))


def result_transitions(model: Model) -> Iterator[tuple[Component, ResultTransition]]:
    """Every ``on RESULT ...`` transition with the component it belongs to."""
    for component in model.components:
        for automaton in component.behaviours:
            for transition in automaton.transitions:
                if isinstance(transition, ResultTransition):
                    yield component, transition


def expressions_of(model: Model) -> Iterator[tuple[str, Expr]]:
    """Every top-level expression with the role it plays: guard, requirement, provide-condition, ..."""
    for component in model.components:
        for automaton in component.behaviours:
            for transition in automaton.transitions:
                if isinstance(transition, TauTransition) and transition.guard is not None:
                    yield "guard", transition.guard
                elif isinstance(transition, ResultTransition):
                    for assignment in transition.assignments:
                        yield "assignment", assignment.value
    for requirement in model.requirements:
        yield "requirement", requirement.condition
    for provide in model.provides:
        if provide.condition is not None:
            yield "provide-condition", provide.condition


def synthesis_variables(model: Model) -> dict[Variable, Expr]:
    """Variables that take part in synthesis (named in a guard, requirement or provide
    condition), each with the first place that names it."""
    found: dict[Variable, Expr] = {}
    for node in walk_all(expr for role, expr in expressions_of(model) if role != "assignment"):
        if isinstance(node, VariableRef):
            found.setdefault(node.variable, node)
    return found


@record
class SynthesisInput:
    """Received data that reaches a synthesis variable: ``variable := ...value...``."""

    communication: Communication
    data: DataRef  # the ``value...`` access
    variable: Variable
    transition: ResultTransition


def synthesis_inputs(model: Model) -> Iterator[SynthesisInput]:
    """Every access to received data in an assignment to a variable that takes part in
    synthesis (the original's "communication input required in synthesis")."""
    in_synthesis = synthesis_variables(model)
    for _component, transition in result_transitions(model):
        for assignment in transition.assignments:
            if assignment.variable not in in_synthesis:
                continue
            for node in walk(assignment.value):
                if isinstance(node, DataRef):
                    yield SynthesisInput(transition.communication, node, assignment.variable, transition)
