"""The full-system (turbine) Campbell diagram in the common style: named modes over rotor speed and the nP lines."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .campbell import EXCITATIONS
from .style import FIGSIZE, colormap, excitation_lines, finish_axes, new_figure, save_figure

if TYPE_CHECKING:
    from ..models.turbine.campbell import TurbineCampbell

__all__ = ["save_turbine_campbell_plot", "turbine_campbell_figure"]

TITLE = "Full-system Campbell diagram (multi-blade coordinates)"
#: with more modes than this, the legend goes below the axes in two columns
MANY = 10


def turbine_campbell_figure(result: TurbineCampbell, harmonics: Sequence[int] = EXCITATIONS, title: str = TITLE,
                            max_frequency_hz: float | None = None):
    """A matplotlib Figure: each named mode against rotor speed (gaps where a mode is not found), the nP lines
    labelled outside the axes; the legend outside, on the right for a few modes or below in two columns for many
    (the full system has about sixteen, with long names)."""
    many = len(result.names) > MANY
    fig, ax = new_figure((FIGSIZE[0], FIGSIZE[1] + 0.16 * math.ceil(len(result.names) / 2)) if many else None)
    found = result.frequencies_hz[np.isfinite(result.frequencies_hz)]
    top = max_frequency_hz or (1.08 * float(found.max()) if found.size else 1.0)
    right = float(result.rpm.max()) or 1.0
    colours = colormap("tab20")
    for i, (name, frequencies) in enumerate(zip(result.names, result.frequencies_hz)):
        ax.plot(result.rpm, frequencies, marker="o", markersize=2.5, linewidth=1.2, label=name,
                color=colours(i % 20), linestyle="-" if i < 20 else "--", zorder=3)
    excitation_lines(ax, harmonics, right, top)
    ax.set_xlim(0.0, right)
    ax.set_ylim(0.0, top)
    finish_axes(ax, title, legend=not many)
    if many:
        fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncol=2, fontsize=7, frameon=False)
    return fig


def save_turbine_campbell_plot(result: TurbineCampbell, path: str | Path,
                               harmonics: Sequence[int] = EXCITATIONS) -> None:
    """Write the diagram (PNG, PDF or SVG by extension) atomically."""
    save_figure(turbine_campbell_figure(result, harmonics), path)
