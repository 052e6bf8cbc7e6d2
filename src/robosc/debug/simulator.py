"""Run the generated supervisor without ROS and check every step against the synthesis result.

The simulator executes the very module that ``robosc generate`` writes (rendered
in memory), so what it shows is what the node does. After every event it checks,
independently of the generated code, that:

* the requirements on the event held in the state it happened in (evaluated on
  the model's expressions, not on the compiled guards);
* a controllable event was allowed by the synthesized supervisor (the BDDs);
* the state reached is inside the controlled behaviour, and a marked state can
  still be reached from it under the supervisor that runs (searched for over the
  plant with the generated guards, not read from synthesis' fixed point).

A failed check raises :class:`Violation` with the step, the event and the state.
"""

from __future__ import annotations

import json
import random
import time
import types
from collections.abc import Callable
from typing import Any, TextIO

from robosc.codegen.module import module_name, render_module
from robosc.codegen.plan import Plan
from robosc.language import model as m
from robosc.language.diagnostics import closest
from robosc.language.render import render
from robosc.plant.network import Network, received_type
from robosc.record import record
from robosc.runtime.onboard.values import Data, plain
from robosc.synthesis.evaluate import Undefined, evaluate
from robosc.synthesis.explicit import Edges, marked, successors
from robosc.synthesis.result import SynthesisResult
from robosc.synthesis.state import NetworkState, describe

SEARCH_LIMIT = 100_000  # states a look-ahead visits before it gives up (then synthesis' own judgement stands)


class Lookahead:
    """Whether a marked state can still be reached from a state, under the supervisor the
    generated module runs: a controllable event where the plant allows it and its guard (your
    condition and the one synthesis added) holds, an uncontrollable one wherever the plant
    allows it. Found by search over the plant, independently of synthesis' fixed point; what a
    search finds is kept (states on a way to a marked state, states with none)."""

    def __init__(self, result: SynthesisResult) -> None:
        self.network = result.network
        self.edges = Edges(self.network)
        self.guards = {g.event: [c for c in (g.required, g.added) if c is not None] for g in result.guards}
        self.good: set[NetworkState] = set()
        self.stuck: set[NetworkState] = set()

    def _allowed(self, event: Any, state: NetworkState) -> bool:
        conditions = self.guards.get(event, ())
        if not conditions:
            return True
        values = dict(zip(self.network.variables, state.values, strict=True))
        try:
            return all(bool(evaluate(c, set(state.locations), values)) for c in conditions)
        except Undefined:
            return False

    def reaches_marked(self, start: NetworkState) -> bool | None:
        """True or False; None when the search met :data:`SEARCH_LIMIT` states first."""
        if start in self.good or marked(self.network, start):
            return True
        if start in self.stuck:
            return False
        parent: dict[NetworkState, NetworkState | None] = {start: None}
        queue = [start]
        for state in queue:  # grows while it is walked: breadth first
            for event in self.network.events:
                if event.controllable and not self._allowed(event, state):
                    continue
                for target in successors(self.edges, state, event):
                    if target in parent or target in self.stuck:
                        continue
                    parent[target] = state
                    if target in self.good or marked(self.network, target):
                        step: NetworkState | None = target
                        while step is not None:
                            self.good.add(step)
                            step = parent[step]
                        return True
                    if len(parent) > SEARCH_LIMIT:
                        return None
                    queue.append(target)
        self.stuck.update(parent)
        return False


class Violation(Exception):
    """A step broke a requirement, or left the controlled behaviour."""

    def __init__(self, step: int, event: str, reason: str, state: str) -> None:
        super().__init__(f"step {step}: {event}: {reason}\n  in state: {state}")
        self.step, self.event, self.reason, self.state = step, event, reason, state


class CommandError(Exception):
    """A script line or typed command that the simulator cannot read."""


@record
class Outcome:
    """What one command did: the events performed, and messages for the user."""

    events: tuple[str, ...]
    messages: tuple[str, ...] = ()
    steps: tuple[int, ...] = ()  # the step of each event (same length as events)


def load_module(plan: Plan) -> types.ModuleType:
    """The generated supervisor module of ``plan``, imported from its rendered text; it
    runs on this process's copy of the runtime (:mod:`robosc.runtime.onboard`)."""
    module = types.ModuleType(module_name(plan))
    module.__package__ = "robosc.runtime"  # so that its ``from .onboard import ...`` finds the runtime
    code = compile(render_module(plan), f"<generated {module_name(plan)}.py>", "exec")
    exec(code, module.__dict__)
    return module


class Simulator:
    def __init__(
        self,
        result: SynthesisResult,
        plan: Plan,
        seed: int | None = None,
        log: TextIO | None = None,
        on_event: Callable[[dict[str, Any]], None] | None = None,
    ) -> None:
        self.result = result
        self.network: Network = result.network
        self.plan = plan
        self.module = load_module(plan)
        self.warnings: list[str] = []
        # the simulator explores the model: the node's wait for its first data is waived, events
        # come as the user or the random run delivers them
        self.supervisor: Any = self.module.Robot(
            seed=seed, warn=self.warnings.append, observer=self._observe, wait_for_data=False
        )
        self.step = 0
        self.log = log
        self.on_event = on_event
        self.start = time.monotonic()
        self.events: list[str] = []
        self._locations: list[tuple[str | None, dict[str, m.State], m.State]] = []
        for automaton, (_, field) in zip(self.network.automata, plan.automata, strict=True):  # network order
            by_name = {loc.name: loc for loc in automaton.locations}
            self._locations.append((field, by_name, automaton.initial))  # no field: one location
        variable_fields = dict(plan.variables)
        self._variables = []
        for v in self.network.variables:
            values = {getattr(x, "name", x): x for x in self.network.domains[v]}
            self._variables.append((variable_fields[f"{v.owner}.{v.name}"], values))
        self._before = self.network_state()
        self._violation: Violation | None = None
        self.lookahead = Lookahead(result)
        self.unjudged = 0  # states where the look-ahead gave up (synthesis' own judgement stood)
        # an event with several outcomes (the model's transitions from one place on one event to
        # different places): the simulator stands for the robot and says which one it had: the
        # one a script names (``status -> broken``), a random one in a random run, else the first
        self.pick: str | None = None
        self.rng: random.Random | None = None
        self.told: list[str] = []  # what it said since the last command
        self.naming = "EVENT"  # the event the user named (for the hint how to pick)
        self.supervisor.outcome = self._outcome

    # ---- state ---------------------------------------------------------------------------
    def network_state(self) -> NetworkState:
        sup = self.supervisor
        locations = tuple(only if f is None else by_name[getattr(sup, f)] for f, by_name, only in self._locations)
        values = tuple(values[getattr(sup, f)] for f, values in self._variables)
        return NetworkState(locations, values)

    def describe(self) -> str:
        return describe(self.network, self.network_state())

    def snapshot(self) -> dict[str, Any]:
        return dict(self.supervisor.snapshot())

    # ---- checks (called for every event, through the module's observer hook) ----------
    def _observe(self, name: str, controllable: bool, data: object) -> None:
        # the generated module shields itself from its observer's exceptions: keep the
        # first violation and raise it when the command returns (see _checked)
        try:
            self._check(name, controllable, data)
        except Violation as violation:
            if self._violation is None:
                self._violation = violation

    def _since(self, before: int) -> Outcome:
        """The events performed since ``before`` (an index into :attr:`events`), all of this
        step, checked."""
        events = tuple(self.events[before:])
        return self._checked(Outcome(events, steps=(self.step,) * len(events)))

    def _checked(self, outcome: Outcome) -> Outcome:
        violation, self._violation = self._violation, None
        if violation is not None:
            raise violation
        return outcome

    def _check(self, name: str, controllable: bool, data: object) -> None:
        before, after = self._before, self.network_state()
        self._before = after
        self.events.append(name)
        event = self.network.event(name)
        locations = set(before.locations)
        values = dict(zip(self.network.variables, before.values, strict=True))
        for requirement in self.network.requirements_on(event):
            try:
                holds = evaluate(requirement.condition, locations, values)
            except Undefined:
                holds = False
            if not holds:
                raise Violation(self.step, name, f"breaks '{requirement.description}'", describe(self.network, before))
        if controllable and not self.result.allows(event, before):
            raise Violation(
                self.step, name, "the synthesized supervisor does not allow it here", describe(self.network, before)
            )
        if not self.result.controlled(after):
            raise Violation(
                self.step,
                name,
                "leads outside the controlled behaviour (no marked state reachable)",
                describe(self.network, after),
            )
        self.judge(name, after)
        if self.log is not None or self.on_event is not None:
            record = {
                "time": round(time.monotonic() - self.start, 6),
                "step": self.step,
                "event": name,
                "controllable": controllable,
                "data": plain(data),
                "state": self.supervisor.snapshot(),
            }
            if self.log is not None:
                self.log.write(json.dumps(record, sort_keys=True) + "\n")
            if self.on_event is not None:
                self.on_event(record)

    def judge(self, name: str, state: NetworkState) -> None:
        """A marked state can still be reached from ``state`` under the supervisor the module runs
        (:class:`Lookahead`), or :class:`Violation`; a search that gives up is counted."""
        found = self.lookahead.reaches_marked(state)
        if found is None:
            self.unjudged += 1
        elif not found:
            raise Violation(
                self.step,
                name,
                "no marked state can be reached from here under the supervisor that runs (it blocks)",
                describe(self.network, state),
            )

    def _outcome(self, label: str, outcomes: tuple[Any, ...]) -> Any:
        """Which of ``outcomes`` the event had, for ``label`` (see ``pick``), said to the user."""
        if self.pick is not None and self.pick in outcomes:
            chosen, how = self.pick, "as picked"
        elif self.rng is not None:
            chosen, how = self.rng.choice(outcomes), "at random"
        else:
            other = next(o for o in outcomes if o != outcomes[0])
            chosen, how = outcomes[0], f"the first; say `{self.naming} -> {other}` for another"
        self.told.append(f"{label} -> {chosen} (one of {', '.join(map(str, outcomes))}: {how})")
        return chosen

    def _told(self, outcome: Outcome) -> Outcome:
        """``outcome`` with what the simulator said of the outcomes it chose."""
        told, self.told, self.pick, self.naming = self.told, [], None, "EVENT"
        return Outcome(outcome.events, (*told, *outcome.messages), outcome.steps) if told else outcome

    def _picked(self, name: str, value: object, raw: bool, pick: str) -> None:
        """``name -> pick``: ``pick`` must be an outcome the event can have now."""
        event = self.supervisor.EVENT[name]
        if raw and event.convert is not None:
            try:
                value = event.convert[0](value)
            except Exception:
                value = None
        outcomes = self.supervisor.outcomes(name, value)
        if not any(pick in values for values in outcomes.values()):
            have = "; ".join(f"{label}: {' or '.join(map(str, v))}" for label, v in outcomes.items())
            raise CommandError(
                f"{name} -> {pick}: " + (f"its outcomes now are {have}" if have else f"{name} has one outcome now")
            )
        self.pick = pick

    # ---- commands -------------------------------------------------------------------------
    def tick(self) -> Outcome:
        self.step += 1
        before = len(self.events)
        self.supervisor.tick()
        return self._counted(self._since(before))

    def _counted(self, outcome: Outcome) -> Outcome:
        """A step is a command that performed an event: one that did nothing takes no number."""
        if not outcome.events:
            self.step -= 1
        return outcome

    def allowed(self) -> list[str]:
        return list(self.supervisor.allowed())

    def expected(self) -> list[str]:
        return list(self.supervisor.expected())

    def perform(self, name: str) -> Outcome:
        """A controllable event, if the supervisor allows it now."""
        self.step += 1
        before = len(self.events)
        if not self.supervisor.perform(name):
            return self._counted(self._checked(Outcome((), (f"refused: {self.refusal(name)}",))))
        return self._since(before)

    def refusal(self, name: str) -> str:
        """Why the supervisor does not allow controllable ``name`` now: the plant, the parts
        of the user's requirements that are false, or the condition synthesis added."""
        event = self.network.event(name)
        state = self.network_state()
        locations = frozenset(state.locations)
        values = dict(zip(self.network.variables, state.values, strict=True))
        for automaton, location in zip(self.network.automata, state.locations, strict=True):
            if event in automaton.alphabet and not any(
                e.event is event and e.source is location for e in automaton.edges
            ):
                return f"{name} cannot happen while {automaton.name} is in {location.name} (the plant)"
        false = []
        for requirement in self.network.requirements_on(event):
            parts = [_operand(p) for p in _conjuncts(requirement.condition) if not _holds(p, locations, values)]
            if parts:
                origin = requirement.origin
                where = f"the requirement at line {origin.span.line}" if origin else requirement.description
                false.append(f"{where} needs {' and '.join(parts)}")
        if false:
            return f"{name} is not allowed now: " + "; ".join(false) + " (false now)"
        guard = next((g for g in self.result.guards if g.event is event), None)
        if guard is not None and guard.added is not None:
            conjuncts = _conjuncts(guard.added)
            parts = [render(p) for p in conjuncts if not _holds(p, locations, values)]
            which = f"false here: {', '.join(parts)}" if len(conjuncts) > 1 and parts else "which is false here"
            return (
                f"{name} is not allowed now: synthesis added {render(guard.added)}, {which} "
                "('robosc synthesize' explains why)"
            )
        return f"the supervisor does not allow {name} now"

    def deliver(self, name: str, value: object = None, raw: bool = True) -> Outcome:
        """An uncontrollable event with its data (raw data goes through the enum rules)."""
        self.step += 1
        before = len(self.events)
        self.supervisor.last_ignored = ""
        if not self.supervisor.deliver(name, value, raw):
            why = self.supervisor.last_ignored or "cannot happen now (the plant does not expect it)"
            return self._counted(self._checked(Outcome((), (f"ignored: {name}: {why}",))))
        return self._since(before)

    def run(self, line: str) -> Outcome:
        """One script line: ``tick [N]``, an event name with optional data, ``expect NAME VALUE``
        or ``sleep SECONDS`` (to watch a script in the live view)."""
        text = line.strip()
        if not text or text.startswith("#"):
            return Outcome(())
        text, arrow, pick = text.partition("->")
        text, pick = text.strip(), pick.strip()
        if arrow and not pick:
            raise CommandError("-> names the outcome: `status -> broken`")
        word, _, rest = text.partition(" ")
        rest = rest.strip()
        if arrow and word not in self.event_names() and self.full_name(word) is None:
            raise CommandError(f"-> {pick}: only after an event (`status -> {pick}`)")
        if word == "tick":
            if rest and not rest.isdigit():
                raise CommandError(f"tick takes a number of cycles, not '{rest}'")
            count = int(rest) if rest else 1
            if count > 100_000:
                raise CommandError(f"tick {count}: at most 100000 cycles at a time")
            events: list[str] = []
            steps: list[int] = []
            for _ in range(count):
                outcome = self.tick()
                events += outcome.events
                steps += outcome.steps
            return self._told(Outcome(tuple(events), steps=tuple(steps)))
        if word == "expect":
            return self.expect(rest)
        if word == "sleep":
            try:
                seconds = float(rest)
            except ValueError:
                raise CommandError(f"sleep takes seconds, not '{rest}'") from None
            time.sleep(max(0.0, min(seconds, 3600.0)))
            return Outcome(())
        if word in self.event_names():
            self.naming = word
        if word in self.supervisor.CONTROLLABLE:
            if rest:
                raise CommandError(f"{word} is controllable: the supervisor provides its data")
            if arrow:
                self._picked(word, None, False, pick)
            return self._told(self.perform(word))
        if word in self.supervisor.UNCONTROLLABLE:
            value, raw = self.parse_data(word, rest)
            if arrow:
                self._picked(word, value, raw, pick)
            return self._told(self.deliver(word, value, raw))
        full = self.full_name(word)
        if full is not None:
            return self.run(f"{full} {rest}" + (f" -> {pick}" if arrow else ""))
        raise CommandError(f"unknown command or event '{word}'" + _suggest(word, [*COMMANDS, *self.event_names()]))

    def full_name(self, word: str) -> str | None:
        """The event a communication's name stands for: ``pick`` is ``pick.c_trigger`` when that
        is the only one of pick's events that can happen now. None when ``word`` names no
        communication; CommandError when several or none of its events can happen now."""
        named = [e for e in self.event_names() if e.split(".", 1)[0] == word and "." in e]
        if not named:
            return None
        now = set(self.allowed()) | set(self.expected())
        possible = [e for e in named if e in now]
        if len(possible) == 1:
            return possible[0]
        if possible:
            raise CommandError(f"'{word}' could be {' or '.join(possible)} now: say which")
        raise CommandError(
            f"none of {word}'s events can happen now ({', '.join(named)}); allowed: "
            f"{', '.join(self.allowed()) or '(none)'}; robot events possible: {', '.join(self.expected()) or '(none)'}"
        )

    def event_names(self) -> list[str]:
        return [*self.supervisor.CONTROLLABLE, *self.supervisor.UNCONTROLLABLE]

    def parse_data(self, name: str, text: str) -> tuple[object, bool]:
        if not text:
            return None, True
        enum = self.received_enum(name)
        if enum is not None and enum.value(text) is not None:
            return text, False  # an enum value, given directly
        try:
            parsed = json.loads(text)
            return Data.wrap(parsed), True
        except json.JSONDecodeError as error:
            hint = f" (or one of {', '.join(v.name for v in enum.values)})" if enum is not None else ""
            raise CommandError(f"data for {name} must be JSON{hint}: {error.msg}") from None
        except (RecursionError, ValueError):
            raise CommandError(f"data for {name} is nested too deeply") from None

    def received_enum(self, name: str) -> m.EnumType | None:
        t = received_type(self.network.event(name))
        return t if isinstance(t, m.EnumType) else None

    def expect(self, text: str) -> Outcome:
        name, _, wanted = text.partition(" ")
        wanted = wanted.strip()
        snapshot = self.snapshot()
        found = {**snapshot["communications"], **snapshot["data"], **snapshot["automata"], **snapshot["variables"]}
        if name not in found:
            raise CommandError(f"expect: no automaton or variable '{name}'" + _suggest(name, list(found)))
        actual = found[name]
        shown = actual if isinstance(actual, str) else json.dumps(actual)
        if shown != wanted:
            raise Violation(self.step, f"expect {name} {wanted}", f"{name} is {shown}", self.describe())
        return Outcome(())

    # ---- random runs -------------------------------------------------------------------------
    def random_step(self, rng: random.Random) -> Outcome:
        """A tick, or an uncontrollable event the plant can take (with random data)."""
        options = ["tick", *self.expected()]
        choice = rng.choice(options)
        self.rng = rng  # an event with several outcomes has a random one
        try:
            if choice == "tick":
                return self._told(self.tick())
            enum = self.received_enum(choice)
            if enum is not None:
                return self._told(self.deliver(choice, rng.choice(enum.values).name, raw=False))
            return self._told(self.deliver(choice, self.random_data(choice, rng)))
        finally:
            self.rng = None

    def random_data(self, name: str, rng: random.Random) -> object:
        """Random data of the type the event carries (plain values, Data objects, lists)."""
        t = received_type(self.network.event(name))
        return Data.wrap(_random_value(t, rng)) if t is not None else None


def _random_value(t: m.DataType, rng: random.Random, depth: int = 0) -> object:
    if isinstance(t, m.BasicType):
        if t.kind is m.BasicKind.BOOLEAN:
            return rng.random() < 0.5
        if t.kind is m.BasicKind.INTEGER:
            low, high = (t.low, t.high) if t.low is not None and t.high is not None else (-10, 10)
            return rng.randint(low, high)
        if t.kind is m.BasicKind.DOUBLE:
            return round(rng.uniform(-1.0, 1.0), 3)
        if t.kind is m.BasicKind.STRING:
            return rng.choice(["", "a", "hello"])
        return None
    if isinstance(t, m.EnumType):
        return _random_value(t.source, rng, depth)
    if depth > 4:
        return None
    if isinstance(t, m.ArrayType):
        return [_random_value(t.element, rng, depth + 1) for _ in range(rng.randint(0, 3))]
    if isinstance(t, m.ObjectType):
        return {p.name: _random_value(p.type, rng, depth + 1) for p in t.properties}
    return None


COMMANDS = ("tick", "expect", "sleep", "state", "help", "quit")


def _suggest(word: str, options: list[str]) -> str:
    found = closest(word, options)
    return f"; did you mean '{found}'?" if found else ""


def _conjuncts(e: m.Expr) -> list[m.Expr]:
    if isinstance(e, m.Binary) and e.op == "and":
        return [*_conjuncts(e.left), *_conjuncts(e.right)]
    return [e]


def _operand(e: m.Expr) -> str:
    """``e`` rendered to stand as one operand of ``and``."""
    text = render(e)
    return f"({text})" if isinstance(e, m.Binary) and e.op in ("or", "=>") else text


def _holds(e: m.Expr, locations: frozenset[m.State], values: dict[m.Variable, Any]) -> bool:
    try:
        return bool(evaluate(e, locations, values))
    except (Undefined, KeyError):
        return True  # cannot tell: not named as a reason
