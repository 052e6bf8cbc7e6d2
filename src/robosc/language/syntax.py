"""Syntax nodes: the parse of one file, before names are resolved.

Every node keeps its :class:`Span`; spans take no part in equality, so two
parses of differently laid-out text compare equal when they say the same thing
(the formatter's round-trip test relies on this).
"""

from __future__ import annotations

from robosc.language.source import Span
from robosc.record import field, record

NO_SPAN = Span("", 0, 0, 0, 0, 0, 0)


def _span() -> Span:
    return field(default=NO_SPAN, compare=False, repr=False)


@record
class Name:
    """An identifier as written (``^`` escapes already removed)."""

    text: str
    span: Span = _span()


@record
class QualifiedName:
    """``instance.name``: a communication of one instance (``bot1.go``)."""

    instance: Name
    name: Name
    span: Span = _span()

    @property
    def text(self) -> str:
        return f"{self.instance.text}.{self.name.text}"


Ref = Name | QualifiedName


@record
class Comment:
    text: str
    span: Span = _span()


# ---- expressions ---------------------------------------------------------


@record
class IntLit:
    value: int
    span: Span = _span()


@record
class DoubleLit:
    text: str  # as written, e.g. "0.25"; keeps "100.0" distinct from "100.00" for fmt
    span: Span = _span()

    @property
    def value(self) -> float:
        return float(self.text)


@record
class StrLit:
    raw: str  # with its quotes, as written
    value: str
    span: Span = _span()


@record
class BoolLit:
    value: bool
    span: Span = _span()


@record
class MemberStep:
    name: Name
    span: Span = _span()


@record
class IndexStep:
    index: int
    span: Span = _span()


Step = MemberStep | IndexStep


@record
class Access:
    """``head.step[n]...``; ``head`` is None for the keyword ``value``."""

    head: Name | None
    steps: tuple[Step, ...]
    span: Span = _span()


@record
class Unary:
    op: str  # "!" or "-"
    operand: Expr
    span: Span = _span()


@record
class Binary:
    op: str
    left: Expr
    right: Expr
    span: Span = _span()


@record
class Paren:
    inner: Expr
    span: Span = _span()


@record
class Quantifier:
    """``all(q in bot: body)``, ``any(...)`` or ``count(...)``: over every instance of ``group``."""

    kind: Name  # all, any or count (checked when resolving)
    binder: Name
    group: Name
    body: Expr
    span: Span = _span()


@record
class Call:
    """``count(a, b, c)`` (how many hold), ``all(...)`` or ``any(...)`` over the conditions written."""

    kind: Name
    args: tuple[Expr, ...]
    span: Span = _span()


Expr = IntLit | DoubleLit | StrLit | BoolLit | Access | Unary | Binary | Paren | Quantifier | Call

# ---- data types ----------------------------------------------------------


@record
class BasicTypeSyntax:
    kind: str  # string, boolean, double, none, integer
    low: int | None = None
    high: int | None = None
    span: Span = _span()


@record
class ArrayTypeSyntax:
    element: TypeSyntax
    span: Span = _span()


@record
class NamedTypeSyntax:
    name: Name
    span: Span = _span()


TypeSyntax = BasicTypeSyntax | ArrayTypeSyntax | NamedTypeSyntax


@record
class PropertySyntax:
    name: Name
    type: TypeSyntax
    span: Span = _span()


@record
class ObjectTypeSyntax:
    name: Name
    properties: tuple[PropertySyntax, ...]
    span: Span = _span()


@record
class EnumRuleSyntax:
    condition: Expr | None  # None for the default rule
    value: Name
    span: Span = _span()


@record
class EnumTypeSyntax:
    name: Name
    source: TypeSyntax
    rules: tuple[EnumRuleSyntax, ...]
    span: Span = _span()


@record
class InterfaceSyntax:
    name: Name
    ros_type: Name
    package: Name
    span: Span = _span()


# ---- communication -------------------------------------------------------


@record
class MessageSyntax:
    direction: str  # "incoming" or "outgoing"
    name: Name
    identifier: StrLit | None
    type: TypeSyntax
    links: Name | None
    span: Span = _span()


@record
class ServiceSyntax:
    name: Name
    identifier: StrLit | None
    request: TypeSyntax
    response: TypeSyntax
    links: Name | None
    span: Span = _span()


@record
class ActionSyntax:
    name: Name
    identifier: StrLit | None
    request: TypeSyntax
    response: TypeSyntax
    feedback: TypeSyntax
    links: Name | None
    span: Span = _span()


CommunicationSyntax = MessageSyntax | ServiceSyntax | ActionSyntax

# ---- behaviour -----------------------------------------------------------


@record
class VariableSyntax:
    name: Name
    type: TypeSyntax
    initial: Expr | None
    span: Span = _span()


@record
class AssignmentSyntax:
    target: Access
    value: Expr
    span: Span = _span()


@record
class ResultTransitionSyntax:
    result: str  # request, response, feedback, error, cancel
    preposition: str  # from, to
    communication: Ref
    assignments: tuple[AssignmentSyntax, ...]
    target: Name | None
    span: Span = _span()


@record
class TauTransitionSyntax:
    guard: Expr | None
    target: Name | None
    span: Span = _span()


TransitionSyntax = ResultTransitionSyntax | TauTransitionSyntax


@record
class StateSyntax:
    name: Name
    initial: bool
    marked: bool
    transitions: tuple[TransitionSyntax, ...]
    span: Span = _span()


BehaviourItem = VariableSyntax | StateSyntax | ResultTransitionSyntax | TauTransitionSyntax


@record
class BehaviourSyntax:
    items: tuple[BehaviourItem, ...]
    span: Span = _span()


@record
class Instances:
    """``[count]`` after a component's name, with its options: where the instances' ROS names
    go (``namespace "/fleet"``) and where each starts (``initial s1, s2``)."""

    count: IntLit | None
    namespace: StrLit | None = None
    initial: tuple[Name, ...] = ()
    span: Span = _span()


@record
class LocalComponentSyntax:
    name: Name
    items: tuple[BehaviourSyntax | CommunicationSyntax, ...]
    span: Span = _span()
    instances: Instances | None = None


@record
class ImportedComponentSyntax:
    name: Name
    library: Name
    component: Name
    span: Span = _span()
    instances: Instances | None = None


ComponentSyntax = LocalComponentSyntax | ImportedComponentSyntax

# ---- robot-level statements ----------------------------------------------


@record
class EventsSyntax:
    names: tuple[Ref, ...]
    is_set: bool
    span: Span = _span()


@record
class RequirementSyntax:
    kind: str  # "needs" or "disables"
    events: EventsSyntax
    condition: Expr
    span: Span = _span()


@record
class FieldValueSyntax:
    name: Name
    value: Expr | ObjectValueSyntax
    span: Span = _span()


@record
class ObjectValueSyntax:
    fields: tuple[FieldValueSyntax, ...]
    span: Span = _span()


@record
class ProvideSyntax:
    communication: Ref
    data: Expr | ObjectValueSyntax
    condition: Expr | None
    span: Span = _span()


@record
class ForEachSyntax:
    """``for r in bot { ... }``: the statements once for each instance of ``group``."""

    binder: Name
    group: Name
    items: tuple[RequirementSyntax | ProvideSyntax | ForEachSyntax, ...]
    span: Span = _span()


Definition = (
    ForEachSyntax
    | LocalComponentSyntax
    | ImportedComponentSyntax
    | RequirementSyntax
    | ProvideSyntax
    | ObjectTypeSyntax
    | EnumTypeSyntax
    | InterfaceSyntax
)


@record
class FileSyntax:
    """One parsed file: a ``robot`` or a ``library``."""

    kind: str  # "robot" or "library"
    name: Name
    definitions: tuple[Definition, ...]
    comments: tuple[Comment, ...] = field(default=(), compare=False, repr=False)
    span: Span = _span()
