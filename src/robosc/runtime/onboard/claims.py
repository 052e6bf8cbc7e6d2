# -*- coding: utf-8 -*-
"""One controller commands a robot or a fleet (a part of :class:`~.node.NodeCore`).

Every controller node publishes a *claim* on ``robosc/coordinator`` (std_msgs/String, JSON,
relative to its namespace: the same topic for two nodes started with the same command line)
every ``CLAIM_INTERVAL`` seconds, and reads the others'. The node started first (the earliest
``since``; a tie goes to the smaller ``id``) commands; any other holds every command, says why in
its log and on ``health`` (``coordinator``), and keeps listening. A node commands only after it
has listened for ``CLAIM_WAIT`` seconds since it started and heard every claim the middleware
knows to be published (ROS 2: the claim topic's publishers discovered; ``CLAIM_TIMEOUT`` more at
most, since DDS lists a killed node's publisher for its lease), or since it last could not publish
its claim for ``CLAIM_TIMEOUT`` seconds (a process stopped and resumed: another may have taken
over meanwhile). A claim not heard for ``CLAIM_TIMEOUT`` seconds is gone: the next node in line
takes over, with everything it believes unconfirmed (it asks the drivers' reports, and waits
for fresh data), within ``CLAIM_TIMEOUT`` + ``CLAIM_INTERVAL`` seconds of the last claim heard.

Standard library only, Python 3.8 or newer (ROS Noetic).
"""

from __future__ import absolute_import, annotations

import binascii
import json
import math
import os
import socket
import time
from typing import Any, Dict, Optional, Tuple

from .node_base import NodeBase

CLAIM_TOPIC = "robosc/coordinator"
CLAIM_INTERVAL = 0.5  # seconds between two claims of a node
CLAIM_TIMEOUT = 2.0  # seconds without a claim from a node before it counts as gone
CLAIM_WAIT = 2.0  # seconds a node listens for others before it commands
MAX_CLAIM_TEXT = 1000  # characters of a claim read at most


class NodeClaims(NodeBase):
    """A controller's claim to command, and the others'."""

    claim: Optional[Dict[str, Any]] = None  # this node's (None: a supervision layer makes none)
    commanding = False  # whether this node commands (a controller, once no older one is heard)
    standby: Optional[str] = None  # why it holds, while another commands

    def start_claims(self) -> None:
        self.claim = {
            "id": binascii.hexlify(os.urandom(8)).decode("ascii"),
            "since": time.time(),
            "host": socket.gethostname(),
            "pid": os.getpid(),
        }
        self.others: Dict[str, Tuple[float, Dict[str, Any]]] = {}  # id -> (when heard, monotonic; claim)
        self.listening_since = time.monotonic()  # commands nothing until CLAIM_WAIT after this
        self.claimed: Optional[float] = None  # when this node last published its claim (monotonic)
        self.commanding = False
        self.standby = None
        self.taken_over = False  # it has held for another: it starts again unconfirmed when it commands
        # claims gone (no claim for CLAIM_TIMEOUT) whose publishers the middleware may still list
        # (ROS 2 keeps a dead node's for its lease, 20 s), and how many it listed at the last look
        self.gone = 0
        self.listed = 0

    def claim_heard(self, message: Any) -> None:
        """A claim on ``robosc/coordinator`` (this node's own too, which it skips)."""
        text = getattr(message, "data", None)
        if self.claim is None or not isinstance(text, str) or len(text) > MAX_CLAIM_TEXT:
            return
        try:
            claim = json.loads(text)
            key, since = claim["id"], float(claim["since"])
            if not isinstance(key, str) or not math.isfinite(since):
                raise ValueError(key)
        except (ValueError, KeyError, TypeError):
            self.warnings("unreadable claim on %s: %r" % (CLAIM_TOPIC, text[:100]), "claim")
            return
        if key == self.claim["id"]:
            return
        if key not in self.others:
            self.log("warning", "another controller of this robot or fleet: %s" % describe(claim))
        self.others[key] = (time.monotonic(), claim)
        self.decide()

    def claims_cycle(self) -> None:
        """Publish this node's claim when due, forget the claims gone, decide who commands."""
        if self.claim is None:
            return
        now = time.monotonic()
        last = self.claimed
        if last is None or now - last >= CLAIM_INTERVAL:
            if last is not None and now - last > CLAIM_TIMEOUT and self.commanding:
                # it could not claim for a while (stopped, starved): another may have taken over
                self.log("warning", "no claim published for %.1f s: listening again before commanding" % (now - last))
                self.commanding = False
                self.taken_over = True
                self.listening_since = now
            try:
                self.publish_text(CLAIM_TOPIC, json.dumps(self.claim, sort_keys=True))
                self.claimed = now
            except Exception as error:
                self.warnings("cannot publish the claim: %s" % (error,), "claim")
        for key, (heard, claim) in list(self.others.items()):
            if now - heard > CLAIM_TIMEOUT:
                del self.others[key]
                self.gone += 1
                self.log("warning", "the controller %s is gone (no claim for %.1f s)" % (describe(claim), now - heard))
        self.decide()

    def decide(self) -> None:
        """Who commands: the earliest live claim; this node only after listening ``CLAIM_WAIT``."""
        assert self.claim is not None
        mine = (self.claim["since"], self.claim["id"])
        older = [claim for _, claim in self.others.values() if (float(claim["since"]), claim["id"]) < mine]
        if older:
            first = min(older, key=lambda c: (float(c["since"]), c["id"]))
            why = "another controller commands: %s" % describe(first)
            if self.commanding or self.standby != why:
                self.log("warning", "holding every command: %s" % why)
                self.supervisor.health_changes += 1
            self.commanding = False
            self.standby = why
            self.taken_over = True
            return
        if time.monotonic() - self.listening_since < CLAIM_WAIT:
            return
        listed = self.claimers()
        if listed < self.listed:  # the middleware dropped publishers: of the gone ones first
            self.gone = max(0, self.gone - (self.listed - listed))
        self.listed = listed
        unheard = listed - len(self.others) - self.gone
        # the middleware lists a claim publisher not heard yet: wait for its claim, CLAIM_TIMEOUT at
        # most (a live node claims every CLAIM_INTERVAL; one killed stays listed for its lease)
        waited = time.monotonic() - self.listening_since
        if unheard > 0 and not self.commanding and waited < CLAIM_WAIT + CLAIM_TIMEOUT:
            if self.standby is None:
                self.standby = "%d other controller(s) on %s not heard from yet" % (unheard, CLAIM_TOPIC)
                self.log("warning", "holding every command: %s" % self.standby)
                self.supervisor.health_changes += 1
            return
        if not self.commanding:
            self.commanding = True
            self.standby = None
            self.supervisor.health_changes += 1
            if self.taken_over:  # what it believes may be stale: asked again, and fresh data waited for
                self.taken_over = False
                self.supervisor.reset(confirmed=False)
                self.asked.clear()
                self.log("warning", "commanding now (no older controller left); where the robots are is unconfirmed")

    def claimers(self) -> int:
        """How many other nodes publish on ``CLAIM_TOPIC``, as the middleware knows (0: it cannot
        tell); a node waits for the claim of each before it commands."""
        return 0

    def claim_health(self) -> Optional[Dict[str, Any]]:
        """What ``health`` says of the claims (None: a supervision layer, or ``claim`` false)."""
        if self.claim is None:
            return None
        return {"id": self.claim["id"], "commanding": self.commanding, "standby": self.standby,
                "others": sorted(self.others)}


def describe(claim: Dict[str, Any]) -> str:
    return "%s (pid %s on %s, started %s)" % (
        claim.get("id"),
        claim.get("pid"),
        claim.get("host"),
        time.strftime("%H:%M:%S", time.localtime(float(claim.get("since", 0)))),
    )
