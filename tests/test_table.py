"""The terminal tables of robosc synthesize, sim and simulate (robosc.cli.table)."""

from __future__ import annotations

import click
import pytest

from robosc.cli.table import Cell, boxed, listing

HEADERS = ("controllable event", "your condition", "added by synthesis")
ROWS = [
    ("pick.c_trigger", "Base.at_shelf and Arm.stowed and !Tray.full", Cell("Tray.empty or Tray.one")),
    ("drop.c_reset", "-", "-"),
]


def test_a_boxed_table_without_a_width_keeps_each_cell_on_one_line() -> None:
    text = click.unstyle(boxed(HEADERS, ROWS, title="supervisor for R"))
    lines = text.splitlines()
    assert lines[0] == "supervisor for R"
    assert lines[1].startswith("┏━") and lines[3].startswith("┡━") and lines[-1].startswith("└─")
    assert lines[2] == "┃ controllable event ┃ your condition                              ┃ added by synthesis     ┃"
    assert lines[4] == "│ pick.c_trigger     │ Base.at_shelf and Arm.stowed and !Tray.full │ Tray.empty or Tray.one │"
    assert len({len(line) for line in lines[1:]}) == 1  # a rectangle


def test_cells_marked_bold_and_the_header_are_styled() -> None:
    text = boxed(HEADERS, ROWS)
    assert click.style("Tray.empty or Tray.one", bold=True) in text
    assert click.style("controllable event", bold=True) in text
    assert click.style("-", bold=True) not in text


def test_a_narrow_terminal_wraps_the_columns_that_may_wrap() -> None:
    lines = click.unstyle(boxed(HEADERS, ROWS, no_wrap=(0,), width=60)).splitlines()
    assert all(len(line) <= 60 for line in lines)
    assert any(line.startswith("│ pick.c_trigger     │") for line in lines)  # not wrapped
    body = lines[lines.index(next(line for line in lines if line.startswith("┡"))) + 1 : -1]
    columns = [" ".join(line.split("│")[i].strip() for line in body[:-1]).split() for i in (1, 2, 3)]
    assert columns[0] == ["pick.c_trigger"]
    assert " ".join(columns[1]) == "Base.at_shelf and Arm.stowed and !Tray.full"  # every word, in order
    assert " ".join(columns[2]) == "Tray.empty or Tray.one"
    assert len(body) > 3  # the first row took several lines


def test_right_aligned_columns() -> None:
    lines = boxed(("robot", "distance"), [("r1", "5.20 m"), ("robot2", "12.00 m")], right=(1,)).splitlines()
    assert lines[-3] == "│ r1     │   5.20 m │"
    assert lines[-2] == "│ robot2 │  12.00 m │"


def test_a_listing_has_no_box_and_no_trailing_spaces() -> None:
    text = click.unstyle(listing(("automaton / variable", "value"), [("Lidar", "sensing"), ("Lidar.safety", "unsafe")]))
    assert text.splitlines() == [
        "automaton / variable  value",
        "Lidar                 sensing",
        "Lidar.safety          unsafe",
    ]


def test_a_terminal_that_reports_no_width_gets_the_usual_80_columns(monkeypatch: pytest.MonkeyPatch) -> None:
    """A terminal of 0 columns (a serial console, some CI runners): before, `robosc synthesize`
    ended with `internal error: ValueError: invalid width 0`."""
    import fcntl
    import os
    import struct
    import termios

    from robosc.cli.table import terminal_width

    monkeypatch.delenv("COLUMNS", raising=False)
    leader, follower = os.openpty()
    try:
        with os.fdopen(follower, "w", closefd=False) as stream:
            for columns, wanted in ((0, 80), (5, 80), (120, 120)):
                fcntl.ioctl(follower, termios.TIOCSWINSZ, struct.pack("HHHH", 24, columns, 0, 0))
                assert terminal_width(stream) == wanted
                lines = click.unstyle(boxed(HEADERS, ROWS, no_wrap=(0,), width=terminal_width(stream))).splitlines()
                assert all(len(line) <= wanted for line in lines)
    finally:
        os.close(leader)
        os.close(follower)
