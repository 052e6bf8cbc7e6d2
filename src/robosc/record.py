"""Frozen records: the part of ``@dataclass(frozen=True)`` the pipeline's objects use, cheaper to define.

Defining a dataclass costs about half a millisecond (the ``dataclasses`` module generates and
compiles six methods per class, and importing it pulls in ``inspect``); the language stage alone
defines over a hundred node classes, which made that most of ``robosc check``'s start-up. A
:func:`record` generates no code: ``__init__``, equality, hashing, ``repr`` and immutability
are shared functions driven by the class's field list.

What a record gives, as a frozen dataclass would:

* ``__init__`` taking the annotated fields in order (base records' fields first), with defaults;
* ``==`` and ``hash`` over the fields declared ``compare=True`` (the default) and only between
  objects of the same class; ``@record(eq=False)`` keeps identity instead (entities);
* ``repr`` over the fields declared ``repr=True``, safe on cycles;
* assignment and deletion raise :class:`FrozenError` (``object.__setattr__`` still works, for the
  one place that ties a knot while building); ``@record(frozen=False)`` allows them;
* ``field(default_factory=...)`` for a fresh default per object, and ``__post_init__`` called
  after the fields are set.

Type checkers read records as frozen dataclasses (:pep:`681`).
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from operator import attrgetter
from typing import Any, TypeVar, dataclass_transform, overload

__all__ = ["FrozenError", "field", "record"]

_T = TypeVar("_T", bound=type)
_V = TypeVar("_V")


class FrozenError(AttributeError):
    """Raised on assignment to a record's attribute."""


class _Missing:
    def __repr__(self) -> str:
        return "<no default>"


_MISSING: Any = _Missing()


class _Field:
    __slots__ = ("compare", "default", "factory", "repr")

    def __init__(self, default: Any, factory: Any, compare: bool, repr: bool) -> None:
        self.default = default
        self.factory = factory
        self.compare = compare
        self.repr = repr

    @property
    def required(self) -> bool:
        return self.default is _MISSING and self.factory is _MISSING


@overload
def field(*, default: _V, compare: bool = True, repr: bool = True) -> _V: ...


@overload
def field(*, default_factory: Callable[[], _V], compare: bool = True, repr: bool = True) -> _V: ...


@overload
def field(*, compare: bool = True, repr: bool = True) -> Any: ...


def field(
    *,
    default: Any = _MISSING,
    default_factory: Callable[[], Any] = _MISSING,
    compare: bool = True,
    repr: bool = True,
) -> Any:
    """A field with options: ``span: Span = field(default=NO_SPAN, compare=False, repr=False)``."""
    if default is not _MISSING and default_factory is not _MISSING:
        raise TypeError("a field takes a default or a default_factory, not both")
    return _Field(default, default_factory, compare, repr)


def _frozen_setattr(self: object, name: str, value: object) -> None:
    raise FrozenError(f"cannot assign to field {name!r} of {type(self).__name__}")


def _frozen_delattr(self: object, name: str) -> None:
    raise FrozenError(f"cannot delete field {name!r} of {type(self).__name__}")


_repr_running = threading.local()


def _repr(self: object) -> str:
    running: set[int] = _repr_running.__dict__.setdefault("ids", set())
    if id(self) in running:
        return "..."
    running.add(id(self))
    try:
        shown = type(self).__record_shown__  # type: ignore[attr-defined]
        parts = ", ".join(f"{name}={getattr(self, name)!r}" for name in shown)
    finally:
        running.discard(id(self))
    return f"{type(self).__qualname__}({parts})"


def _key_getter(names: tuple[str, ...]) -> Callable[[object], tuple[Any, ...]]:
    if not names:
        return lambda self: ()
    if len(names) == 1:
        get = attrgetter(names[0])
        return lambda self: (get(self),)
    return attrgetter(*names)


def _fields(cls: type) -> dict[str, _Field]:
    """Field name to options, base records' fields first, in declaration order."""
    fields: dict[str, _Field] = {}
    for base in reversed(cls.__mro__[1:]):
        fields.update(base.__dict__.get("__record_options__", {}))
    # (a class's own annotations only, on Python 3.10 and later; inspect.get_annotations would
    # cost the import this module avoids)
    for name, annotation in cls.__annotations__.items():
        if str(annotation).startswith(("ClassVar", "typing.ClassVar")):
            continue
        value = cls.__dict__.get(name, _MISSING)
        if isinstance(value, _Field):
            options = value
            if options.default is _MISSING:
                delattr(cls, name)
            else:
                setattr(cls, name, options.default)
        else:
            options = _Field(value, _MISSING, True, True)
        fields.pop(name, None)
        fields[name] = options
    return fields


def _make_init(cls: type, fields: dict[str, _Field]) -> Callable[..., None]:
    """One ``__init__`` for every record, bound to the class's field list (no code generated:
    compiling a specialised one per class cost more at start-up than it saved per object)."""
    names = tuple(fields)
    count = len(names)
    defaults = {n: o.default for n, o in fields.items() if not o.required and o.factory is _MISSING}
    factories = {n: o.factory for n, o in fields.items() if o.factory is not _MISSING}
    post_init = hasattr(cls, "__post_init__")
    qualname = cls.__qualname__

    def __init__(self: Any, *args: Any, **kwargs: Any) -> None:
        if len(args) > count:
            raise TypeError(f"{qualname}() takes {count} arguments but {len(args)} were given")
        d = self.__dict__
        d.update(zip(names, args, strict=False))  # args may be fewer than names
        for name in names[len(args) :]:
            if name in kwargs:
                d[name] = kwargs.pop(name)
            elif name in defaults:
                d[name] = defaults[name]
            elif name in factories:
                d[name] = factories[name]()
            else:
                raise TypeError(f"{qualname}() missing argument {name!r}")
        if kwargs:
            name = next(iter(kwargs))
            problem = "got multiple values for" if name in names else "got an unexpected keyword"
            raise TypeError(f"{qualname}() {problem} argument {name!r}")
        if post_init:
            self.__post_init__()

    __init__.__qualname__ = f"{qualname}.__init__"
    return __init__


def _define(cls: _T, eq: bool, frozen: bool) -> _T:
    fields = _fields(cls)
    seen_default = False
    for name, options in fields.items():
        if options.required and seen_default:
            raise TypeError(f"{cls.__name__}: field {name!r} without a default follows one with a default")
        seen_default = seen_default or not options.required
    names = tuple(fields)
    cls.__record_options__ = fields  # type: ignore[attr-defined]
    cls.__record_shown__ = tuple(n for n in names if fields[n].repr)  # type: ignore[attr-defined]
    cls.__match_args__ = names  # type: ignore[attr-defined,misc]
    cls.__init__ = _make_init(cls, fields)  # type: ignore[misc]
    if frozen:
        cls.__setattr__ = _frozen_setattr  # type: ignore[assignment,method-assign]
        cls.__delattr__ = _frozen_delattr  # type: ignore[assignment,method-assign]
    if "__repr__" not in cls.__dict__:
        cls.__repr__ = _repr  # type: ignore[assignment,method-assign]
    if eq:
        key = _key_getter(tuple(n for n in names if fields[n].compare))

        def __eq__(self: object, other: object) -> bool:
            if other.__class__ is self.__class__:
                return bool(key(self) == key(other))
            return NotImplemented

        def __hash__(self: object) -> int:
            return hash(key(self))

        if "__eq__" not in cls.__dict__:
            cls.__eq__ = __eq__  # type: ignore[assignment,method-assign]
        if not frozen:  # as a dataclass: mutable and compared by value, so not hashable
            cls.__hash__ = None  # type: ignore[assignment]
        elif cls.__dict__.get("__hash__") is None:  # absent, or None because the class defines __eq__
            cls.__hash__ = __hash__  # type: ignore[assignment,method-assign]
    return cls


@overload
@dataclass_transform(frozen_default=True, field_specifiers=(field,))
def record(cls: _T, /) -> _T: ...


@overload
def record(*, eq: bool = True, frozen: bool = True) -> Callable[[_T], _T]: ...


def record(cls: Any = None, /, *, eq: bool = True, frozen: bool = True) -> Any:
    """Make ``cls`` a record: ``@record`` (frozen, compared by fields), ``@record(eq=False)`` (by
    identity), ``@record(frozen=False)`` (attributes may be reassigned)."""
    if cls is None:
        return lambda c: _define(c, eq, frozen)
    return _define(cls, eq, frozen)
