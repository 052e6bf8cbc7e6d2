"""The sequence-of-events plot of the paper (Fig. 14, Fig. 15): time along the x axis,
one row per event, controllable events orange and uncontrollable ones blue."""

from __future__ import annotations

import unicodedata
from collections.abc import Sequence
from pathlib import Path

from robosc.debug.eventlog import Record
from robosc.record import record

CONTROLLABLE = "#f28e2b"  # orange
UNCONTROLLABLE = "#4e79a7"  # blue
OTHERS = "#555555"  # the label of the row the rarest events share


MAX_ROWS = 60  # rows drawn; the events beyond share the last row
MAX_LABEL = 60  # characters of a row's label; a longer name is cut (its row stays its own)
MAX_TITLE = 120
COLUMNS = 2000  # positions along the time axis: finer than the image's pixels


@record
class Row:
    label: str
    controllable: bool | None  # None: the row of the other events, of both kinds
    events: int  # how many of the log's events it shows


@record
class Layout:
    """What the plot shows, decided before drawing: bounded whatever the log."""

    rows: tuple[Row, ...]
    points: tuple[tuple[float, int, bool], ...]  # (seconds from the first event, row, controllable)
    title: str


def _cut(text: str, most: int) -> str:
    """``text`` as a label: at most ``most`` characters, no control character, and no ``$``
    that matplotlib would take for mathematics."""
    text = "".join("?" if unicodedata.category(c) == "Cc" else c for c in text)
    text = text if len(text) <= most else text[: most - 3] + "..."
    return text.replace("$", r"\$")


def layout(records: Sequence[Record], title: str | None = None) -> Layout:
    """The rows, top to bottom: each event once, in order of first occurrence; with more than
    :data:`MAX_ROWS` events, the most frequent keep a row of their own and the others share the
    last one ("N other events"). The points: one per row, kind and column of the time axis
    (so a million events draw as at most ``MAX_ROWS * COLUMNS * 2`` marks)."""
    counts: dict[str, int] = {}
    kinds: dict[str, bool] = {}
    for r in records:
        counts[r.event] = counts.get(r.event, 0) + 1
        kinds.setdefault(r.event, r.controllable)
    names = list(counts)
    if len(names) > MAX_ROWS:
        kept = set(sorted(names, key=lambda n: -counts[n])[: MAX_ROWS - 1])
        names = [n for n in names if n in kept]
    index = {name: i for i, name in enumerate(names)}
    rows = [Row(_cut(n, MAX_LABEL), kinds[n], counts[n]) for n in names]
    if len(counts) > len(names):
        others = len(counts) - len(names)
        rows.append(Row(f"({others:,} other events)", None, sum(counts.values()) - sum(r.events for r in rows)))
    start = records[0].time if records else 0.0
    span = max((r.time - start for r in records), default=0.0) or 1.0
    points = {
        (round((r.time - start) / span * COLUMNS), index.get(r.event, len(names)), r.controllable) for r in records
    }
    heading = _cut(title, MAX_TITLE) if title else f"sequence of events ({len(records):,} events)"
    return Layout(
        tuple(rows),
        tuple(sorted((column * span / COLUMNS, row, kind) for column, row, kind in points)),
        heading,
    )


def plot(records: Sequence[Record], output: str | Path, title: str | None = None) -> Path:
    """Draw the plot into ``output`` (``.png``, ``.svg`` or ``.pdf``)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    output = Path(output)
    shown = layout(records, title)
    rows = shown.rows
    height = min(40.0, max(3.0, 0.28 * len(rows) + 1.6))
    fig, ax = plt.subplots(figsize=(12, height))
    many = len(shown.points) >= 2000
    for controllable, color in ((True, CONTROLLABLE), (False, UNCONTROLLABLE)):
        chosen = [(x, row) for x, row, kind in shown.points if kind is controllable]
        if not chosen:
            continue
        ax.scatter(
            [x for x, _ in chosen],
            [row for _, row in chosen],
            marker="|",
            s=40 if many else 120,
            linewidths=0.6 if many else 1.2,
            color=color,
            rasterized=len(shown.points) > 5000,  # keeps an SVG of 10,000 events small
        )
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels([row.label for row in rows], fontsize=8 if len(rows) > 20 else 9)
    for label, row in zip(ax.get_yticklabels(), rows, strict=True):
        label.set_color(OTHERS if row.controllable is None else CONTROLLABLE if row.controllable else UNCONTROLLABLE)
    ax.set_ylim(len(rows) - 0.5, -0.5)
    ax.set_xlabel("time (s)")
    ax.grid(axis="x", alpha=0.3)
    ax.set_title(shown.title, fontsize=10, loc="left")
    ax.legend(
        handles=[
            Line2D([], [], color=CONTROLLABLE, marker="|", linestyle="", markersize=10, label="controllable"),
            Line2D([], [], color=UNCONTROLLABLE, marker="|", linestyle="", markersize=10, label="uncontrollable"),
        ],
        loc="lower right",
        bbox_to_anchor=(1.0, 1.0),
        ncol=2,
        fontsize=8,
        frameon=False,
    )
    fig.tight_layout()
    fig.savefig(output, dpi=110)
    plt.close(fig)
    return output
