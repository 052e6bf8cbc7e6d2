"""Resolves expressions: names to objects, and each node's type."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager

from robosc.language import model as m
from robosc.language import simplify
from robosc.language import syntax as s
from robosc.language import types as t
from robosc.language.codes import Code
from robosc.language.diagnostics import closest
from robosc.language.formatter import expr as show
from robosc.language.resolver import instances as inst
from robosc.language.resolver.reporter import Reporter
from robosc.language.resolver.tables import ComponentTables
from robosc.language.source import Span
from robosc.record import record

# the operators '=>' binds tighter than (LANGUAGE.md section 2), where it surprises
LOOSER_THAN_IMPLIES = frozenset(["or", "and", "=", "!=", ">", ">=", "<", "<="])

# Finds a component by the name used in an expression: its tables, or a
# message saying why it cannot be used there, or None when no such component exists.
ComponentLookup = Callable[[str], "ComponentTables | str | None"]


@record
class ExprContext:
    component: ComponentTables | None  # whose variables are named directly
    value_type: m.DataType | None  # the type of ``value``; None where ``value`` means nothing
    where: str  # for messages: "a requirement", "an enum rule", ...
    no_value_reason: str = ""
    assigning: bool = False  # the target of an assignment: only the component's own variables


class ExpressionResolver:
    def __init__(
        self,
        reporter: Reporter,
        enum_values: dict[str, tuple[m.EnumType, m.EnumValue]],
        components: ComponentLookup,
        component_names: Callable[[], list[str]],
        groups: dict[str, list[str]] | None = None,
    ) -> None:
        self.reporter = reporter
        self.enum_values = enum_values
        self.components = components
        self.component_names = component_names
        self.groups = groups if groups is not None else {}  # bot -> [bot1, .., botN]
        # an implication that is an operand of a looser operator -> how it grouped, for its type error
        self.hints: dict[int, str] = {}
        self.bound: dict[str, str] = {}  # instance variables (``q`` in ``all(q in bot: ...)``) -> instance
        # quantifiers already resolved where what they read is bound alike (see _shared_key), and
        # the names each quantifier's body uses
        self.quantified: dict[tuple[object, ...], m.Expr] = {}
        self.names_in: dict[int, tuple[s.Quantifier, frozenset[str]]] = {}

    # -- instances -------------------------------------------------------------------
    def group(self, name: s.Name, binder: s.Name, what: str) -> list[str] | None:
        """The instances a quantifier or a ``for`` ranges over, or None after saying why it cannot."""
        found = self.groups.get(name.text)
        if binder.text in self.bound or self.components(binder.text) is not None:
            self.reporter.error(
                binder.span,
                f"'{binder.text}' already names "
                + ("an instance here" if binder.text in self.bound else "a component")
                + f": give the instances of {what} another name",
                Code.INSTANCES,
            )
            return None
        if found is not None:
            return found
        if name.text in self.bound or self.components(name.text) is not None:
            single = self.bound.get(name.text, name.text)
            self.reporter.error(
                name.span,
                f"{what} ranges over nothing: '{name.text}' is one component ({single}), not a group of instances",
                Code.INSTANCES,
                f"a group is declared with a count, as in 'component {name.text}[4] ...'",
            )
            return None
        self.reporter.unknown(name.span, "group of instances", name.text, self.groups)
        return None

    @contextmanager
    def binding(self, binder: str, instance: str) -> Iterator[None]:
        self.bound[binder] = instance
        try:
            yield
        finally:
            del self.bound[binder]

    def expanding(self, span: Span) -> bool:
        """Whether expansion may go on: at most :data:`~instances.MAX_EXPANSION` expression nodes."""
        if self.reporter.made <= inst.MAX_EXPANSION:
            return True
        if not self.reporter.expansion_stopped:  # said once
            self.reporter.expansion_stopped = True
            self.reporter.error(
                span,
                f"the quantifiers and 'for' blocks here expand to more than {inst.MAX_EXPANSION:,} expression nodes",
                Code.LIMIT,
                "nest fewer quantifiers, or write the condition over fewer instances",
            )
        return False

    def _quantifier(self, syntax: s.Quantifier | s.Call, context: ExprContext) -> m.Expr:
        kind = syntax.kind.text
        if kind not in inst.QUANTIFIERS:
            self.reporter.error(
                syntax.kind.span,
                f"unknown function '{kind}'",
                Code.UNKNOWN_NAME,
                "RoboSC has all(q in group: condition), any(q in group: condition) and count(q in group: condition), "
                "and all, any and count of conditions written out: count(A.x, B.y) <= 1",
            )
            return m.Invalid(syntax.span)
        terms = []
        group = ""
        key: tuple[object, ...] | None = None  # a quantifier's, to share what it resolves to
        if isinstance(syntax, s.Call):
            for arg in syntax.args:
                terms.append(self.expr(arg, context))
        else:
            group = syntax.group.text
            # inside `for r in bot`, `any(q in bot: q.out1)` is the same for every r: resolved
            # once and shared, so that a fleet's requirements grow linearly with it, not squared
            key = self._shared_key(syntax, context)
            shared = self.quantified.get(key)
            if shared is not None:
                return shared
            names = self.group(syntax.group, syntax.binder, f"'{kind}'")
            if names is None:
                return m.Invalid(syntax.span)
            for name in names:
                if not self.expanding(syntax.span):
                    return m.Invalid(syntax.span)
                with self.binding(syntax.binder.text, name):
                    terms.append(self.expr(syntax.body, context))
        for term in terms:
            if t.is_error(term.type):
                return m.Invalid(syntax.span)
            if not t.is_boolean(term.type):
                self.reporter.error(term.span, f"the conditions of '{kind}' are boolean, not {term.type}", Code.TYPES)
                return m.Invalid(syntax.span)
        terms = [simplify.fold(term) for term in terms]
        if kind == "count":
            made: m.Expr = m.Count(group, tuple(terms), m.BasicType(m.BasicKind.INTEGER, 0, len(terms)), syntax.span)
        else:
            made = simplify.join("and" if kind == "all" else "or", terms, syntax.span)
            if group and len(terms) >= 2 and isinstance(made, m.Binary) and len(simplify.chain(made, len(terms))) == len(terms):
                # every term kept: shown as written, any(q in bot: ...) (render checks the terms)
                made = m.Binary(made.op, made.left, made.right, made.type, made.span, over=(group, len(terms)))
        if key is not None:
            self.quantified[key] = made
        return made

    def _shared_key(self, syntax: s.Quantifier, context: ExprContext) -> tuple[object, ...]:
        """What resolving ``syntax`` depends on: where it is, in which context, and the instances
        bound to the names its body uses (not the others: a `for` variable it does not name)."""
        known = self.names_in.get(id(syntax))
        if known is None:  # (the syntax is kept with it: its id stays its own)
            known = self.names_in[id(syntax)] = (syntax, frozenset(_names(syntax.body)))
        used = known[1]
        bound = tuple(sorted((n, i) for n, i in self.bound.items() if n in used or n == syntax.group.text))
        return (id(syntax), id(context.component), id(context.value_type), context.where, context.assigning, bound)

    def _same_instance(self, syntax: s.Binary) -> m.Expr | None:
        """``q = r`` / ``q != r`` between instance variables, or ``r = bot1`` / ``r != bot1``
        between one and an instance of its group (one robot singled out): decided here, or None
        when ``syntax`` compares something else."""
        if syntax.op not in ("=", "!="):
            return None
        names = [e.head.text if isinstance(e, s.Access) and e.head is not None and not e.steps else None for e in (syntax.left, syntax.right)]
        if None in names or not any(name in self.bound for name in names):
            return None
        instances = []
        for name in names:
            assert name is not None
            if name in self.bound:
                instances.append(self.bound[name])
                continue
            groups = [g for g, members in self.groups.items() if name in members]
            bound = next(self.bound[n] for n in names if n in self.bound)
            if not groups or bound not in self.groups[groups[0]]:
                return None  # not an instance of the same group: said where it resolves as a value
            instances.append(name)
        return simplify.literal((instances[0] == instances[1]) == (syntax.op == "="), syntax.span)

    def _an_instance(self, instance: str) -> str:
        """The first instance of the group ``instance`` is one of (for hints)."""
        return next((members[0] for members in self.groups.values() if instance in members and members), instance)

    # -- entry points --------------------------------------------------------------
    def condition(self, syntax: s.Expr, context: ExprContext, what: str) -> m.Expr:
        """An expression that must be boolean (a guard, a requirement, a provide condition)."""
        expr = self.expr(syntax, context)
        if not t.is_error(expr.type) and not t.is_boolean(expr.type):
            self.reporter.error(expr.span, f"{what} must be a boolean expression, not {expr.type}", Code.TYPES)
        return expr

    def expr(self, syntax: s.Expr, context: ExprContext) -> m.Expr:
        self.reporter.made += 1
        if isinstance(syntax, s.Paren):
            return self.expr(syntax.inner, context)
        if isinstance(syntax, s.IntLit):
            return m.Literal(syntax.value, m.INTEGER, syntax.span)
        if isinstance(syntax, s.DoubleLit):
            return m.Literal(syntax.value, m.DOUBLE, syntax.span)
        if isinstance(syntax, s.StrLit):
            return m.Literal(syntax.value, m.STRING, syntax.span)
        if isinstance(syntax, s.BoolLit):
            return m.Literal(syntax.value, m.BOOLEAN, syntax.span)
        if isinstance(syntax, s.Unary):
            operand = self.expr(syntax.operand, context)
            result = t.unary_type(syntax.op, operand.type)
            return m.Unary(syntax.op, operand, self._checked(result, syntax.span), syntax.span)
        if isinstance(syntax, (s.Quantifier, s.Call)):
            return self._quantifier(syntax, context)
        if isinstance(syntax, s.Binary):
            same = self._same_instance(syntax) if self.bound else None
            if same is not None:
                return same
            grouping = self._surprising(syntax)
            if grouping is not None:  # a type error of the implication itself says how it grouped
                self.hints[id(grouping[3])] = grouping[2]
            left = self.expr(syntax.left, context)
            right = self.expr(syntax.right, context)
            result = t.binary_type(syntax.op, left.type, right.type)
            if grouping is not None:
                if self.hints.pop(id(grouping[3]), None) is None:  # said with the implication's error
                    return m.Binary(syntax.op, left, right, m.ERROR, syntax.span)
                if isinstance(result, str):  # the type error the grouping leads to
                    self.reporter.error(syntax.span, result, Code.TYPES, grouping[2])
                    return m.Binary(syntax.op, left, right, m.ERROR, syntax.span)
                self.reporter.warning(syntax.span, grouping[0], Code.PRECEDENCE, grouping[1])
            node = m.Binary(syntax.op, left, right, self._checked(result, syntax.span, syntax), syntax.span)
            if (
                self.bound
                and syntax.op in ("and", "or", "=>")
                and (simplify.boolean_constant(left) is not None or simplify.boolean_constant(right) is not None)
            ):
                return simplify.fold(node)  # inside 'for' or a quantifier: a decided 'r != bot1' folded away
            return node
        return self.access(syntax, context)

    @staticmethod
    def _surprising(syntax: s.Binary) -> tuple[str, str, str, s.Binary] | None:
        """Where ``=>`` is an operand of a looser operator (and, or, a comparison) without
        parentheses: how robosc reads it, the parentheses to write (for a warning, and for the
        type error it may lead to), and the implication."""
        if syntax.op not in LOOSER_THAN_IMPLIES:
            return None
        for side in (syntax.left, syntax.right):
            if not (isinstance(side, s.Binary) and side.op == "=>"):
                continue
            a, b = show(side.left), show(side.right)
            other = show(syntax.right if side is syntax.left else syntax.left)
            if side is syntax.left:
                read, meant = f"({a} => {b}) {syntax.op} {other}", f"{a} => ({b} {syntax.op} {other})"
            else:
                read, meant = f"{other} {syntax.op} ({a} => {b})", f"({other} {syntax.op} {a}) => {b}"
            said = f"'=>' binds tighter than '{syntax.op}': this reads as {read} (as in the original tool)"
            return (
                said,
                f"write the parentheses: {meant} if that is what you mean, or {read} to keep this reading "
                "and silence this warning",
                f"{said}; write the parentheses: {meant}",
                side,
            )
        return None

    def _checked(self, result: m.DataType | str, span: Span, syntax: s.Expr | None = None) -> m.DataType:
        if isinstance(result, str):
            hint = self.hints.pop(id(syntax), None) if syntax is not None else None
            self.reporter.error(span, result, Code.TYPES, hint)
            return m.ERROR
        return result

    # -- accesses --------------------------------------------------------------------
    def access(self, syntax: s.Access, context: ExprContext) -> m.Expr:
        if syntax.head is None:
            return self._value(syntax, context)
        name = syntax.head.text
        steps = syntax.steps
        own = context.component
        if name in self.bound:
            if not steps:
                self.reporter.error(
                    syntax.span,
                    f"'{name}' stands for an instance, which is not a value",
                    Code.INSTANCES,
                    f"name one of its states ('{name}.<state>') or compare it with another instance "
                    f"('{name} != {'q' if name != 'q' else 'r'}', or '{name} != {self._an_instance(self.bound[name])}')",
                )
                return m.Invalid(syntax.span)
            instance = self.bound[name]
            tables = self.components(instance)
            if tables is not None:
                return self._component_member(instance, tables, syntax, refer_head=False)
        if own is not None and name in own.variables:
            self.reporter.refer(syntax.head.span, own.variables[name])
            return self._variable(own.variables[name], steps, syntax.span)
        component = self.components(name)
        if component is not None:
            return self._component_member(name, component, syntax)
        if name in self.enum_values:
            enum, value = self.enum_values[name]
            if steps:
                self.reporter.error(steps[0].span, f"enum value '{name}' has no properties", Code.TYPES)
                return m.Invalid(syntax.span)
            self.reporter.refer(syntax.head.span, value)
            return m.EnumLiteral(enum, value, syntax.span)
        if context.assigning and own is not None:  # only what may be assigned here is proposed
            self.reporter.unknown(
                syntax.head.span,
                "variable",
                name,
                own.variables,
                f" in component '{own.name}'",
                otherwise=lambda: self._assigned_elsewhere(name, own.name),
            )
            return m.Invalid(syntax.span)
        candidates = list(self.component_names()) + list(self.enum_values)
        if own is not None:
            candidates += list(own.variables)
        self.reporter.unknown(
            syntax.head.span, "name", name, candidates, otherwise=lambda: self._member_elsewhere(name)
        )
        return m.Invalid(syntax.span)

    def _assigned_elsewhere(self, name: str, own: str) -> str | None:
        """Why a variable of another component cannot be assigned here, and what to do instead."""
        for component_name in self.component_names():
            tables = self.components(component_name)
            if component_name == own or tables is None or isinstance(tables, str) or name not in tables.variables:
                continue
            return (
                f"'{name}' is a variable of {component_name}, and a transition assigns only its own component's "
                f"variables (rule 7): assign it in a transition of {component_name} (which can react to the same "
                f"event), or give {own} a variable of its own"
            )
        return None

    def _member_elsewhere(self, name: str, skip: str | None = None) -> str | None:
        """A hint naming ``Component.member`` for the closest state or variable of any component."""
        qualified: dict[str, str] = {}
        for component_name in self.component_names():
            tables = self.components(component_name)
            if component_name == skip or tables is None or isinstance(tables, str):
                continue
            for member in [*tables.states, *tables.variables]:
                qualified.setdefault(member, f"{component_name}.{member}")
        found = closest(name, qualified)
        return f"did you mean '{qualified[found]}'?" if found else None

    def _value(self, syntax: s.Access, context: ExprContext) -> m.Expr:
        if context.value_type is None:
            reason = context.no_value_reason or f"'value' means nothing in {context.where}"
            self.reporter.error(
                syntax.span,
                reason,
                Code.TYPES,
                "'value' is the received data: use it in enum rules and in 'do' of transitions that receive data",
            )
            return m.Invalid(syntax.span)
        steps, data_type = self.steps(context.value_type, syntax.steps)
        return m.DataRef(steps, data_type, syntax.span)

    def _component_member(
        self, name: str, component: ComponentTables | str, syntax: s.Access, refer_head: bool = True
    ) -> m.Expr:
        if isinstance(component, str):
            if not component:  # its import failed, which is reported already
                return m.Invalid(syntax.span)
            self.reporter.error(syntax.head.span if syntax.head else syntax.span, component, Code.UNKNOWN_NAME)
            return m.Invalid(syntax.span)
        if not syntax.steps or not isinstance(syntax.steps[0], s.MemberStep):
            self.reporter.error(
                syntax.span,
                f"'{name}' is a component: name one of its states or variables, as in '{name}.<state>'",
                Code.TYPES,
            )
            return m.Invalid(syntax.span)
        member = syntax.steps[0].name
        rest = syntax.steps[1:]
        if syntax.head is not None and refer_head:  # the component named (its tables, the component once built)
            self.reporter.refer(syntax.head.span, component)
        if member.text in component.states:
            if rest:
                self.reporter.error(rest[0].span, f"state '{name}.{member.text}' has no properties", Code.TYPES)
                return m.Invalid(syntax.span)
            self.reporter.refer(member.span, component.states[member.text])
            return m.StateRef(component.states[member.text], syntax.span)
        if member.text in component.variables:
            self.reporter.refer(member.span, component.variables[member.text])
            return self._variable(component.variables[member.text], rest, syntax.span)
        self.reporter.unknown(
            member.span,
            "state or variable",
            member.text,
            [*component.states, *component.variables],
            f" in component '{name}'",
            otherwise=lambda: self._member_elsewhere(member.text, skip=name),
        )
        return m.Invalid(syntax.span)

    def _variable(self, variable: m.Variable, steps: tuple[s.Step, ...], span: Span) -> m.Expr:
        resolved, data_type = self.steps(variable.type, steps)
        return m.VariableRef(variable, resolved, data_type, span)

    def steps(self, data_type: m.DataType, steps: tuple[s.Step, ...]) -> tuple[tuple[m.Step, ...], m.DataType]:
        """Follow ``.property`` and ``[n]`` steps into data of ``data_type``."""
        resolved: list[m.Step] = []
        for step in steps:
            if t.is_error(data_type):
                return tuple(resolved), data_type
            if isinstance(step, s.IndexStep):
                if not isinstance(data_type, m.ArrayType):
                    self.reporter.error(step.span, f"cannot index [{step.index}] into {data_type}", Code.TYPES)
                    return tuple(resolved), m.ERROR
                resolved.append(m.IndexStep(step.index))
                data_type = data_type.element
                continue
            if not isinstance(data_type, m.ObjectType):
                self.reporter.error(step.span, f"{data_type} has no property '{step.name.text}'", Code.TYPES)
                return tuple(resolved), m.ERROR
            prop = data_type.property(step.name.text)
            if prop is None:
                self.reporter.unknown(
                    step.name.span,
                    "property",
                    step.name.text,
                    [p.name for p in data_type.properties],
                    f" in {data_type.name}",
                )
                return tuple(resolved), m.ERROR
            self.reporter.refer(step.name.span, prop)
            resolved.append(m.FieldStep(prop))
            data_type = prop.type
        return tuple(resolved), data_type


def _names(node: object) -> Iterator[str]:
    """Every name written in a piece of syntax."""
    if isinstance(node, s.Name):
        yield node.text
        return
    if isinstance(node, (list, tuple)):
        for item in node:
            yield from _names(item)
        return
    for attribute in getattr(type(node), "__match_args__", ()):
        if attribute != "span":
            yield from _names(getattr(node, attribute))
