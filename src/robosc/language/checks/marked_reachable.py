"""Rule 3: every state reachable from the initial state can reach a marked state
(following transitions, guards ignored)."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Automaton, Model, State


def successors(automaton: Automaton, state: State) -> set[State]:
    return {t.target or state for t in automaton.transitions_from(state)}


def check(model: Model) -> Iterator[Diagnostic]:
    for component in model.components:
        for automaton in component.behaviours:
            if len(automaton.initial_states) != 1:
                continue  # rule 2 reports it
            reachable = [automaton.initial_states[0]]
            seen = set(reachable)
            for state in reachable:
                for nxt in successors(automaton, state) - seen:
                    seen.add(nxt)
                    reachable.append(nxt)
            if not any(s.marked for s in automaton.states):
                yield error(
                    automaton.span,
                    f"no state of '{component.name}' is marked, so it can never finish",
                    Code.MARKED_REACHABLE,
                    "mark the states where the component is at rest, as in 'initial marked state idle'",
                )
                continue
            can_finish = {s for s in automaton.states if s.marked}
            changed = True
            while changed:
                changed = False
                for state in automaton.states:
                    if state not in can_finish and successors(automaton, state) & can_finish:
                        can_finish.add(state)
                        changed = True
            for state in reachable:
                if state not in can_finish:
                    yield error(
                        state.span,
                        f"state '{component.name}.{state.name}' is reachable but cannot reach a marked state",
                        Code.MARKED_REACHABLE,
                    )
