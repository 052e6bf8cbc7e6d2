"""What a long synthesis is doing, for a display: the phase, the round of the bad-state loop,
the images and preimages computed, the BDD nodes in use and the time so far.

The fixed points tell a :class:`Watch` as they work (:meth:`Watch.step`, cheap: it looks at the
clock), and it passes a :class:`Progress` to its ``report`` at most every ``every`` seconds. The
synthesis result is the same whether anyone watches."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

from robosc.record import record


@record
class Progress:
    """``phase``: what synthesis does now (see :data:`PHASES`); ``round``: the round of the loop
    between controllability and nonblocking (0 outside it); ``steps``: images and preimages
    computed so far; ``live_nodes``: BDD nodes in use now; ``seconds``: since synthesis began."""

    phase: str
    round: int
    steps: int
    live_nodes: int
    seconds: float


PHASES = {
    "counting": "finding copies of a robot and counting them",
    "encoding": "encoding the automata and requirements as BDDs",
    "forward": "the states the requirements let the system reach (where the search for bad states looks)",
    "bad states": "the states from which an uncontrollable event breaks a requirement",
    "nonblocking": "the states from which a marked state stays reachable",
    "reachable": "the states the supervised fleet reaches",
    "conditions": "the condition added to each controllable event",
}

# seconds between two countings of the BDD nodes in use: counting walks CUDD's tables (15 ms at
# 700,000 nodes), so a display that reports every quarter of a second shows a count up to this old
NODES_EVERY = 2.0


class Watch:
    """Passes :class:`Progress` to ``report`` at most every ``every`` seconds while synthesis
    works (and once at each new phase, once ``every`` has passed since the start)."""

    def __init__(self, report: Callable[[Progress], Any], every: float = 0.25) -> None:
        self.report = report
        self.every = every
        self.start = time.monotonic()
        self.next = self.start + every
        self.phase_name = "encoding"
        self.round = 0
        self.steps = 0
        self.nodes: Callable[[], int] = lambda: 0
        self.counted = (-math.inf, 0)  # when the nodes were last counted, and how many

    @classmethod
    def quiet(cls) -> Watch:
        """A watch that tells no one (where synthesis is not watched)."""
        return cls(lambda _: None, every=math.inf)

    def phase(self, name: str, round: int = 0) -> None:
        self.phase_name, self.round = name, round
        self.counted = (-math.inf, 0)  # a new phase: the nodes counted again
        self.tell(time.monotonic())

    def step(self) -> None:
        """An image or preimage was computed."""
        self.steps += 1
        self.beat()

    def beat(self) -> None:
        """Some other piece of work was done (a relation built): reported if it is time."""
        now = time.monotonic()
        if now >= self.next:
            self.tell(now)

    def tell(self, now: float) -> None:
        if now - self.start < self.every:
            return
        self.next = now + self.every
        if now - self.counted[0] >= NODES_EVERY:
            self.counted = (now, self.nodes())
        self.report(Progress(self.phase_name, self.round, self.steps, self.counted[1], now - self.start))
