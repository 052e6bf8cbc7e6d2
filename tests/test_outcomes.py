"""Events with several outcomes (issue 47, part 3): ``status`` ends a task in ``done`` or
``broken``. The generated controller took the first transition written, believed ``done`` and
never offered ``repair``. Now the component is unconfirmed among the outcomes until the robot
tells which (a message, an answer, its driver's report), in the stand-alone module and the node
alike; ``robosc simulate`` stands for the robot and says which (picked in a script, at random
in a random run); ``robosc check`` warns, saying what tells the outcomes apart."""

from __future__ import annotations

import random
import time
from pathlib import Path

import pytest

from robosc.api import check_text, load_model, plan_supervisor, synthesize_model
from robosc.debug.simulator import CommandError, Simulator, load_module
from robosc.runtime.onboard.claims import CLAIM_WAIT
from ros_support import Ros2, build_package
from test_belief import Node
from worker_stand_in import Worker

ROOT = Path(__file__).resolve().parent.parent
MODEL = ROOT / "docs/models/outcomes.rscd"


def worker() -> type:
    return load_module(plan_supervisor(synthesize_model(load_model(MODEL)))).Robot


def test_after_an_event_with_two_outcomes_the_module_holds_until_the_robot_tells() -> None:
    robot = worker()(seed=1)
    assert robot.perform("start") and robot.deliver("status")
    assert robot.unsure() == {"arm": {"why": "arm may be done or broken (an event with several outcomes)",
                                      "may_be": {"arm": ["done", "broken"]}}}
    assert robot.allowed() == []  # neither home (done) nor repair (broken) is sure to be right
    assert robot.confirm("arm", "broken") is None
    assert robot.allowed() == ["repair"]


def test_a_node_asks_the_driver_at_once_and_repairs_a_broken_worker() -> None:
    node = Node(str(MODEL), rate=20.0, seed=1, trust_initial_state=True, ack_timeout=0.01)
    node.listening_since -= CLAIM_WAIT  # (no other controller to listen for)
    node.answers = {}
    node.cycle()  # start
    assert [name for name, _ in node.published] == ["start"]
    time.sleep(0.02)
    node.checkpoint()  # start arrived (ROS 1: its topic kept its subscriber through ack_timeout)
    asked = node.asked_for.count("arm")
    node.answers["arm"] = "broken"  # what its driver says when asked
    node.receive(node.inputs["status"], None)
    assert node.asked_for.count("arm") == asked + 1
    for _ in range(5):
        node.cycle()
    sent = [name for name, _ in node.published]
    assert sent[:2] == ["start", "repair"] and "home" not in sent  # before: home, for a broken arm


def simulator() -> Simulator:
    result = synthesize_model(load_model(MODEL))
    return Simulator(result, plan_supervisor(result), seed=1)


def test_simulate_takes_the_outcome_a_script_picks_else_the_first_and_says_which() -> None:
    sim = simulator()
    sim.run("start")
    assert sim.run("status -> broken").messages == ("arm -> broken (one of done, broken: as picked)",)
    sim.run("expect arm broken")
    assert sim.run("tick").events == ("repair",)
    sim.run("start")
    said = sim.run("status").messages
    assert said == ("arm -> done (one of done, broken: the first; say `status -> broken` for another)",)
    sim.run("expect arm done")
    with pytest.raises(CommandError, match="has one outcome now"):
        sim.run("home -> idle")
    sim.run("tick")
    sim.run("start")
    with pytest.raises(CommandError, match=r"status -> idle: its outcomes now are arm: done or broken"):
        sim.run("status -> idle")


def test_a_random_simulation_explores_both_outcomes() -> None:
    sim = simulator()
    rng = random.Random(5)
    seen = set()
    for _ in range(200):
        sim.random_step(rng)
        seen.add(sim.snapshot()["automata"]["arm"])
    assert {"done", "broken"} <= seen


SETTLED = ("state done {", "state done {\n                on response from reset goto idle"), (
    "state broken {", "state broken {\n                on response from reset goto idle")
ALARM = ("state broken {", "state broken {\n                on response from alarm goto broken")


def variant(*changes: tuple[str, str]) -> str:
    """The model with a message more (``alarm``, ``reset``) and ``changes`` made to its text."""
    text = MODEL.read_text().replace(
        "outgoing message status",
        "outgoing message alarm with type: none\n        outgoing message reset with type: none\n        outgoing message status",
    )
    for old, new in changes:
        text = text.replace(old, new)
    return text


def outcome_warnings(text: str) -> list[str]:
    return [d.message for d in check_text(text).diagnostics if d.code == "several-outcomes"]


def test_check_says_what_settles_the_outcomes_or_that_only_a_report_tells() -> None:
    only_report = "only the driver's report (robosc/report/arm) tells which"
    [said] = outcome_warnings(MODEL.read_text())
    assert said.startswith("'on response from status' in arm's state 'working' has 2 outcomes (done, broken)")
    assert said.endswith(only_report)
    [said] = outcome_warnings(variant(ALARM))  # taken in broken only: may be a stray
    assert said.endswith(only_report)
    [said] = outcome_warnings(variant(*SETTLED))
    assert "what settles it: 'on response from reset', or the driver's report" in said
    assert outcome_warnings(MODEL.read_text().replace("goto broken", "goto done")) == []


def robot(text: str) -> object:
    checked = check_text(text)
    assert checked.model is not None
    return load_module(plan_supervisor(synthesize_model(checked.model))).Robot(seed=1)


def test_a_message_taken_in_one_outcome_only_tells_nothing_and_one_that_settles_does() -> None:
    stray = robot(variant(ALARM))
    assert stray.perform("start") and stray.deliver("status")
    stray.deliver("alarm")  # broken takes it; from done it may be a stray
    assert set(stray.unconfirmed.values()) == {("done", "broken")} and stray.allowed() == []
    settled = robot(variant(*SETTLED))
    assert settled.perform("start") and settled.deliver("status")
    assert settled.deliver("reset")  # from either outcome to idle
    assert settled.unconfirmed == {} and settled.allowed() == ["start"]


def test_ros2_a_worker_that_breaks_down_is_repaired_and_one_that_is_done_sent_home(ros2: Ros2, tmp_path: Path) -> None:
    """On ROS 2: the stand-in's task ends broken, done, broken, ... in turn, and its driver
    reports where the arm is. Every command the node sends must be right where the arm really is
    (before: home after every status, repair never). With ``confirm_answers`` false: the node
    does not doubt status as a possible second copy (that would ask the driver too), so only the
    two outcomes make it ask."""
    package = build_package(MODEL.relative_to(ROOT), 2, "controller", tmp_path)
    worker = Worker(ros2.node)
    ros2.start(package, confirm_answers=False)

    def work() -> bool:
        worker.step()
        return worker.sent.count("repair") >= 2 and worker.sent.count("home") >= 2

    assert ros2.spin_until(work, 60), (worker.sent, ros2.processes.output()[-3000:])
    assert worker.wrong == [], worker.wrong
