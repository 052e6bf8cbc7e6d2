# -*- coding: utf-8 -*-
"""The belief: what the supervisor believes of where the robots are (:class:`Belief`, a part of
the supervisor). The values a field may have, and the completions tried over them, are
``unknown.py``'s.

Standard library only, Python 3.8 or newer (ROS Noetic).
"""

from __future__ import absolute_import, annotations

import copy
import json
import time
from typing import Any, Callable, Dict, Optional, Tuple

from .answers import moved
from .outcomes import Outcomes
from .reading import Unreadable, fits
from .tables import Event
from .unknown import TooMany, Unknown, completions, distinct
from .values import Data, plain


class Belief(Outcomes):
    """What the supervisor believes of where the robots are.

    It owns ``unconfirmed`` (field -> the values it may have, None: any), ``why`` (per
    component) and ``versions`` (field -> how many times its candidates changed). While part of
    the state is unconfirmed, a controllable event is performed only where it is allowed in
    every state the robots may be in and sends the same data in each, and an uncontrollable
    event moves each field to what it leads to in the states where it can happen; a report
    (:meth:`confirm`) makes a component known. Answers and commands are :class:`Answers`'."""

    def _reset_belief(self, confirmed: bool) -> None:
        # unconfirmed field -> the values it may have (None: any); why, per component
        self.unconfirmed: Dict[str, Optional[Tuple[Any, ...]]] = {}
        self.why: Dict[str, str] = {}
        self.versions: Dict[str, int] = {}  # field -> how many times its candidates changed
        self._trying = False  # while _over tries completions: outcomes are noted, not unconfirmed
        self._forked: list[Tuple[str, Tuple[Any, ...]]] = []  # (field, outcomes) of the event tried
        if not confirmed:
            self.unconfirm(
                dict((attribute, self.CANDIDATES[attribute]) for attribute in self.COMPONENT_OF),
                "not confirmed since the start",
            )

    def unsure(self) -> Dict[str, Dict[str, Any]]:
        """The unconfirmed components: {component: {"why": ..., "may_be": {field label: [values]
        or "any"}}}."""
        out: Dict[str, Dict[str, Any]] = {}
        for attribute, values in self.unconfirmed.items():
            component = self.COMPONENT_OF.get(attribute, self.LABELS[attribute])
            entry = out.setdefault(component, {"why": self.why.get(component, "unconfirmed"), "may_be": {}})
            entry["may_be"][self.LABELS[attribute]] = "any" if values is None else [plain(v) for v in values]
        return out

    def unconfirm(self, fields: Dict[str, Optional[Tuple[Any, ...]]], why: str) -> None:
        """The ``fields`` (attribute -> the values each may have, None: any) are not known any
        more, for the reason ``why`` (said per component). A field with one value is known."""
        for attribute, values in fields.items():
            if values is not None:
                values = distinct(list(values))
            if values is not None and len(values) == 1:
                self.know(attribute, values[0])
                continue
            if attribute not in self.unconfirmed or self.unconfirmed[attribute] != values:
                self.versions[attribute] = self.versions.get(attribute, 0) + 1
            self.unconfirmed[attribute] = values
            self.health_changes += 1
            setattr(self, attribute, Unknown(attribute))
            component = self.COMPONENT_OF.get(attribute, self.LABELS[attribute])
            if self.why.get(component) != why:
                self.why[component] = why
                self.health_changes += 1
        self._dirty = True

    def know(self, attribute: str, value: Any) -> None:
        """The field ``attribute`` is confirmed to hold ``value``."""
        if attribute in self.unconfirmed:
            del self.unconfirmed[attribute]
            self.health_changes += 1
            self.versions[attribute] = self.versions.get(attribute, 0) + 1
            component = self.COMPONENT_OF.get(attribute, self.LABELS[attribute])
            if not any(self.COMPONENT_OF.get(a, self.LABELS[a]) == component for a in self.unconfirmed):
                self.why.pop(component, None)
        setattr(self, attribute, value)
        self._dirty = True

    def confirm(self, component: str, report: Any, since: Optional[float] = None) -> Optional[str]:
        """A report of where ``component`` is, from its driver: a location name, or an object
        with ``state`` (the location) and values of its variables by name. Taken (None) when
        every value is in its field's domain, else nothing changes and why is returned. A report
        is the robot's own word: where it contradicts the belief (a value the component was not
        thought able to have now), the belief is what was wrong; the report is taken, and a
        warning says so. Variables it does not give stay as they are. ``since``: when (this
        wall clock) the driver was asked; an answer stamped later may not be in the report: it
        is taken."""
        fields = self.COMPONENTS.get(component)
        if fields is None:
            return "no component %s" % (component,)
        if isinstance(report, str) and report.lstrip().startswith("{"):
            try:
                report = json.loads(report)
            except ValueError as error:
                return "not a location or a JSON object (%s)" % (error,)
        if isinstance(report, str):
            report = {"state": report.strip()}
        if not isinstance(report, dict):
            return "not a location or a JSON object"
        values: Dict[str, Any] = {}
        contradicted: list[str] = []
        by_label = dict((self.LABELS[a], a) for a in fields)
        for key, value in report.items():
            attribute = by_label.get(component if key == "state" else "%s.%s" % (component, key))
            if attribute is None:
                return "%s has no %s" % (component, "location" if key == "state" else "variable %s" % key)
            domain = next(f[4] for f in self.FIELDS if f[0] == attribute)
            if not fits(domain, value):
                return "%s: %r is outside its domain" % (key, value)
            may = self.unconfirmed.get(attribute, ())
            if attribute in self.unconfirmed:
                if may is not None and not any(type(v) is type(value) and v == value for v in may):
                    contradicted.append("%s %r (the belief: %s)" % (key, value, " or ".join(map(repr, may))))
            elif not (type(getattr(self, attribute)) is type(value) and getattr(self, attribute) == value):
                contradicted.append("%s %r (the belief: %r)" % (key, value, getattr(self, attribute)))
            values[attribute] = value
        if contradicted:
            self.warn("%s reported %s: the belief was wrong, the report is taken" % (component, ", ".join(contradicted)))
        for attribute, value in values.items():
            self.know(attribute, Data.wrap(value) if isinstance(value, (dict, list)) else value)
            if self.watching and self.awaited(attribute):
                # as reported: waiting for its answer from when the driver was asked
                self.commanded[attribute] = since if since is not None else time.time()
            else:
                self.commanded.pop(attribute, None)
        return None

    def _answer_trial(self, method: str, attribute: str) -> Callable[[], Any]:
        def run() -> Any:
            getattr(self, method)(Unknown("value"))
            return [state[self.INDEX[attribute]] for state in self._variants()]

        return run

    def after_answers(self, attribute: str) -> Dict[str, Optional[Tuple[Any, ...]]]:
        """Where the component whose location is ``attribute`` may be when an answer it waits for
        may have come: where it is, or where any of them leads (every field of the component
        anywhere in its domain when an answer's effect reads its data)."""
        values = [getattr(self, attribute)]
        for name in self.awaited(attribute):
            try:
                outcomes = self._over(self._answer_trial(self.EVENT[name].method, attribute))
            except TooMany:
                component = self.COMPONENT_OF.get(attribute, attribute)
                return dict((a, self.CANDIDATES[a]) for a in self.COMPONENTS.get(component, (attribute,)))
            values.extend(value for _, some in outcomes for value in some)
        return {attribute: distinct(values)}

    def _over(self, run: Callable[[], Any]) -> list[Tuple[Dict[str, Any], Any]]:
        """``run()`` once per completion of the unconfirmed fields it reads (``belief.completions``),
        each from the state as it is now, which is put back afterwards; nothing is recorded
        meanwhile. Raises ``TooMany`` when the answer cannot be had by trying."""
        saved = [getattr(self, attribute) for attribute in self.ATTRIBUTES]
        mutable = [isinstance(value, (Data, list, dict)) for value in saved]
        dirty, sent, observer = self._dirty, self._sent, self.observer
        self.observer = None

        def assign(fixed: Dict[str, Any]) -> None:
            for attribute, value, copied in zip(self.ATTRIBUTES, saved, mutable):
                setattr(self, attribute, copy.deepcopy(value) if copied else value)
            for attribute, value in fixed.items():
                setattr(self, attribute, value)
            self._dirty = True
            self._sent = {}
            self._forked = []

        self._trying = True
        try:
            return completions(self.unconfirmed, assign, run)
        finally:
            for attribute, value in zip(self.ATTRIBUTES, saved):
                setattr(self, attribute, value)
            self._dirty, self._sent, self.observer = dirty, sent, observer
            self._trying = False
            self._forked = []

    def _settle_fields(self, states: list[list[Any]]) -> None:
        """After an event taken in several completions: each field known where it has one value
        in all of them, else unconfirmed with the values it has (its earlier candidates where a
        completion left it unknown)."""
        for index, attribute in enumerate(self.ATTRIBUTES):
            values = [state[index] for state in states]
            found: list[Any] = []
            anything = False
            for value in values:
                if isinstance(value, Unknown):
                    earlier = self.unconfirmed.get(attribute)
                    if earlier is None:
                        anything = True
                    else:
                        found.extend(earlier)
                else:
                    found.append(value)
            if anything:
                if self.unconfirmed.get(attribute, ()) is not None or attribute not in self.unconfirmed:
                    self.unconfirm({attribute: None}, self.why.get(self.COMPONENT_OF.get(attribute, ""), "unconfirmed"))
                continue
            found_values = distinct(found)
            if len(found_values) == 1:
                self.know(attribute, found_values[0])
            elif attribute not in self.unconfirmed or self.unconfirmed[attribute] != found_values:
                component = self.COMPONENT_OF.get(attribute, self.LABELS[attribute])
                self.unconfirm({attribute: found_values}, self.why.get(component, "unconfirmed"))

    def _current_unsure(self) -> Tuple[Callable[..., Optional[str]], ...]:
        """While part of the state is unconfirmed: the controllable events allowed wherever the
        robots may be (none when that cannot be told by trying)."""

        def run() -> Tuple[str, ...]:
            self._provide()
            allowed = self._allowed()
            return tuple(p.__name__ for p in (self._filter(allowed) if self.stale else allowed))

        try:
            outcomes = self._over(run)
        except TooMany as too_many:
            self.warn(
                "holding every command: too much is unconfirmed to tell what is allowed (%s)"
                % self.LABELS.get(too_many.field, too_many.field),
                "too many",
            )
            return ()
        if not outcomes:
            return ()
        first = outcomes[0][1]
        common = [name for name in first if all(name in names for _, names in outcomes[1:])]
        return tuple(self._unsure_event(name) for name in common)

    def _unsure_event(self, method: str) -> Callable[..., Optional[str]]:
        def perform(data: Any = None) -> Optional[str]:
            return self._perform_unsure(method, data)

        perform.__name__ = method
        return perform

    def _perform_unsure(self, method: str, data: Any) -> Optional[str]:
        """Perform a controllable event allowed wherever the robots may be: only when it sends the
        same data in every completion; then each field is where the event leaves it."""
        event = self.BY_METHOD[method]
        send = self.__dict__.get("send")

        def run() -> Tuple[Optional[str], list[Any], list[Any]]:
            self._provide()
            sent: list[Any] = []

            def stub(name: str, data: Any) -> bool:
                sent.append(data)
                return True

            self.send = stub  # type: ignore[method-assign]
            try:
                result = getattr(self, method)(data)
            finally:
                if send is None:
                    del self.send
                else:
                    self.send = send  # type: ignore[method-assign]
            return result, sent, self._variants()

        try:
            outcomes = self._over(run)
        except TooMany:
            return None
        if not outcomes or any(result is None for _, (result, _, _) in outcomes):
            return None
        sent = outcomes[0][1][1]
        if any(plain(other[1][1]) != plain(sent) for other in outcomes[1:]):
            self.warn(
                "held: %s would send different data where the robots may be (unconfirmed)" % event.name,
                "differs " + event.name,
            )
            return None
        if sent and not self.send(event.name, sent[0]):
            return None
        self._settle_fields([state for _, (_, _, states) in outcomes for state in states])
        self._dirty = True
        if self.observer is not None:
            self._record(event.name, True, sent[0] if sent else data)
        return event.name

    def _deliver_unsure(self, event: Event, value: Any, stamp: Optional[float]) -> bool:
        """An uncontrollable event while part of the state is unconfirmed: taken in each
        completion where it can be, ignored (nothing changes) in the others, which therefore
        stay possible: an answer may be spurious or a duplicate, so it tells where a component
        is only where every place it may be leads to the same one."""

        doubt = self.may_repeat(event.name)
        befores: list[list[Any]] = []

        def run() -> Any:
            why = self._not_taken(event.name, stamp)
            state = [getattr(self, attribute) for attribute in self.ATTRIBUTES]
            if why is not None:
                return why, [state]
            if doubt:  # a second copy of an earlier answer leaves it where it was
                befores.append(state)
            try:
                getattr(self, event.method)(value)
            except Unreadable as error:
                return error
            return None, self._variants()

        saved = type(self).GETTER(self)
        try:
            outcomes = self._over(run)
        except TooMany as too_many:  # it reads what cannot be tried: anything it may change is unknown
            self.unconfirm(
                dict((a, self.CANDIDATES[a]) for a in self.COMPONENT_OF),
                "%s came while too much was unconfirmed to follow it (%s)"
                % (event.name, self.LABELS.get(too_many.field, too_many.field)),
            )
            return self.ignore(event.name, "too much is unconfirmed to tell what it changes")
        unreadable = [result for _, result in outcomes if isinstance(result, Unreadable)]
        if unreadable:
            return self._unreadable(event, unreadable[0])
        if all(why is not None for _, (why, _) in outcomes):
            return self.ignore(event.name, outcomes[0][1][0] if outcomes else "not expected now")
        states = [state for _, (_, some) in outcomes for state in some] + befores
        if befores and self._settles_as_it_is(states):  # a copy, or an answer: the belief has both already
            for field, _ in self.ANSWERS[event.name]:  # but something may have changed: ask at once
                component = self.COMPONENT_OF[field]
                if field in self.unconfirmed:
                    self.doubt(component)
            return self.ignore(event.name, "it changes nothing the node believes (it may be a second copy)")
        self._settle_fields(states)
        self._delivered(event, value, saved, stamp)
        return True

    def _settles_as_it_is(self, states: list[list[Any]]) -> bool:
        """Whether :meth:`_settle_fields` would leave every field as it is: known where it has its
        value in all ``states``, else unconfirmed with the values it has now."""
        for index, attribute in enumerate(self.ATTRIBUTES):
            earlier = self.unconfirmed.get(attribute, ())
            if earlier is None:
                continue  # it may have any value, and keeps that
            found: list[Any] = []
            for state in states:
                value = state[index]
                found.extend(earlier if isinstance(value, Unknown) else (value,))
            values = distinct(found)
            now = earlier if attribute in self.unconfirmed else (getattr(self, attribute),)
            if len(values) != len(now) or len(distinct(list(now) + list(values))) != len(now):
                return False
        return True

    def _doubt(self, name: str, saved: Any) -> None:
        """The answer ``name`` moved fields from their values in ``saved``: it may have been a second
        copy of an earlier answer, so each stays unconfirmed between where it was and where it is
        now (where the belief was unconfirmed already, it kept where it was) until its driver
        reports; the components are ``doubted``, for the node to ask their drivers at once."""
        fields: Dict[str, Optional[Tuple[Any, ...]]] = {}
        components = []
        for place, attribute in self.TRACKED:
            new, old = getattr(self, attribute), saved[place]
            if new is old or not moved(new, old):
                continue
            component = self.COMPONENT_OF[attribute]
            if component not in components:
                components.append(component)
            if not isinstance(old, Unknown) and not isinstance(new, Unknown):
                fields[attribute] = (old, new)
        why = "%s may be a second copy of an earlier answer: its driver is asked" % (name,)
        self.unconfirm(fields, why)
        for component in components:
            self.why[component] = why
            self.doubt(component)
