"""Run the generated supervisor without ROS and check every step against the synthesis result.

The simulator executes the very module that ``robosc generate`` writes (rendered
in memory), so what it shows is what the node does. After every event it checks,
independently of the generated code, that:

* the requirements on the event held in the state it happened in (evaluated on
  the model's expressions, not on the compiled guards);
* a controllable event was allowed by the synthesized supervisor (the BDDs);
* the state reached is inside the controlled behaviour, so a marked state is
  still reachable.

A failed check raises :class:`Violation` with the step, the event and the state.
"""

from __future__ import annotations

import json
import random
import time
import types
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TextIO

from robosc.language import model as m
from robosc.plant.network import Network, received_type
from robosc.runtime.module import module_name, render_module
from robosc.runtime.onboard.values import Data, plain
from robosc.runtime.plan import Plan
from robosc.synthesis.evaluate import Undefined, evaluate
from robosc.synthesis.result import SynthesisResult
from robosc.synthesis.state import NetworkState, describe


class Violation(Exception):
    """A step broke a requirement, or left the controlled behaviour."""

    def __init__(self, step: int, event: str, reason: str, state: str) -> None:
        super().__init__(f"step {step}: {event}: {reason}\n  in state: {state}")
        self.step, self.event, self.reason, self.state = step, event, reason, state


class CommandError(Exception):
    """A script line or typed command that the simulator cannot read."""


@dataclass(frozen=True)
class Outcome:
    """What one command did: the events performed, and messages for the user."""

    events: tuple[str, ...]
    messages: tuple[str, ...] = ()


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
        self.supervisor: Any = self.module.Robot(seed=seed, warn=self.warnings.append, observer=self._observe)
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

    # ---- commands -------------------------------------------------------------------------
    def tick(self) -> Outcome:
        self.step += 1
        before = len(self.events)
        self.supervisor.tick()
        return self._checked(Outcome(tuple(self.events[before:])))

    def allowed(self) -> list[str]:
        return list(self.supervisor.allowed())

    def expected(self) -> list[str]:
        return list(self.supervisor.expected())

    def perform(self, name: str) -> Outcome:
        """A controllable event, if the supervisor allows it now."""
        self.step += 1
        before = len(self.events)
        if not self.supervisor.perform(name):
            return self._checked(Outcome((), (f"refused: the supervisor does not allow {name} now",)))
        return self._checked(Outcome(tuple(self.events[before:])))

    def deliver(self, name: str, value: object = None, raw: bool = True) -> Outcome:
        """An uncontrollable event with its data (raw data goes through the enum rules)."""
        self.step += 1
        before = len(self.events)
        if not self.supervisor.deliver(name, value, raw):
            return self._checked(Outcome((), (f"ignored: {name} cannot happen now (the plant does not expect it)",)))
        return self._checked(Outcome(tuple(self.events[before:])))

    def run(self, line: str) -> Outcome:
        """One script line: ``tick [N]``, an event name with optional data, ``expect NAME VALUE``
        or ``sleep SECONDS`` (to watch a script in the live view)."""
        text = line.strip()
        if not text or text.startswith("#"):
            return Outcome(())
        word, _, rest = text.partition(" ")
        rest = rest.strip()
        if word == "tick":
            count = int(rest) if rest.isdigit() else 1
            events: list[str] = []
            for _ in range(count):
                events += self.tick().events
            return Outcome(tuple(events))
        if word == "expect":
            return self.expect(rest)
        if word == "sleep":
            try:
                seconds = float(rest)
            except ValueError:
                raise CommandError(f"sleep takes seconds, not '{rest}'") from None
            time.sleep(max(0.0, min(seconds, 3600.0)))
            return Outcome(())
        if word in self.supervisor.CONTROLLABLE:
            if rest:
                raise CommandError(f"{word} is controllable: the supervisor provides its data")
            return self.perform(word)
        if word in self.supervisor.UNCONTROLLABLE:
            value, raw = self.parse_data(word, rest)
            return self.deliver(word, value, raw)
        raise CommandError(f"unknown command or event '{word}'" + _suggest(word, self.event_names()))

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
        except json.JSONDecodeError as error:
            hint = f" (or one of {', '.join(v.name for v in enum.values)})" if enum is not None else ""
            raise CommandError(f"data for {name} must be JSON{hint}: {error.msg}") from None
        return Data.wrap(parsed), True

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
        if choice == "tick":
            return self.tick()
        enum = self.received_enum(choice)
        if enum is not None:
            return self.deliver(choice, rng.choice(enum.values).name, raw=False)
        return self.deliver(choice, self.random_data(choice, rng))

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


def _suggest(word: str, options: list[str]) -> str:
    import difflib

    close = difflib.get_close_matches(word, options, n=1)
    return f"; did you mean '{close[0]}'?" if close else ""
