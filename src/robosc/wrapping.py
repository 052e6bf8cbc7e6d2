"""Prose fitted to a width: the command line's messages and the diagnostics' text."""

from __future__ import annotations

import textwrap


def fill(text: str, width: int | None, indent: str = "    ") -> str:
    """Each line of ``text`` wrapped to ``width`` (None: as it is); the lines a wrap adds keep
    the line's own leading spaces plus ``indent``."""
    if width is None or all(len(line) <= width for line in text.split("\n")):
        return text
    out = []
    for line in text.split("\n"):
        lead = line[: len(line) - len(line.lstrip(" "))]
        out += textwrap.wrap(line, width, subsequent_indent=lead + indent, break_on_hyphens=False) or [line]
    return "\n".join(out)
