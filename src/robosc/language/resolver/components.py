"""Resolves components: first their names (communications, states, variables),
then, once every component's names are known, their transitions."""

from __future__ import annotations

from collections.abc import Callable

from robosc.language import model as m
from robosc.language import syntax as s
from robosc.language import types as t
from robosc.language.codes import Code
from robosc.language.resolver.expressions import ExprContext, ExpressionResolver
from robosc.language.resolver.instances import Instance, ros_identifier
from robosc.language.resolver.reporter import Reporter
from robosc.language.resolver.scope import FileScope
from robosc.language.resolver.tables import ComponentTables


def declare(
    syntax: s.LocalComponentSyntax, owner: str, scope: FileScope, instance: Instance | None = None, reporter: Reporter | None = None
) -> ComponentTables:
    """Phase 1: a component's communications, states and variables (no transitions yet);
    for an ``instance``, under its names (``reporter``: the robot's, for what the instance adds)."""
    instance = instance or Instance(owner, None, None, None, None)
    reporter = reporter or scope.reporter
    tables = ComponentTables(owner)
    constants = ExpressionResolver(scope.reporter, scope.enum_values, lambda _: None, list)
    for item in syntax.items:
        if isinstance(item, s.BehaviourSyntax):
            for entry in item.items:
                if isinstance(entry, s.StateSyntax):
                    state = m.State(entry.name.text, owner, entry.initial, entry.marked, entry.span)
                    tables.states.setdefault(state.name, state)
                elif isinstance(entry, s.VariableSyntax):
                    variable = _variable(entry, owner, scope, constants)
                    tables.variables.setdefault(variable.name, variable)
        else:
            communication = _communication(item, owner, scope, *ros_identifier(item, instance, reporter))
            tables.communications.append(communication)
            tables.local.setdefault(item.name.text, communication)
    if instance.initial is not None:
        _start_in(tables, instance.initial, reporter)
    return tables


def _start_in(tables: ComponentTables, initial: s.Name, reporter: Reporter) -> None:
    """An instance starts in ``initial`` instead of its automaton's initial state."""
    if initial.text not in tables.states:
        reporter.unknown(initial.span, "state", initial.text, tables.states, f" in '{tables.name}'")
        return
    reporter.refer(initial.span, tables.states[initial.text])
    for name, state in tables.states.items():
        tables.states[name] = m.State(state.name, state.owner, name == initial.text, state.marked, state.span)


def _communication(
    syntax: s.CommunicationSyntax, owner: str, scope: FileScope, name: str, identifier: str | None
) -> m.Communication:
    interface = scope.lookup_interface(syntax.links) if syntax.links is not None else None
    if isinstance(syntax, s.MessageSyntax):
        return m.Message(
            name,
            owner,
            m.Direction(syntax.direction),
            identifier,
            scope.data_type(syntax.type),
            interface,
            syntax.span,
        )
    request = scope.data_type(syntax.request)
    response = scope.data_type(syntax.response)
    if isinstance(syntax, s.ServiceSyntax):
        return m.Service(name, owner, identifier, request, response, interface, syntax.span)
    feedback = scope.data_type(syntax.feedback)
    return m.Action(name, owner, identifier, request, response, feedback, interface, syntax.span)


def _variable(syntax: s.VariableSyntax, owner: str, scope: FileScope, constants: ExpressionResolver) -> m.Variable:
    data_type = scope.data_type(syntax.type)
    initial = None
    if syntax.initial is not None:
        context = ExprContext(None, None, "an initial value")
        initial = constants.expr(syntax.initial, context)
        check_value_fits(scope.reporter, initial, data_type, f"variable '{syntax.name.text}'", ranges=False)
        if not _is_constant(initial):
            scope.reporter.error(
                initial.span, "the initial value of a variable must be a literal or an enum value", Code.TYPES
            )
    return m.Variable(syntax.name.text, owner, data_type, initial, syntax.span)


def _is_constant(expr: m.Expr) -> bool:
    if isinstance(expr, m.Unary) and expr.op == "-":
        return _is_constant(expr.operand)
    return isinstance(expr, (m.Literal, m.EnumLiteral, m.Invalid))


def check_value_fits(reporter: Reporter, value: m.Expr, target: m.DataType, what: str, ranges: bool = True) -> None:
    """An assigned, initial or provided value must fit its target's type (and, with ``ranges``, a
    constant must lie in an integer's range; for variables the checks decide that, see
    :mod:`robosc.language.checks.variable_ranges`)."""
    if not t.fits(value.type, target):
        reporter.error(value.span, f"a value of type {value.type} does not fit {what} of type {target}", Code.TYPES)
        return
    constant = _constant_int(value)
    if ranges and isinstance(target, m.BasicType) and target.is_ranged_integer and constant is not None:
        assert target.low is not None and target.high is not None
        if not target.low <= constant <= target.high:
            reporter.error(value.span, f"{constant} is outside the range of {what} ({target})", Code.TYPES)


def _constant_int(expr: m.Expr) -> int | None:
    if isinstance(expr, m.Literal) and isinstance(expr.value, int) and not isinstance(expr.value, bool):
        return expr.value
    if isinstance(expr, m.Unary) and expr.op == "-":
        inner = _constant_int(expr.operand)
        return None if inner is None else -inner
    return None


def value_type(communication: m.Communication, result: m.ResultKind) -> tuple[m.DataType | None, str]:
    """What ``value`` is on a transition ``on RESULT from COMMUNICATION``."""
    data: m.DataType | None
    if isinstance(communication, m.Message):
        data = communication.type
    elif result is m.ResultKind.REQUEST:
        data = communication.request_type
    elif result is m.ResultKind.RESPONSE:
        data = communication.response_type
    elif result is m.ResultKind.FEEDBACK and isinstance(communication, m.Action):
        data = communication.feedback_type
    else:
        return None, f"an '{result.value}' of '{communication.name}' carries no data"
    if isinstance(data, m.BasicType) and data.kind is m.BasicKind.NONE:
        return None, f"'{communication.name}' carries no data here (its type is none)"
    return data, ""


class BehaviourResolver:
    """Phase 2: the transitions of one component."""

    def __init__(
        self,
        tables: ComponentTables,
        expressions: ExpressionResolver,
        reporter: Reporter,
        communications: Callable[[str], m.Communication | None],
        communication_names: Callable[[], list[str]],
    ) -> None:
        self.tables = tables
        self.expressions = expressions
        self.reporter = reporter
        self.communications = communications
        self.communication_names = communication_names

    def automaton(self, syntax: s.BehaviourSyntax) -> m.Automaton:
        transitions: list[m.Transition | None] = []
        states: list[m.State] = []
        variables: list[m.Variable] = []
        for item in syntax.items:
            if isinstance(item, s.StateSyntax):
                state = self._own_state(item)
                states.append(state)
                transitions += [self.transition(tr, state) for tr in item.transitions]
            elif isinstance(item, s.VariableSyntax):
                variable = self.tables.variables[item.name.text]
                variables.append(variable if variable.span == item.span else self._duplicate_variable(item))
            else:
                transitions.append(self.transition(item, None))
        kept = tuple(tr for tr in transitions if tr is not None)
        return m.Automaton(tuple(states), tuple(variables), kept, syntax.span)

    def _own_state(self, syntax: s.StateSyntax) -> m.State:
        state = self.tables.states[syntax.name.text]
        if state.span == syntax.span:
            return state
        # A second state of the same name (reported by rule 1): keep it, as its own object.
        return m.State(syntax.name.text, self.tables.name, syntax.initial, syntax.marked, syntax.span)

    def _duplicate_variable(self, syntax: s.VariableSyntax) -> m.Variable:
        first = self.tables.variables[syntax.name.text]
        return m.Variable(first.name, first.owner, first.type, first.initial, syntax.span)

    def transition(self, syntax: s.TransitionSyntax, source: m.State | None) -> m.Transition | None:
        """The transition, or None when its communication is unknown (already reported)."""
        target = self._target(syntax.target)
        if isinstance(syntax, s.TauTransitionSyntax):
            context = ExprContext(self.tables, None, "a guard", "'value' means nothing in a guard")
            guard = None if syntax.guard is None else self.expressions.condition(syntax.guard, context, "a guard")
            return m.TauTransition(source, guard, target, syntax.span)
        communication = self._communication(syntax.communication)
        result = m.ResultKind(syntax.result)
        if communication is None:
            return None
        data, reason = value_type(communication, result)
        context = ExprContext(self.tables, data, "an assignment", reason)
        assignments = tuple(self._assignment(a, context) for a in syntax.assignments)
        return m.ResultTransition(source, result, communication, assignments, target, syntax.span)

    def _target(self, name: s.Name | None) -> m.State | None:
        if name is None:
            return None
        state = self.tables.states.get(name.text)
        if state is None:
            self.reporter.unknown(name.span, "state", name.text, self.tables.states, f" in '{self.tables.name}'")
        else:
            self.reporter.refer(name.span, state)
        return state

    def _communication(self, name: s.Ref) -> m.Communication | None:
        own = self.tables.local.get(name.text) if isinstance(name, s.Name) else None
        found = own or self.communications(name.text)
        if found is None:
            self.reporter.unknown(name.span, "communication", name.text, self.communication_names())
        else:
            self.reporter.refer(name.name.span if isinstance(name, s.QualifiedName) else name.span, found)
        return found

    def _assignment(self, syntax: s.AssignmentSyntax, context: ExprContext) -> m.Assignment:
        target = self.expressions.access(
            syntax.target, ExprContext(self.tables, None, "an assignment target", assigning=True)
        )
        value = self.expressions.expr(syntax.value, context)
        if not isinstance(target, m.VariableRef):
            if not isinstance(target, m.Invalid):
                self.reporter.error(target.span, "only a variable can be assigned", Code.TYPES)
            placeholder = m.Variable("<invalid>", self.tables.name, m.ERROR, None, syntax.target.span)
            return m.Assignment(placeholder, (), value, syntax.span)
        check_value_fits(self.reporter, value, target.type, f"'{target.variable.name}'", ranges=False)
        return m.Assignment(target.variable, target.steps, value, syntax.span)
