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
    env.filters["xml"] = xml.sax.saxutils.escape
    env.filters["xmlattr"] = xml.sax.saxutils.quoteattr
    return env


def _python_literal(value: object) -> str:
    """A string (or number) from the model as a Python literal: ``repr`` escapes it."""
    if isinstance(value, str | int | float | bool) or value is None:
        return repr(value)
    raise TypeError(f"no Python literal for {value!r}")


def _docstring_text(value: object) -> str:
    """Text from the model made safe inside a triple-quoted docstring."""
    return repr(str(value))[1:-1].replace('"', '\\"')
