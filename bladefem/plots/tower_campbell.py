"""The tower's rotor-speed chart (soft-stiff design chart): tower frequencies as lines over rotor speed, the 1P and
blade-passing excitation lines, and the bands they sweep over the operating range."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .campbell import mark_operating
from .labels import mode_labels
from .style import KIND_STYLES, colormap, excitation_lines, finish_axes, new_figure, save_figure

if TYPE_CHECKING:
    from ..models.tower_campbell import TowerCampbell

__all__ = ["save_tower_campbell_plot", "tower_campbell_figure"]

BAND_COLOURS = {1: "tab:orange", 3: "tab:green"}


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
        ax.axhspan(band.low_hz * (1 - chart.margin), band.high_hz * (1 + chart.margin), color=colour, alpha=0.08,
                   linewidth=0, zorder=0, label=f"{band.harmonic}P band \u00b1{chart.margin:.0%} margin")
        ax.axhspan(band.low_hz, band.high_hz, color=colour, alpha=0.22, linewidth=0, zorder=0,
                   label=f"{band.harmonic}P band ({band.low_hz:.3g}-{band.high_hz:.3g} Hz)")
    colours = colormap("tab10")
    speeds = np.array([float(chart.rpm.min()), right])
    for i, (mode, label) in enumerate(zip(chart.modes.modes, mode_labels(chart.modes.modes))):
        if mode.frequency_hz > top:
            continue
        ax.plot(speeds, [mode.frequency_hz] * 2, KIND_STYLES.get(mode.kind, "-"), color=colours(i % 10),
                linewidth=1.5, label=f"{label} ({mode.frequency_hz:.4g} Hz)", zorder=3)
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
