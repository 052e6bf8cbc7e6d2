# -*- coding: utf-8 -*-
"""Confirming where the robots are (a part of :class:`~.node.NodeCore`): the driver of each
unconfirmed component is asked for a report (a ``std_srvs/Trigger`` service at
``REPORT_PREFIX`` + its name), a report asked for before a change is not taken, and a
component that waited too long for an answer the model expects is unconfirmed."""

from __future__ import absolute_import, annotations

import time
from typing import Any, List

from .node_base import NodeBase

REPORT_PREFIX = "robosc/report/"  # + a component's name: the std_srvs/Trigger service its driver offers
MAX_REQUESTS = 100  # report requests of one component out at once, at most


class NodeReports(NodeBase):
    """Asking the drivers for reports, and taking them."""

    def ask_reports(self, now: float) -> None:
        """Ask the driver of each unconfirmed component (but those waiting for an acknowledgement)
        for its state: as soon as its report service is there, then every ``report_interval``
        seconds (a request that could not go out, no server yet, is tried at the next look)."""
        waiting = self.delivery.waiting()
        for component in self.supervisor.unsure():
            if component in waiting:
                continue
            if now - self.asked.get(component, -1e18) < self.params["report_interval"]:
                continue
            client = self.report_clients.get(component)
            if client is None:
                continue
            queue = self.requests.setdefault(component, [])
            if len(queue) >= MAX_REQUESTS:  # a driver that answers none: no more until it does
                continue
            request = (time.time(), self.supervisor.changes.get(component, 0))
            queue.append(request)
            self.asked_since[component] = queue[0][0]
            try:
                sent = self.ask_report(component, client)
            except Exception as error:
                sent = False
                self.asked[component] = now
                self.warnings("cannot ask %s for its state: %s" % (component, error), "ask " + component)
            if sent:
                self.asked[component] = now
            elif request in queue:  # it did not go out
                queue.remove(request)
                self._answered(component)

    def _answered(self, component: str) -> None:
        """A request of ``component`` is answered or did not go out: the oldest still out, if any."""
        queue = self.requests.get(component)
        if queue:
            self.asked_since[component] = queue[0][0]
        else:
            self.requests.pop(component, None)
            self.asked_since.pop(component, None)

    def reported_by(self, component: str, future: Any) -> None:
        """A report request's future (rclpy's) is done: its std_srvs/Trigger response, or why not."""
        try:
            response = future.result()
        except Exception as error:
            self.not_answered(component)
            self.warnings("%s could not report: %s" % (component, error), "report " + component)
            return
        if response is not None:
            self.report(component, bool(response.success), str(response.message))

    def not_answered(self, component: str) -> None:
        """The oldest report request of ``component`` out will not be answered (it failed, or the
        adapter gave up on it)."""
        queue = self.requests.get(component)
        if queue:
            queue.pop(0)
        self._answered(component)

    def ask_again(self, components: List[str]) -> None:
        """Ask the drivers of ``components`` (an answer left them unconfirmed) at once, not at the
        next ``report_interval``; what a request already out tells may be from before the answer,
        so it is not taken (``report``)."""
        for component in components:
            self.asked.pop(component, None)
        del components[:]
        self.ask_reports(time.time())

    def report(self, component: str, success: bool, message: str) -> None:
        """A driver's answer to its oldest report request not answered yet (``success`` False: it
        could not tell)."""
        queue = self.requests.get(component)
        request = queue.pop(0) if queue else None
        self._answered(component)
        if component not in self.supervisor.unsure():
            return
        if not success:
            self.warnings("%s could not report its state: %s" % (component, message), "report " + component)
            return
        if request is None or self.supervisor.changes.get(component, 0) != request[1]:
            # asked for before a command to it went out or an answer moved it (or a request given
            # up on): its driver may have answered before that; asked again at once (once no
            # command is on its way: ask_reports)
            self.asked.pop(component, None)
            self.log("info", "report of %s not taken: it changed since it was asked (a command or an answer)" % (component,))
            self.ask_reports(time.time())
            return
        why = self.supervisor.confirm(component, message, request[0])
        if why is None:
            self.log("info", "%s confirmed by its driver: %s" % (component, message))
        else:
            self.warnings("report of %s refused: %s" % (component, why), "report " + component)
        self.checkpoint()

    def overdue(self, now: float) -> None:
        """Components that waited longer than ``answer_timeout`` for an answer the model expects:
        unconfirmed (the answer may have come and been lost), and their drivers asked."""
        limit = self.params["answer_timeout"]
        if limit <= 0:
            return
        supervisor = self.supervisor
        for attribute, since in list(supervisor.commanded.items()):
            if now - since < limit or attribute in supervisor.unconfirmed:
                continue
            awaited = supervisor.awaited(attribute)
            del supervisor.commanded[attribute]  # said once: its driver's report tells from now on
            if not awaited:
                continue
            component = supervisor.COMPONENT_OF.get(attribute, attribute)
            supervisor.unconfirm(
                supervisor.after_answers(attribute),
                "no answer (%s) for %.1f s" % (", ".join(awaited), now - since),
            )
            self.log(
                "warning",
                "%s: no answer (%s) for %.1f s; unconfirmed, its driver is asked"
                % (component, ", ".join(awaited), now - since),
            )
