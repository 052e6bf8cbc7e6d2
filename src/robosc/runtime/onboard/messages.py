# -*- coding: utf-8 -*-
"""ROS messages from the supervisor's data and back, the same on ROS 1 and ROS 2.

* :func:`wire_type`: the ROS type of a communication: its linked interface, or for
  basic data the original RoboSC's ``std_msgs`` mapping (``double`` as Float32,
  ``integer`` as Int16, ...), so robots written for the original work unchanged.
* :func:`fill`: provided data (nested dicts) into a message, refusing what the
  message cannot carry (a number out of its field's range, NaN or infinity, a field
  the message does not have) with :class:`Unsendable`: nothing half-filled is sent.
* :func:`received`: the data of a received message as the model sees it.
* :func:`candidates`: which events a controller's message can be (supervision layer).
"""

from __future__ import absolute_import, annotations

import importlib
import math
from typing import Any, Sequence

from .values import finite

STD_MSGS = {"string": "String", "boolean": "Bool", "integer": "Int16", "double": "Float32", "none": "Empty"}
FLOAT32_MAX = 3.4028234663852886e38
INTEGER_RANGES = {
    "int8": (-(2**7), 2**7 - 1),
    "uint8": (0, 2**8 - 1),
    "byte": (0, 2**8 - 1),
    "octet": (0, 2**8 - 1),
    "char": (-(2**7), 2**8 - 1),
    "int16": (-(2**15), 2**15 - 1),
    "uint16": (0, 2**16 - 1),
    "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1),
    "int64": (-(2**63), 2**63 - 1),
    "uint64": (0, 2**64 - 1),
}
FLOATS = {"float32": FLOAT32_MAX, "float": FLOAT32_MAX, "float64": None, "double": None}
TOLERANCE = 1e-6  # relative: a float32 on the wire matches the double the model wrote


class Unsendable(ValueError):
    """Data that a message cannot carry."""


class MissingType(ImportError):
    """A ROS interface package that is not installed."""


def wire_type(communication: Any) -> tuple[str, str]:
    """``(package, type name)`` of a message communication on the wire."""
    if communication.interface:
        package, _, name = communication.interface.partition("/")
        return package, name
    return "std_msgs", STD_MSGS.get(communication.data, "Empty")


def load(package: str, module: str, name: str) -> Any:
    """The class ``package.module.name`` (e.g. sensor_msgs.msg.LaserScan), or MissingType."""
    try:
        found = getattr(importlib.import_module(package + "." + module), name)
    except (ImportError, AttributeError) as error:
        raise MissingType(
            "cannot import %s.%s.%s (%s): is the package installed?" % (package, module, name, error)
        ) from None
    return found


def field_types(message: Any) -> dict[str, str]:
    """Field name -> ROS type name ("float64", "double", "int16", "geometry_msgs/Vector3", ...)."""
    fields = getattr(message, "get_fields_and_field_types", None)  # ROS 2
    if fields is not None:
        return dict((str(name).lstrip("_"), str(kind)) for name, kind in fields().items())
    slots = getattr(message, "__slots__", ())  # ROS 1 (genpy)
    kinds = getattr(message, "_slot_types", ())
    return dict(zip(slots, kinds))


def _scalar(kind: str, value: Any, where: str) -> Any:
    """``value`` in the field type ``kind``; Unsendable when it cannot be."""
    if isinstance(value, (dict, list, tuple)):
        raise Unsendable("%s: cannot put %r into a %s" % (where, value, kind))
    if kind in ("bool", "boolean"):
        if not isinstance(value, bool):
            raise Unsendable("%s: %r is not a boolean" % (where, value))
        return value
    if kind in INTEGER_RANGES:
        if isinstance(value, float) and math.isfinite(value) and value.is_integer():
            value = int(value)
        if isinstance(value, bool) or not isinstance(value, int):
            raise Unsendable("%s: %r is not an integer" % (where, value))
        low, high = INTEGER_RANGES[kind]
        if not low <= value <= high:
            raise Unsendable("%s: %d is outside %s (%d..%d)" % (where, value, kind, low, high))
        return value
    if kind in FLOATS:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise Unsendable("%s: %r is not a number" % (where, value))
        value = float(value)
        if not math.isfinite(value):
            raise Unsendable("%s: %r is not finite" % (where, value))
        limit = FLOATS[kind]
        if limit is not None and abs(value) > limit:
            raise Unsendable("%s: %r is outside %s" % (where, value, kind))
        return value
    if kind == "string" or kind.startswith("string<"):
        if not isinstance(value, str):
            raise Unsendable("%s: %r is not a string" % (where, value))
        return value
    if not finite(value):
        raise Unsendable("%s: %r is not finite" % (where, value))
    return value


def fill(message: Any, data: Any, where: str = "") -> Any:
    """Copy provided data into ``message`` and return it; fields the model does not set keep
    their defaults. Raises Unsendable for data the message cannot carry."""
    if data is None:
        return message
    kinds = field_types(message)
    if not isinstance(data, dict):
        if "data" not in kinds:
            raise Unsendable("%s: %s has no 'data' field for %r" % (where, type(message).__name__, data))
        data = {"data": data}
    for key, value in data.items():
        if key not in kinds:
            raise Unsendable("%s: %s has no field %r" % (where, type(message).__name__, key))
        place = "%s.%s" % (where, key) if where else key
        if isinstance(value, dict):
            fill(getattr(message, key), value, place)
            continue
        try:
            setattr(message, key, _scalar(kinds[key], value, place))
        except Unsendable:
            raise
        except Exception as error:  # the message class refused it (ROS 2 checks types and ranges)
            raise Unsendable("%s: %s" % (place, error)) from None
    return message


def received(communication: Any, message: Any) -> Any:
    """The data of a received message as the model sees it: basic data from ``.data``,
    nothing for ``none``, the message itself for objects."""
    if communication.data == "none":
        return None
    if communication.data == "object":
        return message
    return getattr(message, "data", message)


def matches(message: Any, signature: Any) -> bool:
    """Whether a message carries the constant fields an event's provided data sets
    (``signature`` None: no constant field, any message)."""
    if signature is None:
        return True
    if isinstance(signature, dict):
        for key, expected in signature.items():
            try:
                actual = getattr(message, key)
            except Exception:
                return False
            if not matches(actual, expected):
                return False
        return True
    actual = message
    if not isinstance(message, (bool, int, float, str)) and hasattr(message, "data"):
        actual = message.data
    if isinstance(signature, bool) or isinstance(actual, bool):
        return isinstance(actual, bool) and isinstance(signature, bool) and actual == signature
    if isinstance(signature, (int, float)):
        if not isinstance(actual, (int, float)) or not math.isfinite(float(actual)):
            return False
        return abs(float(actual) - float(signature)) <= TOLERANCE * max(1.0, abs(float(signature)))
    return bool(actual == signature)


def candidates(message: Any, events: Sequence[Any]) -> list[Any]:
    """The events a controller's message can be, failing closed: none when a number in it is
    not finite; the event itself when one event alone uses the topic; otherwise those
    whose provided constant data it carries (none, when it carries nobody's)."""
    if not finite(message):
        return []
    if len(events) == 1:
        return list(events)
    found = []
    for event in events:
        alternatives = event.signature if event.signature else (None,)
        if any(matches(message, alternative) for alternative in alternatives):
            found.append(event)
    return found
