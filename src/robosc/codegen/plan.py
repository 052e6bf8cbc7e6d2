"""The run-time plan: a synthesized supervisor laid out for code generation.

:func:`plan` turns a :class:`~robosc.synthesis.result.SynthesisResult` into plain
data -- field names, Python condition text, the lines of each event's effect --
that ``templates/supervisor.py.j2`` places into the generated per-robot module.
Nothing here is evaluated; every condition is Python source made by
:mod:`robosc.codegen.pyexpr`. What every robot shares (the cycle, conversion,
recording, ROS) is not generated: it is :mod:`robosc.runtime.onboard`.

Generated identifiers come from one :class:`~robosc.codegen.pyexpr.Identifiers`
scheme: automata ``a<N>_<name>``, variables ``v<N>_<Component>_<name>``,
controllable events ``e<N>_<event>``, uncontrollable ones ``u<N>_<event>``,
provided data ``data<N>_<communication>`` / ``DATA<N>_<communication>``, enum
rules ``enum<N>_<Enum>``.
"""

from __future__ import annotations

from typing import Any

from robosc.codegen.outcomes import Branch, forked, landing
from robosc.codegen.pyexpr import Identifiers, Names, conjunction, constant, python, step_path
from robosc.codegen.routes import Driver, Route, Shape, drivers, routes
from robosc.language import model as m
from robosc.language.source import Span
from robosc.plant.domains import initial_value
from robosc.plant.network import Automaton, AutomatonKind, Event, EventKind, event_of, received_type
from robosc.record import record
from robosc.synthesis.reached import reached_locations
from robosc.synthesis.result import SynthesisResult

K = EventKind
INDENT = "    "
# which part of the snapshot an automaton's location goes to
GROUPS = {
    AutomatonKind.COMPONENT: "automata",
    AutomatonKind.MESSAGE: "communications",
    AutomatonKind.SERVICE: "communications",
    AutomatonKind.ACTION: "communications",
    AutomatonKind.DATA: "data",
}


@record
class Field:
    """One field of the supervisor's state."""

    name: str  # the Python attribute
    label: str  # as the user knows it: "Platform", "Distance.front", "set_light"
    group: str  # "automata", "communications", "data" or "variables"
    initial: str  # Python literal
    synthesis: bool = True  # takes part in synthesis (variables only)
    domain: str = "None"  # Python literal: the values it takes (locations, an enum's values, a type), for restoring


@record
class Part:
    """What one automaton does on one event, and where it can."""

    lines: list[str]
    moves: list[tuple[str, str | None, Any]] | None
    gates: list[str]


@record
class Communication:
    name: str
    kind: str  # "outgoing", "incoming", "service", "action"
    ros_name: str
    component: str
    package: str | None  # ROS package of the linked interface
    ros_type: str | None  # the linked interface's type name
    data_kind: str  # messages: "string", "boolean", "integer", "double", "none" or "object"
    span: Span
    interface_span: Span | None = None

    @property
    def interface(self) -> str | None:
        """``package/Type`` of the linked interface."""
        return f"{self.package}/{self.ros_type}" if self.package and self.ros_type else None


@record
class EventPlan:
    name: str
    method: str
    controllable: bool
    kind: str  # EventKind value
    enabled: str  # Python condition: the plant allows it (and, when controllable, the supervisor)
    plant: str  # the plant part of ``enabled``
    supervisor: str  # the supervisor part (required and added)
    effect: tuple[str, ...]  # Python lines (indented relative to the method body)
    moves: tuple[tuple[str, str | None, Any], ...] | None  # the effect as location changes only, if it is (a
    # tuple target: its outcomes)
    communication: Communication | None = None
    convert: str | None = None  # Python: (rules function, enum name, default) for enum data
    data: str | None = None  # constant data: Python expression for it; computed data: the method computing it
    computed: bool = False  # ``data`` is computed from the state (it may be refused)
    # Python literal: (data plant field, {location: template}) where a template is the data
    # with ANY where the model computes a value; None: it sends no data (the type's defaults)
    signature: str | None = None
    reads: tuple[str, ...] = ()  # controllable: communications whose received data its condition or data reads
    # uncontrollable: (component location field, locations where the model answers it), for each component
    # automaton that answers it, when one of them does not answer it everywhere (else None)
    answers: tuple[tuple[str, tuple[str, ...]], ...] | None = None

    @property
    def sends(self) -> bool:
        """Performing it puts something on the middleware (a message, a call, a cancel)."""
        return self.controllable and self.communication is not None and self.kind in ("message", "trigger", "cancel")

    @property
    def is_request(self) -> bool:
        """Sent on the controller's behalf (what a supervision layer forwards or blocks)."""
        return self.controllable and self.kind in ("message", "trigger")

    @property
    def changes(self) -> bool:
        return bool(self.effect)

    @property
    def table_driven(self) -> bool:
        """Nothing to send and only location changes: the runtime's ``moves`` performs it."""
        return self.moves is not None and bool(self.moves) and not self.sends and self.data is None


@record
class Conversion:
    """An enum's rules: raw middleware data to one of the enum's values."""

    function: str
    enum: str
    source: str  # the type converted from, for the reader
    rules: tuple[tuple[str, str], ...]  # (Python condition on ``value``, value name)
    default: str


@record
class DataChoice:
    location: str
    event: str  # the provide event's name
    enabled: str  # Python condition (plant guard, required and added)
    data: str  # Python expression of the data
    constant: bool  # reads no state
    checks: tuple[str, ...] = ()  # Python conditions on ``data``: each computed number is finite
    template: str = "None"  # Python: the data with ANY where it is computed (see _template)


@record
class DataPlant:
    field: str
    communication: str
    method: str  # the method returning the data of the current location (computed data)
    table: str  # the module-level table of the data per location (constant data)
    choices: tuple[DataChoice, ...]
    none_event: str | None
    none_enabled: str | None  # when there is a "provide none" event

    @property
    def constant(self) -> bool:
        return all(c.constant for c in self.choices)

    @property
    def choose(self) -> str:
        """Python: the location this data plant moves to now (None: it stays)."""
        options = [(c.location, c.enabled) for c in self.choices]
        if self.none_enabled is not None:
            options.append(("none", self.none_enabled))
        text = ""
        for location, enabled in options:
            if enabled == "True":
                return text + repr(location)
            text += f"{location!r} if {_wrapped(enabled)} else "
        return text + "None"


@record
class Plan:
    robot: str
    source: str  # the model's path, for the header
    fields: tuple[Field, ...]
    events: tuple[EventPlan, ...]
    conversions: tuple[Conversion, ...]
    data_plants: tuple[DataPlant, ...]
    communications: tuple[Communication, ...]
    automata: tuple[tuple[str, str | None], ...]  # (network automaton name, field or None: one location), network order
    variables: tuple[tuple[str, str], ...]  # (Component.variable, field), synthesis variables, network order
    shared: tuple[tuple[str, str], ...] = ()  # (method, Python condition): long conditions written once
    # (attribute, fields): the values of fields a count reads, tallied at each evaluation of _allowed
    tallies: tuple[tuple[str, tuple[str, ...]], ...] = ()
    drivers: tuple[Driver, ...] = ()  # per component automaton, in network order
    routes: tuple[Route, ...] = ()  # per component automaton with a location field, in network order
    shapes: tuple[Shape, ...] = ()

    @property
    def controllable(self) -> tuple[EventPlan, ...]:
        return tuple(e for e in self.events if e.controllable)

    @property
    def uncontrollable(self) -> tuple[EventPlan, ...]:
        return tuple(e for e in self.events if not e.controllable)

    @property
    def replies(self) -> tuple[str, ...]:
        """The uncontrollable events that answer a command: a component takes them in a location
        a controllable event leads to (a driver's answer, which a retry or a bridge may send
        twice); all that some component answers where a command's effect is not only a change of
        location (its targets are not told here)."""
        entered: set[tuple[str, str]] = set()
        every = False
        for e in self.controllable:
            if e.moves is None:
                every = True
            else:
                for field, _, target in e.moves:
                    entered.update((field, t) for t in (target if isinstance(target, tuple) else (target,)))
        return tuple(
            e.name
            for e in self.uncontrollable
            if e.answers and any(every or (field, place) in entered for field, places in e.answers for place in places)
        )

    def event(self, name: str) -> EventPlan:
        return next(e for e in self.events if e.name == name)

    def communication(self, name: str) -> Communication:
        return next(c for c in self.communications if c.name == name)


def _constant(a: Automaton) -> bool:
    """A message's plant: one location, a self-loop; nothing reads or changes its location."""
    return a.kind is AutomatonKind.MESSAGE and len(a.locations) == 1


def _wrapped(condition: str) -> str:
    return f"({condition})" if " or " in condition or " if " in condition else condition


def _literal(e: m.Expr | None) -> object:
    """The value of a literal (or a negated one), else None."""
    if isinstance(e, m.Literal):
        return e.value
    if isinstance(e, m.EnumLiteral):
        return e.value.name
    if isinstance(e, m.Unary) and e.op == "-" and isinstance(e.operand, m.Literal):
        value = e.operand.value
        return -value if isinstance(value, int | float) and not isinstance(value, bool) else None
    return None


def _start(v: m.Variable) -> object:
    """A variable's start value: its initial value, else the plant's rule for finite types
    (false, 0 or the range's value closest to 0, the enum's first value), else 0 / 0.0 / ""
    / None (objects and arrays: nothing received yet)."""
    try:
        value = initial_value(v)
    except ValueError:  # no finite domain
        given = _literal(v.initial)
        if given is not None:
            return given
        t = v.type
        if isinstance(t, m.BasicType):
            return {m.BasicKind.INTEGER: 0, m.BasicKind.DOUBLE: 0.0, m.BasicKind.STRING: ""}.get(t.kind)
        return None
    return value.name if isinstance(value, m.EnumValue) else value


def _type_check(v: m.Variable, steps: tuple[m.Step, ...]) -> str:
    """What the runtime checks a new value against (Python literal; None: anything)."""
    t = v.type
    if steps:
        return "None"
    if isinstance(t, m.EnumType):
        return repr(tuple(x.name for x in t.values))
    if isinstance(t, m.BasicType) and t.is_ranged_integer:
        return repr(("integer", t.low, t.high))
    if isinstance(t, m.BasicType) and t.kind is not m.BasicKind.NONE:
        return repr(t.kind.value)
    return "None"


def _template(data: m.Expr | m.ObjectValue) -> str:
    """Provided data as a Python literal that a supervision layer compares a controller's
    message with: its constants, and ``ANY`` where the model computes the value (any
    finite value in range passes there); fields it does not name hold their defaults."""
    if isinstance(data, m.ObjectValue):
        return "{" + ", ".join(f"{f.property.name!r}: {_template(f.value)}" for f in data.fields) + "}"
    value = _literal(data)
    return constant(value) if value is not None else "ANY"


def _checks(data: m.Expr | m.ObjectValue, path: str = "data") -> list[str]:
    """What must hold of computed data before it is sent: every computed number finite
    (``isfinite`` for numbers, ``finite`` for whole objects); constants need no check."""
    if isinstance(data, m.ObjectValue):
        return [c for f in data.fields for c in _checks(f.value, f"{path}[{f.property.name!r}]")]
    if not any(isinstance(n, m.VariableRef | m.StateRef | m.DataRef) for n in m.walk(data)):
        return []
    t = data.type
    if isinstance(t, m.BasicType):
        numeric = t.kind in (m.BasicKind.INTEGER, m.BasicKind.DOUBLE)
        return [f"isfinite({path})"] if numeric else []
    return [] if isinstance(t, m.EnumType) else [f"finite({path})"]


def _expressions(data: m.Expr | m.ObjectValue) -> list[m.Expr]:
    if isinstance(data, m.ObjectValue):
        return [e for f in data.fields for e in _expressions(f.value)]
    return list(m.walk(data))


class _Planner:
    def __init__(self, result: SynthesisResult) -> None:
        self.result = result
        self.network = network = result.network
        self.model = network.model
        self.ids = ids = Identifiers()
        locations: dict[m.State, tuple[str, str]] = {}
        self.automaton_field: dict[Automaton, str] = {}
        for automaton in network.automata:
            f = ids.new("a", automaton.name)
            self.automaton_field[automaton] = f
            for location in automaton.locations:
                locations[location] = (f, location.name)
        variables = {}
        for component in self.model.components:
            for behaviour in component.behaviours:
                for v in behaviour.variables:
                    variables[v] = ids.new("v", component.name, v.name)
        self.names = Names(locations, variables, shared={})
        # the supervisor's conditions (evaluated in _allowed only): counts read from tallies
        self.guards = Names(
            locations, variables, shared=self.names.shared, tallies={}, groups=self.group_fields(variables)
        )
        self.checked = Names(locations, variables, checked=True)  # where received data is read
        self.kept = set(network.variables)
        self.conversions: dict[m.EnumType, Conversion] = {}

    def group_fields(self, variables: dict[m.Variable, str]) -> dict[str, tuple[str, ...]]:
        """Each field of a robot of a group -> the fields of the same role (its automaton, a
        variable of the same name) of every robot of the group, in order."""
        out: dict[str, tuple[str, ...]] = {}
        for instances in self.model.groups.values():
            rows = [
                [f for a, f in self.automaton_field.items() if a.component is c and a.kind is AutomatonKind.COMPONENT]
                + [variables[v] for b in c.behaviours for v in sorted(b.variables, key=lambda v: v.name)]
                for c in instances
            ]
            if len(rows) < 2 or any(len(row) != len(rows[0]) for row in rows):
                continue
            for role in zip(*rows, strict=True):
                out.update((f, role) for f in role)
        return out

    # -- expressions -------------------------------------------------------------------------
    def py(self, expr: m.Expr | None) -> str:
        return "True" if expr is None else python(expr, self.names)

    def guard_py(self, expr: m.Expr | None) -> str:
        """A condition of the supervisor's, evaluated in ``_allowed`` (which makes the tallies)."""
        return "True" if expr is None else python(expr, self.guards)

    def data_py(self, data: m.Expr | m.ObjectValue) -> str:
        if isinstance(data, m.ObjectValue):
            items = ", ".join(f"{f.property.name!r}: {self.data_py(f.value)}" for f in data.fields)
            return "{" + items + "}"
        return self.py(data)

    def conversion(self, enum: m.EnumType) -> Conversion:
        if enum not in self.conversions:
            rules = tuple(
                (python(r.condition, self.checked), r.value.name) for r in enum.rules if r.condition is not None
            )
            default = enum.default or (enum.values[0] if enum.values else None)
            source = enum.source.name if isinstance(enum.source, m.ObjectType | m.EnumType) else str(enum.source)
            self.conversions[enum] = Conversion(
                self.ids.new("enum", enum.name), enum.name, source, rules, default.name if default else ""
            )
        return self.conversions[enum]

    # -- state -------------------------------------------------------------------------------
    def fields(self) -> list[Field]:
        """The automata (but messages' plants: one location, never read), then the variables."""
        out = [
            Field(
                self.automaton_field[a],
                a.name,
                GROUPS[a.kind],
                repr(a.initial.name),
                domain=repr(tuple(location.name for location in a.locations)),
            )
            for a in self.network.automata
            if not _constant(a)
        ]
        for component in self.model.components:
            for behaviour in component.behaviours:
                for v in behaviour.variables:
                    label = f"{component.name}.{v.name}"
                    field = self.names.variables[v]
                    start = constant(_start(v))
                    out.append(Field(field, label, "variables", start, v in self.kept, _type_check(v, ())))
        return out

    def assignments(self, transition: m.ResultTransition, received: bool) -> list[str]:
        """The ``self._assign(...)`` call of a transition's assignments, as lines; for an
        uncontrollable event (``received``) ``self._receive(...)``, which reads the received
        data through the runtime's checks and refuses the event when a value cannot be read."""
        items = []
        names = self.checked if received else self.names
        if received and len(transition.assignments) == 1:
            a = transition.assignments[0]
            if not a.steps and isinstance(a.variable.type, m.EnumType) and python(a.value, names) == "value":
                # an enum read from the data as it came: one of the enum's names, else not taken
                label = f"{a.variable.owner}.{a.variable.name}"
                enum = _type_check(a.variable, ())
                return [
                    f"self.{self.names.variables[a.variable]} = value if type(value) is str and value in {enum}"
                    f" else self._outside({label!r}, value)"
                ]
        for a in transition.assignments:
            label = f"{a.variable.owner}.{a.variable.name}"
            field = self.names.variables[a.variable]
            parts = [repr(field), repr(step_path(a.steps)), repr(label), f"lambda: {python(a.value, names)}"]
            items.append(f"({', '.join(parts)}, {_type_check(a.variable, a.steps)})")
        call = "self._receive" if received else "self._assign"
        if len(items) <= 1:
            return [f"{call}({item})" for item in items]
        return [f"{call}(", *(f"{INDENT}{item}," for item in items), ")"]

    @staticmethod
    def branch_lines(field: str, branches: list[Branch], gated: bool) -> list[str]:
        """if / elif over an automaton's ways to take part in an event: (source, guard,
        target, assignment lines). Unconditional where there is one way and the event's
        condition already requires it (``gated``), or it is taken from every state."""
        lines: list[str] = []
        first = True
        branches = forked(branches)
        bodies = [[*assigns, *landing(field, source, target)] for source, _, target, assigns in branches]
        if gated and bodies and all(body == bodies[0] for body in bodies):
            return bodies[0]  # every way the event can happen here does the same
        for source, guard, target, assigns in branches:
            body = [*assigns, *landing(field, source, target)]
            if not body:
                continue
            test = conjunction(["True" if source is None else f"self.{field} == {source!r}", guard])
            if first and (test == "True" or (gated and len(branches) == 1)):
                return body
            if len(body) == 1 and len(test) + len(body[0]) < 80:
                lines.append(f"{'if' if first else 'elif'} {test}: {body[0]}")
            else:
                lines.append(f"{'if' if first else 'elif'} {test}:")
                lines += [INDENT + line for line in body]
            first = False
        return lines

    @staticmethod
    def branch_moves(field: str, branches: list[Branch], gated: bool) -> list[tuple[str, str | None, Any]] | None:
        """The same as :meth:`branch_lines` as data, (field, source or None, target) tried in
        order, the first that applies for a field wins; None when a branch assigns or tests a
        guard (then it needs code)."""
        moves: list[tuple[str, str | None, Any]] = []
        changes = forked(branches)
        if any(assigns for *_, assigns in changes):
            return None
        targets = [
            tuple(source if t is None else t for t in target) if isinstance(target, tuple)
            else target if target is not None and target != source else None
            for source, _, target, _ in changes
        ]
        if gated and changes and all(x == targets[0] for x in targets):
            return [(field, None, targets[0])] if targets[0] is not None else []
        for (source, guard, _, _), target in zip(changes, targets, strict=True):
            if target is None:
                continue
            if source is None and guard == "True" and not moves:
                return [(field, None, target)]
            if gated and len(changes) == 1:
                return [(field, None, target)]
            if guard != "True":
                return None
            moves.append((field, source, target))
        return moves

    # -- events --------------------------------------------------------------------------------
    def component_part(self, event: Event, automaton: Automaton, gated: bool) -> Part:
        """The effect (lines and, where it is only location changes, moves) and the Python
        conditions where the component can take part."""
        component = automaton.component
        assert component is not None and component.automaton is not None
        field = self.automaton_field[automaton]
        branches = []
        gates = []
        for transition in component.automaton.transitions:
            if event_of(self.network, transition) is not event:
                continue
            assigns: list[str] = []
            if isinstance(transition, m.TauTransition):
                guard = self.py(transition.guard)
            else:
                guard, assigns = "True", self.assignments(transition, not event.controllable)
            source, target = transition.source, transition.target
            branches.append((source.name if source else None, guard, target.name if target else None, assigns))
            here = "True" if source is None else f"self.{field} == {source.name!r}"
            gates.append(conjunction([here, guard]))
        return Part(self.branch_lines(field, branches, gated), self.branch_moves(field, branches, gated), gates)

    def plant_part(self, event: Event, automaton: Automaton) -> Part:
        field = self.automaton_field[automaton]
        branches: list[tuple[str | None, str, str | None, list[str]]] = []
        gates = []
        for e in automaton.edges:
            if e.event is not event:
                continue
            source = e.source.name if len(automaton.locations) > 1 else None
            guard = self.py(e.guard)
            branches.append((source, guard, e.target.name if e.target is not e.source else None, []))
            gates.append(conjunction(["True" if source is None else f"self.{field} == {source!r}", guard]))
        # the plant's condition is always checked first
        return Part(self.branch_lines(field, branches, True), self.branch_moves(field, branches, True), gates)

    @staticmethod
    def gate(options: list[str]) -> str:
        """Where an automaton can take part in its event (as Python)."""
        if not options:
            return "False"
        if "True" in options:
            return "True"
        return options[0] if len(options) == 1 else " or ".join(f"({o})" for o in options)

    def event(self, event: Event) -> EventPlan:
        effect: list[str] = []
        moves: list[tuple[str, str | None, Any]] | None = []
        gates: list[str] = []
        for automaton in self.network.automata:
            if event not in automaton.alphabet:
                continue
            if automaton.kind is AutomatonKind.COMPONENT:
                total = not event.controllable or event.kind is K.CANCEL  # responsiveness
                part = self.component_part(event, automaton, not total)
                if not total:
                    gates.append(self.gate(part.gates))
            else:
                part = self.plant_part(event, automaton)
                gates.append(self.gate(part.gates))
            effect += part.lines
            moves = None if moves is None or part.moves is None else [*moves, *part.moves]
        plant = conjunction(gates)
        supervisor = "True"
        if event.controllable:
            guard = self.result.guard(event.name)
            supervisor = conjunction([self.guard_py(guard.required), self.guard_py(guard.added)])
        communication = convert = data = signature = None
        computed = False
        if event.communication is not None:
            communication = self.communications[event.communication]
            t = received_type(event)
            if isinstance(t, m.EnumType):
                c = self.conversion(t)
                convert = f"({c.function}, {c.enum!r}, {c.default!r})"
            is_sent = event.kind in (K.MESSAGE, K.TRIGGER) and event.controllable
            if is_sent and event.communication in self.data_plants:
                d = self.data_plants[event.communication]
                if d.constant:
                    data = f"{d.table}[self.{d.field}]"
                else:
                    data, computed = d.method, True
                templates = "".join(f"{c.location!r}: {c.template}, " for c in d.choices)
                signature = f"({d.field!r}, {{{templates}'none': None}})"
        prefix = "e" if event.controllable else "u"
        return EventPlan(
            event.name,
            self.ids.new(prefix, event.name.replace(".", "_")),
            event.controllable,
            event.kind.value,
            conjunction([plant, supervisor]),
            plant,
            supervisor,
            tuple(effect),
            tuple(moves) if moves is not None else None,
            communication,
            convert,
            data,
            computed,
            signature,
            self.reads(event) if event.controllable else (),
            None if event.controllable else self.answers(event),
        )

    def answers(self, event: Event) -> tuple[tuple[str, tuple[str, ...]], ...] | None:
        """Where the components answer the uncontrollable ``event`` with a transition the user
        wrote (not the self-loop responsiveness adds): (field, locations) per component automaton
        taking it; None when one of them answers it everywhere, or it also moves a communication's
        plant (a service's response): then it is always taken."""
        out = []
        for automaton in self.network.automata:
            if event not in automaton.alphabet:
                continue
            if automaton.kind is not AutomatonKind.COMPONENT:
                if len(automaton.locations) > 1:
                    return None  # it moves a service's or an action's plant: always taken
                continue
            component = automaton.component
            assert component is not None and component.automaton is not None
            sources = [
                t.source
                for t in component.automaton.transitions
                if not isinstance(t, m.TauTransition) and event_of(self.network, t) is event
            ]
            if not sources:
                continue
            if None in sources or len(automaton.locations) == 1:
                return None
            names = tuple(location.name for location in automaton.locations if location in sources)
            if len(names) == len(automaton.locations):
                return None
            out.append((self.automaton_field[automaton], names))
        return tuple(out) or None

    # -- communications and data ---------------------------------------------------------
    def communication(self, component: m.Component, c: m.Communication) -> Communication:
        if isinstance(c, m.Message):
            kind = c.direction.value
        elif isinstance(c, m.Service):
            kind = "service"
        else:
            kind = "action"
        interface = c.interface
        data_kind = "none"
        if isinstance(c, m.Message):
            t = c.type
            while isinstance(t, m.EnumType):
                t = t.source
            data_kind = t.kind.value if isinstance(t, m.BasicType) else "object"
        return Communication(
            c.name,
            kind,
            c.ros_name,
            component.name,
            interface.package if interface else None,
            interface.ros_type if interface else None,
            data_kind,
            c.span,
            interface.span if interface else None,
        )

    def data_plant(self, automaton: Automaton) -> DataPlant:
        choices = []
        none_event = none_enabled = None
        comm_name = automaton.name[: -len("_data")]
        for event in sorted(automaton.alphabet, key=self.network.events.index):
            guard = self.result.guard(event.name)
            supervisor = [self.py(guard.required), self.py(guard.added)]
            edge = next(e for e in automaton.edges if e.event is event)
            enabled = conjunction([self.py(edge.guard), *supervisor])
            if event.provide is None:
                none_event, none_enabled = event.name, enabled
                continue
            data = event.provide.data
            constant = not any(isinstance(n, m.VariableRef | m.StateRef) for n in _expressions(data))
            checks = tuple(_checks(data))
            choices.append(
                DataChoice(
                    edge.target.name, event.name, enabled, self.data_py(data), constant, checks, _template(data)
                )
            )
        return DataPlant(
            self.automaton_field[automaton],
            comm_name,
            self.ids.new("data", comm_name),
            self.ids.new("DATA", comm_name),
            tuple(choices),
            none_event,
            none_enabled,
        )

    # -- which received data each controllable event depends on ----------------------------
    def data_reach(self) -> dict[m.Variable, frozenset[str]]:
        """For each variable, the communications whose received data reaches it: assigned from
        ``value``, or from a variable such data reached (to a fixpoint)."""
        reach: dict[m.Variable, set[str]] = {}
        uses: dict[m.Variable, set[m.Variable]] = {}
        for component in self.model.components:
            if component.automaton is None:
                continue
            for t in component.automaton.transitions:
                if not isinstance(t, m.ResultTransition):
                    continue
                for a in t.assignments:
                    for node in m.walk(a.value):
                        if isinstance(node, m.DataRef):
                            reach.setdefault(a.variable, set()).add(t.communication.name)
                        elif isinstance(node, m.VariableRef):
                            uses.setdefault(a.variable, set()).add(node.variable)
        changed = True
        while changed:
            changed = False
            for v, sources in uses.items():
                for w in sources:
                    extra = reach.get(w, set()) - reach.get(v, set())
                    if extra:
                        reach.setdefault(v, set()).update(extra)
                        changed = True
        return {v: frozenset(c) for v, c in reach.items()}

    def conditions(self, event: Event) -> list[m.Expr]:
        """Every condition on ``event``: the plants' guards, your requirements, what synthesis added."""
        out: list[m.Expr] = []
        for automaton in self.network.automata:
            if event not in automaton.alphabet:
                continue
            if automaton.kind is AutomatonKind.COMPONENT:
                assert automaton.component is not None and automaton.component.automaton is not None
                for t in automaton.component.automaton.transitions:
                    if isinstance(t, m.TauTransition) and t.guard is not None and event_of(self.network, t) is event:
                        out.append(t.guard)
            else:
                out += [e.guard for e in automaton.edges if e.event is event and e.guard is not None]
        guard = self.result.guard(event.name)
        return out + [g for g in (guard.required, guard.added) if g is not None]

    def reads(self, event: Event) -> tuple[str, ...]:
        """The communications whose received data a controllable event's conditions read, and
        for a command, the conditions and data of what it sends."""
        expressions = self.conditions(event)
        if event.kind in (K.MESSAGE, K.TRIGGER) and event.communication is not None:
            for automaton in self.network.automata:
                if automaton.kind is not AutomatonKind.DATA or event.communication not in {
                    e.communication for e in automaton.alphabet
                }:
                    continue
                for provide in automaton.alphabet:
                    expressions += self.conditions(provide)
                    if provide.provide is not None:
                        expressions += _expressions(provide.provide.data)
        found: set[str] = set()
        for expression in expressions:
            for node in m.walk(expression):
                if isinstance(node, m.VariableRef):
                    found |= self.reach.get(node.variable, frozenset())
        return tuple(sorted(found))

    def build(self) -> Plan:
        self.reach = self.data_reach()
        self.communications = {
            c: self.communication(component, c) for component in self.model.components for c in component.communications
        }
        self.data_plants: dict[m.Communication, DataPlant] = {}
        for automaton in self.network.automata:
            if automaton.kind is AutomatonKind.DATA:
                event = next(iter(automaton.alphabet))
                assert event.communication is not None
                self.data_plants[event.communication] = self.data_plant(automaton)
        events = tuple(self.event(e) for e in self.network.events if e.kind is not K.PROVIDE)
        return Plan(
            self.model.name,
            self.model.path,
            tuple(self.fields()),
            events,
            tuple(self.conversions.values()),
            tuple(self.data_plants.values()),
            tuple(self.communications.values()),
            tuple((a.name, None if _constant(a) else self.automaton_field[a]) for a in self.network.automata),
            tuple((f"{v.owner}.{v.name}", self.names.variables[v]) for v in self.network.variables),
            tuple((name, code) for code, name in (self.names.shared or {}).items()),
            tuple((name, fields) for fields, name in (self.guards.tallies or {}).items()),
            drivers(self.network),
            *routes(self.network, self.automaton_field, reached_locations(self.result)),
        )


def plan(result: SynthesisResult) -> Plan:
    """Lay out a successful synthesis result for code generation."""
    if not result.ok:
        raise ValueError("no supervisor to run: synthesis failed")
    return _Planner(result).build()
