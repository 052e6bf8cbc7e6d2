# -*- coding: utf-8 -*-
"""Plain data: what the supervisor sends and receives, as the middleware has it.

``Data`` gives attribute access to dicts and lists (data typed in the simulator),
``plain`` turns ROS 1 / ROS 2 messages into JSON-ready data, ``finite`` says
whether every number in some data is finite (no NaN or infinity is ever sent).
"""

from __future__ import absolute_import, annotations

import math
from typing import Any

MAX_DEPTH = 16  # deeper data is malformed: a real message nests a few levels


class Data(object):
    """Attribute access to plain data (dicts and lists), e.g. data typed in the simulator."""

    def __init__(self, fields: dict[Any, Any]) -> None:
        for key, value in fields.items():
            vars(self)[str(key)] = Data.wrap(value)  # not setattr: a key such as "__class__" stays data

    @staticmethod
    def wrap(value: Any, depth: int = 0) -> Any:
        if depth > MAX_DEPTH:
            raise ValueError("data nested more than %d levels" % MAX_DEPTH)
        if isinstance(value, dict):
            data = Data({})
            for key, item in value.items():
                vars(data)[str(key)] = Data.wrap(item, depth + 1)
            return data
        if isinstance(value, list):
            return [Data.wrap(item, depth + 1) for item in value]
        return value

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Data) and vars(self) == vars(other)

    def __ne__(self, other: object) -> bool:
        return not self == other

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return "Data(%r)" % (plain(self),)


def fields_of(value: Any) -> list[str]:
    """The field names of a ROS 1 or ROS 2 message (empty for anything else)."""
    fields = getattr(value, "get_fields_and_field_types", None)  # ROS 2
    if fields is not None:
        return [str(name).lstrip("_") for name in fields()]
    slots = getattr(type(value), "__slots__", None)  # ROS 1 (genpy)
    if slots and hasattr(value, "_type"):
        return list(slots)
    return []


def plain(value: Any, depth: int = 0) -> Any:
    """``value`` as JSON-ready data: ROS messages (ROS 1 and 2) and Data objects become dicts;
    a number that is not finite becomes its name ("nan", "inf")."""
    if value is None or isinstance(value, (bool, int, str)):
        return value
    if isinstance(value, float):
        return value if math.isfinite(value) else str(value)
    if depth > MAX_DEPTH:
        return "..."
    if isinstance(value, (list, tuple)) or type(value).__name__ in ("array", "ndarray"):
        return [plain(item, depth + 1) for item in list(value)]
    if isinstance(value, dict):
        return dict((str(k), plain(v, depth + 1)) for k, v in value.items())
    if isinstance(value, Data):
        return dict((k, plain(v, depth + 1)) for k, v in vars(value).items())
    names = fields_of(value)
    if names:
        return dict((n, plain(getattr(value, n, None), depth + 1)) for n in names)
    if isinstance(value, bytes):
        return list(bytearray(value))
    return repr(value)


_SCALARS = frozenset((bool, int, str, bytes, type(None)))
_isfinite = math.isfinite


def finite(value: Any, depth: int = 0) -> bool:
    """Whether every number in ``value`` (plain data, a Data object or a ROS message) is finite.
    Data nested deeper than MAX_DEPTH is refused. (On the path of every computed command:
    plain dicts of floats are checked without a call per item.)"""
    kind = type(value)
    if kind is float:
        return _isfinite(value)
    if kind in _SCALARS:
        return True
    if depth > MAX_DEPTH:
        return False
    if kind is dict:
        for item in value.values():
            item_kind = type(item)
            if item_kind is float:
                if not _isfinite(item):
                    return False
            elif item_kind not in _SCALARS and not finite(item, depth + 1):
                return False
        return True
    if kind is list or kind is tuple:
        return all(finite(v, depth + 1) for v in value)
    if isinstance(value, float):
        return _isfinite(value)
    if isinstance(value, (bool, int, str, bytes)):
        return True
    if isinstance(value, (dict, list, tuple)):
        return finite(dict(value) if isinstance(value, dict) else list(value), depth)
    if type(value).__name__ in ("array", "ndarray"):
        try:
            return all(_isfinite(float(v)) for v in list(value)) if _is_float_array(value) else True
        except (TypeError, ValueError):
            return True
    if isinstance(value, Data):
        return all(finite(v, depth + 1) for v in vars(value).values())
    names = fields_of(value)
    return all(finite(getattr(value, n, None), depth + 1) for n in names)


def _is_float_array(value: Any) -> bool:
    typecode = getattr(value, "typecode", None)  # array.array (ROS 2 sequences of numbers)
    if typecode is not None:
        return typecode in ("f", "d")
    kind = getattr(getattr(value, "dtype", None), "kind", None)  # numpy (ROS 2 fixed arrays)
    return kind == "f"
