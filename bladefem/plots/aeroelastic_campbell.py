"""The aeroelastic Campbell diagram over wind speed in the common style: frequencies of the named modes with the
nP lines of the rotor speed at each wind speed (top), their damping ratios (bottom).

Each mode family (a tower mode, the drivetrain, a blade mode with its collective and whirling forms, ...) has one
colour, its members one line style each (collective or single: solid; backward whirl: dashed; forward whirl:
dotted), the same in both panels. The damping axis is linear up to 1 % and logarithmic above (negative damping,
an instability, stays visible below zero).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .campbell import EXCITATIONS
from .style import (
    DPI,
    EXCITATION_COLOUR,
    FIGSIZE,
    LABEL_COLOUR,
    colormap,
    finish_axes,
    pyplot,
    save_figure,
    spread,
)

if TYPE_CHECKING:
    from ..models.turbine.aeroelastic_campbell import AeroelasticCampbell

__all__ = ["aeroelastic_campbell_figure", "family_of", "save_aeroelastic_campbell_plot"]

TITLE = "Aeroelastic Campbell diagram (multi-blade coordinates)"
WIND_LABEL = "Wind speed (m/s)"
DAMPING_LABEL = "Damping ratio (%)"
#: below this damping ratio (%) the damping axis is linear
LINEAR_DAMPING = 1.0


def family_of(name: str) -> str:
    """A mode's family: its name without the collective/asymmetric form and whirl ('1st blade flap', '1st tower
    fore-aft', '1st drivetrain torsion')."""
    name = re.sub(r" \((backward|forward) whirl\)| \((pitch|yaw)\)| \(\d+\)", "", name)
    return re.sub(r" (collective|asymmetric)", "", name)


def line_style(name: str) -> str:
    return "--" if "backward whirl" in name else ":" if "forward whirl" in name else "-"


def aeroelastic_campbell_figure(result: AeroelasticCampbell, harmonics: Sequence[int] = EXCITATIONS,
                                title: str = TITLE, max_frequency_hz: float | None = None):
    """A matplotlib Figure with the frequency and damping panels over wind speed, the legend below."""
    families = list(dict.fromkeys(family_of(name) for name in result.names))
    colours = colormap("tab10" if len(families) <= 10 else "tab20")
    rows = int(np.ceil(len(result.names) / 2))
    fig, (top, bottom) = pyplot().subplots(2, 1, sharex=True, height_ratios=(3, 2), dpi=DPI, layout="constrained",
                                           figsize=(FIGSIZE[0], FIGSIZE[1] * 1.7 + 0.16 * rows))
    wind = result.wind_speeds
    found = result.frequencies_hz[np.isfinite(result.frequencies_hz)]
    ceiling = max_frequency_hz or (1.08 * float(found.max()) if found.size else 1.0)
    for name, frequencies, damping in zip(result.names, result.frequencies_hz, result.damping_ratios):
        colour = colours(families.index(family_of(name)) % colours.N)
        style = dict(color=colour, linestyle=line_style(name), marker="o", markersize=2.5, linewidth=1.2, zorder=3)
        top.plot(wind, frequencies, label=name, **style)
        bottom.plot(wind, 100.0 * damping, **style)
    excitations(top, wind, result.rpm, harmonics, ceiling)
    left, right = float(wind.min()), float(wind.max())
    top.set_xlim(left, right if right > left else left + 1.0)
    top.set_ylim(0.0, ceiling)
    finish_axes(top, title, xlabel="", legend=False)
    finish_axes(bottom, "", xlabel=WIND_LABEL, ylabel=DAMPING_LABEL, legend=False)
    damping_axis(bottom, 100.0 * result.damping_ratios)
    fig.legend(*top.get_legend_handles_labels(), loc="outside lower center", ncol=2, fontsize=7, frameon=False)
    return fig


def damping_axis(ax, percent: np.ndarray) -> None:
    """Linear up to :data:`LINEAR_DAMPING` per cent, logarithmic above, plain numbers; from zero unless a mode is
    unstable (negative damping), with a line at zero then."""
    from matplotlib.ticker import FuncFormatter, SymmetricalLogLocator

    ax.set_yscale("symlog", linthresh=LINEAR_DAMPING)
    ax.yaxis.set_minor_locator(SymmetricalLogLocator(linthresh=LINEAR_DAMPING, base=10, subs=range(2, 10)))
    ax.yaxis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    finite = percent[np.isfinite(percent)]
    low = float(finite.min()) if finite.size else 0.0
    high = float(finite.max()) if finite.size else 1.0
    if low < 0:
        ax.axhline(0.0, color=EXCITATION_COLOUR, linewidth=0.8, zorder=1)
    ax.set_ylim(min(low * 1.3, 0.0), max(high * 1.3, 10.0))


def excitations(ax, wind, rpm, harmonics: Sequence[int], ceiling: float) -> None:
    """The nP lines ``n rpm(U) / 60`` over wind speed, labelled just outside the right edge (spread apart) or
    above the top where they leave there."""
    at_edge = []
    for n in harmonics:
        line = n * np.asarray(rpm) / 60.0
        ax.plot(wind, line, color=EXCITATION_COLOUR, linewidth=0.8, zorder=1)
        if line[-1] <= ceiling:
            at_edge.append((n, float(line[-1])))
        elif line.min() <= ceiling:
            where = float(np.interp(ceiling, line, wind)) if np.all(np.diff(line) >= 0) else float(wind[0])
            ax.annotate(f"{n}P", (where, ceiling), textcoords="offset points", xytext=(0, 2), ha="center",
                        va="bottom", fontsize=8, color=LABEL_COLOUR, annotation_clip=False)
    for (n, _), y in zip(at_edge, spread([y for _, y in at_edge], 0.045 * ceiling)):
        ax.annotate(f"{n}P", (float(wind[-1]), y), xytext=(5, 0), textcoords="offset points", ha="left",
                    va="center", fontsize=8, color=LABEL_COLOUR, annotation_clip=False)


def save_aeroelastic_campbell_plot(result: AeroelasticCampbell, path: str | Path,
                                   harmonics: Sequence[int] = EXCITATIONS) -> None:
    """Write the diagram (PNG, PDF or SVG by extension) atomically."""
    save_figure(aeroelastic_campbell_figure(result, harmonics), path)
