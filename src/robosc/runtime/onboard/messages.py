# -*- coding: utf-8 -*-
"""ROS messages from the supervisor's data and back, the same on ROS 1 and ROS 2.

* :func:`wire_type`: the ROS type of a communication: its linked interface, or for
  basic data the original RoboSC's ``std_msgs`` mapping (``double`` as Float32,
  ``integer`` as Int16, ...), so robots written for the original work unchanged.
* :func:`fill`: provided data (nested dicts) into a message, refusing what the
  message cannot carry (a number out of its field's range, NaN or infinity, a field
  the message does not have) with :class:`Unsendable`: nothing half-filled is sent.
* :func:`received`: the data of a received message as the model sees it.
* :func:`conforms`: whether a controller's message is exactly an event's data (supervision layer).
"""

from __future__ import absolute_import, annotations

import importlib
import math
import struct
from typing import Any, Dict

from .supervisor import ANY
from .values import fields_of, finite

SENSOR_PACKAGE = "sensor_msgs"  # its topics come best effort from most drivers (ROS 2)
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


_FIELD_TYPES: Dict[type, Dict[str, str]] = {}  # per message class: what field_types says (it never changes)


def field_types(message: Any) -> dict[str, str]:
    """Field name -> ROS type name ("float64", "double", "int16", "geometry_msgs/Vector3", ...)."""
    kind = type(message)
    found = _FIELD_TYPES.get(kind)
    if found is None:
        found = _field_types(message)
        if len(_FIELD_TYPES) < 1000 and (found or hasattr(message, "get_fields_and_field_types")):
            _FIELD_TYPES[kind] = found
    return found


def _field_types(message: Any) -> dict[str, str]:
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


def _f32(value: float) -> float:
    """``value`` as a float32 field carries it on the wire."""
    return float(struct.unpack("f", struct.pack("f", value))[0])


def _leaf_equal(kind: str, actual: Any, expected: Any) -> bool:
    """A field's value equals what is expected of it, as the wire carries the field's type:
    exactly (no tolerance), a float32 field after rounding both to float32."""
    if isinstance(expected, bool) or isinstance(actual, bool):
        return isinstance(actual, bool) == isinstance(expected, bool) and bool(actual == expected)
    if kind in FLOATS or isinstance(expected, float):
        try:
            a, e = float(actual), float(expected)
        except (TypeError, ValueError):
            return False
        if not (math.isfinite(a) and math.isfinite(e)):
            return False
        return _f32(a) == _f32(e) if FLOATS.get(kind) is not None else a == e
    if isinstance(actual, (bytes, bytearray)) or isinstance(expected, (bytes, bytearray)):
        return bytes(actual) == bytes(expected)
    try:
        if isinstance(expected, (list, tuple)) or type(expected).__name__ in ("array", "ndarray"):
            a_items, e_items = list(actual), list(expected)
            element = kind.split("[")[0] if "[" in kind else kind.replace("sequence<", "").rstrip(">")
            return len(a_items) == len(e_items) and all(_same(x, y, element) for x, y in zip(a_items, e_items))
        return bool(actual == expected)
    except Exception:
        return False


def _same(actual: Any, default: Any, kind: str = "") -> bool:
    """``actual`` equals ``default`` on every field (a whole message, or one value)."""
    return conforms(actual, None, default) if fields_of(default) else _leaf_equal(kind, actual, default)


def conforms(message: Any, template: Any, default: Any = None) -> bool:
    """Whether a controller's ``message`` is exactly the data of an event: equal to the
    ``template``'s constants, finite where the template says ``ANY`` (the model computes the
    value), and equal to the message type's default on every field the template does not
    name (``template`` None: the event sends no data, every field at its default). Equal as
    the wire carries each field, with no tolerance: a velocity of 1e-7 is not 0."""
    if default is None:
        default = type(message)()
    kinds = field_types(default)
    if not kinds:  # not a message: a value
        if template is ANY:
            return finite(message)
        return _leaf_equal("", message, template if template is not None else default)
    if template is not None and not isinstance(template, dict):
        if "data" not in kinds:
            return False
        template = {"data": template}  # std_msgs types: the model's basic data is their 'data'
    template = template or {}
    for key in template:
        if key not in kinds:
            return False
    for key, kind in kinds.items():
        try:
            actual, expected = getattr(message, key), getattr(default, key)
        except AttributeError:
            return False
        wanted = template.get(key, None) if key in template else None
        if key in template and wanted is ANY:
            if not finite(actual):
                return False
        elif fields_of(expected):
            if not conforms(actual, wanted if isinstance(wanted, dict) else None, expected):
                return False
        elif not _leaf_equal(kind, actual, wanted if key in template else expected):
            return False
    return True
