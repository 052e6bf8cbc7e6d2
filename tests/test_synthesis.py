"""Synthesis on textbook cases with known answers, failures with explanations, and the examples."""

from __future__ import annotations

import json

import pytest

from conftest import EXAMPLES
from robosc.api import check_text, synthesize_model
from robosc.cli.main import main
from robosc.language.render import render
from robosc.plant import build_network
from robosc.synthesis import synthesize, synthesize_explicit
from robosc.synthesis.restrictions import restriction
from robosc.synthesis.state import NetworkState, initial_state

# Ramadge & Wonham's small factory: machine 1 makes a part into a one-slot buffer,
# machine 2 takes it out. A part made while the buffer is full overflows it.
SMALL_FACTORY = """
robot SmallFactory {
    interface trigger use Trigger from std_srvs
    component M1 {
        service make with request: none, response: none links trigger
    }
    component M2 {
        service take with request: none, response: none links trigger
    }
    component Buffer {
        behaviour {
            initial marked state empty {
                on response from make goto full
            }
            marked state full {
                on request to take goto empty
                on response from make goto overflow
            }
            state overflow {
                on request to clear goto empty
            }
        }
    }
    // Clearing an overflow needs an operator, who never comes: an overflow blocks.
    component Operator {
        service clear with request: none, response: none links trigger
    }
    requirement clear needs Buffer.empty
}
"""


def load(text: str):
    result = check_text(text)
    assert result.model is not None, result.render()
    return result.model


def test_small_factory_known_supervisor():
    result = synthesize_model(load(SMALL_FACTORY))
    assert result.ok
    # Known answer: machine 1 may start only when the buffer is empty; machine 2 only needs
    # the plant (it takes from a full buffer), so synthesis adds nothing there.
    assert render(result.guard("make.c_trigger").added) == "Buffer.empty"
    assert result.guard("take.c_trigger").added is None


def test_small_factory_agrees_with_explicit_synthesis():
    network = build_network(load(SMALL_FACTORY))
    symbolic, explicit = synthesize(network), synthesize_explicit(network)
    assert symbolic.ok and explicit.ok
    assert symbolic.reachable_states == explicit.reachable_states
    supervisor = explicit.supervisor
    for state in supervisor.states:
        for event in network.events:
            assert symbolic.allows(event, state) == explicit.allows(event, state)


UNAVOIDABLE = """
robot Unavoidable {
    component Sensor {
        outgoing message detect with type: none
        outgoing message beep with type: none
        behaviour {
            initial marked state quiet {
                on response from detect goto alert
            }
            marked state alert {
                on response from beep goto quiet
            }
        }
    }
    requirement beep needs Sensor.quiet
}
"""


def test_failure_names_the_requirement_and_the_shortest_path():
    result = synthesize_model(load(UNAVOIDABLE))
    assert not result.ok
    explanation = result.explanation
    assert [step.event.name for step in explanation.path] == ["detect"]
    assert explanation.path[0].state == "Sensor.alert"
    assert "uncontrollable event 'beep'" in explanation.reason
    assert "requirement beep needs Sensor.quiet" in explanation.reason
    assert explanation.initial_state == "Sensor.quiet"


def test_failure_in_the_initial_state_has_an_empty_path():
    result = synthesize_model(load(UNAVOIDABLE.replace("needs Sensor.quiet", "needs Sensor.alert")))
    assert not result.ok and result.explanation.path == ()
    assert "requirement beep needs Sensor.alert" in result.explanation.reason


BLOCKING = """
robot Blocking {
    interface trigger use Trigger from std_srvs
    component Robot {
        outgoing message crash with type: none
        service repair with request: none, response: none links trigger
        behaviour {
            initial marked state working {
                on response from crash goto broken
            }
            state broken {
                on request to repair goto working
            }
        }
    }
    requirement repair needs Robot.working
}
"""


def test_blocking_failure_is_explained():
    result = synthesize_model(load(BLOCKING))
    assert not result.ok
    assert [step.event.name for step in result.explanation.path] == ["crash"]
    assert "would block" in result.explanation.reason
    assert "Robot.broken" in result.explanation.reason


def test_responsiveness_lets_uncontrollable_events_happen_in_every_state():
    # Motor mentions 'overheat' only in on_state, but components never block uncontrollable
    # events (SEMANTICS.md 1): overheat can come in 'off' too. Since overheat needs the door
    # closed, the supervisor may never open the door.
    text = """
    robot Pump {
        interface trigger use Trigger from std_srvs
        component Door {
            incoming message open with type: none
            incoming message close with type: none
            behaviour {
                initial marked state closed { on request to open goto opened }
                marked state opened { on request to close goto closed }
            }
        }
        component Motor {
            service run with request: none, response: none links trigger
            outgoing message overheat with type: none
            behaviour {
                initial marked state off {
                    on request to run goto on_state
                }
                marked state on_state {
                    on response from overheat
                    on response from run goto off
                }
            }
        }
        requirement overheat needs Door.closed
    }
    """
    result = synthesize_model(load(text))
    assert result.ok
    assert render(result.guard("open").added) == "false"
    assert result.guard("close").added is None and result.guard("run.c_trigger").added is None


@pytest.mark.parametrize("n", [2, 3, 4])
def test_dining_philosophers_guards_prevent_the_deadlock(n: int):
    from families import philosophers
    from test_synthesis_agreement import assert_readable_guards_are_exact

    network = build_network(load(philosophers(n)))
    symbolic, explicit = synthesize(network), synthesize_explicit(network)
    assert symbolic.ok and symbolic.reachable_states == explicit.reachable_states
    assert {g.event.name for g in symbolic.added_guards} == {f"take_left{i}" for i in range(n)}
    assert_readable_guards_are_exact(symbolic, explicit.supervisor)
    if n == 3:
        assert render(symbolic.guard("take_left1").added) == "P0.thinking or P2.thinking"


def test_transfer_line_guards():
    from families import transfer_line

    result = synthesize_model(load(transfer_line(4)))
    assert [(g.event.name, render(g.added)) for g in result.added_guards] == [
        ("work1.c_trigger", "B1.empty"),
        ("work2.c_trigger", "B2.empty"),
        ("work3.c_trigger", "B3.empty"),
    ]


@pytest.mark.parametrize("name", ["line_follower", "maze_solver", "pick_and_light"])
def test_examples_synthesize_and_agree(name: str):
    from robosc.api import load_model

    model = load_model(EXAMPLES / f"{name}.rscd")
    network = build_network(model)
    symbolic = synthesize(network)
    explicit = synthesize_explicit(network)
    assert symbolic.ok and explicit.ok
    assert symbolic.reachable_states == explicit.reachable_states > 0


def test_cli_synthesize_text_and_json(capsys):
    assert main(["synthesize", str(EXAMPLES / "maze_solver.rscd")]) == 0
    out = capsys.readouterr().out
    assert "supervisor for MazeSolver" in out and "128 reachable states" in out
    assert main(["synthesize", "--json", str(EXAMPLES / "maze_solver.rscd")]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["ok"] and data["reachable_states"] == 128
    movement = next(e for e in data["events"] if e["event"] == "movement")
    assert movement["required"].startswith("Platform.ready and ")


def test_cli_synthesize_failure_exits_one_with_explanation(tmp_path, capsys):
    model = tmp_path / "u.rscd"
    model.write_text(UNAVOIDABLE)
    assert main(["synthesize", str(model)]) == 1
    out = capsys.readouterr().out
    assert "synthesis failed" in out and "1. detect" in out and "requirement beep needs Sensor.quiet" in out
    assert main(["synthesize", "--json", str(model)]) == 1
    data = json.loads(capsys.readouterr().out)
    assert data["ok"] is False and data["explanation"]["path"][0]["event"] == "detect"


def test_cli_synthesize_model_error_exits_one(tmp_path, capsys):
    model = tmp_path / "bad.rscd"
    model.write_text("robot R { requirement x needs true }")
    assert main(["synthesize", str(model)]) == 1
    assert "unknown communication 'x'" in capsys.readouterr().err


def test_api_answers_whether_an_event_is_allowed():
    from robosc.api import synthesize_file

    result = synthesize_file(EXAMPLES / "maze_solver.rscd")
    wall_ahead = result.state({"Platform": "ready", "Distance.front": "wall_front"})
    assert result.allows("turn_left", wall_ahead)
    assert not result.allows("movement", wall_ahead)
    turning = result.state({"Platform": "turning", "Distance.front": "wall_front"})
    assert not result.allows("turn_left", turning)
    assert result.allows("rotate_done", turning)
    with pytest.raises(KeyError):
        result.state({"Platform": "flying"})
    with pytest.raises(KeyError):
        result.state({"Nobody": "x"})


def test_explicit_method_from_the_cli(capsys):
    assert main(["synthesize", "--explicit", "--json", str(EXAMPLES / "maze_solver.rscd")]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["method"] == "explicit" and data["reachable_states"] == 128


def test_show_network_lists_plants_and_requirements(capsys):
    assert main(["synthesize", "--show-network", str(EXAMPLES / "maze_solver.rscd")]) == 0
    out = capsys.readouterr().out
    assert "uncontrollable scan_front" in out and "component Platform:" in out
    assert "--turn_left--> turning" in out
    assert "turn_left only if Platform.ready and Distance.front = wall_front" in out


def test_cli_synthesize_a_library_is_a_usage_error(capsys):
    assert main(["synthesize", str(EXAMPLES / "emergency_stop.rscd")]) == 2
    assert "is a library; synthesis needs a robot" in capsys.readouterr().err


def test_piped_table_keeps_each_condition_on_one_line(capsys):
    assert main(["synthesize", str(EXAMPLES / "maze_solver.rscd")]) == 0
    out = capsys.readouterr().out
    assert "Platform.ready and Distance.front = wall_front" in out


# ---- why synthesis added a condition ---------------------------------------------------

GRAB = """
robot Grab {
    interface grab_srv use Trigger from std_srvs
    component Grabber {
        service grab with request: none, response: none links grab_srv
        incoming message wave with type: none
        behaviour {
            initial marked state idle {
                on request to grab goto grabbing
                on request to wave
            }
            state grabbing { on response from grab goto idle }
        }
    }
    requirement wave needs Grabber.grabbing and Grabber.idle
}
"""


def test_added_guard_is_explained_by_a_shortest_run_and_what_would_follow():
    result = synthesize_model(load(SMALL_FACTORY))
    why = restriction(result, "make.c_trigger")
    assert why is not None and not why.never
    assert [s.event.name for s in why.path] == ["make.c_trigger", "make.u_response", "make.c_reset"]
    assert why.state == "Buffer.full" and why.after == "make.wait, Buffer.full"
    assert [s.event.name for s in why.consequence.path] == ["make.u_response"]
    assert why.consequence.path[-1].state == "make.ready, Buffer.overflow"
    assert "would block" in why.consequence.reason and "Buffer.overflow" in why.consequence.reason
    # the run is one of the controlled system, and its last state really disables make
    state = result.state({"Buffer": "full"})
    assert result.controlled(state) and not result.allows("make.c_trigger", state)
    assert restriction(result, "take.c_trigger") is None  # nothing added to take


def test_event_synthesis_never_allows_is_a_warning_with_its_reason():
    from robosc.synthesis.warnings import synthesis_warnings

    result = synthesize_model(load(GRAB))
    why = restriction(result, "grab.c_trigger")
    assert why is not None and why.never and why.path == ()
    assert [s.event.name for s in why.consequence.path] == ["grab.u_error"]
    assert "stuck outside a marked state: Grabber.grabbing)" in why.consequence.reason
    assert why.consequence.reason.endswith(
        "Grabber stays in grabbing (waits for grab.u_response, which cannot happen here)"
    )
    found = {(d.code.value, d.span.line) for d in synthesis_warnings(result)}
    assert ("never-allowed", 5) in found  # the service's declaration
    assert ("never-holds", 15) in found  # Grabber.grabbing and Grabber.idle
    assert ("unreached-state", 12) in found  # grabbing: grab is never allowed
    assert all(d.severity.value == "warning" for d in synthesis_warnings(result))


def test_unreached_states_say_whether_the_supervisor_avoids_them():
    from robosc.synthesis.warnings import synthesis_warnings

    # the supervisor keeps the buffer from overflowing: that is what it is for, and it says so
    [avoided] = synthesis_warnings(synthesize_model(load(SMALL_FACTORY)))
    assert avoided.message == (
        "no controlled run reaches state 'Buffer.overflow': the supervisor keeps the robot out of it"
    )
    unreachable = SMALL_FACTORY.replace("on response from make goto overflow", "on response from make")
    [never] = synthesis_warnings(synthesize_model(load(unreachable)))
    assert never.message == "state 'Buffer.overflow' can never be reached: no run of the model leads there"


def test_exact_state_count_agrees_with_cudd_where_cudd_is_exact():
    import random

    from dd import cudd

    from robosc.synthesis.encoding import _minterms

    bdd = cudd.BDD()
    names = [f"v{i}" for i in range(8)]
    bdd.declare(*names)
    rng = random.Random(3)
    for _ in range(200):
        clauses = [
            " /\\ ".join(rng.choice(["", "~"]) + rng.choice(names) for _ in range(rng.randint(1, 4)))
            for _ in range(rng.randint(1, 4))
        ]
        u = bdd.add_expr(" \\/ ".join(f"({c})" for c in clauses))
        assert _minterms(bdd, u, len(names)) == int(bdd.count(u, nvars=len(names)))


def test_an_action_no_component_cancels_is_never_cancelled_and_draws_no_warning() -> None:
    """A battery dock with no 'on cancel to dock' (before: 'dock.c_cancel' never allowed, with
    the condition '!Base.needs_charge' the user never wrote); with one, the supervisor cancels
    a running dock exactly when its requirement stops holding, as before."""
    from pathlib import Path

    from robosc.synthesis.warnings import synthesis_warnings

    text = (Path(__file__).parent / "network" / "s1_action_never_cancelled.rscd").read_text()
    model = check_text(text).model
    assert model is not None
    result = synthesize_model(model)
    assert result.ok
    assert [g.event.name for g in result.guards] == ["dock.c_trigger", "dock.c_reset"]
    assert synthesis_warnings(result) == []
    cancelling = text.replace(
        "on error from dock goto needs_charge", "on error from dock goto needs_charge\n on cancel to dock goto roaming"
    )
    model = check_text(cancelling).model
    assert model is not None
    result = synthesize_model(model)
    cancel = result.guard("dock.c_cancel")
    assert cancel.required is not None and render(cancel.required) == "!Base.needs_charge"


def test_the_explanation_names_the_fix_where_it_goes() -> None:
    """The grabber of the original's tutorial has no 'on error from grab': grab is never
    allowed, and the explanation, the warning and the editor's hover name the transition to
    add and the state it goes in (before: "change the model so that this cannot happen")."""
    from robosc.editor.hover import guard_notes
    from robosc.synthesis.warnings import synthesis_warnings

    result = synthesize_model(load(GRAB))
    why = restriction(result, "grab.c_trigger")
    assert why is not None
    [fix] = why.consequence.fixes
    assert fix.text.startswith("add 'on error from grab' to state grabbing of Grabber: grab can end with an error")
    assert fix.span is not None and (fix.span.line, fix.span.column) == (12, 13)  # state grabbing
    [never] = [w for w in synthesis_warnings(result) if w.code.value == "never-allowed"]
    assert never.hint is not None and never.hint.startswith("fix: add 'on error from grab' to state grabbing")
    assert never.hint.endswith(":12:13)")
    assert "fix: add 'on error from grab'" in "\n".join(guard_notes(result)["grab"])
    # with the transition added, grab is allowed and nothing is left to fix
    fixed = GRAB.replace("state grabbing { on response from grab goto idle }",
                         "state grabbing { on response from grab goto idle on error from grab goto idle }")
    assert synthesize_model(load(fixed)).guard("grab.c_trigger").added is None


def test_a_requirement_that_shuts_the_only_way_out_is_named() -> None:
    door = """
robot Doors {
    component Door {
        incoming message open with type: none
        incoming message close with type: none
        behaviour {
            initial marked state closed { on request to open goto opened }
            state opened { on request to close goto closed }
        }
    }
    requirement close needs Door.closed
}
"""
    why = restriction(synthesize_model(load(door)), "open")
    assert why is not None and why.never
    [fix] = why.consequence.fixes
    assert fix.text == (
        "requirement close needs Door.closed shuts Door's only way out of opened here: allow close in this "
        "state, or keep the robot out of it"
    )
    assert fix.span is not None and fix.span.line == 11


def test_only_components_that_are_really_stuck_are_blamed() -> None:
    """A component waiting for an uncontrollable event that can happen is not stuck (before:
    "Detector stays in seeing (waits for lost)")."""
    detector = """
    component Detector {
        outgoing message seen with type: none
        outgoing message lost with type: none
        behaviour {
            initial marked state searching { on response from seen goto seeing }
            state seeing { on response from lost goto searching }
        }
    }
    requirement wave"""
    why = restriction(synthesize_model(load(GRAB.replace("\n    requirement wave", detector, 1))), "grab.c_trigger")
    assert why is not None
    assert "Grabber stays in grabbing" in why.consequence.reason
    assert "Detector stays" not in why.consequence.reason


def test_a_missing_error_transition_is_named_before_the_requirements_it_leaves_shut(tmp_path) -> None:
    """The shelf picker without 'on error from unload' (as it was once written): the fix is
    the missing transition in Tray.emptying, not the requirements that then keep Base put."""
    text = (EXAMPLES / "shelf_picker.rscd").read_text()
    broken = "\n".join(line for line in text.splitlines() if "on error from unload" not in line)
    why = restriction(synthesize_model(load(broken)), "pick.c_trigger")
    assert why is not None
    assert [f.text.split(":")[0] for f in why.consequence.fixes] == [
        "add 'on error from unload' to state emptying of Tray"
    ]


@pytest.mark.parametrize("family", ["ring", "philosophers", "transfer_line"])
def test_conditions_kept_apart_from_the_relations_give_the_same_supervisor(monkeypatch, family: str) -> None:
    """Requirements large enough to be kept apart from the transition relations (fleets) and
    small ones conjoined into them give one and the same supervisor, which the explicit-state
    method confirms."""
    import families
    from robosc.synthesis import encoding
    from robosc.synthesis.options import SynthesisOptions

    model = load(getattr(families, family)(3))
    results = []
    for threshold in (0, 10**9):  # every condition kept apart; every condition conjoined
        monkeypatch.setattr(encoding, "SMALL_GUARD", threshold)
        result = synthesize_model(model, options=SynthesisOptions(fleet="monolithic"))  # the fleet's whole state
        results.append((result.reachable_states, [(g.event.name, render(g.added) if g.added else None) for g in result.guards]))
    assert results[0] == results[1]
    explicit = synthesize_explicit(build_network(model))
    assert explicit.reachable_states == results[0][0]


@pytest.mark.parametrize(
    "order",
    [
        "interaction",
        "model",
        "sorted",
        "reverse",
        "model->force",
        "sorted->force->slidwin",
        "interaction->reverse",
        "model->dcsh->force",
    ],
)
@pytest.mark.parametrize("reorder", [False, True])
def test_synthesis_options_never_change_the_supervisor(order: str, reorder: bool) -> None:
    import families
    from robosc.synthesis.options import SynthesisOptions

    models = [load((EXAMPLES / "shelf_picker.rscd").read_text()), load(families.ring(3)), load(families.philosophers(3))]
    for model in models:
        default = synthesize_model(model)
        edges = "reverse" if reorder else "sorted"  # the edge orders too, each with half the cases
        explore = "chained" if "->" in order else "saturation"  # and both explorations (the default: auto)
        forward = "first" if reorder else "never"  # bad states among those the requirements reach, or all
        options = SynthesisOptions(order, reorder, edges=edges, explore=explore, forward=forward)
        tuned = synthesize_model(model, options=options)
        assert tuned.reachable_states == default.reachable_states
        assert [g.added is None for g in tuned.guards] == [g.added is None for g in default.guards]
        # the same events allowed in the same states (an added condition may be written
        # differently: its shortest form depends on the variable order)
        net = default.network
        for state in synthesize_explicit(net).supervisor.controlled_states():
            named = {a.name: loc.name for a, loc in zip(net.automata, state.locations, strict=True)}
            named.update({f"{v.owner}.{v.name}": x for v, x in zip(net.variables, state.values, strict=True)})
            there = tuned.state(named)  # the same state in the tuned run's network
            for guard in default.guards:
                assert tuned.allows(guard.event.name, there) == default.allows(guard.event, state), (guard.event, named)


def test_an_unknown_order_is_refused() -> None:
    from robosc.synthesis.options import SynthesisOptions

    with pytest.raises(ValueError, match="unknown variable order 'random'"):
        SynthesisOptions("random")
    with pytest.raises(ValueError, match="unknown order improvement 'sifting'"):
        SynthesisOptions("model->sifting")
    with pytest.raises(ValueError, match="unknown forward reachability 'always'"):
        SynthesisOptions(forward="always")
    with pytest.raises(ValueError, match="unknown exploration 'bfs'"):
        SynthesisOptions(explore="bfs")


def test_force_and_sliding_window_bring_what_interacts_together() -> None:
    """On a transfer line the model's order puts every machine before every buffer: FORCE pulls
    each buffer next to its two machines (ESCET's measure, the total span, falls), and the
    sliding window never makes it worse; both keep every item exactly once."""
    import families
    from robosc.synthesis.ordering import force, hyperedges, initial_order, sliding_window, total_span

    network = build_network(load(families.transfer_line(12)))
    model_order = initial_order(network, "model")
    edges = hyperedges(network, model_order)
    start = list(range(len(model_order)))
    forced = force(start, edges)
    windowed = sliding_window(forced, edges)
    assert sorted(forced) == start and sorted(windowed) == start
    assert total_span(forced, edges) < total_span(start, edges) / 2
    assert total_span(windowed, edges) <= total_span(forced, edges)
    shuffled = start[1::2] + start[0::2]
    assert total_span(sliding_window(shuffled, edges), edges) < total_span(shuffled, edges)
    assert initial_order(network, "model->force->slidwin") == [model_order[i] for i in windowed]


def test_dcsh_numbers_what_interacts_close_together() -> None:
    """Cuthill-McKee and Sloan walk a scrambled chain from one end to the other (the least total
    span there is), number parts that share nothing one after the other, and DCSH, the better
    of them, repairs the transfer line's model order as FORCE does."""
    import families
    from robosc.synthesis.ordering import cuthill_mckee, dcsh, graph_of, hyperedges, initial_order, sloan, total_span

    chain = [[i, i + 1] for i in range(9)]
    scrambled = [3, 7, 0, 9, 5, 1, 8, 2, 6, 4]
    for method in (cuthill_mckee, sloan):
        found = method(graph_of(scrambled, chain), scrambled)
        assert sorted(found) == list(range(10)) and total_span(found, chain) == 9
    assert total_span(dcsh(scrambled, chain), chain) == 9
    two = [[i, i + 1] for i in range(4)] + [[i, i + 1] for i in range(5, 9)]  # 0..4 and 5..9
    found = dcsh(scrambled, two)
    assert sorted(found) == list(range(10)) and total_span(found, two) == 8

    network = build_network(load(families.transfer_line(12)))
    model_order = initial_order(network, "model")
    edges = hyperedges(network, model_order)
    start = list(range(len(model_order)))
    found = dcsh(start, edges)
    assert sorted(found) == start and total_span(found, edges) < total_span(start, edges) / 2
    assert initial_order(network, "model->dcsh") == [model_order[i] for i in found]


def test_dcsh_keeps_the_best_of_its_candidates_and_never_worsens_an_order() -> None:
    import random

    from robosc.synthesis.ordering import cuthill_mckee, dcsh, force, graph_of, sliding_window, sloan, total_span

    rng = random.Random(5)
    for _ in range(200):
        n = rng.randint(3, 12)
        path = rng.sample(range(n), n)  # one part: a random path through all, and random groups
        edges = [sorted(path[i : i + 2]) for i in range(n - 1)]
        edges += [sorted(rng.sample(range(n), rng.randint(2, min(4, n)))) for _ in range(rng.randint(0, 6))]
        order = rng.sample(range(n), n)
        if rng.random() < 0.5:  # an order already improved, often better than either numbering
            order = sliding_window(force(order, edges), edges)
        found = dcsh(order, edges)
        assert sorted(found) == list(range(n))
        assert total_span(found, edges) <= total_span(order, edges)
        for method in (cuthill_mckee, sloan):
            candidate = method(graph_of(order, edges), order)
            assert total_span(found, edges) <= min(total_span(candidate, edges), total_span(candidate[::-1], edges))


NONDETERMINISTIC = """robot Nondeterministic {
    component Arm {
        incoming message go with type: none
        incoming message reset with type: none
        incoming message fix with type: none
        behaviour {
            initial marked state idle {
                on request to go goto fine
                on request to go goto broken
            }
            marked state fine { on request to reset goto idle }
            state broken { on request to fix goto idle }
        }
    }
    requirement fix needs Arm.idle
}
"""


@pytest.mark.parametrize("explore", ["saturation", "chained"])
def test_an_event_that_may_lead_to_a_good_or_a_bad_state_is_disabled_and_its_good_target_unreached(explore: str):
    """go may end in fine or in broken (which blocks): the supervisor disables it, so fine is
    never reached, though it is a good state one step from the start."""
    from robosc.synthesis.options import SynthesisOptions

    model = load(NONDETERMINISTIC)
    result = synthesize_model(model, options=SynthesisOptions(explore=explore))
    explicit = synthesize_explicit(build_network(model))
    assert result.reachable_states == explicit.reachable_states == 1
    assert not result.allows("go", result.state({"Arm": "idle"}))


def test_a_requirement_is_split_by_where_its_robot_is_and_means_the_same(monkeypatch) -> None:
    """A requirement written per robot (`R4.at0 => ... and R4.at1 => ...`) is kept as one case per
    location its event leaves where it is large as a whole: each case a small BDD, their union
    the whole where the event can happen, and the supervisor the same as from the whole."""
    import families
    from robosc.synthesis import cases
    from robosc.synthesis.options import SynthesisOptions
    from robosc.synthesis.symbolic import fixpoint

    model = load(families.ring_homes(5))
    network = build_network(model)
    fp = fixpoint(network)
    assert all(len(fp.cases[e]) == 1 for e in network.events)  # 5 robots: none is large yet
    monkeypatch.setattr(cases, "WHOLE_AT_MOST", 2000)
    fp = fixpoint(network)
    enc = fp.enc
    last = network.event("go4")
    whole = enc.boolean(next(iter(network.requirements_on(last))).condition)
    assert len(fp.cases[last]) == 10  # R4's ten zones
    assert all(case.condition.dag_size * 10 < whole.dag_size for case in fp.cases[last])
    first = network.event("go0")  # R0 comes first in the order: its requirement is small, kept whole
    assert len(fp.cases[first]) == 1 and fp.cases[first][0].region == enc.true
    assert fp.cases[first][0].condition.dag_size <= cases.WHOLE_AT_MOST
    for event in network.controllable:
        (requirement,) = network.requirements_on(event)
        expected = fp.enabled[event] & enc.boolean(requirement.condition)
        assert fp.enabled[event] & fp.required[event] == expected, event.name
    assert all(len(fp.cases[e]) == 1 and fp.cases[e][0].region == enc.true for e in network.uncontrollable)
    # where each event is allowed is asked of its cases, without making their union
    start = initial_state(network)
    moved = NetworkState(
        tuple(a.initial if a.name != "R4" else next(s for s in a.locations if s.name == "at9") for a in network.automata),
        start.values,
    )  # R4 one zone past its home, right behind R0's: it may not move on while R0 is there
    controllable = set(network.controllable)
    assert fp.allowed_events(start) & controllable == controllable
    assert fp.allowed_events(moved) & controllable == controllable - {last}
    assert not fp.allowed.made
    assert [fp.allows(e, moved) for e in network.controllable] == [
        (fp.state(moved) & fp.allowed[e]) != enc.false for e in network.controllable
    ]

    def supervisor() -> tuple[int, list[tuple[str, str | None]]]:
        result = synthesize_model(model, options=SynthesisOptions(fleet="monolithic"))
        return result.reachable_states, [(g.event.name, render(g.added) if g.added else None) for g in result.guards]

    split = supervisor()
    monkeypatch.setattr(cases, "splitter", lambda *_: None)
    assert supervisor() == split


@pytest.mark.parametrize("family", ["ring_homes", "lift", "warehouse", "crossing"])
def test_a_requirement_decided_at_each_location_means_the_requirement_there(family: str) -> None:
    """Where an automaton is in a location, its location references are decided and only the parts
    that name one are rebuilt (`at_location`): no reference to its locations is left, and the
    states are the whole requirement's there, for every requirement, automaton and location."""
    import families
    from robosc.language import model as m
    from robosc.synthesis.cases import at_location
    from robosc.synthesis.encoding import Encoding

    network = build_network(load(getattr(families, family)(3)))
    enc = Encoding(network)
    checked = 0
    for requirement in network.requirements:
        whole = enc.boolean(requirement.condition)
        for automaton in network.automata:
            for location in automaton.locations:
                decided = at_location(requirement.condition, automaton, location)
                here = enc.at(location) & enc.valid()
                assert enc.boolean(decided) & here == whole & here, (requirement.description, location.name)
                own = {id(s) for s in automaton.locations}
                assert not any(isinstance(n, m.StateRef) and id(n.state) in own for n in m.walk(decided))
                checked += decided is not requirement.condition
    assert checked > 0
