"""An event with several outcomes: two transitions from one state on the same event (and the
same assignments) to different states, such as ``on response from status goto done`` and ``on
response from status goto broken``. Synthesis covers both; a running controller cannot know
which one the robot had, so the component is unconfirmed among them until a message, an answer
or its driver's report tells (docs/howto/restarts.md). The warning says which events the robot
sends settle it (taken in every outcome, to one state), or that only the driver's report can: a
message taken in one outcome only may be a stray or a second copy, and tells nothing."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, warning
from robosc.language.model import Automaton, Model, ResultKind, ResultTransition, State
from robosc.language.render import render

SENT_BY_THE_ROBOT = (ResultKind.RESPONSE, ResultKind.FEEDBACK, ResultKind.ERROR)


def _label(t: ResultTransition) -> str:
    way = "to" if t.result in (ResultKind.REQUEST, ResultKind.CANCEL) else "from"
    return f"on {t.result.value} {way} {t.communication.name}"


def _leads(automaton: Automaton, state: State) -> dict[str, set[str]]:
    """The events the robot sends that the automaton takes in ``state`` (by a transition of its
    own, or one from every state), each with where it leads."""
    out: dict[str, set[str]] = {}
    for t in automaton.transitions:
        if isinstance(t, ResultTransition) and t.source in (state, None) and t.result in SENT_BY_THE_ROBOT:
            landing = t.target if t.target is not None else state
            out.setdefault(_label(t), set()).add(landing.name)
    return out


def check(model: Model) -> Iterator[Diagnostic]:
    for component in model.components:
        for automaton in component.behaviours:
            groups: dict[tuple[object, ...], list[ResultTransition]] = {}
            for t in automaton.transitions:
                if not isinstance(t, ResultTransition) or t.source is None:
                    continue
                assigns = tuple(f"{a.variable.name} := {render(a.value)}" for a in t.assignments)
                groups.setdefault((t.source.name, t.communication.name, t.result, assigns), []).append(t)
            for transitions in groups.values():
                targets: list[State] = []
                for t in transitions:
                    landing = t.target if t.target is not None else t.source
                    if landing is not None and landing not in targets:
                        targets.append(landing)
                if len(targets) < 2:
                    continue
                first = transitions[0]
                names = ", ".join(s.name for s in targets)
                leads = [_leads(automaton, s) for s in targets]
                # an event settles it where every outcome takes it to one and the same state (one
                # taken in some outcomes only may be a stray or a second copy: it tells nothing)
                settle = sorted(
                    label for label in set.intersection(*(set(x) for x in leads))
                    if len(set().union(*(x[label] for x in leads))) == 1
                )
                if settle:
                    tells = "what settles it: " + "; ".join(f"'{x}'" for x in settle) + f", or the driver's report (robosc/report/{component.name})"
                else:
                    tells = f"only the driver's report (robosc/report/{component.name}) tells which"
                assert first.source is not None
                yield warning(
                    transitions[1].span,
                    f"'{_label(first)}' in {component.name}'s state '{first.source.name}' has {len(targets)} outcomes "
                    f"({names}): the controller holds {component.name} unconfirmed among them until the robot tells "
                    f"which; {tells}",
                    Code.SEVERAL_OUTCOMES,
                    None if settle else f"have {component.name}'s driver offer the report service "
                    f"robosc/report/{component.name}: a message taken in one outcome only may be a stray and tells nothing",
                )
