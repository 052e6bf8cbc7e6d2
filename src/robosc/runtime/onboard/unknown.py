# -*- coding: utf-8 -*-
"""What the supervisor knows of the robots, and what it does not.

After a start (or a restart: nothing is taken from a file), and after a command whose
delivery is uncertain or an answer that did not come, part of the robots' state is
*unconfirmed*: a field of a component (its location, one of its variables) holds
:class:`Unknown`, with the values it may have (its *candidates*, or any value). The
generated conditions and effects read fields as they always do; reading an unknown one
raises :class:`Unconfirmed` (a ``BaseException``, so that no ``except Exception`` of the
generated code or the runtime can take it for bad data). :func:`completions` then runs
the same code again once per candidate of the field it read, and so on: a controllable
event is allowed only where it is allowed in every completion, and an uncontrollable
event moves each field to the values it has after it in the completions where it can
happen. A field with too many candidates, or any value, is never enumerated: what reads
it is held until the robot confirms it (a report, an event that tells, fresh data).

Standard library only, Python 3.8 or newer (ROS Noetic).
"""

from __future__ import absolute_import, annotations

from typing import Any, Callable, Dict, List, Optional, Tuple

ENUMERABLE = 64  # a field with more candidates than this is "any value" (never enumerated)
SEARCH_LIMIT = 4096  # completions tried for one question before the answer is "unknown"


class Unconfirmed(BaseException):
    """Raised where generated code reads a field whose value is not confirmed."""

    def __init__(self, field: str) -> None:
        super(Unconfirmed, self).__init__(field)
        self.field = field


class Unknown(object):
    """The value of an unconfirmed field: any use of it raises :class:`Unconfirmed`."""

    __slots__ = ("field",)

    def __init__(self, field: str) -> None:
        self.field = field

    def _read(self, *_args: Any) -> Any:
        raise Unconfirmed(self.field)

    __eq__ = __ne__ = __lt__ = __le__ = __gt__ = __ge__ = _read
    __bool__ = __hash__ = __len__ = __iter__ = __contains__ = __getitem__ = _read
    __add__ = __radd__ = __sub__ = __rsub__ = __mul__ = __rmul__ = _read
    __truediv__ = __rtruediv__ = __floordiv__ = __rfloordiv__ = __mod__ = __rmod__ = _read
    __pow__ = __rpow__ = __neg__ = __pos__ = __abs__ = _read
    __int__ = __float__ = __index__ = __round__ = _read

    def __getattr__(self, name: str) -> Any:
        raise Unconfirmed(self.field)

    def __repr__(self) -> str:
        return "<unconfirmed>"


def enumerable(domain: Any) -> Optional[Tuple[Any, ...]]:
    """The values a field of ``domain`` (as the generated ``FIELDS`` give it) can take, when
    they are few enough to try one by one; None otherwise (a double, a string, a wide range)."""
    if isinstance(domain, tuple):
        if len(domain) == 3 and domain[0] == "integer" and type(domain[1]) is int:
            low, high = domain[1], domain[2]
            return tuple(range(low, high + 1)) if high - low < ENUMERABLE else None
        return tuple(domain) if len(domain) <= ENUMERABLE else None
    if domain == "boolean":
        return (False, True)
    return None


def distinct(values: List[Any]) -> Tuple[Any, ...]:
    """``values`` without repeats, in order (compared with ``==``: values need not hash)."""
    out: List[Any] = []
    for value in values:
        if not any(value is seen or (type(value) is type(seen) and value == seen) for seen in out):
            out.append(value)
    return tuple(out)


class TooMany(Exception):
    """A question needs more completions than :data:`SEARCH_LIMIT`, or a field it reads has
    any value: its answer is unknown."""

    def __init__(self, field: str) -> None:
        super(TooMany, self).__init__(field)
        self.field = field


def completions(
    fields: Dict[str, Optional[Tuple[Any, ...]]],
    assign: Callable[[Dict[str, Any]], None],
    run: Callable[[], Any],
    limit: int = SEARCH_LIMIT,
) -> List[Tuple[Dict[str, Any], Any]]:
    """``run()`` in every completion of the unconfirmed ``fields`` (attribute -> candidates,
    None: any value) that it reads: ``[(values fixed, result)]``. ``assign(fixed)`` puts a
    completion in place (the fields fixed, the others unknown) before each run. Raises
    :class:`TooMany` when a field read has any value or the runs would exceed ``limit``."""
    out: List[Tuple[Dict[str, Any], Any]] = []
    stack: List[Dict[str, Any]] = [{}]
    runs = 0
    while stack:
        fixed = stack.pop()
        runs += 1
        if runs > limit:
            raise TooMany(next(iter(fields)) if fields else "")
        assign(fixed)
        try:
            result = run()
        except Unconfirmed as unconfirmed:
            field = unconfirmed.field
            values = fields.get(field)
            if values is None or field in fixed:
                raise TooMany(field) from None
            for value in reversed(values):
                branch = dict(fixed)
                branch[field] = value
                stack.append(branch)
            continue
        out.append((fixed, result))
    return out
