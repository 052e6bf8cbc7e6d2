# -*- coding: utf-8 -*-
"""Confirming where the robots are (a part of :class:`~.node.NodeCore`): the driver of each
unconfirmed component is asked for a report (a ``std_srvs/Trigger`` service at
``REPORT_PREFIX`` + its name), a report asked for before a change is not taken, and a
component that waited too long for an answer the model expects is unconfirmed."""

from __future__ import absolute_import, annotations

import time

from .node_base import NodeBase

REPORT_PREFIX = "robosc/report/"  # + a component's name: the std_srvs/Trigger service its driver offers


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
            if client is not None:
                try:
                    if component not in self.asked_since:  # the first request of a round
                        self.asked_since[component] = time.time()
                        self.asked_after[component] = self.supervisor.changes.get(component, 0)
                    if self.ask_report(component, client):
                        self.asked[component] = now
                except Exception as error:
                    self.asked[component] = now
                    self.warnings("cannot ask %s for its state: %s" % (component, error), "ask " + component)

    def report(self, component: str, success: bool, message: str) -> None:
        """A driver's answer to a report request (``success`` False: it could not tell)."""
        since = self.asked_since.pop(component, None)  # the round of requests ends
        after = self.asked_after.pop(component, None)
        if component not in self.supervisor.unsure():
            return
        if not success:
            self.warnings("%s could not report its state: %s" % (component, message), "report " + component)
            return
        if since is None or self.supervisor.changes.get(component, 0) != after:
            # asked for before a command to it went out or an answer moved it (or an answer to an
            # earlier round): its driver may have answered before that; asked again (once no
            # command is on its way: ask_reports)
            self.asked.pop(component, None)
            self.log("info", "report of %s not taken: it changed since it was asked (a command or an answer)" % (component,))
            return
        why = self.supervisor.confirm(component, message, since)
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
