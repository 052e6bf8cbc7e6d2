"""Type rules for expressions (LANGUAGE.md section 4), as pure functions."""

from __future__ import annotations

from robosc.language.model import (
    BOOLEAN,
    DOUBLE,
    INTEGER,
    ArrayType,
    BasicKind,
    BasicType,
    DataType,
    EnumType,
    ErrorType,
    ObjectType,
)

LOGICAL = {"or", "and", "=>"}
EQUALITY = {"=", "!="}
ORDERING = {"<", "<=", ">", ">="}
ARITHMETIC = {"+", "-", "*"}


def is_kind(t: DataType, kind: BasicKind) -> bool:
    return isinstance(t, BasicType) and t.kind is kind


def is_boolean(t: DataType) -> bool:
    return is_kind(t, BasicKind.BOOLEAN)


def is_numeric(t: DataType) -> bool:
    return is_kind(t, BasicKind.INTEGER) or is_kind(t, BasicKind.DOUBLE)


def is_error(t: DataType) -> bool:
    return isinstance(t, ErrorType)


def comparable(a: DataType, b: DataType) -> bool:
    """Whether ``a = b`` makes sense: numbers with numbers, an enum with itself, like with like."""
    if is_numeric(a) and is_numeric(b):
        return True
    if isinstance(a, BasicType) and isinstance(b, BasicType):
        return a.kind is b.kind and a.kind is not BasicKind.NONE
    return isinstance(a, EnumType) and a is b


def binary_type(op: str, left: DataType, right: DataType) -> DataType | str:
    """The type of ``left op right``, or a message saying why it is wrong."""
    if is_error(left) or is_error(right):
        return ErrorType()
    if op in LOGICAL:
        if is_boolean(left) and is_boolean(right):
            return BOOLEAN
        return f"'{op}' needs boolean operands, not {left} and {right}"
    if op in EQUALITY:
        if comparable(left, right):
            return BOOLEAN
        return f"cannot compare {left} with {right} using '{op}'"
    if op in ORDERING:
        if is_numeric(left) and is_numeric(right):
            return BOOLEAN
        return f"'{op}' needs numeric operands, not {left} and {right}"
    if op in ARITHMETIC:
        if is_numeric(left) and is_numeric(right):
            both_int = is_kind(left, BasicKind.INTEGER) and is_kind(right, BasicKind.INTEGER)
            return INTEGER if both_int else DOUBLE
        return f"'{op}' needs numeric operands, not {left} and {right}"
    if op == "/":
        if is_numeric(left) and is_numeric(right):
            return DOUBLE
        return f"'/' needs numeric operands, not {left} and {right}"
    return f"unknown operator '{op}'"


def unary_type(op: str, operand: DataType) -> DataType | str:
    if is_error(operand):
        return ErrorType()
    if op == "!":
        return BOOLEAN if is_boolean(operand) else f"'!' needs a boolean operand, not {operand}"
    if is_numeric(operand):
        return operand if is_kind(operand, BasicKind.DOUBLE) else INTEGER
    return f"'-' needs a numeric operand, not {operand}"


def fits(value: DataType, target: DataType) -> bool:
    """Whether a value of type ``value`` may be stored in (or sent as) ``target``."""
    if is_error(value) or is_error(target):
        return True
    if isinstance(target, BasicType):
        if target.kind is BasicKind.DOUBLE:
            return is_numeric(value)
        return isinstance(value, BasicType) and value.kind is target.kind
    if isinstance(target, ArrayType):
        return isinstance(value, ArrayType) and fits(value.element, target.element)
    if isinstance(target, (EnumType, ObjectType)):
        return value is target
    return False
