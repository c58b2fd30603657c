"""The tower's rotor-speed chart (soft-stiff design chart): tower frequencies as lines over rotor speed, the 1P and
blade-passing excitation lines, and the bands they sweep over the operating range."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .campbell import mark_operating
from .labels import mode_labels
from .style import KIND_STYLES, excitation_lines, finish_axes, new_figure, save_figure

if TYPE_CHECKING:
    from ..models.tower_campbell import TowerCampbell

__all__ = ["save_tower_campbell_plot", "tower_campbell_figure"]

BAND_COLOURS = {1: "tab:orange", 3: "tab:green"}
#: tower mode lines: none of the band colours
MODE_COLOURS = ("tab:blue", "tab:red", "tab:purple", "tab:brown", "tab:pink", "tab:olive", "tab:cyan", "black")


def tower_campbell_figure(chart: TowerCampbell, title: str = "", max_frequency_hz: float | None = None):
    """A matplotlib Figure: each tower mode as a horizontal line, the 1P and nP lines, the bands (widened by the
    margin, lighter) shaded across the chart, and the operating range shaded."""
    fig, ax = new_figure()
    bands = chart.bands
    right = float(chart.rpm.max()) or 1.0
    first = chart.first_bending.frequency_hz
    top = max_frequency_hz or 1.25 * max(first, bands[1].high_hz * (1 + chart.margin))
    for band in bands:
        colour = BAND_COLOURS.get(band.harmonic, "tab:purple")
        margin_label = f"{band.harmonic}P band \u00b1{chart.margin:.0%} margin"
        for low, high in ((band.low_hz * (1 - chart.margin), band.low_hz),
                          (band.high_hz, band.high_hz * (1 + chart.margin))):
            ax.axhspan(low, high, facecolor="none", edgecolor=colour, hatch="////", linewidth=0, zorder=0,
                       label=margin_label)
            margin_label = None
        ax.axhspan(band.low_hz, band.high_hz, color=colour, alpha=0.22, linewidth=0, zorder=0,
                   label=f"{band.harmonic}P band ({band.low_hz:.3g}-{band.high_hz:.3g} Hz)")
    speeds = np.array([float(chart.rpm.min()), right])
    for i, (mode, label) in enumerate(zip(chart.modes.modes, mode_labels(chart.modes.modes))):
        if mode.frequency_hz > top:
            continue
        style = KIND_STYLES.get(mode.kind, "-")
        solid = style == "-"          # a solid line drawn wider and below, so a dashed one on top never hides it
        ax.plot(speeds, [mode.frequency_hz] * 2, style, color=MODE_COLOURS[i % len(MODE_COLOURS)],
                linewidth=3.0 if solid else 1.4, label=f"{label} ({mode.frequency_hz:.4g} Hz)",
                zorder=3 if solid else 4)
    excitation_lines(ax, (1, chart.blades), right, top)
    mark_operating(ax, chart.operating_rpm)
    ax.set_xlim(0.0, right)
    ax.set_ylim(0.0, top)
    finish_axes(ax, title or f"Tower frequencies and rotor excitation bands: {chart.verdict}")
    return fig


def save_tower_campbell_plot(chart: TowerCampbell, path: str | Path, title: str = "",
                             max_frequency_hz: float | None = None) -> None:
    """Write the chart (PNG, PDF or SVG by extension) atomically."""
    save_figure(tower_campbell_figure(chart, title, max_frequency_hz), path)
