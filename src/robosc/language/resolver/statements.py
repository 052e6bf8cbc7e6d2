"""Resolves the robot-level statements: requirements and provide statements."""

from __future__ import annotations

from collections.abc import Callable

from robosc.language import model as m
from robosc.language import syntax as s
from robosc.language.codes import Code
from robosc.language.resolver.components import check_value_fits
from robosc.language.resolver.expressions import ExprContext, ExpressionResolver
from robosc.language.resolver.reporter import Reporter

ROBOT_LEVEL = "'value' means nothing at robot level: name a component's state or variable instead"


class StatementResolver:
    def __init__(
        self,
        expressions: ExpressionResolver,
        reporter: Reporter,
        communications: Callable[[str], m.Communication | None],
        communication_names: Callable[[], list[str]],
    ) -> None:
        self.expressions = expressions
        self.reporter = reporter
        self.communications = communications
        self.communication_names = communication_names

    def statement(
        self,
        syntax: s.RequirementSyntax | s.ProvideSyntax | s.ForEachSyntax,
        requirements: list[m.Requirement],
        provides: list[m.Provide],
    ) -> None:
        """Resolve one robot-level statement into ``requirements`` and ``provides``."""
        if isinstance(syntax, s.RequirementSyntax):
            requirements.append(self.requirement(syntax))
        elif isinstance(syntax, s.ProvideSyntax):
            provide = self.provide(syntax)
            if provide is not None:
                provides.append(provide)
        else:
            self.for_each(syntax, requirements, provides)

    def for_each(self, syntax: s.ForEachSyntax, requirements: list[m.Requirement], provides: list[m.Provide]) -> None:
        """``for r in bot { ... }``: the statements once for each instance, in order."""
        names = self.expressions.group(syntax.group, syntax.binder, "'for'")
        for name in names or ():
            if not self.expressions.expanding(syntax.span):
                return
            with self.expressions.binding(syntax.binder.text, name):
                for item in syntax.items:
                    self.statement(item, requirements, provides)

    def _communication(self, name: s.Ref) -> m.Communication | None:
        text = name.text
        refer = name.span
        if isinstance(name, s.QualifiedName):
            refer = name.name.span
            instance = self.expressions.bound.get(name.instance.text, name.instance.text)
            text = f"{instance}.{name.name.text}"
            if name.instance.text in self.expressions.groups:
                self.reporter.error(
                    name.instance.span,
                    f"'{name.instance.text}' is a group of instances: name one (as in "
                    f"'{name.instance.text}1.{name.name.text}'), or write the statement in "
                    f"'for r in {name.instance.text} {{ ... }}' with 'r.{name.name.text}'",
                    Code.INSTANCES,
                )
                return None
        found = self.communications(text)
        if found is None:
            self.reporter.unknown(name.span, "communication", text, self.communication_names())
        else:
            self.reporter.refer(refer, found)
        return found

    def requirement(self, syntax: s.RequirementSyntax) -> m.Requirement:
        found = (self._communication(n) for n in syntax.events.names)
        communications = tuple(c for c in found if c is not None)
        context = ExprContext(None, None, "a requirement", ROBOT_LEVEL)
        condition = self.expressions.condition(syntax.condition, context, "a requirement")
        return m.Requirement(m.RequirementKind(syntax.kind), communications, condition, syntax.span)

    def provide(self, syntax: s.ProvideSyntax) -> m.Provide | None:
        communication = self._communication(syntax.communication)
        context = ExprContext(None, None, "a provide statement", ROBOT_LEVEL)
        condition = None
        if syntax.condition is not None:
            condition = self.expressions.condition(syntax.condition, context, "a provide condition")
        if communication is None:
            return None
        target = communication.request_type
        data = self._data(syntax.data, target, context, f"the data of '{communication.name}'")
        return m.Provide(communication, data, condition, syntax.span)

    def _data(
        self, syntax: s.Expr | s.ObjectValueSyntax, target: m.DataType, context: ExprContext, what: str
    ) -> m.Expr | m.ObjectValue:
        if not isinstance(syntax, s.ObjectValueSyntax):
            value = self.expressions.expr(syntax, context)
            check_value_fits(self.reporter, value, target, what)
            return value
        if not isinstance(target, m.ObjectType):
            if not isinstance(target, m.ErrorType):
                self.reporter.error(syntax.span, f"{what} is of type {target}, not an object", Code.TYPES)
            return m.ObjectValue(target, (), syntax.span)
        fields = []
        for field in syntax.fields:
            prop = target.property(field.name.text)
            if prop is None:
                self.reporter.unknown(
                    field.name.span,
                    "property",
                    field.name.text,
                    [p.name for p in target.properties],
                    f" in {target.name}",
                )
                continue
            data = self._data(field.value, prop.type, context, f"property '{prop.name}'")
            fields.append(m.FieldValue(prop, data, field.span))
        return m.ObjectValue(target, tuple(fields), syntax.span)
