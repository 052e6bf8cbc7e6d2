"""The sequence-of-events plot of the paper (Fig. 14, Fig. 15): time along the x axis,
one row per event, controllable events orange and uncontrollable ones blue."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from robosc.debug.eventlog import Record

CONTROLLABLE = "#f28e2b"  # orange
UNCONTROLLABLE = "#4e79a7"  # blue


def rows(records: Sequence[Record]) -> list[tuple[str, bool]]:
    """The plot's rows, top to bottom: each event once, in order of first occurrence."""
    seen: dict[str, bool] = {}
    for r in records:
        seen.setdefault(r.event, r.controllable)
    return list(seen.items())


def plot(records: Sequence[Record], output: str | Path, title: str | None = None) -> Path:
    """Draw the plot into ``output`` (``.png``, ``.svg`` or ``.pdf``)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    output = Path(output)
    order = rows(records)
    index = {name: i for i, (name, _) in enumerate(order)}
    start = records[0].time if records else 0.0
    height = min(40.0, max(3.0, 0.28 * len(order) + 1.6))
    fig, ax = plt.subplots(figsize=(12, height))
    for controllable, color in ((True, CONTROLLABLE), (False, UNCONTROLLABLE)):
        chosen = [r for r in records if r.controllable is controllable]
        if not chosen:
            continue
        ax.scatter(
            [r.time - start for r in chosen],
            [index[r.event] for r in chosen],
            marker="|",
            s=120 if len(records) < 2000 else 40,
            linewidths=1.2 if len(records) < 2000 else 0.6,
            color=color,
            rasterized=len(records) > 5000,  # keeps an SVG of 10,000 events small
        )
    ax.set_yticks(range(len(order)))
    ax.set_yticklabels([name for name, _ in order], fontsize=8 if len(order) > 20 else 9)
    for label, (_, controllable) in zip(ax.get_yticklabels(), order, strict=True):
        label.set_color(CONTROLLABLE if controllable else UNCONTROLLABLE)
    ax.set_ylim(len(order) - 0.5, -0.5)
    ax.set_xlabel("time (s)")
    ax.grid(axis="x", alpha=0.3)
    ax.set_title(title or f"sequence of events ({len(records):,} events)", fontsize=10, loc="left")
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
