"""Plant construction (SEMANTICS.md sections 1-4): a checked model to an automata network.

* one plant per communication (message, service, action);
* one automaton per component behaviour, with a self-loop added for every
  uncontrollable event (and every cancel) of its alphabet in each state that
  does not handle it (responsiveness);
* one controllable event per tau transition;
* a data plant per communication with provide statements;
* requirements as state-event exclusions on trigger events, plus the cancel
  requirement of actions.

An action has a cancel event only when some component says when to cancel it
(``on cancel to A``); otherwise the model never cancels it, as in the original
tool's CIF, whose action plant has no cancel edge: no event that no automaton
could take part in meaningfully, and no condition the user did not write.

Variables that no guard, requirement or provide condition mentions are left
out; an update that depends on received data (or on a variable left out) may
give the variable any value of its domain.
"""

from __future__ import annotations

from functools import partial

from robosc.language import model as m
from robosc.language.render import render
from robosc.plant.domains import domain, initial_value
from robosc.plant.expressions import NO_SPAN, all_of, any_of, negate, reads_data, variables_in
from robosc.plant.network import Automaton, AutomatonKind, Edge, Event, EventKind, Later, Network, Requirement, Update
from robosc.record import field, record

R = m.ResultKind
K = EventKind


def _location(name: str, owner: str, initial: bool = False, marked: bool = False) -> m.State:
    return m.State(name, owner, initial, marked, NO_SPAN)


@record(frozen=False)
class _Builder:
    model: m.Model
    events: list[Event] = field(default_factory=list)
    automata: list[Automaton] = field(default_factory=list)
    requirements: list[Requirement] = field(default_factory=list)
    # (communication, result kind) -> event
    result_events: dict[tuple[m.Communication, m.ResultKind], Event] = field(default_factory=dict)
    trigger: dict[m.Communication, Event] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.variables = tuple(v for v in m.synthesis_variables(self.model))
        self.kept = set(self.variables)
        self.cancelled = {  # the actions some component says when to cancel (on cancel to A)
            t.communication for _, t in m.result_transitions(self.model) if t.result is R.CANCEL
        }

    def event(self, name: str, controllable: bool, kind: EventKind, **origin: object) -> Event:
        event = Event(name, controllable, kind, **origin)  # type: ignore[arg-type]
        self.events.append(event)
        return event

    # -- communication plants ----------------------------------------------------------
    def communication_plant(self, c: m.Communication) -> None:
        if isinstance(c, m.Message):
            event = self.event(c.name, c.direction is m.Direction.INCOMING, K.MESSAGE, communication=c)
            only = _location("idle", c.name, initial=True, marked=True)
            result = R.REQUEST if event.controllable else R.RESPONSE
            self.result_events[(c, result)] = event
            self.trigger[c] = event
            self.automata.append(
                Automaton(c.name, AutomatonKind.MESSAGE, (only,), only, (Edge(only, only, event),), frozenset({event}))
            )
            return
        is_action = isinstance(c, m.Action)
        idle = _location("idle", c.name, initial=True, marked=True)
        busy = _location("executing" if is_action else "wait", c.name)
        ready = _location("ready", c.name)
        failed = _location("error", c.name)
        trigger = self.event(f"{c.name}.c_trigger", True, K.TRIGGER, communication=c)
        response = self.event(f"{c.name}.u_response", False, K.RESPONSE, communication=c)
        error = self.event(f"{c.name}.u_error", False, K.ERROR, communication=c)
        reset = self.event(f"{c.name}.c_reset", True, K.RESET, communication=c)
        edges = [
            Edge(idle, busy, trigger),
            Edge(busy, ready, response),
            Edge(busy, failed, error),
            Edge(ready, idle, reset),
            Edge(failed, idle, reset),
        ]
        self.trigger[c] = trigger
        self.result_events.update({(c, R.REQUEST): trigger, (c, R.RESPONSE): response, (c, R.ERROR): error})
        if is_action:
            feedback = self.event(f"{c.name}.u_feedback", False, K.FEEDBACK, communication=c)
            edges.append(Edge(busy, busy, feedback))
            self.result_events[(c, R.FEEDBACK)] = feedback
            if c in self.cancelled:  # an action no component cancels is never cancelled
                cancel = self.event(f"{c.name}.c_cancel", True, K.CANCEL, communication=c)
                edges.append(Edge(busy, idle, cancel))
                self.result_events[(c, R.CANCEL)] = cancel
        kind = AutomatonKind.ACTION if is_action else AutomatonKind.SERVICE
        alphabet = frozenset(e.event for e in edges)
        self.automata.append(Automaton(c.name, kind, (idle, busy, ready, failed), idle, tuple(edges), alphabet))

    # -- component automata ---------------------------------------------------------------
    def updates(self, transition: m.ResultTransition) -> tuple[Update, ...]:
        updates = []
        for assignment in transition.assignments:
            if assignment.variable not in self.kept:
                continue
            value: m.Expr | None = assignment.value
            assert value is not None
            if assignment.steps or reads_data(value) or not variables_in(value) <= self.kept:
                value = None  # depends on data the controller receives: any value of the domain
            updates.append(Update(assignment.variable, value))
        return tuple(updates)

    def component_automaton(self, component: m.Component, automaton: m.Automaton) -> None:
        edges: list[Edge] = []
        taus = 0
        for transition in automaton.transitions:
            sources = automaton.states if transition.source is None else (transition.source,)
            if isinstance(transition, m.TauTransition):
                taus += 1
                source_name = transition.source.name if transition.source else "any"
                target_name = transition.target.name if transition.target else source_name
                name = f"{component.name}.tau{taus}_{source_name}_to_{target_name}"
                event = self.event(name, True, K.TAU, transition=transition)
                for source in sources:
                    edges.append(Edge(source, transition.target or source, event, transition.guard))
                continue
            event = self.result_events[(transition.communication, transition.result)]
            updates = self.updates(transition)
            for source in sources:
                edges.append(Edge(source, transition.target or source, event, None, updates))
        alphabet = frozenset(e.event for e in edges)
        for event in sorted(alphabet, key=self.events.index):
            if event.controllable and event.kind is not K.CANCEL:
                continue
            for state in automaton.states:
                if not any(e.source is state and e.event is event for e in edges):
                    edges.append(Edge(state, state, event))  # responsiveness
        initial = automaton.initial_states[0]
        self.automata.append(
            Automaton(
                component.name,
                AutomatonKind.COMPONENT,
                automaton.states,
                initial,
                tuple(edges),
                alphabet,
                component,
            )
        )

    # -- data plants --------------------------------------------------------------------------
    def data_plant(self, c: m.Communication, provides: list[m.Provide]) -> None:
        owner = f"{c.name}_data"
        none = _location("none", owner, initial=True, marked=True)
        chosen = [_location(f"provide{i}", owner, marked=True) for i in range(1, len(provides) + 1)]
        locations = (none, *chosen)
        edges: list[Edge] = []
        for i, (provide, target) in enumerate(zip(provides, chosen, strict=True), 1):
            event = self.event(f"{owner}.provide{i}", True, K.PROVIDE, communication=c, provide=provide)
            edges += [Edge(source, target, event, provide.condition) for source in locations]
        if all(p.condition is not None for p in provides):
            no_data = negate(any_of([p.condition for p in provides if p.condition is not None]))
            event = self.event(f"{owner}.provide_none", True, K.PROVIDE, communication=c)
            edges += [Edge(source, none, event, no_data) for source in locations]
        alphabet = frozenset(e.event for e in edges)
        self.automata.append(Automaton(owner, AutomatonKind.DATA, locations, none, tuple(edges), alphabet))

    # -- requirements ----------------------------------------------------------------------------
    def requirement(self, requirement: m.Requirement) -> None:
        condition = requirement.condition
        allowed = condition if requirement.kind is m.RequirementKind.NEEDS else negate(condition)
        for c in requirement.communications:
            event = self.trigger[c]
            text = Later(partial(_told, requirement.kind, c.name, condition))
            self.requirements.append(Requirement(event, allowed, text, requirement))

    def cancel_requirements(self) -> None:
        for c in self.model.communications:
            if not isinstance(c, m.Action):
                continue
            conditions = [r.condition for r in self.requirements if r.event is self.trigger[c]]
            if conditions and c in self.cancelled:
                cancel = self.result_events[(c, R.CANCEL)]
                allowed = negate(all_of(conditions))
                text = f"{c.name} is cancelled only when one of its requirements no longer holds"
                self.requirements.append(Requirement(cancel, allowed, text))

    def build(self) -> Network:
        for communication in self.model.communications:
            self.communication_plant(communication)
        for component in self.model.components:
            if component.automaton is not None:
                self.component_automaton(component, component.automaton)
        provides: dict[m.Communication, list[m.Provide]] = {}
        for provide in self.model.provides:
            provides.setdefault(provide.communication, []).append(provide)
        for communication, statements in provides.items():
            self.data_plant(communication, statements)
        for requirement in self.model.requirements:
            self.requirement(requirement)
        self.cancel_requirements()
        return Network(
            self.model,
            tuple(self.events),
            tuple(self.automata),
            self.variables,
            {v: domain(v) for v in self.variables},
            {v: initial_value(v) for v in self.variables},
            tuple(self.requirements),
        )


def _told(kind: m.RequirementKind, name: str, condition: m.Expr) -> str:
    """A requirement on communication ``name`` as the model writes it."""
    if kind is m.RequirementKind.NEEDS:
        return f"requirement {name} needs {render(condition)}"
    return f"requirement {render(condition)} disables {name}"


def build_network(model: m.Model) -> Network:
    """The automata network of a checked robot model."""
    if model.kind != "robot":
        raise ValueError(f"'{model.name}' is a library; synthesis needs a robot")
    return _Builder(model).build()
