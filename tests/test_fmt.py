"""``robosc fmt``: canonical layout, comments kept, and the same model after formatting."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import EXAMPLES
from robosc.api import check_text, format_text
from robosc.language.parser import parse_text

EXAMPLE_FILES = sorted(EXAMPLES.glob("*.rscd"))

MESSY = """// leading comment
robot   Messy{datatype object P{x:double /* inline */ y : double}
  datatype enum E from P to{value.x>1.0->big // big ones
  default->small}
interface p use Point from geometry_msgs
component C{outgoing message m with identifier:'/m',type:E links p
incoming message cmd with type:integer(0..3)
behaviour{variable e:E=small
on response from m do e:=value
initial marked state a{on request to cmd goto b}
state b{transition if (e=big)or !C.a goto a}
// before the end of behaviour
}}
component ^state from Lib import X
requirement{cmd}needs C.a and e2 = -1
requirement C.b disables cmd
provide cmd with 1+2*3 if C.a   // trailing
} // after everything
"""


def test_examples_are_in_canonical_layout():
    for path in EXAMPLE_FILES:
        text = path.read_text()
        assert format_text(text, str(path)) == text, f"{path} is not in canonical layout"


@pytest.mark.parametrize("path", EXAMPLE_FILES, ids=lambda p: p.name)
def test_round_trip_of_every_example_gives_the_same_model(path: Path):
    text = path.read_text()
    original = parse_text(text).syntax
    # a different layout of the same model: everything on one line where comments allow
    squashed = "\n".join(line if line.lstrip().startswith("*") else line.strip() for line in text.splitlines())
    assert parse_text(squashed).syntax == original
    formatted = format_text(squashed)
    assert isinstance(formatted, str)
    assert parse_text(formatted).syntax == original
    assert formatted == text


def test_messy_layout_is_normalised_with_every_comment_kept():
    formatted = format_text(MESSY)
    assert isinstance(formatted, str)
    assert parse_text(formatted).syntax == parse_text(MESSY).syntax
    assert format_text(formatted) == formatted  # idempotent
    for comment in [
        "// leading comment",
        "/* inline */",
        "// big ones",
        "// before the end of behaviour",
        "// trailing",
        "// after everything",
    ]:
        assert formatted.count(comment) == 1, comment
    assert "    provide cmd with 1 + 2 * 3 if C.a // trailing\n" in formatted
    assert "        value.x > 1.0 -> big // big ones\n" in formatted
    assert "    component ^state from Lib import X\n" in formatted
    assert "            transition if (e = big) or !C.a goto a\n" in formatted
    assert "    requirement {cmd} needs C.a and e2 = -1\n" in formatted
    assert formatted.startswith("// leading comment\nrobot Messy {\n")
    assert formatted.endswith("} // after everything\n")


def test_formatting_keeps_diagnostics_the_same():
    formatted = format_text(MESSY)
    before = [(d.code, d.message) for d in check_text(MESSY).diagnostics]
    after = [(d.code, d.message) for d in check_text(formatted).diagnostics]
    assert before == after and before  # MESSY has errors (e2, Lib): they survive formatting
