# -*- coding: utf-8 -*-
"""What the generated methods call to change the state (a part of the supervisor, mixed into
:class:`~.supervisor.Supervisor`): a data plant's choice (:meth:`Effects._choose`), computed
data that must not be sent (:meth:`Effects._refuse`), the assignments of a transition
(:meth:`Effects._assign`: kept where a value cannot be computed or is outside its type) and
of an uncontrollable event that reads received data (:meth:`Effects._receive`: Unreadable
then, and the event is not delivered). It owns no state of its own."""

from __future__ import absolute_import, annotations, print_function

from typing import Any, Callable, Optional, Tuple

from .reading import Unreadable, fits, set_path
from .tables import KEEP, NO_DATA, REFUSED, Tables
from .values import plain


class Effects(Tables):
    """The generated methods' helpers."""

    def _choose(self, field: str, location: str) -> None:
        """A data plant moves to ``location`` (step 1 of the cycle)."""
        setattr(self, field, location)
        self._dirty = True
        if self.observer is not None:
            label = self.LABELS[field]
            self._record(label + (".provide_none" if location == NO_DATA else "." + location), True, None)

    def _refuse(self, communication: str, error: Optional[BaseException]) -> Any:
        """Computed data that must not be sent: it could not be computed (``error``), or a
        number in it is not finite. Reported; the event is then not performed."""
        if error is None:
            self.warn("%s: a number in the data is not finite; not sent" % (communication,), "finite " + communication)
        else:
            why = "%s: %s" % (type(error).__name__, error)
            self.warn("%s: cannot compute the data (%s); not sent" % (communication, why), "data " + communication)
        return REFUSED

    def _assign(self, *assignments: Tuple[str, Tuple[Any, ...], str, Callable[[], Any], Any]) -> None:
        """Assignments of one transition: each (field, steps, label, compute, check); every
        value is computed first, then stored. A value that cannot be computed, or is outside
        the variable's type, leaves the variable as it was (with a warning)."""
        values = []
        for _field, _steps, label, compute, _check in assignments:
            try:
                value = compute()
            except Exception as error:
                self.warn(
                    "%s: cannot compute the new value (%s: %s); kept" % (label, type(error).__name__, error),
                    "compute " + label,
                )
                value = KEEP
            values.append(value)
        for (field, steps, label, _compute, check), value in zip(assignments, values):
            if value is KEEP:
                continue
            if steps:
                try:
                    set_path(getattr(self, field), steps, value)
                except Exception as error:
                    self.warn(
                        "%s: cannot store (%s: %s); kept" % (label, type(error).__name__, error), "store " + label
                    )
            elif fits(check, value):
                setattr(self, field, value)
            else:
                self.warn("%s: %r is outside its type; kept" % (label, plain(value)), "outside " + label)

    def _receive(self, *assignments: Tuple[str, Tuple[Any, ...], str, Callable[[], Any], Any]) -> None:
        """Assignments of an uncontrollable event, which read received data: every value is
        computed and checked first, then stored. Unreadable when one cannot be computed or is
        outside its variable's type (the event is then not delivered)."""
        values = []
        for _field, _steps, label, compute, check in assignments:
            try:
                value = compute()
            except Unreadable as error:
                raise Unreadable("%s: %s" % (label, error)) from None
            except Exception as error:
                raise Unreadable("%s: %s: %s" % (label, type(error).__name__, error)) from None
            if not fits(check, value):
                raise Unreadable("%s: %r is outside its type" % (label, plain(value)))
            values.append(value)
        for (field, steps, label, _compute, _check), value in zip(assignments, values):
            if steps:
                try:
                    set_path(getattr(self, field), steps, value)
                except Exception as error:
                    raise Unreadable("%s: cannot store (%s: %s)" % (label, type(error).__name__, error)) from None
            else:
                setattr(self, field, value)

    @staticmethod
    def _outside(label: str, value: Any) -> Any:
        """Received data outside the type of the variable ``label`` (an enum read from the data
        as it came, which is not one of its names): Unreadable, the event is not delivered."""
        raise Unreadable("%s: %r is outside its type" % (label, plain(value)))

    def _unchanged(self, value: Any) -> None:
        """An uncontrollable event that changes nothing (a message no transition reads)."""
