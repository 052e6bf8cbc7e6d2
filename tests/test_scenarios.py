"""The conflicts fleet managers' users report, in one world (benchmarks/scenarios.py): two robots
head-on in one lane, two robots swapping places again and again, four robots at one crossing.
Each runs with random speeds and start delays; robosc's supervisor never deadlocks or collides,
and the hand-written rule (the requirements alone: enter a cell when it is free) does, so these
tests can fail."""

from __future__ import annotations

import pytest

import scenarios

pytest.importorskip("irsim")


@pytest.mark.parametrize("name", sorted(scenarios.ROUTES))
def test_the_scenario_models_are_what_their_routes_write(name: str) -> None:
    path = scenarios.FOLDER / f"{name}.rscd"
    assert path.read_text(encoding="utf-8") == scenarios.model(name, scenarios.ROUTES[name])


def test_holding_a_cell_is_being_in_it_or_on_the_way_in_or_out() -> None:
    # bot1 of the lane: l2 is position 2 (out) and 6 (back)
    assert scenarios.holding(scenarios.LANE[0], "l2") == [
        "to_2", "stopped_2", "at_2", "to_3", "stopped_3", "to_6", "stopped_6", "at_6", "to_7", "stopped_7",
    ]
    assert scenarios.holding(scenarios.LANE[0], "l1")[-2:] == ["to_home", "stopped_8"]


@pytest.mark.parametrize(("scenario", "runs"), [("lane", 2), ("swap", 1), ("crossing", 2)])
def test_robosc_never_deadlocks_or_collides_where_the_hand_written_rule_does(scenario: str, runs: int) -> None:
    from robosc.sim.world import load_world

    model_name, world_name, tasks = scenarios.SCENARIOS[scenario]
    world = load_world(scenarios.ROOT / "examples" / "worlds" / f"{world_name}.yaml")
    coordinators = scenarios.coordinators(model_name)
    for seed in range(runs):
        report = scenarios.run_once(coordinators["robosc"], world, tasks, seed)
        assert report.ok, f"seed {seed}: {report.why}"  # type: ignore[attr-defined]
        assert report.collisions == 0 and all(s.tasks >= tasks for s in report.robots)  # type: ignore[attr-defined]
    failed = [scenarios.run_once(coordinators["rule"], world, tasks, seed) for seed in range(runs)]
    assert all(r.why.startswith(("deadlock", "collision")) for r in failed), [r.why for r in failed]  # type: ignore[attr-defined]


def test_the_lane_written_for_a_fleet_size_says_left_where_its_model_takes_it() -> None:
    """benchmarks/fleet_worlds.py's lane of two robots (west1 and east1, homed at its two ends): every answer the
    drivers give, ``left`` included, is one the model takes where the robot is, each robot says
    ``left`` in every leg that starts in a cell (ten of its twelve), and the tasks get done."""
    import fleet_worlds
    from robosc.api import plan_supervisor
    from robosc.debug.simulator import load_module
    from robosc.sim.fleet import FleetRun
    from robosc.sim.run import drive

    world_text, model_text = fleet_worlds.lane(1)
    module = load_module(plan_supervisor(fleet_worlds.synthesized(model_text)))
    events: list[str] = []
    run = FleetRun(fleet_worlds.load(world_text), module, 2, tasks=1, on_event=lambda r: events.append(r["event"]))
    refused: list[tuple[float, str]] = []
    deliver = run.coordinator.deliver

    def checked(name: str, *args: object, **kwargs: object) -> bool:
        taken = deliver(name, *args, **kwargs)
        if not taken:
            refused.append((run.sim.time, name))
        return bool(taken)

    run.coordinator.deliver = checked
    report = drive(run, timeout=600)
    assert report.ok, report.why  # type: ignore[attr-defined]
    assert refused == []
    routes = fleet_worlds.Street(("l1", "l2", "l3"), ("gw", "ge"), (0.0, 0.0), (1.0, 0.0), ("west", "east")).route(0, "t1")
    assert sum(leg.leaves for leg in routes) == 10 and len(routes) == 12
    assert events.count("west1.left") == 10 and events.count("east1.left") == 10, events
