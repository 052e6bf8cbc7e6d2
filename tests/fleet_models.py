"""A hypothesis strategy for small random fleets (valid by construction), the oracle's models:
robots written once with a count, shared components, and copies written by hand; requirements
whose quantifiers mix a robot's state with shared state and with the robot they are about,
counts written out with several terms per robot, data variables, uncontrollable events,
controllable events with several outcomes, services and actions, per-instance starts.

:func:`fleets` draws ``(text, features)``: the model and the names of the features it uses, so
that a run can say how often it met each (``FEATURES``)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from hypothesis import strategies as st

FEATURES = (
    "several templates",
    "shared component",
    "quantifier mixing robot and shared state",
    "quantifier reading the robot it is about",
    "q = r / q != r",
    "one robot singled out (r = bot1)",
    "written-out count, several terms per robot",
    "asymmetric condition",
    "data variable",
    "uncontrollable event",
    "requirement on an uncontrollable event",
    "controllable event with several outcomes",
    "trap state",
    "guard over the fleet",
    "service",
    "action",
    "per-instance start",
    "copies by hand",
    "copies by hand that differ",
)


@dataclass
class Kind:
    """One robot template (``component bot[3]``) or a pair of copies written by hand."""

    name: str
    count: int
    states: list[str]
    commands: list[str]  # incoming messages: controllable
    reports: list[str]  # outgoing messages: uncontrollable
    variable: bool
    service: bool = False
    action: bool = False
    copies: list[str] = field(default_factory=list)  # the copies' component names (written by hand)

    def instances(self) -> list[str]:
        return self.copies or [f"{self.name}{i}" for i in range(1, self.count + 1)]


@dataclass
class Shared:
    name: str
    states: list[str]
    command: str
    report: str | None
    variable: bool


def _behaviour(
    draw: st.DrawFn, kind: Kind, suffix: str, features: set[str], guard: Callable[[], str], differ: bool = False
) -> list[str]:
    """The behaviour of one robot of ``kind`` (its communication names end in ``suffix``)."""
    lines = ["        behaviour {"]
    if kind.variable:
        lines.append("            variable n: integer(0..1) = 0")
    events = [("request to", c + suffix) for c in kind.commands] + [("response from", r + suffix) for r in kind.reports]
    if kind.service:
        srv = kind.name[0] + "srv" + suffix
        events += [("request to", srv), ("response from", srv), ("error from", srv)]
    if kind.action:
        act = kind.name[0] + "act" + suffix
        events += [("request to", act), ("response from", act), ("feedback from", act)]
    plain = [s for s in kind.states if s != "trap"]
    marked = draw(st.lists(st.sampled_from(plain), min_size=1, max_size=len(plain), unique=True))
    if differ:  # a copy that differs a little: one more marked state, or one less
        extra = [s for s in kind.states if s not in marked]
        marked = marked + extra[:1] if extra else marked[:-1] or marked
    for i, state in enumerate(kind.states):
        flags = ("initial " if i == 0 else "") + ("marked " if state in marked else "")
        lines.append(f"            {flags}state {state} {{")
        for _ in range(draw(st.integers(0, 2))):
            word, name = draw(st.sampled_from(events))
            target = draw(st.sampled_from(kind.states))
            assignment = ""
            if kind.variable and word != "request to" and draw(st.booleans()):
                assignment = draw(st.sampled_from([" do n := 1 - n", " do n := 0", " do n := n + 1"]))
            lines.append(f"                on {word} {name}{assignment} goto {target}")
            if word == "request to" and draw(st.integers(0, 2)) == 0:  # a second outcome
                other = "trap" if "trap" in kind.states and draw(st.booleans()) else draw(st.sampled_from(kind.states))
                if other != target:
                    features.add("controllable event with several outcomes")
                    lines.append(f"                on {word} {name} goto {other}")
        # every state can reach a marked one (rule 3): by a command, a report or a guarded move
        home = marked[0]
        if state == "trap":  # its way out: the last command, which a requirement often forbids here
            lines.append(f"                on request to {kind.commands[-1]}{suffix} goto {home}")
        elif state not in marked or draw(st.booleans()):
            way = draw(st.sampled_from(["command", "command", "report", "move"]))
            if way == "report" and kind.reports:
                lines.append(f"                on response from {kind.reports[0]}{suffix} goto {home}")
            elif way == "move":
                condition = guard()
                lines.append(f"                transition{' if ' + condition if condition else ''} goto {home}")
            else:
                lines.append(f"                on request to {kind.commands[0]}{suffix} goto {home}")
                if "trap" in kind.states and draw(st.booleans()):  # or into the trap
                    features.add("controllable event with several outcomes")
                    lines.append(f"                on request to {kind.commands[0]}{suffix} goto trap")
        lines.append("            }")
    lines.append("        }")
    return lines


@dataclass
class Conditions:
    """Draws conditions over the fleet, about one robot (``me``: its kind and how it is named:
    ``r`` in a ``for`` block, or a copy's component name) or about none."""

    draw: st.DrawFn
    kinds: list[Kind]
    shared: list[Shared]
    features: set[str]

    def shared_atom(self) -> str | None:
        if not self.shared:
            return None
        d = self.draw(st.sampled_from(self.shared))
        if d.variable and self.draw(st.booleans()):
            return f"{d.name}.k"
        return f"{d.name}.{self.draw(st.sampled_from(d.states))}"

    def robot_atom(self, kind: Kind, who: str) -> str:
        if kind.variable and self.draw(st.integers(0, 3)) == 0:
            return f"{who}.n {self.draw(st.sampled_from(['=', '<', '>=']))} {self.draw(st.integers(0, 1))}"
        return f"{who}.{self.draw(st.sampled_from(kind.states))}"

    def body(self, kind: Kind, q: str, me: tuple[Kind, str] | None) -> str:
        """A quantifier's body over ``q`` of ``kind``: its state, maybe with shared state and
        the state of ``me``."""
        parts = [self.robot_atom(kind, q)]
        if self.draw(st.booleans()) and (atom := self.shared_atom()) is not None:
            parts.append(atom)
            self.features.add("quantifier mixing robot and shared state")
        if me is not None and self.draw(st.integers(0, 3)) == 0:
            parts.append(self.robot_atom(*me))
            self.features.add("quantifier reading the robot it is about")
        if len(parts) > 1 and self.draw(st.integers(0, 3)) == 0:
            parts[-1] = f"!({parts[-1]})"
        text = f" {self.draw(st.sampled_from(['and', 'or']))} ".join(parts)
        return f"({text})" if len(parts) > 1 else text

    def quantified(self, me: tuple[Kind, str] | None) -> str:
        templates = [k for k in self.kinds if not k.copies]
        if not templates:
            return self.written_count(me)
        kind = self.draw(st.sampled_from(templates))
        body = self.body(kind, "q", me)
        mine = me is not None and me[0] is kind and me[1] == "r"
        if mine and self.draw(st.booleans()):
            self.features.add("q = r / q != r")
            body = f"q != r and {body}" if self.draw(st.booleans()) else f"q = r or {body}"
        how = self.draw(st.sampled_from(["any", "all", "count"]))
        if how == "count":
            bound = self.draw(st.integers(0, kind.count))
            return f"count(q in {kind.name}: {body}) {self.draw(st.sampled_from(['<=', '>=', '<']))} {bound}"
        return f"{how}(q in {kind.name}: {body})"

    def written_count(self, me: tuple[Kind, str] | None) -> str:
        """``count(...)`` written out: the same terms for each robot of a kind (maybe not quite)."""
        kind = self.draw(st.sampled_from(self.kinds))
        shapes = [self.body(kind, "@", None)]
        for _ in range(self.draw(st.integers(0, 2))):  # more terms per robot, often holding with the first
            if self.draw(st.booleans()):
                shapes.append(f"{shapes[0]} or {self.robot_atom(kind, '@')}")
            else:
                shapes.append(self.body(kind, "@", None))
        if len(shapes) > 1:
            self.features.add("written-out count, several terms per robot")
        terms = []
        robots = kind.instances()
        odd = robots[-1] if self.draw(st.integers(0, 5)) == 0 else None
        for robot in robots:
            mine = [s.replace("@", robot) for s in shapes]
            if robot == odd:
                self.features.add("asymmetric condition")
                mine = mine[:1] if len(mine) > 1 else [*mine, mine[0]]
            terms += mine
        bound = self.draw(st.integers(1, max(1, len(terms) // 2 + 1)))
        return f"count({', '.join(terms)}) {self.draw(st.sampled_from(['<=', '<=', '>=']))} {bound}"

    def condition(self, me: tuple[Kind, str] | None, depth: int = 0) -> str:
        if me is not None and me[1] == "r" and depth == 0 and self.draw(st.integers(0, 4)) == 0:
            self.features.add("one robot singled out (r = bot1)")
            one = self.draw(st.sampled_from(me[0].instances()))
            rest = self.condition(me, depth + 1)
            return f"(r != {one} and {rest})" if self.draw(st.booleans()) else f"(r = {one} or {rest})"
        choice = self.draw(st.integers(0, 9))
        if choice <= 2 and me is not None:
            return self.robot_atom(*me)
        if choice <= 3 and (atom := self.shared_atom()) is not None:
            return atom
        if choice <= 5:
            return self.quantified(me)
        if choice <= 7:
            return self.written_count(me)
        if depth < 1:
            left, right = self.condition(me, depth + 1), self.condition(me, depth + 1)
            op = self.draw(st.sampled_from(["and", "or"]))
            negated = "!" if self.draw(st.booleans()) else ""
            return f"{negated}({left} {op} {right})"
        return self.quantified(me)


@st.composite
def fleets(draw: st.DrawFn, faudes: bool = False) -> tuple[str, frozenset[str]]:
    """A random fleet and the features it uses. ``faudes``: no variables, guards, services or
    actions (what the libFAUDES oracle takes)."""
    features: set[str] = set()
    kinds: list[Kind] = []
    budget = 6  # robots in all: the explicit reference enumerates every state
    for index in range(draw(st.integers(1, 3))):
        if budget < 2:
            break
        count = draw(st.integers(2, min(4, budget)))
        budget -= count
        states = [f"s{i}" for i in range(draw(st.integers(2, 3)))]
        name = ["bot", "arm", "cart"][index]
        kind = Kind(
            name,
            count,
            states,
            commands=[f"{name[0]}go{i}" for i in range(draw(st.integers(1, 2)))],
            reports=[f"{name[0]}ev{i}" for i in range(draw(st.integers(0, 1)))],
            variable=not faudes and draw(st.integers(0, 2)) == 0,
        )
        if draw(st.integers(0, 2)) == 0:  # a state whose way out is often forbidden: a trap for a second outcome
            kind.states.append("trap")
            features.add("trap state")
        if not faudes and count <= 2:
            kind.service = draw(st.integers(0, 3)) == 0
            kind.action = not kind.service and draw(st.integers(0, 5)) == 0
        if index > 0 and count == 2 and draw(st.integers(0, 2)) == 0:
            kind.copies = [f"{name.capitalize()}A", f"{name.capitalize()}B"]
        kinds.append(kind)
    shared = []
    for index in range(draw(st.integers(0, 2))):
        name = ["Door", "Lift"][index]
        shared.append(
            Shared(
                name,
                [f"{name[0].lower()}{i}" for i in range(2)],
                f"{name.lower()}_go",
                f"{name.lower()}_ev" if draw(st.booleans()) else None,
                variable=not faudes and draw(st.integers(0, 3)) == 0,
            )
        )
    conditions = Conditions(draw, kinds, shared, features)
    if len(kinds) > 1:
        features.add("several templates")
    if shared:
        features.add("shared component")

    def fleet_guard() -> str:
        if faudes or draw(st.integers(0, 2)):
            return ""
        features.add("guard over the fleet")
        return conditions.condition(None)

    lines = ["robot Oracle {", "  interface trigger use Trigger from std_srvs", "  interface fib use Fibonacci from test_msgs"]
    for kind in kinds:
        for copy_index, robot in enumerate(kind.copies or [None]):  # type: ignore[list-item]
            suffix = f"_{copy_index}" if robot is not None else ""
            head = robot if robot is not None else f"{kind.name}[{kind.count}]"
            if robot is None and draw(st.integers(0, 3)) == 0:
                starts = [draw(st.sampled_from(kind.states)) for _ in range(kind.count)]
                head += " initial " + ", ".join(starts)
                features.add("per-instance start")
            lines.append(f"    component {head} {{")
            lines += [f"        incoming message {c}{suffix} with type: none" for c in kind.commands]
            lines += [f"        outgoing message {r}{suffix} with type: none" for r in kind.reports]
            if kind.service:
                lines.append(f"        service {kind.name[0]}srv{suffix} with request: none, response: none links trigger")
                features.add("service")
            if kind.action:
                lines.append(f"        action {kind.name[0]}act{suffix} with request: none, response: none, feedback: none links fib")
                features.add("action")
            differ = robot is not None and copy_index == 1 and draw(st.integers(0, 2)) == 0
            if differ:
                features.add("copies by hand that differ")
            if robot is not None:
                features.add("copies by hand")
            lines += _behaviour(draw, kind, suffix, features, fleet_guard, differ)
            lines.append("    }")
        if kind.variable:
            features.add("data variable")
        if kind.reports or kind.service or kind.action:
            features.add("uncontrollable event")
    for d in shared:
        lines.append(f"    component {d.name} {{")
        lines.append(f"        incoming message {d.command} with type: none")
        if d.report:
            lines.append(f"        outgoing message {d.report} with type: none")
        lines.append("        behaviour {")
        if d.variable:
            lines.append("            variable k: boolean = false")
        first, second = d.states
        lines.append(f"            initial marked state {first} {{ on request to {d.command} goto {second} }}")
        back = f"on response from {d.report}{' do k := !k' if d.variable else ''} goto {first}" if d.report else None
        guard = fleet_guard()
        move = f"transition{' if ' + guard if guard else ''} goto {first}"
        lines.append(f"            {'marked ' if draw(st.booleans()) else ''}state {second} {{ {back or move} }}")
        lines.append("        }")
        lines.append("    }")
    # requirements: for every robot of a template, for each copy written out, and on shared events
    for kind in kinds:
        if "trap" in kind.states:
            command = kind.commands[-1]
            for copy_index, robot in enumerate(kind.copies):
                lines.append(_requirement(f"{command}_{copy_index}", f"!{robot}.trap", True))
            if not kind.copies:
                lines.append(f"    for r in {kind.name} {{")
                unless = f" or {conditions.condition((kind, 'r'))}" if draw(st.booleans()) else ""
                lines.append("    " + _requirement(f"r.{command}", f"!r.trap{unless}", True))
                lines.append("    }")
        for _ in range(draw(st.integers(0, 2))):
            command = draw(st.sampled_from(kind.commands + kind.reports + ([kind.name[0] + "srv"] if kind.service else [])))
            if command in kind.reports:
                features.add("requirement on an uncontrollable event")
            verb = draw(st.booleans())
            if kind.copies:  # the same requirement, written for each copy
                condition = conditions.condition((kind, "@"))
                first, second = kind.copies
                swapped = condition.replace(f"{first}.", "#.").replace(f"{second}.", f"{first}.").replace("#.", f"{second}.")
                for copy_index, (robot, text) in enumerate(zip(kind.copies, (condition, swapped), strict=True)):
                    lines.append(_requirement(f"{command}_{copy_index}", text.replace("@", robot), verb))
                continue
            condition = conditions.condition((kind, "r"))
            lines.append("    for r in " + kind.name + " {")
            lines.append("    " + _requirement(f"r.{command}", condition, verb))
            lines.append("    }")
    for d in shared:
        if draw(st.booleans()):
            lines.append(_requirement(d.command, conditions.condition(None), draw(st.booleans())))
    lines.append("}")
    return "\n".join(lines) + "\n", frozenset(features)


def _requirement(event: str, condition: str, needs: bool) -> str:
    if needs:
        return f"    requirement {event} needs {condition}"
    return f"    requirement {condition} disables {event}"
