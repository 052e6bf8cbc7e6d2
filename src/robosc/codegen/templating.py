"""The Jinja2 environments shared by the generators (one per package holding templates)."""

from __future__ import annotations

import xml.sax.saxutils
from functools import lru_cache

import jinja2


@lru_cache(maxsize=4)
def environment(package: str = "robosc.codegen") -> jinja2.Environment:
    """Templates under ``<package>/templates``; strict about undefined names."""
    env = jinja2.Environment(
        loader=jinja2.PackageLoader(package, "templates"),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=True,
        trim_blocks=True,
        lstrip_blocks=True,
        autoescape=False,  # generated code, not HTML: every model string goes through a filter below
    )
    env.filters["py"] = _python_literal
    env.filters["doc"] = _docstring_text
    env.filters["dot"] = _dot_string
    env.filters["edge_label"] = _edge_label
    env.filters["xml"] = xml.sax.saxutils.escape
    env.filters["xmlattr"] = xml.sax.saxutils.quoteattr
    env.filters["md"] = _markdown_code
    return env


def _markdown_code(value: object) -> str:
    """Text from the model (or a file name) inside Markdown backticks: one line, no backtick."""
    return "".join("'" if c == "`" else "?" if c < " " else c for c in str(value))


def markdown_cell(value: object) -> str:
    """Text from the model inside backticks in a Markdown table's cell: as :func:`_markdown_code`,
    and no bar that would end the cell."""
    return _markdown_code(value).replace("|", "\\|")


def _python_literal(value: object) -> str:
    """A string (or number, or a tuple of them) from the model as a Python literal: ``repr``
    escapes it."""
    if isinstance(value, str | int | float | bool) or value is None:
        return repr(value)
    if isinstance(value, tuple):
        return "(" + "".join(_python_literal(item) + ", " for item in value) + ")"
    raise TypeError(f"no Python literal for {value!r}")


def _docstring_text(value: object) -> str:
    """Text from the model made safe inside a triple-quoted docstring."""
    return repr(str(value))[1:-1].replace('"', '\\"')


def _dot_string(value: object) -> str:
    """A Graphviz DOT quoted string."""
    text = str(value).replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
    return f'"{text}"'


def _edge_label(transition: object) -> str:
    """An automaton edge's label: the event, the model's guard / assignments, and the
    conditions the requirements and synthesis put on it (one per line)."""
    import textwrap

    lines = [str(getattr(transition, "event", ""))]
    for prefix, attribute in (("", "detail"), ("needs: ", "required"), ("added: ", "added")):
        value = getattr(transition, attribute, None)
        if value:
            lines += textwrap.wrap(prefix + str(value), 48, subsequent_indent="  ", break_long_words=False)
    return _dot_string("\n".join(lines))
