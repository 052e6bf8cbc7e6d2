"""Tasks given to a fleet at run time and the coordinator's choice with a purpose
(robosc.runtime.onboard.tasks), on generated modules of small fleets."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path
from typing import Any

import pytest

from robosc.api import check_text, synthesize_model
from robosc.codegen.plan import plan
from robosc.debug.simulator import load_module
from robosc.runtime.onboard.tasks import ASSIGNED, DONE, FAILED, QUEUED, Dispatcher

# three robots and one cell that holds one of them
CELL = """
robot Cell {
    component bot[3] {
        incoming message enter with type: none
        incoming message leave with type: none
        behaviour {
            initial marked state home { on request to enter goto inside }
            state inside { on request to leave goto home }
        }
    }
    for r in bot {
        requirement r.enter needs !any(q in bot: q.inside)
    }
}
"""

# two robots that pass a door out and back; the door closes only with nobody in the doorway
DOOR = """
robot Doors {
    component bot[2] {
        incoming message go with type: none
        outgoing message arrived with type: none
        behaviour {
            initial marked state home { on request to go goto passing }
            state passing { on response from arrived goto away }
            state away { on request to go goto returning }
            state returning { on response from arrived goto home }
        }
    }
    component Door {
        incoming message open_door with type: none
        incoming message close_door with type: none
        outgoing message door_opened with type: none
        outgoing message door_closed with type: none
        behaviour {
            initial marked state closed { on request to open_door goto opening }
            state opening { on response from door_opened goto open }
            marked state open { on request to close_door goto closing }
            state closing { on response from door_closed goto closed }
        }
    }
    for r in bot {
        requirement r.go needs Door.open
    }
    requirement close_door needs !any(q in bot: q.passing or q.returning)
}
"""


ANSWERS = {"go": "arrived", "open_door": "door_opened", "close_door": "door_closed"}


class Fleet:
    """A generated coordinator with a dispatcher, on a clock of its own; a command with an
    answer (ANSWERS) is answered at the next step."""

    def __init__(self, text: str, policy: str = "purpose", seed: int = 0) -> None:
        module = load_module(plan(synthesize_model(check_text(text).model)))
        self.now = 0.0
        self.sent: list[str] = []
        self.answered = 0  # the commands answered so far
        fleet = self

        class Coordinator(module.Robot):  # type: ignore[misc, name-defined]
            def send(self, name: str, data: Any) -> bool:
                fleet.sent.append(name)
                return True

        self.robot = Coordinator(seed=seed, warn=lambda text: None, clock=lambda: fleet.now, wait_for_data=False)
        self.changes: list[tuple[str, str]] = []
        self.tasks = Dispatcher(self.robot, policy, on_change=lambda t: self.changes.append((t["id"], t["state"])))
        self.robot.tasks = self.tasks

    def run(self, ticks: int) -> None:
        for _ in range(ticks):
            self.now += 1.0
            for name in self.sent[self.answered :]:
                robot, _, command = name.rpartition(".")
                if command in ANSWERS:
                    assert self.robot.deliver(f"{robot}.{ANSWERS[command]}" if robot else ANSWERS[command])
            self.answered = len(self.sent)
            self.robot.tick()

    def where(self, component: str) -> str:
        return str(getattr(self.robot, self.tasks.routes.route[component].field))


def test_robots_without_a_task_stay_parked_and_nothing_is_sent() -> None:
    fleet = Fleet(CELL)
    fleet.run(20)
    assert fleet.sent == []
    # under the random choice the same coordinator keeps sending what it is allowed to
    loose = Fleet(CELL, "random")
    loose.run(20)
    assert len(loose.sent) == 20


def test_a_task_takes_its_robot_to_each_stop_in_turn_and_only_that_robot_moves() -> None:
    fleet = Fleet(CELL)
    task = fleet.tasks.submit(["inside", "home"], robot="bot2")
    assert task.state == QUEUED
    fleet.run(10)
    assert fleet.sent == ["bot2.enter", "bot2.leave"]
    assert fleet.changes == [(task.id, QUEUED), (task.id, ASSIGNED), (task.id, DONE)]
    assert task.by == "bot2" and task.reached == 2 and fleet.tasks.done["bot2"] == 1


def test_tasks_for_the_group_go_to_idle_robots_one_task_each() -> None:
    fleet = Fleet(CELL)
    first, second = fleet.tasks.submit(["inside", "home"]), fleet.tasks.submit(["inside", "home"])
    fleet.run(1)
    assert (first.by, second.by) == ("bot1", "bot2")
    fleet.run(10)
    assert first.state == second.state == DONE
    assert fleet.sent == ["bot1.enter", "bot1.leave", "bot2.enter", "bot2.leave"]


def test_a_robot_after_a_task_that_ends_away_from_home_goes_home() -> None:
    fleet = Fleet(CELL)
    task = fleet.tasks.submit(["inside"], robot="bot3")
    fleet.run(5)
    assert task.state == DONE
    assert fleet.sent == ["bot3.enter", "bot3.leave"]  # parked where it is marked, not in the cell
    assert fleet.where("bot3") == "home"


def _first_entries(fleet: Fleet) -> list[str]:
    return [name.split(".")[0] for name in fleet.sent if name.endswith(".enter")]


def test_the_robot_waiting_longest_goes_first_so_none_is_starved() -> None:
    # bot1 has six tasks; bot2 and bot3 one each, given after bot1's first: each waits for
    # the cell once, and goes before bot1 goes again
    for seed in range(10):
        fleet = Fleet(CELL, seed=seed)
        for _ in range(6):
            fleet.tasks.submit(["inside", "home"], robot="bot1")
        fleet.run(1)
        fleet.tasks.submit(["inside", "home"], robot="bot2")
        fleet.tasks.submit(["inside", "home"], robot="bot3")
        fleet.run(40)
        assert _first_entries(fleet)[:3] == ["bot1", "bot2", "bot3"]
        assert fleet.tasks.counts()[DONE] == 8


def test_the_random_choice_lets_one_robot_go_again_and_again_while_another_waits() -> None:
    # the same fleet under the random choice (what the fair policy replaces): in some runs bot1
    # enters the cell again before bot2 or bot3 had their turn
    orders = set()
    for seed in range(10):
        fleet = Fleet(CELL, "random", seed=seed)
        for _ in range(6):
            fleet.tasks.submit(["inside", "home"], robot="bot1")
        fleet.run(1)
        fleet.tasks.submit(["inside", "home"], robot="bot2")
        fleet.tasks.submit(["inside", "home"], robot="bot3")
        fleet.run(40)
        orders.add(tuple(_first_entries(fleet)[:3]))
    assert any(order.count("bot1") > 1 for order in orders)


def test_the_door_opens_when_a_robot_needs_to_pass_and_only_then() -> None:
    fleet = Fleet(DOOR)
    fleet.run(10)
    assert fleet.sent == []  # nobody needs the door
    task = fleet.tasks.submit(["away", "home"], robot="bot2")
    fleet.run(12)
    assert task.state == DONE
    assert fleet.sent == ["open_door", "bot2.go", "bot2.go", "close_door"]
    assert fleet.where("Door") == "closed"
    # under the random choice the door flaps
    loose = Fleet(DOOR, "random")
    loose.run(40)
    assert loose.sent.count("open_door") > 3


WORK = DOOR.replace(
    "outgoing message arrived with type: none",
    "outgoing message arrived with type: none\n        incoming message pick with type: none\n"
    "        outgoing message picked with type: none",
).replace(
    "state away { on request to go goto returning }",
    "state away { on request to pick goto picking }\n"
    "            state picking { on response from picked goto full }\n"
    "            state full { on request to go goto returning }",
)


def test_the_door_stays_open_while_the_fleet_works_and_closes_when_it_is_done() -> None:
    """bot1 passes the door, picks (the door is needed by nobody meanwhile) and comes back: the
    door stays open while its task is under way, instead of closing behind it and opening again,
    and closes once the task is done."""
    fleet = Fleet(WORK)
    task = fleet.tasks.submit(["full", "home"], robot="bot1")
    fleet.run(6)
    assert fleet.sent == ["open_door", "bot1.go", "bot1.pick"] and fleet.where("bot1") == "picking"
    fleet.robot.deliver("bot1.picked")
    fleet.run(6)
    assert task.state == DONE
    assert fleet.sent == ["open_door", "bot1.go", "bot1.pick", "bot1.go", "close_door"]


@pytest.mark.parametrize(
    ("stops", "robot", "why"),
    [
        (["shelf"], None, "'shelf' is no location of bot (its locations: home, inside)"),
        (["inside"], "bot9", "no robot or group 'bot9' (robots: bot1, bot2, bot3)"),
        ([], None, "a task names one or more locations to reach in turn (stops)"),
    ],
)
def test_a_task_no_robot_can_do_is_refused_at_once_with_the_reason(stops: list[str], robot: str | None, why: str) -> None:
    fleet = Fleet(CELL)
    task = fleet.tasks.submit(stops, robot=robot)
    assert (task.state, task.why) == (FAILED, why)
    assert fleet.changes == [(task.id, FAILED)]
    fleet.run(5)
    assert fleet.sent == []


def test_a_task_whose_stops_cannot_follow_each_other_is_refused() -> None:
    one_way = CELL.replace(
        "state inside { on request to leave goto home }", "state inside { on request to leave goto gone }\n marked state gone { }"
    )
    fleet = Fleet(one_way)
    task = fleet.tasks.submit(["gone", "home"])
    assert (task.state, task.why) == (FAILED, "bot cannot get from gone to home")
    assert fleet.tasks.submit(["gone"]).state == QUEUED


# ---- the node's task topics (node_tasks.py), middleware aside ---------------------------------


@pytest.mark.parametrize(
    ("text", "read"),
    [
        ("shelf depot", (["shelf", "depot"], None, None)),
        ("bot2: shelf depot", (["shelf", "depot"], "bot2", None)),
        ('{"stops": ["shelf"], "robot": "bot", "id": "order-17"}', (["shelf"], "bot", "order-17")),
        ('  {"stops": ["shelf", "depot"]}  ', (["shelf", "depot"], None, None)),
    ],
)
def test_a_task_message_is_json_or_text(text: str, read: tuple[Any, ...]) -> None:
    from robosc.runtime.onboard.node_tasks import read_task

    assert read_task(text) == read


@pytest.mark.parametrize(
    ("text", "why"),
    [
        ("", "(it was empty)"),
        ("{not json", "a task in JSON could not be read"),
        ('{"stops": "shelf"}', "a task's stops are a list of location names"),
        ('{"stops": ["shelf"], "when": 3}', "a task has stops, robot and id, not when"),
        ('{"stops": ["shelf"], "robot": 2}', "a task's robot is a text"),
        ("x" * 10001, "at most 10000 characters"),
        (None, "(it was empty)"),
    ],
)
def test_a_task_message_that_cannot_be_read_says_why(text: Any, why: str) -> None:
    from robosc.runtime.onboard.node_tasks import read_task

    with pytest.raises(ValueError, match=re.escape(why)):
        read_task(text)


class Message:
    def __init__(self, data: Any) -> None:
        self.data = data


class Empty:
    """std_msgs/Empty."""


def fleet_node(**params: Any) -> Any:
    """The warehouse's coordinator node, middleware aside, its commands std_msgs/Empty."""
    sys.path.insert(0, str(Path(__file__).parent))
    from test_onboard import FakeNode

    node = FakeNode("examples/warehouse.rscd", "controller", **params)
    for topic in node.outputs.values():
        topic.type = Empty
    return node


def test_a_fleet_node_takes_tasks_on_its_topic_and_publishes_the_queue() -> None:
    node = fleet_node(wait_for_data=False)
    assert node.dispatcher is not None and node.supervisor.tasks is node.dispatcher
    node.checkpoint()
    assert [name for name, _ in node.texts if name == "robosc/tasks"] == ["robosc/tasks"]  # the empty queue
    node.texts.clear()
    node.task_given(Message("bot2: shelf depot"))
    node.task_given(Message('{"stops": ["shlf"], "id": "bad"}'))
    node.task_given(Message("{"))
    queues = [json.loads(text) for name, text in node.texts if name == "robosc/tasks"]
    last = queues[-1]
    assert [(t["id"], t["state"]) for t in last["tasks"]] == [("task1", "queued"), ("bad", "failed"), ("task3", "failed")]
    assert last["tasks"][1]["why"].startswith("'shlf' is no location of bot")
    assert last["tasks"][2]["why"].startswith("a task in JSON could not be read")
    assert ("error", "task bad refused: " + last["tasks"][1]["why"]) in node.logs
    node.cycle()  # assigned to bot2, which drives to the place beside the doorway
    assert json.loads(node.queue_text())["tasks"][0]["by"] == "bot2"
    assert [name for name, _ in node.published] == ["bot2/go"]
    response = node.serve_queue(None, Message(None))
    assert response.success is True and json.loads(response.message)["counts"] == {
        "assigned": 1, "done": 0, "failed": 2, "queued": 0}


def test_a_node_without_a_fleet_has_no_tasks_and_the_random_policy_is_a_parameter() -> None:
    sys.path.insert(0, str(Path(__file__).parent))
    from test_onboard import FakeNode

    assert FakeNode("examples/line_follower.rscd", "controller").dispatcher is None
    node = fleet_node(policy="random")
    assert node.dispatcher is not None and node.dispatcher.policy == "random"
    bad = fleet_node(policy="fair")
    assert bad.dispatcher is not None and bad.dispatcher.policy == "purpose"
    assert any("policy must be one of purpose, random, not 'fair'" in text for _, text in bad.logs)


def test_a_task_to_a_state_the_supervisor_never_lets_a_robot_reach_is_refused() -> None:
    # a robot may wander away from home only while inside the cell: never, so it is never away
    wandering = (
        CELL.replace(
            "initial marked state home { on request to enter goto inside }",
            "initial marked state home { on request to enter goto inside\n"
            "                on request to wander goto away }\n"
            "            state away { on request to leave goto home }",
        )
        .replace(
            "incoming message leave with type: none",
            "incoming message leave with type: none\n        incoming message wander with type: none",
        )
        .replace("for r in bot {", "for r in bot {\n        requirement r.wander needs r.inside")
    )
    for robots in ("3", "2"):  # counted, and followed one by one
        fleet = Fleet(wandering.replace("bot[3]", f"bot[{robots}]"))
        task = fleet.tasks.submit(["away"])
        assert (task.state, task.why) == (FAILED, "the supervisor never lets bot reach away (robosc synthesize says why)")
        assert fleet.tasks.submit(["inside"]).state == QUEUED


def test_a_task_named_as_one_given_before_is_refused_under_a_name_of_its_own() -> None:
    fleet = Fleet(CELL)
    first = fleet.tasks.submit(["inside"], id="a")
    again = fleet.tasks.submit(["inside"], id="a")
    unread = fleet.tasks.refuse("a task in JSON could not be read", id="a")
    assert [(t.id, t.state, t.why) for t in (first, again, unread)] == [
        ("a", QUEUED, ""),
        ("a#2", FAILED, "a task named 'a' was given already"),
        ("a#3", FAILED, "a task in JSON could not be read"),
    ]
    assert [t["id"] for t in fleet.tasks.queue()] == ["a", "a#2", "a#3"]
