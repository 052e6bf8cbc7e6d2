"""Rule 12: a service, an action, and a communication with an object type (or an enum from an
object) link an interface (the original refuses a service or action without one at check)."""

from __future__ import annotations

from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import Action, DataType, EnumType, Model, ObjectType, Service, data_types_of


def is_object_data(t: DataType) -> bool:
    return isinstance(t, ObjectType) or (isinstance(t, EnumType) and isinstance(t.source, ObjectType))


def check(model: Model) -> Iterator[Diagnostic]:
    for communication in model.communications:
        if communication.interface is None and isinstance(communication, (Service, Action)):
            kind = "service" if isinstance(communication, Service) else "action"
            yield error(
                communication.span,
                f"{kind} '{communication.name}' must link the ROS {kind} type it calls",
                Code.INTERFACE_LINKS,
                f"add 'links <interface>' and 'interface <interface> use <Ros{kind.title()}Type> from <ros_package>'",
            )
            continue
        if communication.interface is None and any(is_object_data(t) for t in data_types_of(communication)):
            yield error(
                communication.span,
                f"'{communication.name}' carries an object, so it must link the ROS interface that describes it",
                Code.INTERFACE_LINKS,
                "add 'links <interface>' and 'interface <interface> use <RosType> from <ros_package>'",
            )
