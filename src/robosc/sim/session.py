"""The simulation driving the simulator's ROS node (``bridge``) over its standard input and
output: it owns simulated time, publishes ``/clock`` through the node at every step and
paces the steps at ``speed`` times real time.
"""

from __future__ import annotations

import queue
import time
from collections.abc import Callable
from typing import Any

from robosc.jsonlines import LinePeer, PeerGone
from robosc.sim.local import apply_command, scan_message
from robosc.sim.simulation import Message, Simulation


class SessionError(Exception):
    """The simulator's node or the controllers did not come up."""


class Bridge(LinePeer):
    """The simulator's node as a subprocess."""

    def send(self, op: str, **fields: Any) -> None:
        try:
            super().send(op, **fields)
        except PeerGone:
            raise SessionError("the simulator's node ended") from None

    def close(self) -> None:
        self.quit()


def setup(sim: Simulation, bridge: Bridge, robots: list[str], roles: list[str]) -> None:
    scan = scan_message(sim, [])
    del scan["ranges"]
    bridge.send("setup", robots=robots, topics=sim.world.topics, roles=roles, scan=scan)


def wait_for(bridge: Bridge, condition: Callable[[dict[str, Any]], bool], timeout: float, what: str) -> None:
    try:
        found = bridge.wait_for(condition, timeout)
    except PeerGone:
        raise SessionError(f"the simulator's node ended while waiting for {what}") from None
    if found is None:
        raise SessionError(f"timed out after {timeout:g} s waiting for {what}")


def connected(roles: list[str], robots: int) -> Callable[[dict[str, Any]], bool]:
    """The condition: every robot's controller is connected on every topic it uses."""

    def condition(message: dict[str, Any]) -> bool:
        peers = message.get("robots")
        if message.get("op") != "peers" or not isinstance(peers, list) or len(peers) != robots:
            return False
        return all(set(roles) <= set(p) for p in peers)

    return condition


# (direction, robot, role, perf_counter seconds): a message sent ("out"), a command come ("in")
Trace = Callable[[str, int, str, float], None]


def publish(bridge: Bridge, messages: list[Message], trace: Trace | None = None) -> None:
    for m in messages:
        # Python's json writes and reads Infinity (a beam without a return)
        bridge.send("publish", robot=m.robot, role=m.role, value=m.value)
        if trace is not None:
            trace("out", m.robot, m.role, time.perf_counter())


def run(
    sim: Simulation,
    bridge: Bridge,
    timeout: float,
    speed: float = 1.0,
    on_step: Callable[[Simulation], None] | None = None,
    trace: Trace | None = None,
    failed: Callable[[Simulation], str | None] | None = None,
) -> tuple[bool, str]:
    """Step until every robot reached its goal, one collided, ``timeout`` simulated seconds
    passed or ``failed(sim)`` says why the run cannot go on (a controller that died);
    returns (success, why it ended)."""
    started = time.monotonic()
    bridge.send("clock", t=sim.time)
    while True:
        came = arrived(bridge)  # what came from ROS since the last step
        if came is None:
            return False, "the simulator's node ended"
        for message in came:
            _apply(sim, bridge, message, trace)
        if failed is not None:
            why = failed(sim)
            if why is not None:
                return False, why
        out = sim.step()
        bridge.send("clock", t=sim.time)
        publish(bridge, out, trace)
        if on_step is not None:
            on_step(sim)
        ended = sim.verdict(timeout)
        if ended is not None:
            return ended
        pace(started, sim.time, speed)


def arrived(bridge: Bridge) -> list[dict[str, Any]] | None:
    """The lines the simulator's node sent since the last call; None once it has ended."""
    lines: list[dict[str, Any]] = []
    while True:
        try:
            message = bridge.lines.get_nowait()
        except queue.Empty:
            return lines
        if message is None:
            return None
        lines.append(message)


def pace(started: float, simulated: float, speed: float) -> None:
    """Sleep until ``simulated`` seconds of simulated time are due at ``speed`` times real
    time from ``started`` (time.monotonic())."""
    delay = started + simulated / speed - time.monotonic()
    if delay > 0:
        time.sleep(delay)


def _apply(sim: Simulation, bridge: Bridge, message: dict[str, Any], trace: Trace | None = None) -> None:
    op, robot = message.get("op"), message.get("robot")
    if not isinstance(robot, int) or not 0 <= robot < sim.robots:
        return
    if op == "command":
        role = str(message.get("role"))
        if trace is not None:
            trace("in", robot, role, float(message.get("received", time.perf_counter())))
        apply_command(sim, robot, role, message.get("value"))
    elif op == "refused":
        sim.refused(robot)
    elif op == "press":
        publish(bridge, sim.press(robot, bool(message.get("pressed"))), trace)
