"""The automata network as CIF 3 text (Eclipse ESCET), for users who want to cross-check
robosc's supervisor with ESCET's data-based synthesis.

Plants keep their network names: a message plant has one event (``c_trigger``
when the controller sends it, ``u_response`` when it receives it); service and
action plants have ``c_trigger``, ``u_response``, ``u_error``, ``c_reset`` (and
``u_feedback``, ``c_cancel``). Data the controller receives is an input variable.
"""

from __future__ import annotations

from robosc.codegen.templating import environment
from robosc.language import model as m
from robosc.language.render import literal
from robosc.plant.network import Automaton, AutomatonKind, Edge, Event, EventKind, Network
from robosc.record import record

# Reserved words of CIF 3; a name that is one gets CIF's '$' escape.
CIF_KEYWORDS = frozenset(
    [
        "abs",
        "acosh",
        "acos",
        "alg",
        "alphabet",
        "and",
        "asinh",
        "asin",
        "atanh",
        "atan",
        "automaton",
        "bool",
        "break",
        "cbrt",
        "ceil",
        "const",
        "cont",
        "continue",
        "controllable",
        "cosh",
        "cos",
        "cur",
        "default",
        "del",
        "der",
        "dict",
        "disables",
        "disc",
        "div",
        "do",
        "elif",
        "else",
        "empty",
        "end",
        "enum",
        "event",
        "exp",
        "floor",
        "for",
        "fmt",
        "from",
        "func",
        "goto",
        "group",
        "if",
        "import",
        "in",
        "initial",
        "input",
        "int",
        "invariant",
        "kind",
        "list",
        "ln",
        "location",
        "log",
        "marked",
        "max",
        "min",
        "mod",
        "monitor",
        "needs",
        "none",
        "not",
        "now",
        "or",
        "plant",
        "pow",
        "real",
        "requirement",
        "return",
        "round",
        "scale",
        "self",
        "set",
        "sign",
        "sinh",
        "sin",
        "size",
        "sqrt",
        "string",
        "sub",
        "supervisor",
        "svgcopy",
        "svgfile",
        "svgin",
        "svgmove",
        "svgout",
        "switch",
        "tanh",
        "tan",
        "tau",
        "to_real",
        "tuple",
        "type",
        "uncontrollable",
        "urgent",
        "value",
        "void",
        "when",
        "while",
        "edge",
        "true",
        "false",
    ]
)


def name(text: str) -> str:
    """A model name in CIF: keywords escaped; an instance's communication ``bot1.go`` (a CIF
    name has no dot) as ``bot1__go`` (RoboSC names the model's own ``__`` nowhere a ROS name
    can come from: a clash is refused when the network is written)."""
    text = text.replace(".", "__")
    return f"${text}" if text in CIF_KEYWORDS else text


def _local_event(event: Event) -> str:
    """The name an event has inside its plant automaton."""
    if event.kind is EventKind.MESSAGE:
        return "c_trigger" if event.controllable else "u_response"
    return event.name.rsplit(".", 1)[1]


@record(frozen=False)
class _Names:
    network: Network

    def __post_init__(self) -> None:
        self.owner: dict[Event, str] = {}
        for automaton in self.network.automata:
            for event in automaton.alphabet:
                if automaton.kind is not AutomatonKind.COMPONENT or event.kind is EventKind.TAU:
                    self.owner.setdefault(event, automaton.name)

    def event(self, event: Event) -> str:
        return f"{name(self.owner[event])}.{name(_local_event(event))}"

    def input(self, variable: m.Variable) -> str:
        return f"{variable.owner}_{variable.name}_received"


_OPS = {
    "and": "and",
    "or": "or",
    "=>": "=>",
    "=": "=",
    "!=": "!=",
    "<": "<",
    "<=": "<=",
    ">": ">",
    ">=": ">=",
    "+": "+",
    "-": "-",
    "*": "*",
    "/": "/",
}


def expression(e: m.Expr) -> str:
    """A model expression in CIF syntax (fully parenthesised: CIF's precedence differs)."""
    if isinstance(e, m.Binary):
        return f"({expression(e.left)} {_OPS[e.op]} {expression(e.right)})"
    if isinstance(e, m.Count):  # how many hold: CIF adds up if-expressions
        if not e.terms:
            return "0"
        return "(" + " + ".join(f"(if {expression(t)}: 1 else 0 end)" for t in e.terms) + ")"
    if isinstance(e, m.Unary):
        return f"(not {expression(e.operand)})" if e.op == "!" else f"(-{expression(e.operand)})"
    if isinstance(e, m.Literal):
        if isinstance(e.value, bool):
            return "true" if e.value else "false"
        if isinstance(e.value, str):
            return literal(e.value)  # CIF escapes strings as RoboSC does
        return repr(e.value)
    if isinstance(e, m.EnumLiteral):
        return name(e.value.name)
    if isinstance(e, m.StateRef):
        return f"{name(e.state.owner)}.{name(e.state.name)}"
    if isinstance(e, m.VariableRef):
        return f"{name(e.variable.owner)}.{name(e.variable.name)}"
    raise ValueError(f"{type(e).__name__} cannot appear in a CIF guard")


def data_type(variable: m.Variable) -> str:
    t = variable.type
    if isinstance(t, m.EnumType):
        return name(t.name)
    if isinstance(t, m.BasicType) and t.kind is m.BasicKind.BOOLEAN:
        return "bool"
    assert isinstance(t, m.BasicType) and t.low is not None
    return f"int[{t.low}..{t.high}]"


def value(v: object) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, m.EnumValue):
        return name(v.name)
    return str(v)


def _edge(edge: Edge, names: _Names, automaton: Automaton) -> str:
    local = names.owner.get(edge.event) == automaton.name
    text = f"edge {name(_local_event(edge.event)) if local else names.event(edge.event)}"
    if edge.guard is not None:
        text += f" when {expression(edge.guard)}"
    if edge.updates:
        parts = []
        for update in edge.updates:
            target = name(update.variable.name)
            source = names.input(update.variable) if update.value is None else expression(update.value)
            parts.append(f"{target} := {source}")
        text += " do " + ", ".join(parts)
    if edge.target is not edge.source:
        text += f" goto {name(edge.target.name)}"
    return text + ";"


class NameClash(ValueError):
    """Two names of the model are one name in CIF (``bot1.go`` and ``bot1__go``)."""


def to_cif(network: Network, source: str = "") -> str:
    """The network as the text of a CIF 3 specification (raises :class:`NameClash` when two
    of the model's names would be one in CIF)."""
    seen: dict[str, str] = {}
    for automaton in network.automata:
        other = seen.setdefault(name(automaton.name), automaton.name)
        if other != automaton.name:
            raise NameClash(f"'{other}' and '{automaton.name}' would both be '{name(other)}' in CIF: rename one")
    names = _Names(network)
    enums = [
        (name(t.name), ", ".join(name(v.name) for v in t.values))
        for t in network.model.enums
        if any(v.type is t for v in network.variables)
    ]
    inputs = sorted(
        {
            (data_type(u.variable), names.input(u.variable))
            for a in network.automata
            for e in a.edges
            for u in e.updates
            if u.value is None
        }
    )
    automata = []
    for automaton in network.automata:
        own = [e for e in network.events if names.owner.get(e) == automaton.name]
        automata.append(
            {
                "name": name(automaton.name),
                "kind": automaton.kind.value,
                "controllable": [name(_local_event(e)) for e in own if e.controllable],
                "uncontrollable": [name(_local_event(e)) for e in own if not e.controllable],
                "variables": [
                    (data_type(v), name(v.name), value(network.initial_values[v]))
                    for v in network.variables
                    if automaton.component is not None and v.owner == automaton.component.name
                ],
                "locations": [
                    {
                        "name": name(location.name),
                        "initial": location is automaton.initial,
                        "marked": location.marked,
                        "edges": [_edge(e, names, automaton) for e in automaton.edges if e.source is location],
                    }
                    for location in automaton.locations
                ],
            }
        )
    requirements = [
        {"event": names.event(r.event), "condition": expression(r.condition), "description": r.description}
        for r in network.requirements
    ]
    return (
        environment()
        .get_template("cif.cif.j2")
        .render(
            model=network.model.name,
            source=source,
            enums=enums,
            inputs=inputs,
            automata=automata,
            requirements=requirements,
        )
    )
