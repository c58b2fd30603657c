"""The full-system (turbine) Campbell diagram in the common style: named modes over rotor speed and the nP lines."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .campbell import EXCITATIONS, excitation_crossings, label_crossings, mark_operating
from .style import FIGSIZE, excitation_lines, finish_axes, new_figure, save_figure

if TYPE_CHECKING:
    from ..models.turbine.campbell import TurbineCampbell

__all__ = ["save_turbine_campbell_plot", "turbine_campbell_figure"]

TITLE = "Full-system Campbell diagram (multi-blade coordinates)"
#: harmonics whose crossings are marked (the rotor's 1P and the blade-passing 3P and 6P of a three-bladed rotor)
MARKED = (1, 3, 6)
#: with more modes than this, the legend goes below the axes in two columns
MANY = 10
#: colour by what moves (first and second of each), line style by the rotor's motion, marker by the order
FAMILY_COLOURS = (("tower fore-aft", ("tab:blue", "navy")), ("tower side-side", ("tab:cyan", "teal")),
                  ("flap", ("tab:green", "darkolivegreen")), ("edge", ("tab:red", "darkred")),
                  ("drivetrain", ("black", "black")), ("yaw", ("tab:gray", "tab:gray")))
WHIRL_STYLES = (("backward", "--"), ("forward", "-."))
ORDER_MARKERS = (("1st", "o"), ("2nd", "s"), ("3rd", "^"))


def mode_style(name: str) -> dict:
    """Colour, line style and marker of a named full-system mode: one hue per family (tower fore-aft, side-side,
    flap, edge, drivetrain, yaw; darker for the second), solid for collective or fixed-frame modes, dashed for
    the backward and dash-dotted for the forward whirl, a circle for the first, a square for the second."""
    second = name.startswith("2nd")
    colour = next((pair[second] for key, pair in FAMILY_COLOURS if all(word in name for word in key.split())),
                  "tab:purple")
    return {"color": colour, "linestyle": next((style for key, style in WHIRL_STYLES if key in name), "-"),
            "marker": next((marker for key, marker in ORDER_MARKERS if name.startswith(key)), "D")}


def turbine_campbell_figure(result: TurbineCampbell, harmonics: Sequence[int] = EXCITATIONS, title: str = TITLE,
                            max_frequency_hz: float | None = None,
                            operating_rpm: float | tuple[float, float] | None = None):
    """A matplotlib Figure: each named mode against rotor speed (gaps where a mode is not found; styled by
    :func:`mode_style`), the nP lines labelled outside the axes, their crossings with the modes circled and marked
    with n, the operating speed or range (rpm); the legend outside, on the right for a few modes or below in two
    columns for many (the full system has about sixteen, with long names)."""
    many = len(result.names) > MANY
    fig, ax = new_figure((FIGSIZE[0], FIGSIZE[1] + 0.16 * math.ceil((len(result.names) + 2) / 2)) if many else None)
    found = result.frequencies_hz[np.isfinite(result.frequencies_hz)]
    top = max_frequency_hz or (1.08 * float(found.max()) if found.size else 1.0)
    right = float(result.rpm.max()) or 1.0
    marks = []
    for name, frequencies in zip(result.names, result.frequencies_hz):
        ax.plot(result.rpm, frequencies, markersize=3, linewidth=1.2, label=name, zorder=3, **mode_style(name))
        found = np.isfinite(frequencies)
        for n in (n for n in harmonics if n in MARKED):
            marks += [(speed, f, n) for speed, f in excitation_crossings(result.rpm[found], frequencies[found], n)
                      if 0 < speed and f <= top]
    excitation_lines(ax, harmonics, right, top)
    marks = list({(round(speed, 1), n): (speed, f, n) for speed, f, n in marks}.values())   # one mark a place
    if marks:
        ax.plot([m[0] for m in marks], [m[1] for m in marks], "o", markerfacecolor="none", markeredgecolor="black",
                markersize=6.5, markeredgewidth=0.9, linestyle="none", label="crossing with nP (n marked)", zorder=4)
    mark_operating(ax, operating_rpm)
    ax.set_xlim(0.0, right)
    ax.set_ylim(0.0, top)
    finish_axes(ax, title, legend=not many)
    if many:
        fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncol=2, fontsize=7, frameon=False)
    label_crossings(ax, marks)
    return fig


def save_turbine_campbell_plot(result: TurbineCampbell, path: str | Path,
                               harmonics: Sequence[int] = EXCITATIONS, title: str = TITLE,
                               operating_rpm: float | tuple[float, float] | None = None) -> None:
    """Write the diagram (PNG, PDF or SVG by extension) atomically."""
    save_figure(turbine_campbell_figure(result, harmonics, title, operating_rpm=operating_rpm), path)
