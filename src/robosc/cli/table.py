"""Tables for the terminal: a boxed table with a title (``synthesize``, ``sim``) and a plain
two-column listing (``simulate``'s state). Bold is written as ANSI codes, which ``click.echo``
removes when the output is not a terminal; cells wrap when a terminal is too narrow.
(Written here rather than with a table library: importing one cost ``robosc synthesize``
a fifth of its start-up.)"""

from __future__ import annotations

import os
import sys
import textwrap
from collections.abc import Sequence
from typing import Any

import click


class Cell(str):
    """A cell's text shown in bold."""


_MIN_WIDTH = 10  # a wrapped column keeps at least this many characters a line


def terminal_width(stream: Any = None) -> int | None:
    """The width to fit output to: ``COLUMNS`` when set (even when the output is piped: the
    user asked for it), else the terminal's width, or None when ``stream`` (standard output by
    default) is not a terminal: then lines are left as they are, one line per item, for
    programs that read them."""
    columns = os.environ.get("COLUMNS", "")
    if columns.isdigit() and int(columns) > 0:
        return max(int(columns), 2 * _MIN_WIDTH)
    stream = sys.stdout if stream is None else stream
    isatty = getattr(stream, "isatty", None)
    if isatty is None or not isatty():
        return None
    try:
        columns_now = os.get_terminal_size(stream.fileno()).columns
    except (OSError, ValueError):
        return 80
    # a terminal that reports no width (0 columns: a serial console, some CI runners) or one
    # too narrow for a table: the usual 80
    return columns_now if columns_now >= 2 * _MIN_WIDTH else 80


PIPED_WIDTH = 160  # a table's width piped without COLUMNS: a wide terminal's (--json is for programs)


def table_width(stream: Any = None) -> int:
    """The width to fit a table to: ``terminal_width``'s, or ``PIPED_WIDTH`` when the output is
    piped. A table is for people: piped to a file it stays as readable (a condition that
    grows with a fleet wraps within its cell, not into a line of tens of thousands of
    characters); prose and warnings stay one line each."""
    return terminal_width(stream) or PIPED_WIDTH


def _wrap(text: str, width: int) -> list[str]:
    return textwrap.wrap(text, width, break_on_hyphens=False) or [""]


def _widths(headers: Sequence[str], rows: Sequence[Sequence[str]], wrap: Sequence[bool], limit: int | None) -> list[int]:
    widths = [max([len(h), *(len(r[i]) for r in rows)]) for i, h in enumerate(headers)]
    if limit is None:
        return widths
    excess = sum(widths) + 3 * len(widths) + 1 - limit
    while excess > 0:  # take a character at a time from the widest column that may wrap
        candidates = [i for i, w in enumerate(widths) if wrap[i] and w > _MIN_WIDTH]
        if not candidates:
            break
        widest = max(candidates, key=lambda i: widths[i])
        widths[widest] -= 1
        excess -= 1
    return widths


def boxed(
    headers: Sequence[str],
    rows: Sequence[Sequence[str]],
    *,
    title: str | None = None,
    right: Sequence[int] = (),
    no_wrap: Sequence[int] = (),
    width: int | None = None,
) -> str:
    """A table boxed in line-drawing characters, the header in a heavy box. Columns listed in
    ``right`` are right-aligned; the others wrap when the table is wider than ``width``."""
    wrap = [i not in no_wrap for i in range(len(headers))]
    widths = _widths(headers, rows, wrap, width)

    def rule(left: str, fill: str, middle: str, end: str) -> str:
        return left + middle.join(fill * (w + 2) for w in widths) + end

    def lines(cells: Sequence[str], bar: str, bold: bool = False) -> list[str]:
        parts = [_wrap(c, widths[i]) if wrap[i] and len(c) > widths[i] else [c] for i, c in enumerate(cells)]
        out = []
        for n in range(max(len(p) for p in parts)):
            shown = []
            for i, p in enumerate(parts):
                text = p[n] if n < len(p) else ""
                text = text.rjust(widths[i]) if i in right else text.ljust(widths[i])
                shown.append(click.style(text, bold=True) if bold or isinstance(cells[i], Cell) else text)
            out.append(bar + bar.join(f" {s} " for s in shown) + bar)
        return out

    out = [title] if title else []
    out.append(rule("┏", "━", "┳", "┓"))
    out += lines(headers, "┃", bold=True)
    out.append(rule("┡", "━", "╇", "┩"))
    for row in rows:
        out += lines(row, "│")
    out.append(rule("└", "─", "┴", "┘"))
    return "\n".join(out)


def listing(headers: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    """Columns without a box, two spaces apart, the header in bold."""
    widths = [max([len(h), *(len(r[i]) for r in rows)]) for i, h in enumerate(headers)]
    widths[-1] = 0  # the last column is not padded

    def line(cells: Sequence[str]) -> str:
        return "  ".join(c.ljust(w) for c, w in zip(cells, widths, strict=True))

    return "\n".join([click.style(line(headers), bold=True), *(line(row) for row in rows)])
