"""robosc.record: the frozen records the language stage's nodes are made of."""

from __future__ import annotations

import pickle

import pytest

from robosc.record import FrozenError, field, record


@record
class Point:
    x: int
    y: int = 0
    label: str = field(default="", compare=False, repr=False)


@record(eq=False)
class Entity:
    name: str
    parts: list[int] = field(default_factory=list)


@record
class Child(Point):
    z: int = 5


@record(frozen=False)
class Counter:
    count: int = 0

    def __post_init__(self) -> None:
        self.doubled = self.count * 2


def test_init_takes_fields_in_order_with_defaults():
    p = Point(1)
    assert (p.x, p.y, p.label) == (1, 0, "")
    q = Point(1, 2, label="a")
    assert (q.x, q.y, q.label) == (1, 2, "a")
    assert Point(y=3, x=4).x == 4
    with pytest.raises(TypeError):
        Point()  # type: ignore[call-arg]
    with pytest.raises(TypeError):
        Point(1, 2, "a", 4)  # type: ignore[call-arg]


def test_equality_and_hash_use_compared_fields_only_and_the_same_class():
    assert Point(1, 2, label="a") == Point(1, 2, label="b")
    assert hash(Point(1, 2, label="a")) == hash(Point(1, 2, label="b"))
    assert Point(1, 2) != Point(1, 3)
    assert Point(1, 2) != Child(1, 2, z=5)  # another class, even a subclass
    assert Point(1, 2) != (1, 2)
    assert len({Point(1), Point(1), Point(2)}) == 2


def test_identity_records_compare_by_identity():
    a, b = Entity("a"), Entity("a")
    assert a != b and a == a
    assert len({a, b}) == 2


def test_default_factory_gives_each_object_its_own_value():
    a, b = Entity("a"), Entity("b")
    a.parts.append(1)
    assert b.parts == []
    assert Entity("c", [7]).parts == [7]


def test_frozen_unless_asked():
    p = Point(1)
    with pytest.raises(FrozenError):
        p.x = 2  # type: ignore[misc]
    with pytest.raises(AttributeError):
        del p.x  # type: ignore[misc]
    assert p.x == 1
    object.__setattr__(p, "x", 9)  # the escape hatch for tying knots while building
    assert p.x == 9
    c = Counter(3)
    assert c.doubled == 6  # __post_init__ ran after the fields were set
    c.count = 4
    assert c.count == 4
    with pytest.raises(TypeError):
        hash(c)  # mutable and compared by value: unhashable, as a dataclass


def test_subclass_fields_follow_the_base_fields():
    c = Child(1, 2, "l", 3)
    assert (c.x, c.y, c.label, c.z) == (1, 2, "l", 3)
    assert Child.__match_args__ == ("x", "y", "label", "z")  # type: ignore[attr-defined]


def test_repr_shows_repr_fields_and_survives_cycles():
    assert repr(Point(1, 2, label="hidden")) == "Point(x=1, y=2)"
    e = Entity("loop")
    e.parts.append(e)  # type: ignore[arg-type]
    assert repr(e) == "Entity(name='loop', parts=[...])"


def test_a_required_field_after_a_default_is_refused():
    class Bad:
        a: int = 0
        b: int

    with pytest.raises(TypeError, match="'b' without a default follows one with a default"):
        record(Bad)


def test_default_and_factory_together_are_refused():
    with pytest.raises(TypeError):
        field(default=1, default_factory=list)


def test_records_pickle():
    p = Point(1, 2, label="x")
    copy = pickle.loads(pickle.dumps(p))
    assert copy == p and copy.label == "x"


def test_wrong_arguments_are_type_errors_naming_the_argument():
    with pytest.raises(TypeError, match="takes 3 arguments but 4 were given"):
        Point(1, 2, "a", 4)  # type: ignore[call-arg]
    with pytest.raises(TypeError, match="missing argument 'x'"):
        Point(y=1)  # type: ignore[call-arg]
    with pytest.raises(TypeError, match="multiple values for argument 'x'"):
        Point(1, x=2)  # type: ignore[misc]
    with pytest.raises(TypeError, match="unexpected keyword argument 'w'"):
        Point(1, w=2)  # type: ignore[call-arg]
