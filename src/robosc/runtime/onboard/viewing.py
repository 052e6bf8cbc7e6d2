# -*- coding: utf-8 -*-
"""The node's live view and recording (a part of :class:`~.node.NodeCore`): the event log, the
live view on 127.0.0.1, the ``live_view/*`` topics for ``robosc view`` and their heartbeat;
the supervisor reports its events only while one of them wants them."""

from __future__ import absolute_import, annotations

import json
import os
import sys
import time
from typing import Any, Callable, Dict, Optional

from .node_base import NodeBase
from .recording import Gated, Recorder

VIEW_PAGE_TOPIC = "live_view/page"
VIEW_EVENTS_TOPIC = "live_view/events"
HEARTBEAT = '{"heartbeat": true}'  # on live_view/events every HEARTBEAT_SECONDS while watched
HEARTBEAT_SECONDS = 0.5


class NodeView(NodeBase):
    """The live view, the view topics and the recorder of a node."""

    def start_recording(self, live_view: Optional[Callable[[Dict[str, Any]], Any]] = None) -> None:
        """Events go to the event log, the live view (a sink) and the view topics (while anyone
        listens), if any, stamped by ``self.clock``: the node's clock, which is the simulation's
        under ``use_sim_time``."""
        if live_view is not None:
            self.sinks.append(live_view)
        if self.view_topics:
            self.sinks.append(Gated(self.view_event, lambda: self.text_subscribers(VIEW_EVENTS_TOPIC) > 0))
        if self.sinks:
            self.recorder = Recorder(self.supervisor, self.sinks, self.clock)
            self.observe()

    def observe(self) -> None:
        """The supervisor reports its events only while a sink wants them (a viewer listening on
        live_view/events comes in within a cycle): an event nobody records costs nothing."""
        recorder = self.recorder
        if recorder is not None:
            self.supervisor.observer = recorder if recorder.wanted() else None

    def view_page(self, robot_class: Any) -> Optional[bytes]:
        """The live view's page generated next to the robot's module, read when the live view
        or the view topics are on; None (with the reason logged) when the package has none.
        Sets ``view_topics``: on when asked for and there is a page to show."""
        port = self.params["view_port"]
        if not (port or self.params["view_topics"]):
            return None
        module = sys.modules.get(robot_class.__module__)
        folder = os.path.dirname(os.path.abspath(getattr(module, "__file__", None) or "."))
        try:
            with open(os.path.join(folder, "live_view.html"), "rb") as handle:
                page = handle.read()
        except OSError as error:
            if port:
                self.log(
                    "error", "live view not started on port %d: %s (generate the package with graphviz)" % (port, error)
                )
            else:
                self.log(
                    "warning", "no live view page for robosc view: %s (generate the package with graphviz)" % (error,)
                )
            return None
        self.view_topics = bool(self.params["view_topics"])
        return page

    def open_live_view(self, page: Optional[bytes]) -> Any:
        """The live view on 127.0.0.1:``view_port``, or None when it is off or cannot start."""
        port = self.params["view_port"]
        if not port or page is None:
            return None
        from .live_server import LiveView

        try:
            view = LiveView(page, port=port)
        except (OSError, ValueError) as error:
            self.log("error", "live view not started on port %d: %s" % (port, error))
            return None
        view.last = self.state_record()
        self.log("info", "live view on %s" % view.url)
        return view

    def state_record(self) -> Dict[str, Any]:
        """A record of no event with the current state: what a new page starts from, stamped
        by the node's clock as its events are (the simulation's under ``use_sim_time``)."""
        return {
            "time": round(self.clock(), 6),
            "event": None,
            "controllable": False,
            "data": None,
            "state": self.supervisor.snapshot(),
        }

    def start_view_topics(self, page: Optional[bytes]) -> None:
        """After the adapter made the ``live_view/*`` publishers: the page, once (latched),
        and the current state; each event follows through :meth:`view_event`."""
        if not self.view_topics or page is None:
            return
        self.publish_text(VIEW_PAGE_TOPIC, page.decode("utf-8", "replace"))
        self.publish_text(VIEW_EVENTS_TOPIC, json.dumps(self.state_record(), sort_keys=True, default=str))

    def view_event(self, record: Dict[str, Any]) -> None:
        """A sink (gated by ``start_recording`` on the topic's subscribers): an event record on
        ``live_view/events``."""
        self.publish_text(VIEW_EVENTS_TOPIC, json.dumps(record, sort_keys=True, default=str))

    def heartbeat(self) -> None:
        """Every half second, while someone watches: a record saying this node is there, so
        that a remote live view can tell a quiet robot from one that is gone."""
        now = time.monotonic()
        if now - self.beat >= HEARTBEAT_SECONDS and self.text_subscribers(VIEW_EVENTS_TOPIC) > 0:
            self.beat = now
            self.publish_text(VIEW_EVENTS_TOPIC, HEARTBEAT)
