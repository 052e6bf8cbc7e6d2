"""The options of symbolic synthesis, named and documented as Eclipse ESCET names its own
(docs/synthesis-options.md has the table of what each changes and when to pick it). They
change how long synthesis takes and how much memory it needs, never its result: the same
supervisor comes out whatever the options (tests/test_synthesis.py checks it)."""

from __future__ import annotations

from robosc.record import record

ORDERS = {
    "interaction": "automata and variables that share events, guards or requirements next to each other "
    "(breadth-first over how they interact; the default)",
    "model": "the order of the model: the communications' plants, the components, the data plants, "
    "then the variables",
    "sorted": "by name",
    "reverse": "the interaction order reversed",
}


FLEETS = {
    "counted": "where three or more components are copies of each other (the instances of `component bot[N]`, "
    "or components copied by hand) and the requirements treat them alike, count how many are in each state "
    "instead of tracking each (the default; monolithic where they are not)",
    "monolithic": "one BDD over every component's state, whatever the model (the reference method)",
}


@record
class SynthesisOptions:
    """``order``: the initial BDD variable order, one of :data:`ORDERS`. ``reorder``: let CUDD
    improve the order while it works (dynamic sifting): far fewer BDD nodes and less memory on
    large models, usually more time. ``fleet``: how fleets of identical robots are synthesized,
    one of :data:`FLEETS`."""

    order: str = "interaction"
    reorder: bool = False
    fleet: str = "counted"

    def __post_init__(self) -> None:
        if self.order not in ORDERS:
            raise ValueError(f"unknown variable order '{self.order}' (one of {', '.join(ORDERS)})")
        if self.fleet not in FLEETS:
            raise ValueError(f"unknown fleet method '{self.fleet}' (one of {', '.join(FLEETS)})")


DEFAULT = SynthesisOptions()
