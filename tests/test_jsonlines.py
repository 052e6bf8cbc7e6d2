"""The JSON-lines child process shared by the simulator's node and robosc view's listener."""

from __future__ import annotations

import subprocess
import sys

import pytest

from robosc.jsonlines import LinePeer, PeerGone

ECHO = (
    "import json, sys\n"
    "for line in sys.stdin:\n"
    "    m = json.loads(line)\n"
    "    if m['op'] == 'quit': break\n"
    "    print('not json'); print(json.dumps({'op': 'echo', 'n': m['n']}), flush=True)\n"
)


def peer() -> LinePeer:
    return LinePeer(subprocess.Popen([sys.executable, "-c", ECHO], stdin=subprocess.PIPE, stdout=subprocess.PIPE))


def test_lines_in_and_out_and_waiting_for_one() -> None:
    p = peer()
    for n in range(3):
        p.send("say", n=n)
    found = p.wait_for(lambda m: m.get("n") == 2, 10)
    assert found is not None and found["op"] == "echo" and isinstance(found["received"], float)
    assert p.wait_for(lambda m: True, 0.3) is None  # the lines before it were used up; none came since
    p.quit()
    assert p.process.wait(10) == 0
    with pytest.raises(PeerGone):
        p.wait_for(lambda m: True, 10)  # it ended
    with pytest.raises(PeerGone):
        p.send("say", n=4)
