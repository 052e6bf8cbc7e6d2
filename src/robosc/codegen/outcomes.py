"""Events with several outcomes, as the generated module performs them: the ways a component
takes part in an event that leave one place on one guard for different places are one way whose
target is the tuple of its outcomes; the effect line is then ``self._fork(field, outcomes)``
(runtime/onboard/outcomes.py)."""

from __future__ import annotations

from typing import Any

# a component's way to take part in an event: (source or None: any, guard, target or None: it
# stays, assignment lines); after forked(), a target may be a tuple: the event's outcomes
Branch = tuple[str | None, str, Any, list[str]]


def forked(branches: list[Branch]) -> list[Branch]:
    """The ways an automaton takes part in an event with those of one source and guard that lead
    to different locations (and assign the same) made one, whose target is the tuple of its
    outcomes: the event has several, and which one it had is told by what the robot says next."""
    out: list[Branch] = []
    for source, guard, target, assigns in branches:
        same = [i for i, (s, g, _, a) in enumerate(out) if s == source and g == guard and a == assigns]
        if not same or (source is None and None in (target, out[same[0]][2])):  # (from anywhere, to stay: tried in turn)
            out.append((source, guard, target, assigns))
            continue
        _, _, earlier, _ = out[same[0]]
        targets = earlier if isinstance(earlier, tuple) else (earlier,)
        stays = source if target is None else target
        if stays not in tuple(source if t is None else t for t in targets):
            out[same[0]] = (source, guard, (*targets, target), assigns)
    return out


def landing(field: str, source: str | None, target: Any) -> list[str]:
    """The line that puts ``field`` where a way of taking part in an event leads (none: it stays)."""
    if isinstance(target, tuple):  # several outcomes: unconfirmed among them
        return [f"self._fork({field!r}, {tuple(source if t is None else t for t in target)!r})"]
    return [f"self.{field} = {target!r}"] if target is not None and target != source else []
