"""Arrays only describe middleware data, inside an object (the original's NO_ARRAY_ALLOWED, in
its UsedDataTypeRule and NoArrayAllowedRule):

* a variable cannot have an array type;
* a communication's data (a message's type, a service's or action's request, response or
  feedback) cannot be an array as a whole: ROS messages are objects, so ``type: array(T)``
  describes nothing a node can publish;
* received data assigned to a variable that takes part in synthesis is not an array or an
  element of one.

Turn array data into a few named values with an enum instead: ``datatype enum E from
LaserScan to { ... }``."""

from __future__ import annotations

import itertools
from collections.abc import Iterator

from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic, error
from robosc.language.model import (
    ArrayType,
    DataRef,
    FieldStep,
    IndexStep,
    Model,
    Property,
    data_types_of,
    synthesis_inputs,
)
from robosc.language.source import Span


def check(model: Model) -> Iterator[Diagnostic]:
    yield from _array_variables(model)
    yield from _array_communications(model)
    yield from _array_inputs(model)


def _array_variables(model: Model) -> Iterator[Diagnostic]:
    for variable in model.variables:
        if isinstance(variable.type, ArrayType):
            yield error(
                variable.span,
                f"variable '{variable.name}' has the array type {variable.type}; arrays only describe "
                "middleware data, a variable cannot hold one",
                Code.NO_ARRAY,
                "keep the elements you need, as in 'variable d: double' with 'd := value.ranges[0]'",
            )


def _array_communications(model: Model) -> Iterator[Diagnostic]:
    for communication in model.communications:
        arrays = [str(t) for t in data_types_of(communication) if isinstance(t, ArrayType)]
        if arrays:
            yield error(
                communication.span,
                f"the data of '{communication.name}' is {arrays[0]}; a communication's data is an object "
                "(a ROS message), a basic type or none, not an array",
                Code.NO_ARRAY,
                "describe the ROS message as an object with the array as a property, as in "
                "'datatype object Scan { ranges: array(double) }'",
            )


def _array_inputs(model: Model) -> Iterator[Diagnostic]:
    reported: set[Span] = set()
    for found in synthesis_inputs(model):
        array = _array_property(found.data)
        if array is None or array.span in reported:
            continue
        reported.add(array.span)
        yield error(
            array.span,
            f"property '{array.name}' is an array, and it reaches '{found.variable.name}', which takes part "
            f"in synthesis (at {found.data.span}); synthesis cannot read array data",
            Code.NO_ARRAY,
            "turn the array into a few named values with an enum, as in "
            "'datatype enum E from T to { value.ranges[0] < 0.5 -> near, default -> far }'",
        )


def _array_property(data: DataRef) -> Property | None:
    """The object property holding the array that ``data`` reads (the one just before its first
    index, or the last one read), or None: no array, or the communication's data is itself an
    array, which :func:`_array_communications` reports."""
    steps = data.steps
    for before, step in itertools.pairwise(steps):
        if isinstance(step, IndexStep) and isinstance(before, FieldStep):
            return before.property
    if steps and isinstance(steps[-1], FieldStep) and isinstance(data.type, ArrayType):
        return steps[-1].property
    return None
