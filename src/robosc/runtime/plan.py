"""The run-time plan: a synthesized supervisor laid out for code generation.

:func:`plan` turns a :class:`~robosc.synthesis.result.SynthesisResult` into plain
data (field names, Python condition text, what each event does) that the
templates render into the stand-alone supervisor module and the ROS nodes.
Nothing here is evaluated; every condition is Python source made by
:mod:`robosc.runtime.pyexpr`.

The state of the generated supervisor is one field per automaton (its location
name) and one per variable. Component automata are ``c_<Component>``,
communication plants ``p_<communication>``, data plants ``d_<communication>``,
variables ``v_<Component>_<variable>``.
"""

from __future__ import annotations

from dataclasses import dataclass

from robosc.language import model as m
from robosc.language.source import Span
from robosc.plant.domains import initial_value
from robosc.plant.network import Automaton, AutomatonKind, Event, EventKind, event_of, received_type
from robosc.runtime.pyexpr import Names, conjunction, constant, identifier, python
from robosc.synthesis.result import SynthesisResult

K = EventKind


@dataclass(frozen=True)
class Field:
    """One field of the supervisor's state."""

    name: str  # the Python attribute
    label: str  # as the user knows it: "Platform", "Distance.front", "set_light"
    kind: str  # "component", "message", "service", "action", "data" or "variable"
    initial: str  # Python literal
    synthesis: bool = True  # takes part in synthesis (variables only)


@dataclass(frozen=True)
class Assign:
    field: str  # the variable's field
    steps: str  # Python text of property / index steps into it ("" for the whole variable)
    value: str  # Python expression
    label: str  # "Arm.picks"
    type_check: str  # a condition on ``{}`` that the new value must meet to be stored ("" for any)

    def check(self, name: str) -> str:
        """The type check for a new value held in the Python variable ``name``."""
        return self.type_check.replace("{}", name) if self.type_check else "True"


@dataclass(frozen=True)
class Branch:
    """One way an automaton takes part in an event."""

    source: str | None  # location name; None: from every location
    guard: str  # Python condition
    target: str | None  # location name; None: stays
    assignments: tuple[Assign, ...] = ()

    @property
    def test(self) -> str:
        """Python condition choosing this branch (the automaton's location is in ``here``)."""
        return conjunction(["True" if self.source is None else f"here == {self.source!r}", self.guard])

    @property
    def changes(self) -> bool:
        return (self.target is not None and self.target != self.source) or bool(self.assignments)


@dataclass(frozen=True)
class Part:
    """What one automaton does on one event."""

    field: str
    label: str
    branches: tuple[Branch, ...]


@dataclass(frozen=True)
class Communication:
    name: str
    method: str  # identifier used in method names
    kind: str  # "outgoing", "incoming", "service", "action"
    ros_name: str
    component: str
    package: str | None  # ROS package of the linked interface
    ros_type: str | None  # the linked interface's type name
    data_kind: str  # messages: "string", "boolean", "integer", "double", "none" or "object"
    span: Span


@dataclass(frozen=True)
class EventPlan:
    name: str
    method: str
    controllable: bool
    kind: str  # EventKind value
    parts: tuple[Part, ...]
    enabled: str  # Python condition: the plant allows it (and, when controllable, the supervisor)
    plant: str  # the plant part of ``enabled``
    supervisor: str  # the supervisor part (required and added)
    communication: Communication | None = None
    convert: str | None = None  # enum conversion of the received data
    data: str | None = None  # method building the data to send (triggers with provide statements)
    signature: str | None = None  # Python literal: the constant part of the provided data, if any

    @property
    def hook(self) -> str | None:
        """The method the generated supervisor calls to put this event on the middleware."""
        c = self.communication
        if c is None or not self.controllable:
            return None
        if self.kind == "message":
            return f"send_{c.method}"
        if self.kind == "trigger":
            return f"{'call' if c.kind == 'service' else 'start'}_{c.method}"
        if self.kind == "cancel":
            return f"cancel_{c.method}"
        return None

    @property
    def is_request(self) -> bool:
        """Sent on the controller's behalf (what a supervision layer forwards or blocks)."""
        return self.controllable and self.kind in ("message", "trigger")

    @property
    def changes(self) -> bool:
        return any(b.changes for p in self.parts for b in p.branches)


@dataclass(frozen=True)
class Conversion:
    """An enum's rules: raw middleware data to one of the enum's values."""

    function: str
    enum: str
    rules: tuple[tuple[str, str], ...]  # (Python condition on ``value``, value name)
    default: str


@dataclass(frozen=True)
class DataChoice:
    location: str
    event: str  # the provide event's name
    enabled: str  # Python condition (plant guard, required and added)
    data: str  # Python expression of the data
    constant: bool  # reads no state: computed once, at import


@dataclass(frozen=True)
class DataPlant:
    field: str
    communication: str
    method: str  # the method that returns the data of the current location
    choices: tuple[DataChoice, ...]
    none_event: str | None
    none_enabled: str | None  # when there is a "provide none" event

    @property
    def constant(self) -> bool:
        return all(c.constant for c in self.choices)

    @property
    def table(self) -> str:
        """The module-level table of constant data, per location."""
        return identifier("DATA", self.communication)


@dataclass(frozen=True)
class Plan:
    robot: str
    source: str  # the model's path, for the header
    fields: tuple[Field, ...]
    events: tuple[EventPlan, ...]
    conversions: tuple[Conversion, ...]
    data_plants: tuple[DataPlant, ...]
    communications: tuple[Communication, ...]
    automata: tuple[tuple[str, str], ...]  # (network automaton name, field), network order
    variables: tuple[tuple[str, str], ...]  # (Component.variable, field), synthesis variables, network order

    @property
    def controllable(self) -> tuple[EventPlan, ...]:
        return tuple(e for e in self.events if e.controllable)

    @property
    def uncontrollable(self) -> tuple[EventPlan, ...]:
        return tuple(e for e in self.events if not e.controllable)

    def event(self, name: str) -> EventPlan:
        return next(e for e in self.events if e.name == name)

    def communication(self, name: str) -> Communication:
        return next(c for c in self.communications if c.name == name)

    def data_plant(self, method: str) -> DataPlant:
        return next(d for d in self.data_plants if d.method == method)


def _automaton_field(a: Automaton) -> str:
    prefix = {AutomatonKind.COMPONENT: "c", AutomatonKind.DATA: "d"}.get(a.kind, "p")
    name = a.name[: -len("_data")] if a.kind is AutomatonKind.DATA else a.name
    return identifier(prefix, name)


def _default_value(v: m.Variable) -> object:
    """A variable's start value when it has no initial value: the plant's rule for finite
    types (false, 0 or the range's low end, the enum's first value), else 0 / 0.0 / "" /
    None (objects and arrays: nothing received yet)."""
    try:
        value = initial_value(v)
    except ValueError:  # no finite domain
        t = v.type
        if isinstance(t, m.BasicType):
            return {m.BasicKind.INTEGER: 0, m.BasicKind.DOUBLE: 0.0, m.BasicKind.STRING: ""}.get(t.kind)
        return None
    return value.name if isinstance(value, m.EnumValue) else value


class _Planner:
    def __init__(self, result: SynthesisResult) -> None:
        self.result = result
        self.network = network = result.network
        self.model = network.model
        locations: dict[m.State, tuple[str, str]] = {}
        self.automaton_field: dict[Automaton, str] = {}
        for automaton in network.automata:
            f = _automaton_field(automaton)
            self.automaton_field[automaton] = f
            for location in automaton.locations:
                locations[location] = (f, location.name)
        variables = {}
        for component in self.model.components:
            for behaviour in component.behaviours:
                for v in behaviour.variables:
                    variables[v] = identifier("v", component.name, v.name)
        self.names = Names(locations, variables)
        self.kept = set(network.variables)
        self.conversions: dict[m.EnumType, Conversion] = {}

    # -- expressions -------------------------------------------------------------------------
    def py(self, expr: m.Expr | None) -> str:
        return "True" if expr is None else python(expr, self.names)

    def data_py(self, data: m.Expr | m.ObjectValue) -> str:
        if isinstance(data, m.ObjectValue):
            items = ", ".join(f"{f.property.name!r}: {self.data_py(f.value)}" for f in data.fields)
            return "{" + items + "}"
        return self.py(data)

    def conversion(self, enum: m.EnumType) -> Conversion:
        if enum not in self.conversions:
            rules = tuple((self.py(r.condition), r.value.name) for r in enum.rules if r.condition is not None)
            default = enum.default or (enum.values[0] if enum.values else None)
            self.conversions[enum] = Conversion(
                identifier("enum", enum.name), enum.name, rules, default.name if default else ""
            )
        return self.conversions[enum]

    # -- state -------------------------------------------------------------------------------
    def fields(self) -> list[Field]:
        out = []
        for automaton in self.network.automata:
            out.append(
                Field(
                    self.automaton_field[automaton],
                    automaton.name,
                    automaton.kind.value,
                    repr(automaton.initial.name),
                )
            )
        for component in self.model.components:
            for behaviour in component.behaviours:
                for v in behaviour.variables:
                    initial = self.py(v.initial) if v.initial is not None else constant(_default_value(v))
                    out.append(
                        Field(
                            self.names.variables[v], f"{component.name}.{v.name}", "variable", initial, v in self.kept
                        )
                    )
        return out

    @staticmethod
    def type_check(v: m.Variable, steps: tuple[m.Step, ...]) -> str:
        """A condition on ``{}`` (the new value) that keeps the variable inside its type."""
        t = v.type
        if steps:
            return ""
        if isinstance(t, m.EnumType):
            return "{} in " + repr(tuple(x.name for x in t.values))
        if isinstance(t, m.BasicType) and t.is_ranged_integer:
            return f"isinstance({{}}, int) and {t.low} <= {{}} <= {t.high}"
        if isinstance(t, m.BasicType) and t.kind is m.BasicKind.BOOLEAN:
            return "isinstance({}, bool)"
        if isinstance(t, m.BasicType) and t.kind is m.BasicKind.INTEGER:
            return "isinstance({}, int) and not isinstance({}, bool)"
        if isinstance(t, m.BasicType) and t.kind is m.BasicKind.DOUBLE:
            return "isinstance({}, (int, float)) and not isinstance({}, bool)"
        if isinstance(t, m.BasicType) and t.kind is m.BasicKind.STRING:
            return "isinstance({}, str)"
        return ""

    def assignments(self, transition: m.ResultTransition) -> tuple[Assign, ...]:
        from robosc.runtime.pyexpr import steps as step_text

        return tuple(
            Assign(
                self.names.variables[a.variable],
                step_text(a.steps),
                self.py(a.value),
                f"{a.variable.owner}.{a.variable.name}",
                self.type_check(a.variable, a.steps),
            )
            for a in transition.assignments
        )

    # -- events --------------------------------------------------------------------------------
    def component_part(self, event: Event, automaton: Automaton) -> Part:
        component = automaton.component
        assert component is not None and component.automaton is not None
        branches = []
        for transition in component.automaton.transitions:
            if event_of(self.network, transition) is not event:
                continue
            assignments: tuple[Assign, ...] = ()
            if isinstance(transition, m.TauTransition):
                guard = self.py(transition.guard)
            else:
                guard, assignments = "True", self.assignments(transition)
            source, target = transition.source, transition.target
            branches.append(
                Branch(source.name if source else None, guard, target.name if target else None, assignments)
            )
        return Part(self.automaton_field[automaton], automaton.name, tuple(branches))

    def plant_part(self, event: Event, automaton: Automaton) -> Part:
        branches = tuple(
            Branch(
                e.source.name if len(automaton.locations) > 1 else None,
                self.py(e.guard),
                e.target.name if e.target is not e.source else None,
            )
            for e in automaton.edges
            if e.event is event
        )
        return Part(self.automaton_field[automaton], automaton.name, branches)

    def gate(self, part: Part) -> str:
        """Where ``part`` can take part in its event (as Python)."""
        options = []
        for b in part.branches:
            here = "True" if b.source is None else f"self.{part.field} == {b.source!r}"
            options.append(conjunction([here, b.guard]))
        if not options:
            return "False"
        if "True" in options:
            return "True"
        return options[0] if len(options) == 1 else " or ".join(f"({o})" for o in options)

    def event(self, event: Event) -> EventPlan:
        parts: list[Part] = []
        gates: list[str] = []
        for automaton in self.network.automata:
            if event not in automaton.alphabet:
                continue
            if automaton.kind is AutomatonKind.COMPONENT:
                part = self.component_part(event, automaton)
                total = not event.controllable or event.kind is K.CANCEL  # responsiveness
                if not total:
                    gates.append(self.gate(part))
            else:
                part = self.plant_part(event, automaton)
                gates.append(self.gate(part))
            parts.append(part)
        plant = conjunction(gates)
        supervisor = "True"
        if event.controllable:
            guard = self.result.guard(event.name)
            supervisor = conjunction([self.py(guard.required), self.py(guard.added)])
        communication = None
        convert = None
        data = None
        signature = None
        if event.communication is not None:
            communication = self.communications[event.communication]
            t = received_type(event)
            if isinstance(t, m.EnumType):
                convert = self.conversion(t).function
            is_sent = event.kind in (K.MESSAGE, K.TRIGGER) and event.controllable
            if is_sent and event.communication in self.data_plants:
                data = self.data_plants[event.communication].method
                provides = [p for p in self.model.provides if p.communication is event.communication]
                if len(provides) == 1:
                    signature = _signature(provides[0].data)
        return EventPlan(
            event.name,
            identifier(event.name.replace(".", "_")),
            event.controllable,
            event.kind.value,
            tuple(p for p in parts if any(b.changes for b in p.branches)),
            conjunction([plant, supervisor]),
            plant,
            supervisor,
            communication,
            convert,
            data,
            signature,
        )

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
            identifier(c.name),
            kind,
            c.ros_name,
            component.name,
            interface.package if interface else None,
            interface.ros_type if interface else None,
            data_kind,
            c.span,
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
            choices.append(DataChoice(edge.target.name, event.name, enabled, self.data_py(data), constant))
        return DataPlant(
            self.automaton_field[automaton],
            comm_name,
            identifier("data", comm_name),
            tuple(choices),
            none_event,
            none_enabled,
        )

    def build(self) -> Plan:
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
        # conversions for enum variables assigned from data happen in the handlers
        for c in self.model.communications:
            for t in m.data_types_of(c):
                if isinstance(t, m.EnumType):
                    self.conversion(t)
        return Plan(
            self.model.name,
            self.model.path,
            tuple(self.fields()),
            events,
            tuple(self.conversions.values()),
            tuple(self.data_plants.values()),
            tuple(self.communications.values()),
            tuple((a.name, self.automaton_field[a]) for a in self.network.automata),
            tuple((f"{v.owner}.{v.name}", self.names.variables[v]) for v in self.network.variables),
        )


def _constant(e: m.Expr) -> object:
    if isinstance(e, m.Literal):
        return e.value
    if isinstance(e, m.Unary) and e.op == "-" and isinstance(e.operand, m.Literal):
        value = e.operand.value
        return -value if isinstance(value, int | float) and not isinstance(value, bool) else None
    return None


def _signature(data: m.Expr | m.ObjectValue) -> str | None:
    """The fields of provided data that are constants, as a Python literal (nested dicts):
    what tells the messages of events sharing a topic apart."""
    if isinstance(data, m.ObjectValue):
        items = []
        for f in data.fields:
            inner = _signature(f.value)
            if inner is not None:
                items.append(f"{f.property.name!r}: {inner}")
        return "{" + ", ".join(items) + "}" if items else None
    value = _constant(data)
    return constant(value) if value is not None else None


def _expressions(data: m.Expr | m.ObjectValue) -> list[m.Expr]:
    if isinstance(data, m.ObjectValue):
        return [e for f in data.fields for e in _expressions(f.value)]
    return list(m.walk(data))


def plan(result: SynthesisResult) -> Plan:
    """Lay out a successful synthesis result for code generation."""
    if not result.ok:
        raise ValueError("no supervisor to run: synthesis failed")
    return _Planner(result).build()
