"""Rule 12: a communication with an object type (or an enum from an object) links an interface."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import DataType, EnumType, Model, ObjectType, data_types_of


def is_object_data(t: DataType) -> bool:
    return isinstance(t, ObjectType) or (isinstance(t, EnumType) and isinstance(t.source, ObjectType))


def check(model: Model) -> Iterator[Diagnostic]:
    for communication in model.communications:
        if communication.interface is None and any(is_object_data(t) for t in data_types_of(communication)):
            yield error(
                communication.span,
                f"'{communication.name}' carries an object, so it must link the ROS interface that describes it",
                "rule-12",
                "add 'links <interface>' and 'interface <interface> use <RosType> from <ros_package>'",
            )
