"""One plotting style for every bladefem figure (blade and turbine Campbell diagrams, the tower's rotor-speed chart).

Size 6.5 x 4.2 in at 200 dpi, units in parentheses in the axis labels ("Rotor speed (rpm)"), ticks inside on all
four sides with minor ticks, a light grid, the legend outside the axes on the right (it never covers a curve),
and the excitation lines ``nP`` in grey, labelled just outside the right edge (or above the top where a line
leaves there), the labels spread so that they never overlap each other or sit on a curve.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

FIGSIZE = (6.5, 4.2)
DPI = 200
RPM_LABEL = "Rotor speed (rpm)"
FREQUENCY_LABEL = "Natural frequency (Hz)"
EXCITATION_COLOUR = "0.5"
LABEL_COLOUR = "0.3"
#: the operating speed or range: near-black, unlike any mode family's colour
OPERATING_COLOUR = "0.1"
#: line styles by mode kind (blades and towers)
KIND_STYLES = {"flap": "-", "edge": "--", "torsion": "-.", "axial": ":", "fore-aft": "-", "side-side": "--"}


def pyplot():
    """matplotlib.pyplot on the Agg backend (no display needed)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def colormap(name: str):
    """A matplotlib colormap by name."""
    import matplotlib
    return matplotlib.colormaps[name]


def new_figure(figsize: tuple[float, float] | None = None):
    """(figure, axes) in the common size (or a taller one for a long legend below the axes) and layout."""
    return pyplot().subplots(figsize=figsize or FIGSIZE, dpi=DPI, layout="constrained")


def finish_axes(ax, title: str = "", xlabel: str = RPM_LABEL, ylabel: str = FREQUENCY_LABEL,
                legend: bool = True) -> None:
    """Labels, ticks, grid, title and the legend outside on the right."""
    from matplotlib.ticker import AutoMinorLocator

    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.xaxis.set_minor_locator(AutoMinorLocator())
    ax.yaxis.set_minor_locator(AutoMinorLocator())
    ax.tick_params(which="both", direction="in", top=True, right=True)
    ax.tick_params(axis="x", which="major", pad=8)   # the "0" labels of both axes stay apart at the origin
    if title:
        ax.set_title(title, fontsize=10, pad=14, loc="left")    # clear of nP labels above the top edge
    ax.grid(True, linewidth=0.4, alpha=0.5)
    if legend:
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.07, 1.0), frameon=False, borderaxespad=0.0)


def spread(positions: Sequence[float], gap: float) -> NDArray:
    """Positions moved apart so that neighbours are at least ``gap`` apart: overlapping neighbours are merged into
    evenly spaced clusters centred on the mean of their original positions (order kept, lone positions unmoved)."""
    order = np.argsort(positions)
    values = np.asarray(positions, dtype=float)[order]
    clusters: list[list[float]] = []
    for value in values:
        clusters.append([value])
        while len(clusters) > 1:
            low, high = clusters[-2], clusters[-1]
            if np.mean(high) - (len(high) - 1) * gap / 2 - (np.mean(low) + (len(low) - 1) * gap / 2) >= gap:
                break
            clusters[-2:] = [low + high]
    placed = np.concatenate([np.mean(c) + gap * (np.arange(len(c)) - (len(c) - 1) / 2) for c in clusters])
    out = np.empty_like(placed)
    out[order] = placed
    return out


def excitation_lines(ax, harmonics: Sequence[int], right: float, top: float, left: float = 0.0) -> None:
    """The nP lines ``f = n rpm / 60`` from ``left`` to ``right`` (rpm), labelled just outside the right edge of
    the axes (or above the top where a line leaves there), the right-edge labels spread so that they never
    overlap."""
    speeds = np.array([left, right])
    at_edge = []
    for n in harmonics:
        ax.plot(speeds, n * speeds / 60.0, color=EXCITATION_COLOUR, linewidth=0.8, zorder=1)
        end = n * right / 60.0
        if end <= top:
            at_edge.append((n, end))
        else:
            ax.annotate(f"{n}P", (top * 60.0 / n, top), textcoords="offset points", xytext=(0, 2), ha="center",
                        va="bottom", fontsize=8, color=LABEL_COLOUR, annotation_clip=False)
    labels = spread([y for _, y in at_edge], 0.045 * top)
    for (n, y), y_label in zip(at_edge, labels):
        ax.annotate(f"{n}P", (right, y_label), xytext=(5, 0), textcoords="offset points", ha="left",
                    va="center", fontsize=8, color=LABEL_COLOUR, annotation_clip=False)


def save_figure(fig, path: str | Path) -> None:
    """Write ``fig`` (PNG, PDF or SVG by extension) whole or not at all, and close it."""
    from ..files import write_atomic

    buffer = io.BytesIO()
    try:
        fig.savefig(buffer, format=Path(path).suffix.lower().lstrip(".") or "png")
    finally:
        pyplot().close(fig)
    write_atomic(path, buffer.getvalue())
