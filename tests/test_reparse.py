"""The language server's reparsing (robosc.language.reparse): every version of a file parses
exactly as robosc check parses it, while an edit parses again only the definitions it touched."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from robosc.language import reparse
from robosc.language.parser import parse_source
from robosc.language.reparse import Reparser, cut
from robosc.language.source import SourceFile, Span

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))
from language import generated_model  # noqa: E402

MODELS = {p.name: p.read_text() + "// after the end\n" for p in sorted((ROOT / "examples").glob("*.rscd"))}
MODELS["generated"] = "// a generated model\n" + generated_model(400) + "// its end\n/* really */\n"
SNIPPETS = [
    "\n// a comment\n",
    "x",
    "{",
    "}",
    '"',
    "/*",
    " /* c */ ",
    "\n    requirement go0 needs true\n",
    "\n    component Extra {\n    }\n",
    "\n",
    "requirement ",
]


def deep(value: Any) -> Any:
    """A syntax tree as nested tuples of every field, spans included (which the records'
    own equality leaves out)."""
    if isinstance(value, Span):
        return tuple(value)
    fields = getattr(type(value), "__record_options__", None)
    if fields is not None:
        return (type(value).__name__, *((name, deep(getattr(value, name))) for name in fields))
    if isinstance(value, (tuple, list)):
        return tuple(deep(v) for v in value)
    return value


def same(reparser: Reparser, text: str, path: str = "/m/model.rscd") -> None:
    source = SourceFile(path, text)
    expected, got = parse_source(source), reparser.parse(source)
    assert got.diagnostics == expected.diagnostics
    assert deep(got.syntax) == deep(expected.syntax)  # comments and every span too


def test_every_example_parses_the_same() -> None:
    for name, text in MODELS.items():
        same(Reparser(), text, f"/m/{name}")


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    name=st.sampled_from(sorted(MODELS)),
    edits=st.lists(
        st.tuples(st.floats(0, 1), st.sampled_from(SNIPPETS), st.integers(0, 40)), min_size=1, max_size=6
    ),
)
def test_edited_versions_parse_the_same(name: str, edits: list[tuple[float, str, int]]) -> None:
    """A run of edits (inserting text, deleting some) on one reparser: each version as the
    whole file's parse, syntax errors included."""
    reparser = Reparser()
    text = MODELS[name]
    same(reparser, text)
    for where, insert, delete in edits:
        at = int(where * len(text))
        text = text[:at] + insert + text[at + delete :]
        same(reparser, text)


def test_an_edit_parses_only_the_definition_it_touched(monkeypatch) -> None:
    text = MODELS["generated"]
    _, starts = cut(text) or (0, [])
    assert len(starts) > 20
    parsed: list[str] = []
    original = reparse.parse
    monkeypatch.setattr(reparse, "parse", lambda tables, piece, *rest: parsed.append(piece) or original(tables, piece, *rest))
    reparser = Reparser()
    reparser.parse(SourceFile("/m/g.rscd", text))
    assert len(parsed) == len(starts)  # each definition once
    parsed.clear()
    middle = starts[len(starts) // 2]
    line_end = text.index("\n", middle)
    edited = text[:line_end] + " // edited" + text[line_end:]
    result = reparser.parse(SourceFile("/m/g.rscd", edited))
    assert len(parsed) == 1 and "// edited" in parsed[0]
    assert result.syntax == parse_source(SourceFile("/m/g.rscd", edited)).syntax


def test_what_does_not_cut_is_parsed_whole() -> None:
    assert cut("robot R {\n    component C {\n") is None  # unbalanced
    assert cut("robot R { }\n}\n") is None  # text after the end
    assert cut("robot R {\n}\n// done\n") is None  # no definitions
    text = "robot R {\n    component A {\n    }\n    component B {\n    }\n} // end\n"
    assert cut(text) == (text.rindex("}"), [text.index("    component A"), text.index("    component B")])
