# -*- coding: utf-8 -*-
"""Reading received data as the model declares it: a number, an integer, a boolean or a string
(:func:`num`, :func:`whole`, :func:`flag`, :func:`text`), whether a value fits a field's domain
(:func:`fits`), and :class:`Unreadable`, raised for data that cannot be read (the event is then
not delivered). Standard library only: copied into every generated package."""

from __future__ import absolute_import, annotations, print_function

import math
from typing import Any, Tuple

from .values import finite

isfinite = math.isfinite  # for the generated data checks


class Unreadable(ValueError):
    """Received data that cannot be read as the model declares it."""


def num(value: Any) -> Any:
    """A number read from received data (a double or an integer of the model): not a
    boolean, string or NaN. Infinities pass: REP 117 gives them a meaning in a range
    (no return, too close), and they compare as such."""
    if type(value) is float:
        if value != value:
            raise Unreadable("NaN")
        return value
    if isinstance(value, (bool, str, bytes)) or value is None:
        raise Unreadable("%r is not a number" % (value,))
    try:
        number = float(value)
    except Exception:
        raise Unreadable("%r is not a number" % (value,)) from None
    if number != number:
        raise Unreadable("NaN")
    return value


def whole(value: Any) -> Any:
    """An integer read from received data."""
    if isinstance(value, bool) or not isinstance(value, int):
        try:
            import operator

            return operator.index(value)  # numpy integers
        except Exception:
            raise Unreadable("%r is not an integer" % (value,)) from None
    return value


def flag(value: Any) -> bool:
    """A boolean read from received data."""
    if isinstance(value, bool):
        return value
    if type(value).__name__ == "bool_":  # numpy
        return bool(value)
    raise Unreadable("%r is not a boolean" % (value,))


def text(value: Any) -> str:
    """A string read from received data."""
    if isinstance(value, str):
        return value
    raise Unreadable("%r is not a string" % (value,))


def unreadable_data(enum: str, error: Exception) -> Unreadable:
    """Why the rules of ``enum`` could not read the data: ``error``, said as Unreadable."""
    if isinstance(error, Unreadable):
        return Unreadable("%s: %s" % (enum, error))
    return Unreadable("%s: %s: %s" % (enum, type(error).__name__, error))


def fits(check: Any, value: Any) -> bool:
    """Whether ``value`` is inside a field's domain (``check`` as the generated code gives it:
    None for anything, a type name, ("integer", low, high), or the names an enum or a
    location takes)."""
    if check is None:
        return True
    if isinstance(check, tuple):  # the names of an enum or an automaton, or ("integer", low, high)
        if len(check) == 3 and check[0] == "integer" and type(check[1]) is int:
            return isinstance(value, int) and not isinstance(value, bool) and check[1] <= value <= check[2]
        return isinstance(value, str) and value in check
    if check == "boolean":
        return isinstance(value, bool)
    if check == "integer":
        return isinstance(value, int) and not isinstance(value, bool)
    if check == "double":
        return isinstance(value, (int, float)) and not isinstance(value, bool) and finite(float(value))
    if check == "string":
        return isinstance(value, str)
    return True


def set_path(target: Any, steps: Tuple[Any, ...], value: Any) -> None:
    """``target.a.b[2] = value`` for steps ``("a", "b", 2)``."""
    for step in steps[:-1]:
        target = target[step] if isinstance(step, int) else getattr(target, step)
    last = steps[-1]
    if isinstance(last, int):
        target[last] = value
    else:
        setattr(target, last, value)
