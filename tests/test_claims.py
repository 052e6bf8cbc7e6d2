"""One controller commands (issue 47, part 2), middleware aside: two nodes of one fleet hear each
other's claims on robosc/coordinator; the one started first commands, the other holds and says
why, and takes over, unconfirmed, once the first's claims stop. On ROS 2 and ROS 1:
test_faults_ros.py."""

from __future__ import annotations

import json
import time
from types import SimpleNamespace

from robosc.runtime.onboard.claims import CLAIM_TIMEOUT, CLAIM_TOPIC, CLAIM_WAIT
from test_onboard import FakeNode

MODEL = "docs/models/warehouse_zero_time.rscd"


def claims(node: FakeNode) -> list[str]:
    return [text for name, text in node.texts if name == CLAIM_TOPIC]


def test_the_second_controller_holds_until_the_first_is_gone_then_commands_unconfirmed() -> None:
    first = FakeNode(MODEL, "controller", policy="random", seed=1)
    second = FakeNode(MODEL, "controller", policy="random", seed=2)
    second.listening_since, second.commanding = time.monotonic(), False  # just started: it listens first
    first.cycle()
    second.cycle()
    assert first.commanding and not second.commanding  # the second is still listening
    for text in claims(first):
        second.claim_heard(SimpleNamespace(data=text))
    for text in claims(second):
        first.claim_heard(SimpleNamespace(data=text))
    assert second.standby is not None and second.standby.startswith("another controller commands: " + first.claim["id"])
    assert first.commanding and first.standby is None
    assert any("another controller of this robot or fleet" in text for _, text in first.logs)
    second.listening_since -= CLAIM_WAIT
    published = len(second.published)
    for _ in range(20):
        second.cycle()
    assert len(second.published) == published  # it holds every command
    assert second.health()["coordinator"]["commanding"] is False
    # the first's claims stop: gone after CLAIM_TIMEOUT, and the second takes over, unconfirmed
    heard, claim = second.others[first.claim["id"]]
    second.others[first.claim["id"]] = (heard - CLAIM_TIMEOUT - 0.1, claim)
    second.cycle()
    assert second.commanding and second.supervisor.unsure()  # it asks the drivers before it commands
    assert any("is gone" in text for _, text in second.logs)


def test_an_unreadable_or_foreign_claim_never_makes_a_controller_hold() -> None:
    node = FakeNode(MODEL, "controller", policy="random")
    node.cycle()
    for text in ("", "{", '{"id": 5, "since": 1}', '{"id": "x", "since": "nan"}', "x" * 5000, '[1]'):
        node.claim_heard(SimpleNamespace(data=text))
    node.claim_heard(SimpleNamespace(data=claims(node)[-1]))  # its own
    node.claim_heard(SimpleNamespace(data=json.dumps({"id": "later", "since": time.time() + 60})))  # younger
    node.cycle()
    assert node.commanding and node.standby is None
