"""The standstill (parked-blade) damping against the yaw misalignment: each mode's total damping ratio over yaw at
the first azimuth, the sectors of negative damping shaded; with several azimuths, a second panel maps the smallest
total damping ratio of all modes over yaw and azimuth (negative: red), the zero contour drawn."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .style import DPI, colormap, pyplot, save_figure

if TYPE_CHECKING:
    from ..models.standstill import StandstillResult

YAW_LABEL = "Yaw misalignment (deg)"
DAMPING_LABEL = "Total damping ratio (%)"
#: the damping axis shows at most this many percent above zero (attached-flow flap damping runs to tens of %)
TOP_PERCENT = 10.0


def standstill_figure(result: StandstillResult, title: str = ""):
    """A matplotlib Figure: the damping-against-yaw panel, and the yaw-azimuth map for several azimuths."""
    several = len(result.azimuth_deg) > 1
    fig, axes = pyplot().subplots(2 if several else 1, 1, figsize=(6.5, 7.6 if several else 4.2), dpi=DPI,
                                  layout="constrained", squeeze=False)
    ax = axes[0, 0]
    colours = colormap("tab10")
    lowest = 0.0
    for k, name in enumerate(result.names):
        total = 100 * result.total(name)[:, 0]
        lowest = min(lowest, float(total.min()))
        ax.plot(result.yaw_deg, total, color=colours(k % 10), label=name, marker=".", markersize=3)
        for start, stop in result.negative_sectors(name, 0):
            ax.axvspan(start, stop, color=colours(k % 10), alpha=0.12, linewidth=0)
    ax.axhline(0.0, color="0.2", linewidth=0.8)
    ax.set_ylim(min(-1.0, 1.1 * lowest), TOP_PERCENT)
    ax.set_xlim(result.yaw_deg[0], result.yaw_deg[-1])
    ax.set_xlabel(YAW_LABEL)
    ax.set_ylabel(DAMPING_LABEL)
    ax.grid(True, linewidth=0.3)
    ax.legend(fontsize="small", ncols=3, loc="upper center")
    ax.set_title(title or f"Parked blade, {result.wind_speed:g} m/s, pitch {result.pitch_deg:g} deg, azimuth "
                 f"{result.azimuth_deg[0]:g} deg", fontsize="medium")
    if several:
        ax = axes[1, 0]
        least = 100 * np.min([result.total(name) for name in result.names], axis=0)
        limit = max(abs(float(least.min())), 1.0)
        mesh = ax.pcolormesh(result.yaw_deg, result.azimuth_deg, least.T, cmap="RdBu", vmin=-limit, vmax=limit,
                             shading="nearest")
        if least.min() < 0 < least.max():
            ax.contour(result.yaw_deg, result.azimuth_deg, least.T, levels=[0.0], colors="k", linewidths=0.8)
        fig.colorbar(mesh, ax=ax, label="Least total damping ratio (%)")
        ax.set_xlabel(YAW_LABEL)
        ax.set_ylabel("Rotor azimuth (deg)")
    return fig


def save_standstill_plot(result: StandstillResult, path: str | Path, title: str = "") -> None:
    """Write :func:`standstill_figure` to ``path`` (PNG, PDF or SVG), whole or not at all."""
    save_figure(standstill_figure(result, title), path)
