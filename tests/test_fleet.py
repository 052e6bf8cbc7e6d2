"""Fleets: instances of a component, requirements over them, and synthesis by counting
identical robots, checked against the monolithic and the explicit methods."""

from __future__ import annotations

import re
import sys
from pathlib import Path
from typing import Any

import pytest

from robosc.api import check_text, format_text, synthesize_model
from robosc.language import model as m
from robosc.language.render import render
from robosc.plant import build_network
from robosc.synthesis.counting.network import counted, with_homes
from robosc.synthesis.counting.synthesis import synthesize_counted
from robosc.synthesis.explicit import synthesize_explicit
from robosc.synthesis.options import SynthesisOptions
from robosc.synthesis.restrictions import restriction
from robosc.synthesis.symbolic import synthesize_monolithic

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "benchmarks"))
import families

FLEET = """robot Fleet {
    component bot[3] namespace "/fleet" initial idle, busy, idle {
        incoming message go with type: none
        outgoing message done with identifier: "finished", type: none
        behaviour {
            marked state idle { on request to go goto busy }
            marked state busy { on response from done goto idle }
        }
    }
    component Door {
        incoming message open with type: none
        behaviour { initial marked state closed { on request to open } }
    }
    for r in bot {
        requirement r.go needs count(q in bot: q.busy) <= 1 and all(q in bot: q = r or !q.busy)
    }
    requirement bot1.go needs Door.closed
}
"""


def test_instances_are_components_with_their_own_names_namespaces_and_start():
    model = check_text(FLEET).model
    assert model is not None
    bots = model.groups["bot"]
    assert [c.name for c in bots] == ["bot1", "bot2", "bot3"]
    assert [c.index for c in bots] == [1, 2, 3]
    assert [c.namespace for c in bots] == ["/fleet/bot1", "/fleet/bot2", "/fleet/bot3"]
    assert [[c.name for c in b.communications] for b in bots][1] == ["bot2.go", "bot2.done"]
    assert [[c.ros_name for c in b.communications] for b in bots][1] == ["/fleet/bot2/go", "/fleet/bot2/finished"]
    assert [next(s.name for s in b.automaton.states if s.initial) for b in bots] == ["idle", "busy", "idle"]
    assert model.component("Door").group is None


def test_for_blocks_and_quantifiers_expand_per_instance():
    model = check_text(FLEET).model
    requirements = {r.communications[0].name: r.condition for r in model.requirements}
    count = requirements["bot2.go"].left.left
    assert [render(term) for term in count.terms] == ["bot1.busy", "bot2.busy", "bot3.busy"]  # one per instance
    # shown as written: a count over the group, and what 'any' expanded to for the others
    assert render(requirements["bot2.go"]) == "count(q in bot: q.busy) <= 1 and !bot1.busy and !bot3.busy"
    requirements = {name: render(condition) for name, condition in requirements.items()}
    assert requirements["bot1.go"] == "Door.closed"  # the last one written for bot1
    assert len(model.requirements) == 4


def test_count_of_conditions_written_out():
    text = FLEET.replace(
        "requirement bot1.go needs Door.closed", "requirement open needs count(bot1.idle, Door.closed) >= 2"
    )
    model = check_text(text).model
    condition = model.requirements[-1].condition
    assert isinstance(condition.left, m.Count) and len(condition.left.terms) == 2


def test_fleet_syntax_formats_and_reads_back():
    formatted = format_text(FLEET)
    assert 'component bot[3] namespace "/fleet" initial idle, busy, idle {' in formatted
    assert "for r in bot {" in formatted
    assert format_text(formatted) == formatted
    assert check_text(formatted).model is not None


@pytest.mark.parametrize("word", ["for", "in", "namespace", "all", "count"])
def test_the_new_words_still_name_things(word: str):
    """Models of the original tool may name a message, a state or a variable so."""
    text = f"""robot R {{
        component {word} {{
            incoming message {word} with type: none
            behaviour {{
                variable {word}: boolean
                initial marked state {word} {{ on request to {word} }}
            }}
        }}
        requirement {word} needs {word}.{word}
    }}"""
    result = check_text(text)
    assert result.model is not None, result.render()


def test_a_group_is_not_one_component():
    result = check_text(FLEET.replace("requirement bot1.go needs Door.closed", "requirement bot.go needs true"))
    assert [d.code.value for d in result.diagnostics] == ["instances"]
    assert (result.diagnostics[0].span.line, result.diagnostics[0].span.column) == (17, 17)


@pytest.mark.parametrize("n", [2, 3])
@pytest.mark.parametrize("family", ["ring", "warehouse"])
def test_written_with_instances_a_fleet_means_what_its_copies_mean(family: str, n: int):
    copied = synthesize_monolithic(build_network(check_text(families.FLEETS[family](n)).model))
    instances = synthesize_monolithic(build_network(check_text(families.FLEETS[f"{family}_instances"](n)).model))
    assert copied.ok and instances.ok
    assert copied.reachable_states == instances.reachable_states
    assert [g.added is None for g in copied.guards] == [g.added is None for g in instances.guards]


def agree_with_monolithic(text: str, least: int = 2) -> tuple[object, object]:
    """Counted and monolithic synthesis of ``text``: the same supervisor on every state the
    monolithic one reaches (each event allowed in the same states)."""
    network = build_network(check_text(text).model)
    mono = synthesize_monolithic(network)
    fleet = synthesize_counted(network, least=least)
    assert fleet.method == "symmetric", fleet.fleet
    assert mono.ok == fleet.ok
    if not mono.ok:
        return mono, fleet
    fp = mono.fixpoint
    enc = fp.enc
    for mine, theirs in zip(mono.guards, fleet.guards, strict=True):
        assert mine.event is theirs.event
        added = enc.boolean(theirs.added) if theirs.added is not None else enc.true
        allowed = fp.enabled[mine.event] & fp.required[mine.event] & added
        assert fp.reachable & ~allowed.equiv(fp.allowed[mine.event]) == enc.false, mine.event.name
    return mono, fleet


def counted_states(network, supervisor) -> int:
    """The explicit supervisor's reachable states up to permuting each group's agents."""
    fleet = counted(network)
    seen = set()
    for state in supervisor.controlled_states():
        where = dict(zip(network.automata, state.locations, strict=True))
        values = dict(zip(network.variables, state.values, strict=True))
        key = []
        in_groups = set()
        for group in fleet.groups:
            locals_ = sorted(
                (repr([loc.name for loc in local[0]]), repr(local[1]))
                for local in (
                    (tuple(group.to_rep[id(a)][where[x]] for x in a.automata), tuple(values[v] for v in a.variables))
                    for a in group.agents
                )
            )
            key.append(tuple(locals_))
            in_groups |= {x.name for a in group.agents for x in a.automata}
        key.append(tuple(loc.name for a, loc in where.items() if a.name not in in_groups))
        seen.add(tuple(key))
    return len(seen)


@pytest.mark.parametrize("n", [2, 3, 4])
@pytest.mark.parametrize("family", ["ring", "ring_instances", "warehouse", "warehouse_instances"])
def test_counting_robots_gives_the_monolithic_supervisor(family: str, n: int):
    agree_with_monolithic(families.FLEETS[family](n))


@pytest.mark.parametrize("family", ["ring_instances", "warehouse_instances"])
def test_counted_states_are_the_explicit_states_up_to_order(family: str):
    network = build_network(check_text(families.FLEETS[family](3)).model)
    explicit = synthesize_explicit(network)
    fleet = synthesize_counted(network, least=2)
    assert fleet.reachable_states == counted_states(network, explicit.supervisor)


DEADLOCK = """robot Cell {
    // three robots share three tools; a robot works with two, taken one at a time
    component bot[3] {
        incoming message take with type: none
        incoming message work with type: none
        incoming message put with type: none
        behaviour {
            initial marked state free { on request to take goto one }
            state one { on request to take goto two }
            state two { on request to work goto working }
            state working { on request to put goto free }
        }
    }
    for r in bot {
        // a tool is left: tools held = robots holding one or two, plus those holding two
        requirement r.take needs count(q in bot: !q.free) + count(q in bot: q.two or q.working) <= 2
    }
}
"""


def test_counting_finds_the_conditions_monolithic_synthesis_adds():
    mono, fleet = agree_with_monolithic(DEADLOCK)
    assert [g.added is not None for g in fleet.guards] == [g.added is not None for g in mono.guards]


def test_counted_synthesis_agrees_with_explicit_synthesis_state_by_state():
    network = build_network(check_text(DEADLOCK).model)
    explicit = synthesize_explicit(network)
    fleet = synthesize_counted(network, least=2)
    supervisor = explicit.supervisor
    for state in supervisor.controlled_states():
        for event in network.events:
            assert fleet.allows(event, state) == supervisor.allows(event, state), event.name


def test_a_robot_treated_apart_is_synthesized_monolithically():
    text = FLEET.replace("requirement bot1.go needs Door.closed", "requirement bot1.go needs bot2.idle")
    result = synthesize_model(check_text(text).model, options=SynthesisOptions(fleet="counted"))
    assert result.method == "symbolic"
    assert "monolithic" in result.fleet


def test_the_default_counts_fleets_of_three_or_more():
    model = check_text(families.ring_instances(3)).model
    assert synthesize_model(model).method == "symmetric"
    assert synthesize_model(check_text(families.ring_instances(2)).model).method == "symbolic"
    assert synthesize_model(model, options=SynthesisOptions(fleet="monolithic")).method == "symbolic"


def test_a_counted_guard_runs_in_the_generated_supervisor():
    from robosc.api import supervisor_module

    model = check_text(DEADLOCK).model
    result = synthesize_model(model)
    assert result.method == "symmetric" and any(g.added is not None for g in result.guards)
    source = supervisor_module(result)
    assert "sum((" in source
    compile(source, "supervisor.py", "exec")


STUCK = """robot Stuck {
    component bot[3] {
        incoming message go with type: none
        behaviour {
            initial marked state a { on request to go goto b }
            marked state b { on request to go goto a }
            state c {}
        }
    }
    for r in bot {
        requirement r.go needs count(q in bot: q.b) >= 3
    }
}
"""


def test_a_counted_fleet_gets_the_warnings_of_monolithic_synthesis():
    """At the same places; a state that no robot of the group reaches is said once for them all."""
    from robosc.synthesis.warnings import synthesis_warnings

    model = check_text(STUCK).model
    counted = synthesize_model(model)
    mono = synthesize_model(model, options=SynthesisOptions(fleet="monolithic"))
    assert counted.method == "symmetric"
    mine = synthesis_warnings(counted)
    theirs = synthesis_warnings(mono)
    assert {(d.code, d.span) for d in mine} == {(d.code, d.span) for d in theirs}
    assert len(theirs) == 3 + 3 + 3  # b and c of each robot, each robot's requirement
    assert [d.message for d in mine if d.code.value == "unreached-state"] == [
        "no controlled run brings any of bot1 .. bot3 to state 'b': the supervisor keeps them out",
        "state 'c' of bot1 .. bot3 can never be reached: no run of the model leads there",
    ]
    assert [d.code.value for d in mine].count("never-holds") == 3


TOGGLE = """robot Toggle {
    component bot[3] {
        incoming message go with type: none
        behaviour {
            initial marked state a { on request to go goto b }
            marked state b { on request to go goto a }
        }
    }
    for r in bot {
        requirement r.go needs !any(q in bot: q != r and q.b)
        requirement r.go needs r.a or all(q in bot: q = r or q.a)
    }
}
"""


def test_counting_the_others_leaves_out_the_robot_itself():
    """A robot in b asks whether *another* robot is in b: counted, it is one of the b's."""
    mono, fleet = agree_with_monolithic(TOGGLE)
    alone = fleet.state({"bot1": "b"})
    assert fleet.allows("bot1.go", alone) and mono.allows("bot1.go", mono.state({"bot1": "b"}))
    assert not fleet.allows("bot2.go", alone)  # bot2 in a, bot1 (another) in b


NEVER = """robot Never {
    component bot[3] {
        incoming message go with type: none
        incoming message back with type: none
        behaviour {
            initial marked state a { on request to go goto b }
            state b { on request to back goto a }
        }
    }
    for r in bot {
        // back only while every robot is in a: never, once one of them left
        requirement r.back needs count(q in bot: q.a) >= 3
    }
}
"""


PARTLY = """robot Partly {
    component bot[3] {
        incoming message go with type: none
        incoming message back with type: none
        behaviour {
            initial marked state a { on request to go goto b }
            marked state b {
                on request to go goto c
                on request to back goto a
            }
            state c { on request to back goto a }
        }
    }
    for r in bot {
        requirement r.back needs !r.c // so go from b never: c would have no way out
    }
}
"""


TRAP = """robot Trap {
    component bot[3] {
        incoming message go with type: none
        incoming message back with type: none
        incoming message home with type: none
        incoming message rescue with type: none
        outgoing message fell with type: none
        behaviour {
            initial marked state a { on request to go goto b }
            state b { on request to back goto c }
            state c {
                on request to home goto a
                on response from fell goto pit
            }
            state pit { on request to rescue goto a }
        }
    }
    for r in bot {
        // the way home from b passes c, where a robot can fall into a pit it may not leave
        requirement r.rescue needs r.a
    }
}
"""


def replay(result: Any, restriction: Any) -> None:
    """The explanation's run is a run of the fleet under the (monolithic) supervisor ``result``:
    each step allowed there and reaching the state the explanation names; at its end the
    supervisor disables the event, which would lead outside the controlled behaviour."""
    from robosc.synthesis.explicit import Edges, successors
    from robosc.synthesis.state import describe, initial_state

    network = result.network
    edges = Edges(network)
    here = initial_state(network)
    for step in restriction.path:
        event = network.event(step.event.name)
        assert result.allows(event, here), event.name
        here = next(s for s in successors(edges, here, event) if describe(network, s) == step.state)
        assert result.controlled(here)
    assert describe(network, here) == restriction.state
    restricted = network.event(restriction.event.name)
    assert not result.allows(restricted, here)
    after = next(s for s in successors(edges, here, restricted) if describe(network, s) == restriction.after)
    assert not result.controlled(after)


@pytest.mark.parametrize(
    "text", [DEADLOCK, NEVER, PARTLY, TRAP, "warehouse"], ids=["deadlock", "never", "partly", "trap", "warehouse"]
)
def test_a_counted_fleet_explains_its_conditions_naming_its_robots(text: str):
    """The explanation of each added condition is found on the counted network and followed with
    the fleet's robots: a shortest run of the fleet itself (as long as the monolithic method's),
    never-allowed where the monolithic method says so, and the same warnings."""
    from robosc.synthesis.warnings import synthesis_warnings

    if text == "warehouse":
        text = (Path(__file__).resolve().parent.parent / "examples/warehouse.rscd").read_text()
    model = check_text(text).model
    fleet = synthesize_model(model)
    mono = synthesize_model(model, options=SynthesisOptions(fleet="monolithic"))
    assert fleet.method == "symmetric" and mono.method == "symbolic"
    added = [g.event.name for g in mono.added_guards]
    assert added and added == [g.event.name for g in fleet.added_guards]
    for event in added:
        mine, theirs = restriction(fleet, event), restriction(mono, event)
        assert theirs is not None and mine is not None, event
        assert mine.never == theirs.never and len(mine.path) == len(theirs.path), event
        assert "the same for every robot of bot (bot1 .. bot3)" in mine.note
        replay(mono, mine)
        # what goes wrong is told as the monolithic method tells it (maybe of other robots); where
        # the events that follow have several outcomes (the warehouse's arrived or stopped), the
        # two methods may follow different ones: then the fixes are those of different states
        assert mine.consequence.reason.split(" from state [")[0] == theirs.consequence.reason.split(" from state [")[0]
        if [s.event.name.split(".")[-1] for s in mine.consequence.path] != [
            s.event.name.split(".")[-1] for s in theirs.consequence.path
        ]:
            continue
        assert [f.span for f in mine.consequence.fixes] == [f.span for f in theirs.consequence.fixes]
        # and where the shortest way on is cut, with the robots' events and states
        cut = "The shortest way on to a marked state is cut: "
        assert (cut in mine.consequence.reason) == (cut in theirs.consequence.reason)
        if cut in theirs.consequence.reason:
            assert mine.consequence.reason.split(cut)[1] == theirs.consequence.reason.split(cut)[1]
        if "stuck outside" in theirs.consequence.reason:
            assert "stuck outside a marked state: bot" in mine.consequence.reason
    assert {(d.code, d.span) for d in synthesis_warnings(fleet)} == {(d.code, d.span) for d in synthesis_warnings(mono)}


def test_a_fleet_event_never_allowed_is_said_once_for_the_robots():
    from robosc.synthesis.warnings import synthesis_warnings

    [warning] = [
        d for d in synthesis_warnings(synthesize_model(check_text(NEVER).model)) if d.code.value == "never-allowed"
    ]
    assert warning.message.startswith(
        "synthesis never allows 'bot1.go' (the same for every robot of bot (bot1 .. bot3))"
    )
    assert "[bot1.b, bot2.a, bot3.a]" in warning.message


SINGLED_OUT = """robot Lifted {{
    component bot[{n}] {{
        incoming message go with type: none
        incoming message home with type: none
        behaviour {{
            initial marked state depot {{ on request to go goto lift }}
            state lift {{ on request to go goto top on request to home goto depot }}
            marked state top {{ on request to home goto depot }}
        }}
    }}
    for r in bot {{
        requirement r.go needs r.depot => (r = bot1 or count(q in bot: q.lift) < 2)
        requirement r.go needs r != bot1 or !any(q in bot: q != r and q.top)
    }}
}}
"""


def test_one_robot_singled_out_in_a_for_block_is_read_per_instance():
    model = check_text(SINGLED_OUT.format(n=4)).model
    assert model is not None
    texts = sorted(r.description for r in build_network(model).requirements)
    count = "count(q in bot: q.lift) < 2"  # over bot1 .. bot4 (test_a_count_over_a_group_...)
    assert texts == [
        "requirement bot1.go needs !(bot2.top or bot3.top or bot4.top)",
        "requirement bot1.go needs true",  # bot1.depot => (true or ...)
        f"requirement bot2.go needs bot2.depot => ({count})",  # false or ... folded away
        "requirement bot2.go needs true",
        f"requirement bot3.go needs bot3.depot => ({count})",
        "requirement bot3.go needs true",
        f"requirement bot4.go needs bot4.depot => ({count})",
        "requirement bot4.go needs true",
    ]


def test_singled_out_one_robot_the_others_are_still_counted():
    _, fleet = agree_with_monolithic(SINGLED_OUT.format(n=5), least=3)
    assert fleet.fleet.startswith("counted") and "4 agents" in fleet.fleet, fleet.fleet
    assert explicit_agrees(SINGLED_OUT.format(n=4), least=3)


def required_reach(supervisor: Any) -> set[Any]:
    """The states of an explicit supervisor's plant the requirements let the system reach."""
    reached, stack = {supervisor.states[0]}, [supervisor.states[0]]
    while stack:
        state = stack.pop()
        for event, target in supervisor.transitions[state]:
            if target not in reached and (not event.controllable or supervisor.required_ok[(state, event)]):
                reached.add(target)
                stack.append(target)
    return reached


def explicit_agrees(text: str, least: int) -> bool:
    """The counted supervisor of ``text`` allows what the explicit one does, state by state: in
    every state of the plant when it searches all states, in those the requirements reach when
    it searches those only (the default), holding in the others."""
    network = build_network(check_text(text).model)
    supervisor = synthesize_explicit(network).supervisor
    everywhere = synthesize_counted(network, SynthesisOptions(forward="never"), least=least)
    forward = synthesize_counted(network, least=least)
    assert forward.method == everywhere.method == "symmetric", forward.fleet
    reach = required_reach(supervisor)
    assert len(reach) < len(supervisor.states)  # some states only the plant reaches
    for state in supervisor.states:
        for event in network.events:
            expected = supervisor.allows(event, state)
            assert everywhere.supervisor.allows(event, state) == expected, event.name
            assert forward.supervisor.allows(event, state) == (expected and state in reach), event.name
        assert forward.supervisor.controlled(state) == (state in reach and state not in supervisor.bad)
    return True


def test_why_a_fleet_is_not_counted_names_the_requirement():
    fleet = synthesize_counted(build_network(check_text(SINGLED_OUT.format(n=3)).model), least=3)
    assert fleet.method == "symbolic"
    assert (
        "the requirements of 'bot2' differ from those of 'bot1' (requirement bot1.go needs !(bot2.top or bot3.top) "
        "has no counterpart for 'bot2')"
    ) in fleet.fleet


def test_an_instance_of_another_group_cannot_be_singled_out():
    text = (
        SINGLED_OUT.format(n=3)
        .replace("r != bot1", "r != Lift")
        .replace(
            "    for r in bot", "    component Lift { behaviour { initial marked state up { } } }\n    for r in bot"
        )
    )
    result = check_text(text)
    assert result.model is None and any("stands for an instance" in d.message for d in result.diagnostics), (
        result.render()
    )


def test_two_arrays_of_alike_robots_are_two_kinds_counted_apart() -> None:
    """Eastbound and southbound robots (two instance arrays) have the same automaton; their
    requirements name their own kind as a whole and the other kind at the crossings. Before:
    one group of all six, 'a condition names some agents of east and not the others', and
    monolithic synthesis. Now two groups, counted, and the monolithic supervisor."""
    from families import crossing

    _, fleet = agree_with_monolithic(crossing(6), least=3)
    symmetry = fleet.fleet
    assert symmetry.startswith("counted (east: 3 agents") and "south: 3 agents" in symmetry


@pytest.mark.parametrize(
    ("written", "shown"),
    [
        ("count(q in bot: q.busy) <= 1", "count(q in bot: q.busy) <= 1"),
        ("count(r in bot: r.busy and Door.closed) >= 1", "count(q in bot: q.busy and Door.closed) >= 1"),
        ("count(bot1.busy, bot2.busy, bot3.busy) <= 1", "count(bot1.busy, bot2.busy, bot3.busy) <= 1"),  # written out
        ("count(q in bot: q.busy or bot1.idle) <= 1", "count(bot1.busy or bot1.idle, bot2.busy or bot1.idle, "
         "bot3.busy or bot1.idle) <= 1"),  # not the same of each: shown term by term
        ("!any(q in bot: q.busy or q.idle) and Door.closed", "!any(q in bot: q.busy or q.idle) and Door.closed"),
        ("all(q in bot: q.idle) or any(q in bot: q.busy)", "all(q in bot: q.idle) or any(q in bot: q.busy)"),
        ("any(q in bot: q.busy and bot2.idle)", "(bot1.busy and bot2.idle) or (bot2.busy and bot2.idle) or "
         "(bot3.busy and bot2.idle)"),  # not the same of each (bot2 reads itself twice): shown term by term
        ("bot1.busy or bot2.busy or bot3.busy", "bot1.busy or bot2.busy or bot3.busy"),  # written out
    ],
)
def test_a_count_over_a_group_is_shown_as_written_over_the_group(written: str, shown: str) -> None:
    text = FLEET.replace("requirement bot1.go needs Door.closed", f"requirement bot1.go needs {written}")
    model = check_text(text).model
    assert model is not None
    assert render(model.requirements[-1].condition) == shown


def test_an_added_condition_over_the_lift_fleet_does_not_grow_with_the_fleet() -> None:
    """Before: 'count(bot1.riding_down, bot2.riding_down, ...)' in every added condition, so that
    each grew with the fleet (the issue measured 7 KB at 4 robots, 1.16 MB at 16 for its lift)."""
    from families import lift

    sizes = []
    for n in (3, 6):
        result = synthesize_model(check_text(lift(n)).model)
        assert result.method == "symmetric"
        sizes.append(max(len(render(g.added)) for g in result.added_guards))
        go = next(render(g.added) for g in result.added_guards if g.event.name == "bot1.go")
        # not split on where the lift is when each part says the same (it was
        # "(Lift.ground or Lift.top) and X or (Lift.rising or Lift.sinking) and X"), nor on
        # whether a robot rides up, which where the system goes leaves at most one riding down
        # (it was "... < 2 or any(q in bot: q.riding_up)")
        assert go == "bot1.depot => (count(q in bot: q.riding_down) < 2)"
    assert sizes[1] - sizes[0] < 20 and sizes[1] < 500  # (`any(q in bot: q.depot)` at 3, `count(...) >= 4` at 6)


def test_the_lanes_added_condition_keeps_places_empty_one_any_a_kind_and_splits_on_no_count() -> None:
    """The benchmark's lane (benchmarks/fleet_worlds.py, three robots of each kind): a robot at
    home may go only while no robot of its own kind comes back through the street and none of
    the other kind goes into it. Before: a case for how many robots of the other kind are at
    home ('count(q in east: q.home) < 3 and ... or count(q in east: q.home) = 3 and ...'), each
    place a '!any' of its own: 18,127 characters at 6 robots, 32,376 at 8, 164,852 at 16."""
    import fleet_worlds

    _, text = fleet_worlds.lane(3)
    result = synthesize_model(check_text(text).model)
    assert result.method == "symmetric"
    go = next(render(g.added) for g in result.added_guards if g.event.name == "east1.go")
    assert "count(" not in go
    home, rest = go.split(" and (east1.at_6 => ", 1)
    assert home.startswith("(east1.home => (!any(q in east: q.to_7 or q.at_7 or ")
    # in each case one '!any' for each kind: the places it keeps empty, however many
    assert home.count("!any(q in east: ") == home.count("!any(q in west: ") == 1
    assert rest.count("!any(q in east: ") == rest.count("!any(q in west: ") == 1
    assert len(go) < 1500


def test_a_quantifier_that_does_not_read_the_for_variable_is_resolved_once_for_the_fleet() -> None:
    """`for r in bot { requirement r.dock needs !any(q in bot: q.charging) }`: one expression for
    every r, so that the warehouse's requirements grow linearly with the fleet. Before: each r had
    its own copy, and from about 180 robots `check` refused the warehouse ('expand to more than
    500,000 expression nodes'); at 150 it took 10.5 s here."""
    text = (Path(__file__).resolve().parent.parent / "examples/warehouse.rscd").read_text()
    model = check_text(text.replace("component bot[3]", "component bot[500]")).model
    assert model is not None  # no limit met
    docks = [r.condition for r in model.requirements if r.communications[0].name.endswith(".dock")]
    assert len(docks) == 500 and all(d.operand is docks[0].operand for d in docks)
    # one that reads r is r's own: `(r.depot or r.ready) => !any(...)`: the any is shared, the
    # whole is not
    gos = [r.condition for r in model.requirements if r.communications[0].name.endswith(".go")]
    depot = [
        g for g in gos
        if isinstance(g.left, m.Binary) and isinstance(g.left.left, m.StateRef) and g.left.left.state.name == "depot"
    ]
    first, second = depot[0], depot[1]
    assert first is not second and first.right.operand is second.right.operand


HOME_NOTE = (
    "R0 .. R{last} differ in their marked states (homes of their own); synthesis counted them all the same, as from "
    "every state the requirements reach the fleet can get back to where it started, with every robot home"
)


@pytest.mark.parametrize("n", [3, 4, 5])
def test_robots_with_homes_of_their_own_are_counted_where_the_fleet_can_always_get_back_to_its_start(n: int) -> None:
    """The ring where each robot must get back to its own start (copies by hand, each marked at
    its own zone): counted, with the monolithic method's supervisor, and synthesize says how."""
    _, fleet = agree_with_monolithic(families.ring_homes(n), least=3)
    assert fleet.fleet_note == HOME_NOTE.format(last=n - 1)
    assert "homes of their own" in fleet.fleet
    result = synthesize_model(check_text(families.ring_homes(n)).model)
    assert (result.method, result.fleet_note) == ("symmetric", HOME_NOTE.format(last=n - 1))


@pytest.mark.parametrize("family", ["ring", "ring_instances", "warehouse_instances"])
def test_copies_with_the_same_marked_states_are_counted_as_copies_not_as_robots_with_homes(family: str) -> None:
    """Only copies that differ in their marked states take the way of homes: a fleet of plain
    copies is counted once, with its own marking, and no note about homes."""
    network = build_network(check_text(families.FLEETS[family](3)).model)
    assert not with_homes(network, 2)
    result = synthesize_counted(network)
    assert result.method == "symmetric" and result.fleet_note == ""
    assert "homes" not in result.fleet
    assert with_homes(build_network(check_text(families.ring_homes(3)).model), 2)


def test_robots_with_homes_agree_with_explicit_synthesis_state_by_state() -> None:
    network = build_network(check_text(families.ring_homes(3)).model)
    explicit = synthesize_explicit(network)
    fleet = synthesize_counted(network)
    assert fleet.method == "symmetric"
    supervisor = explicit.supervisor
    for state in supervisor.controlled_states():
        assert [fleet.allows(e, state) for e in network.events] == [supervisor.allows(e, state) for e in network.events]


HOMES_AND_A_DEAD_END = """robot Parking {
    component R0 {
        incoming message go0 with type: none
        behaviour {
            initial marked state home { on request to go0 goto out }
            state out { on request to go0 goto parked }
            marked state parked { on request to go0 goto home }
        }
    }
    component R1 {
        incoming message go1 with type: none
        behaviour {
            initial marked state home { on request to go1 goto out }
            state out { on request to go1 goto parked }
            state parked { on request to go1 goto home }
        }
    }
    component R2 {
        incoming message go2 with type: none
        behaviour {
            initial marked state home { on request to go2 goto out }
            state out { on request to go2 goto parked }
            state parked { on request to go2 goto home }
        }
    }
    requirement go0 needs !R0.parked
    requirement go1 needs !R1.parked
    requirement go2 needs !R2.parked
}
"""


def test_robots_with_homes_that_need_a_supervisor_are_synthesized_monolithically() -> None:
    """Only R0 may rest where no robot is let back from: counted, no state that has left the
    start gets back to it, so which robot is where matters and the monolithic method decides (R0 may
    go, R1 and R2 may not)."""
    network = build_network(check_text(HOMES_AND_A_DEAD_END).model)
    result = synthesize_counted(network)
    assert result.method == "symbolic"
    assert result.fleet_note == (
        "R0 .. R2 are copies of each other, but synthesis did not count them: they differ in their marked states "
        "(each may rest in a place of its own), and counted, the fleet cannot always get back to where it started, "
        "so which robot is where matters; the supervisor is the monolithic method's (exact; slower on large fleets)"
    )
    explicit = synthesize_explicit(network)
    start = next(iter(explicit.supervisor.controlled_states()))
    assert [e.name for e in network.events if result.allows(e, start)] == ["go0"]
    for state in explicit.supervisor.controlled_states():
        for event in network.events:
            assert result.allows(event, state) == explicit.allows(event, state), event.name


def test_robots_with_homes_that_do_not_start_home_are_synthesized_monolithically() -> None:
    """Three robots on a ring of three zones, each to rest in the next zone: none can move, so
    none gets home and there is no supervisor, although the fleet is always at its start."""
    network = build_network(check_text(families.ring_of(3, [0, 1, 2], [1, 2, 0])).model)
    result = synthesize_counted(network)
    assert (result.method, result.ok) == ("symbolic", False)
    assert "not every component starts in a marked state" in result.fleet_note


def test_the_generated_module_writes_each_long_condition_once_and_decides_as_before() -> None:
    """Each robot's guard read every count over the fleet written out, so the module grew with
    the square of the fleet (lift: 89 KB at 8 robots, 261 KB at 16); a long condition is now a
    method of its own, called where it stands (evaluated there, as it was: the same reads)."""
    from families import lift
    from module_check import module_agrees
    from robosc.api import supervisor_module
    from robosc.synthesis.symbolic import synthesize_monolithic

    texts = {n: supervisor_module(synthesize_model(check_text(lift(n)).model)) for n in (5, 10)}
    assert "sum((" not in texts[10] and "rt.tally(" in texts[10]  # each count a lookup in one tally
    assert len(texts[10]) < 2.1 * len(texts[5])  # (it was 2.5 times from 4 to 8 robots)
    assert "self._part0()" in texts[10] and "    def _part0(self):" in texts[10]
    network = build_network(check_text(lift(3)).model)
    counted = synthesize_counted(network)
    assert counted.method == "symmetric"
    assert module_agrees(counted, synthesize_monolithic(network), runs=2, steps=40)


def _modules(text: str, monkeypatch: pytest.MonkeyPatch) -> tuple[Any, Any]:
    """The fleet's generated module as robosc makes it (counts read from tallies) and, as the
    reference, with every count written out as a sum over the robots."""
    from robosc.codegen.plan import _Planner, plan
    from robosc.debug.simulator import load_module

    result = synthesize_model(check_text(text).model)
    tallied = load_module(plan(result))
    with monkeypatch.context() as patch:
        patch.setattr(_Planner, "guard_py", _Planner.py)
        summed = load_module(plan(result))
    return tallied, summed


def _robot_reads(module: Any) -> tuple[Any, list[str]]:
    """A supervisor of ``module`` that notes each read of a robot's field (``bot1``...)."""
    reads: list[str] = []

    class Counting(module.Robot):  # type: ignore[name-defined,misc]
        def __getattribute__(self, name: str) -> Any:
            if "_bot" in name and name[0] == "a":
                reads.append(name)
            return object.__getattribute__(self, name)

    return Counting(seed=0, warn=lambda _: None, wait_for_data=False, confirmed=True), reads


def test_a_count_over_the_fleet_is_read_from_one_tally_per_evaluation(monkeypatch: pytest.MonkeyPatch) -> None:
    """Each robot's guard summed the counts over the whole fleet, so one evaluation of what is
    allowed read every robot's location once per robot (quadratic: the lift's 16 robots, 2,048
    reads); the fields are now tallied once per evaluation and a count is one lookup per value."""
    reads = {}
    for n in (4, 8):
        tallied, summed = _modules(families.lift(n), monkeypatch)
        for name, module in (("tallied", tallied), ("summed", summed)):
            robot, seen = _robot_reads(module)
            robot._allowed()
            reads[name, n] = len(seen)
    assert reads["tallied", 8] <= 2.2 * reads["tallied", 4]  # linear in the fleet: its own guards and one tally
    assert reads["summed", 8] > 3 * reads["summed", 4]  # the reference: each count read per robot
    assert reads["tallied", 8] < reads["summed", 8] / 2


OTHERS = """robot Others {
    component bot[5] initial a, a, b, c, a {
        incoming message go with type: none
        incoming message back with type: none
        behaviour {
            marked state a { on request to go goto b }
            state b { on request to go goto c }
            marked state c { on request to back goto a }
        }
    }
    for r in bot {
        requirement r.go needs !any(q in bot: q != r and q.b) and count(q in bot: q != r and q != bot2 and (q.b or q.c)) < 3
        requirement r.back needs any(q in bot: q.a)
    }
}
"""


@pytest.mark.parametrize("fleet", ["lift", "others"])
def test_counts_read_from_tallies_decide_as_counts_summed_in_every_state(
    fleet: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Every combination of where the robots (and the lift) are: the same events allowed; and
    with one robot's place unconfirmed, the same events allowed wherever it may be. The
    others: counts and quantifiers that leave the robot itself, and one singled out, out."""
    import itertools

    tallied, summed = _modules(families.lift(4) if fleet == "lift" else OTHERS, monkeypatch)
    fields = [f for f in tallied.Robot.FIELDS if f[2] == "automata" and len(f[4]) > 1]
    robots = [tallied.Robot(seed=0, warn=lambda _: None, wait_for_data=False) for _ in range(2)]
    references = [summed.Robot(seed=0, warn=lambda _: None, wait_for_data=False) for _ in range(2)]
    compared = 0
    for values in itertools.product(*(f[4] for f in fields)):
        for robot, reference in zip(robots, references, strict=True):
            for (attribute, *_), value in zip(fields, values, strict=True):
                setattr(robot, attribute, value)
                setattr(reference, attribute, value)
        mine = sorted(p.__name__ for p in robots[0]._allowed())
        assert mine == sorted(p.__name__ for p in references[0]._allowed()), values
        compared += 1
        if compared % 17 == 0:  # a robot's place unconfirmed: allowed wherever it may be
            bot = next(f for f in fields if "_bot2" in f[0])
            for robot in (robots[1], references[1]):
                robot._dirty = True
                robot.unconfirm({bot[0]: bot[4]}, "a test")
            assert sorted(p.__name__ for p in robots[1]._current()) == sorted(
                p.__name__ for p in references[1]._current()
            ), values
            for robot in (robots[1], references[1]):
                robot.reset(True)
    assert compared >= 243
    assert hasattr(tallied.Robot, "_T0") and not hasattr(summed.Robot, "_T0")  # the two ways were compared


def test_the_fleet_how_to_shows_the_zero_time_warehouse_unsafe_and_the_bundled_one_waiting(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """docs/howto/fleet.md's example runs and prints what the page shows: right after bot1.go from
    the aisle's first cell, the zero-time supervisor lets bot2 into that cell and the door close
    on bot1; the bundled warehouse's waits for bot1's arrival."""
    import re

    root = Path(__file__).resolve().parent.parent
    page = (root / "docs/howto/fleet.md").read_text()
    code = re.findall(r"```python\n(.*?)```", page, re.S)[0]
    shown = re.findall(r"prints\n\n```text\n(.*?)```", page, re.S)[0]
    monkeypatch.chdir(root)
    exec(compile(code, "docs/howto/fleet.md", "exec"), {})
    printed = capsys.readouterr().out
    assert printed == shown
    zero, timed = printed.splitlines()
    assert "bot2.go" in zero and "close_door" in zero
    assert "bot2.go" not in timed and "close_door" not in timed and "bot1.go" not in timed


@pytest.mark.parametrize("ros", [1, 2])
def test_the_coordinator_readme_says_what_each_driver_provides(ros: int, tmp_path: Path) -> None:
    """The generated package's README lists, per robot, every topic and service the driver must
    provide with its type and QoS, and which answers the model expects after each command."""
    from robosc.api import load_model, plan_supervisor
    from robosc.codegen.ros import generate

    root = Path(__file__).resolve().parent.parent
    generate(plan_supervisor(synthesize_model(load_model(root / "examples/warehouse.rscd"))), ros, "controller", tmp_path)
    text = (tmp_path / "README.md").read_text()
    empty, trigger = ("std_msgs/Empty", "std_srvs/Trigger") if ros == 1 else ("std_msgs/msg/Empty", "std_srvs/srv/Trigger")
    qos = "TCPROS, queue_size 10" if ros == 1 else "reliable, volatile, keep last 10"
    assert (
        f"| `bot2/go` | `{empty}` | node -> driver | {qos} | subscribe; each message is one command; after it, "
        "publish `bot2/arrived` or `bot2/stopped`, once, when that happens |" in text
    )
    assert f"| `bot3/charged` | `{empty}` | driver -> node | {qos} | publish it once each time it happens" in text
    assert f"| `robosc/report/Door` | `{trigger}` | node -> driver | service | answer `success: true`" in text
    assert "one of `closed`, `opening`, `open`, `closing`" in text
    for name in ("open_door", "close_door", "door_opened", "door_closed", *(f"bot{i}/{c}" for i in (1, 2, 3)
                 for c in ("go", "dock", "arrived", "stopped", "charged"))):
        assert f"| `{name}` |" in text, name


DEEPER = ("out2", "to_out3", "out3", "stopped_out3", "to_shelf", "shelf", "stopped_shelf", "to_back3", "back3",
          "stopped_back3", "to_back2", "back2", "stopped_back2")


@pytest.mark.parametrize("robots", [3, 4])
def test_a_condition_that_keeps_robots_out_of_some_places_is_written_as_one_any(robots: int) -> None:
    """The warehouse: a robot beside the doorway enters the aisle only while no robot is deeper
    in it than its first cell (which the requirement keeps free). Taken apart counter by counter
    that was a case for each way of sharing the other robots out among the depot, the charger
    and the rest (1,547 characters at 3 robots, 5,611 at 8: `bot1.out0 => ((count(q in bot:
    q.depot) = 0 and ((count(q in bot: q.charging) = 0 and ...`); it is one `!any` of the places
    kept empty, the same for any number of robots, and the generated module that reads it
    decides as the monolithic supervisor."""
    from module_check import module_agrees

    text = (Path(__file__).resolve().parent.parent / "examples/warehouse.rscd").read_text()
    network = build_network(check_text(text.replace("component bot[3]", f"component bot[{robots}]")).model)
    counted = synthesize_counted(network)
    go = next(g for g in counted.guards if g.event.name == "bot1.go")
    assert go.added is not None
    assert render(go.added) == "bot1.out0 => !any(q in bot: " + " or ".join(f"q.{s}" for s in DEEPER) + ")"
    if robots == 3:  # the monolithic supervisor of four robots and the person takes a minute
        assert module_agrees(counted, synthesize_monolithic(network), runs=4, steps=60) == 240


def test_a_users_own_count_is_shown_as_written_and_a_made_one_as_an_any() -> None:
    """`count(q in bot: X) = 0` that synthesis made reads `!any(q in bot: X)`; the same written
    in a requirement is shown as it was written."""
    text = """
robot Shelf {
    component bot[3] {
        incoming message go with type: none
        behaviour {
            initial marked state depot { on request to go goto out1 }
            state out1 { on request to go goto shelf }
            state shelf { on request to go goto back1 }
            state back1 { on request to go goto depot }
        }
    }
    for r in bot {
        requirement r.go needs r.depot => (count(q in bot: q.out1 or q.back1) = 0)
        requirement r.go needs r.out1 => !any(q in bot: q.shelf)
        requirement r.go needs r.shelf => !any(q in bot: q.out1 or q.back1)
    }
}
"""
    counted = synthesize_counted(build_network(check_text(text).model))
    go = next(g for g in counted.guards if g.event.name == "bot1.go")
    assert go.added is not None and go.required is not None
    assert render(go.added) == "bot1.depot => !any(q in bot: q.shelf)"
    assert "bot1.depot => (count(q in bot: q.out1 or q.back1) = 0)" in render(go.required)


@pytest.mark.parametrize("fleet", ["counted", "monolithic"])
def test_an_explanation_ends_where_the_deadlock_is_without_events_that_do_not_matter(fleet: str) -> None:
    """Why the warehouse's bot1.go is restricted: after it, bot1 arrives in the aisle's first
    cell, face to face with bot2, and nobody can move. Before, the run went on with the person's
    detector reporting the depot (person_cell, which can happen at any time: the search looked
    for a state with no uncontrollable way on) and the deadlock was told with the person there."""
    text = (Path(__file__).resolve().parent.parent / "examples/warehouse.rscd").read_text()
    result = synthesize_model(check_text(text).model, options=SynthesisOptions(fleet=fleet))
    why = restriction(result, "bot1.go")
    assert why is not None
    # bot1 arrives in out1, or (the monolithic method may follow it) stops on its way there
    (step,) = why.consequence.path
    assert step.event.name in ("bot1.arrived", "bot1.stopped") and step.state.endswith("Person.cell = away")
    cell = "out1" if step.event.name == "bot1.arrived" else "stopped_out1"
    stuck = rf"Person.cell = away\] \(stuck outside a marked state: bot1.{cell}, bot[23].out2\)"
    assert re.search(stuck, why.consequence.reason), why.consequence.reason


def test_robots_whose_requirements_are_the_first_robots_with_the_two_swapped_are_not_translated_again(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The check that every robot's requirements say of it what the first robot's say of the
    first translates the first robot's only when the others' are its own with the two robots
    swapped (a fleet's requirements name every robot: translating each took 118 s for 500);
    a robot whose requirement differs in one place is still found out and translated."""
    from robosc.synthesis.counting import groups, translate

    translated: list[str] = []
    about = translate.Translator.about

    def counting(self: Any, e: m.Expr, me: Any, what: Any, span: Any = None) -> m.Expr:
        if me is not None:
            translated.append(me.component.name)
        return about(self, e, me, what, span)

    monkeypatch.setattr(translate.Translator, "about", counting)
    text = families.ring(4)
    counted(build_network(check_text(text).model))
    assert set(translated) == {"R0"}  # the three others swapped with R0 say the same

    # R2 asks R3 one thing of the next zone that it asks no other robot: the fleet is not counted
    line = next(x for x in text.splitlines() if "requirement go2 " in x)
    changed = text.replace(line, line.replace("R3.moving0 or R3.moving1", "R3.moving0 or R3.at3", 1))
    assert changed != text
    translated.clear()
    with pytest.raises(groups.NotSymmetric):
        counted(build_network(check_text(changed).model))
    assert "R2" in translated


def test_copies_that_cannot_be_counted_look_for_bad_states_where_the_requirements_reach() -> None:
    """Robots with homes of their own are copies synthesized monolithically; by default synthesis
    looks for bad states only among the states the requirements reach, as on a counted fleet (a
    ring of 10 such robots: 61 s before, 18 s), and allows the same events where the fleet goes.
    Asked for the monolithic method, it looks everywhere (the reference)."""
    network = build_network(check_text(families.ring_of(6, [0, 2, 4], [1, 3, 5])).model)  # (not home at the start)
    fleet = synthesize_counted(network)
    first = synthesize_monolithic(network, SynthesisOptions(forward="first"))
    everywhere = synthesize_monolithic(network)
    assert "monolithic" in fleet.fleet
    assert fleet.effort["preimages"] == first.effort["preimages"]
    assert first.effort["preimages"] < everywhere.effort["preimages"]
    assert fleet.reachable_states == everywhere.reachable_states
    for state in synthesize_explicit(network).supervisor.controlled_states():
        for event in network.events:
            assert fleet.allows(event, state) == everywhere.allows(event, state), event.name


def test_a_fleet_of_another_size_without_editing_the_model(tmp_path: Path) -> None:
    """--instances bot=N (sizes={"bot": N}) makes `component bot[3]` N instances, checked and
    synthesized as if written so; a name that is no group, an `initial` list of another length
    and a malformed NAME=N are refused, saying why."""
    from click.testing import CliRunner

    from robosc.api import check_file, load_model, synthesize_file
    from robosc.cli.main import cli

    root = Path(__file__).resolve().parent.parent
    model = root / "docs/models/fleet.rscd"
    five = load_model(model, sizes={"bot": 5})
    assert [c.name for c in five.groups["bot"]] == ["bot1", "bot2", "bot3", "bot4", "bot5"]
    assert [c.name for c in load_model(model).groups["bot"]] == ["bot1", "bot2", "bot3"]
    assert "5 agents" in synthesize_file(model, sizes={"bot": 5}).fleet
    written = tmp_path / "five.rscd"
    written.write_text(model.read_text().replace("component bot[3]", "component bot[5]"))
    assert load_model(written).groups.keys() == five.groups.keys()
    assert [c.name for c in load_model(written).components] == [c.name for c in five.components]

    unknown = check_file(model, sizes={"robot": 4})
    assert not unknown.ok
    assert "--instances robot=...: 'Cell' declares no component 'robot' with instances" in unknown.render()
    assert "its groups of instances: 'bot'" in unknown.render()

    starts = tmp_path / "starts.rscd"
    starts.write_text(model.read_text().replace('namespace "/cell" {', 'namespace "/cell" initial free, free, free {'))
    assert load_model(starts).name == "Cell"
    mismatch = check_file(starts, sizes={"bot": 4})
    assert "3 initial states for 4 instances of 'bot' (--instances bot=4): give one per instance" in mismatch.render()

    runner = CliRunner()
    done = runner.invoke(cli, ["check", str(model), "--instances", "bot=2"])
    assert done.exit_code == 0, done.output
    done = runner.invoke(cli, ["check", str(model), "--instances", "bot2"])
    assert done.exit_code == 2 and "'bot2' is not NAME=N" in done.output
