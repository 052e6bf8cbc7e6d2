"""The options of symbolic synthesis, named and documented as Eclipse ESCET names its own
(docs/synthesis-options.md has the table of what each changes and when to pick it). They
change how long synthesis takes and how much memory it needs, never its result: the same
supervisor comes out whatever the options (tests/test_synthesis.py checks it)."""

from __future__ import annotations

from robosc.record import record

ORDERS = {
    "interaction": "automata and variables that share events, guards or requirements next to each other "
    "(breadth-first over how they interact; the default)",
    "model": "the order of the model: the communications' plants, the components, the data plants, then the variables",
    "sorted": "by name",
    "reverse": "the interaction order reversed",
}

IMPROVEMENTS = {
    "dcsh": "DCSH: Cuthill-McKee and Sloan over the graph of what the events tie together, each also "
    "reversed, keeping the one with the smallest total span",
    "force": "FORCE: each group of things an event ties together pulls its members to its centre, "
    "repeatedly, keeping the order where they are closest (the smallest total span)",
    "slidwin": "sliding window: every 4 neighbours in the order tried in each of their 24 orders, "
    "keeping the one with the smallest total span",
    "reverse": "the order so far, reversed",
}


def order_problem(order: str) -> str | None:
    """Why ``order`` is not an order (an initial order, then improvements, joined by '->')."""
    first, *then = [part.strip() for part in order.split("->")]
    if first not in ORDERS:
        return f"unknown variable order '{first}' (one of {', '.join(ORDERS)})"
    for step in then:
        if step not in IMPROVEMENTS:
            return f"unknown order improvement '{step}' (one of {', '.join(IMPROVEMENTS)})"
    return None


EDGE_ORDERS = {
    "model": "the network's order: each component's events as its transitions name them, a message's "
    "answers right after it (the default)",
    "reverse": "the model's order reversed",
    "sorted": "by name",
}


EXPLORATIONS = {
    "auto": "for each fixed point, saturation unless more than a third of the events read the first tenth of the "
    "variable order, chained then (the default: as fast as the better of the two, or nearly, on each benchmark family)",
    "saturation": "each event's fixed point first in the parts of the state below the highest bit it reads "
    "(saturation): the events lowest in the variable order first, going back down whenever a set grows "
    "(far faster where events read few bits each, as a counted fleet's robot moves do)",
    "chained": "all events over the whole state set, each image added before the next event, round after "
    "round until nothing changes (faster where the sets are wide and events read much of the state)",
}


FORWARDS = {
    "auto": "first on a fleet (counted, or copies of a robot synthesized monolithically because they could not "
    "be counted), never on other models and with --fleet monolithic (the default: a counted warehouse of 50 "
    "robots took 126 s without it and 5 s with it, a ring of 10 robots with homes of their own 61 s and 18 s)",
    "first": "first find the states the requirements let the system reach from its initial state, then search "
    "for bad states among those only (Eclipse ESCET's forward reachability; the supervisor is the same in every "
    "state it can reach, and holds in the others)",
    "never": "search for bad states among all the states the model can be in",
}


FLEETS = {
    "counted": "where three or more components are copies of each other (the instances of `component bot[N]`, "
    "or components copied by hand) and the requirements treat them alike, count how many are in each state "
    "instead of tracking each (the default; monolithic where they are not)",
    "monolithic": "one BDD over every component's state, whatever the model (the reference method)",
}


@record
class SynthesisOptions:
    """``order``: the initial BDD variable order, one of :data:`ORDERS`, optionally followed by
    improvements of :data:`IMPROVEMENTS` (``"interaction->force->slidwin"``). ``reorder``: let CUDD
    improve the order while it works (dynamic sifting): far fewer BDD nodes and less memory on
    large models, usually more time. ``fleet``: how fleets of identical robots are synthesized,
    one of :data:`FLEETS`. ``edges``: the order in which the fixed points apply the events, one
    of :data:`EDGE_ORDERS` (each event's image is added before the next is applied, so the
    order decides how far one round gets). ``explore``: how the fixed points (reachability,
    controllability, nonblocking) apply the events, one of :data:`EXPLORATIONS`. ``forward``: whether
    the search for bad states is confined to the states the requirements let the system reach,
    one of :data:`FORWARDS`."""

    order: str = "interaction"
    reorder: bool = False
    fleet: str = "counted"
    edges: str = "model"
    explore: str = "auto"
    forward: str = "auto"

    def __post_init__(self) -> None:
        problem = order_problem(self.order)
        if problem is not None:
            raise ValueError(problem)
        if self.edges not in EDGE_ORDERS:
            raise ValueError(f"unknown edge order '{self.edges}' (one of {', '.join(EDGE_ORDERS)})")
        if self.explore not in EXPLORATIONS:
            raise ValueError(f"unknown exploration '{self.explore}' (one of {', '.join(EXPLORATIONS)})")
        if self.forward not in FORWARDS:
            raise ValueError(f"unknown forward reachability '{self.forward}' (one of {', '.join(FORWARDS)})")
        if self.fleet not in FLEETS:
            raise ValueError(f"unknown fleet method '{self.fleet}' (one of {', '.join(FLEETS)})")


DEFAULT = SynthesisOptions()
