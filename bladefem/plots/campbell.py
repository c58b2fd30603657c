"""Campbell diagram with matplotlib: mode families, nP excitation lines, crossings, operating speed."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from .labels import kind_labels
from .style import (
    KIND_STYLES,
    OPERATING_COLOUR,
    colormap,
    excitation_lines,
    finish_axes,
    new_figure,
    save_figure,
    spread,
)

if TYPE_CHECKING:
    from ..modal import CampbellResult

__all__ = ["EXCITATIONS", "Crossing", "campbell_figure", "crossings", "excitation_crossings", "family_labels",
           "save_campbell_plot", "spread"]

EXCITATIONS: tuple[int, ...] = (1, 3, 6, 9)


@dataclass(frozen=True)
class Crossing:
    """A family meeting an nP excitation line at rotor speed ``rpm`` and frequency ``frequency_hz``."""

    family: int
    harmonic: int
    rpm: float
    frequency_hz: float


def excitation_crossings(rpm: NDArray, frequencies_hz: NDArray, harmonic: int) -> list[tuple[float, float]]:
    """Where a family's frequency curve (linear between speeds) meets ``harmonic`` times the rotor speed."""
    excitation = harmonic * np.asarray(rpm) / 60.0
    gap = np.asarray(frequencies_hz) - excitation
    found = []
    for k in np.flatnonzero(np.sign(gap[:-1]) * np.sign(gap[1:]) <= 0):
        if gap[k] == gap[k + 1]:
            continue
        t = gap[k] / (gap[k] - gap[k + 1])
        speed = rpm[k] + t * (rpm[k + 1] - rpm[k])
        found.append((float(speed), harmonic * float(speed) / 60.0))
    return found


def crossings(result: CampbellResult, harmonics: Sequence[int] = EXCITATIONS) -> list[Crossing]:
    """All crossings of the families with the excitation lines (excluding the trivial one at 0 rpm)."""
    found = []
    for i, family in enumerate(result.families):
        for n in harmonics:
            for speed, frequency in excitation_crossings(result.rpm, family.frequencies_hz, n):
                if speed > 0:
                    found.append(Crossing(i, n, speed, frequency))
    return found


def family_labels(result: CampbellResult) -> list[str]:
    """'1st flap', '1st edge', '2nd flap', ... in the order of the families."""
    return kind_labels(family.kind for family in result.families)


#: the gid of the "nP" labels beside crossing circles (inside the axes, unlike the nP lines' labels)
CROSSING_LABEL = "crossing-label"
#: where a crossing's "nP" may go, points from the circle: below right first, then around it
LABEL_OFFSETS = ((4, -9), (4, 3), (-15, -9), (-15, 3), (4, -17), (-15, 10), (10, -3), (-21, -3))


def label_crossings(ax, marks: Sequence[tuple[float, float, int]]) -> None:
    """Write "nP" beside each crossing circle (rpm, Hz, n), at the first of :data:`LABEL_OFFSETS` where it
    overlaps no text already in the figure (the figure is laid out first, so the places are final)."""
    figure = ax.figure
    figure.canvas.draw()
    renderer = figure.canvas.get_renderer()
    taken = [text.get_window_extent(renderer) for text in figure.findobj(match=lambda a: hasattr(a, "get_text"))
             if text.get_visible() and text.get_text()]
    for rpm, frequency, harmonic in marks:
        for offset in LABEL_OFFSETS:
            label = ax.annotate(f"{harmonic}P", (rpm, frequency), xytext=offset, textcoords="offset points",
                                fontsize=6.5, color="black", zorder=5)
            label.set_in_layout(False)
            label.set_gid(CROSSING_LABEL)
            box = label.get_window_extent(renderer)
            if not any(box.overlaps(other) for other in taken):
                taken.append(box)
                break
            label.remove()


def mark_operating(ax, operating_rpm: float | tuple[float, float] | None) -> None:
    """The operating speed as a dotted line, or an operating range as a shaded band (both in the legend)."""
    if operating_rpm is None:
        return
    low, high = (operating_rpm, operating_rpm) if np.isscalar(operating_rpm) else operating_rpm
    if low == high:
        ax.axvline(low, color=OPERATING_COLOUR, linewidth=1.6, linestyle=(0, (1, 1.2)), zorder=2,
                   label=f"operating speed ({low:g} rpm)")
    else:
        ax.axvspan(low, high, color=OPERATING_COLOUR, alpha=0.12, linewidth=0, zorder=0,
                   label=f"operating range ({low:g}-{high:g} rpm)")


def campbell_figure(result: CampbellResult, title: str = "", operating_rpm: float | tuple[float, float] | None = None,
                    harmonics: Sequence[int] = EXCITATIONS, max_frequency_hz: float | None = None):
    """A matplotlib Figure of the Campbell diagram: families (MAC-tracked) against rotor speed, nP lines,
    crossings circled, the operating speed (rpm) as a dotted line or an operating range (low, high) shaded."""
    fig, ax = new_figure()
    colours = colormap("tab10")
    top = max_frequency_hz or max(float(np.max(f.frequencies_hz)) for f in result.families) * 1.08
    right = float(result.rpm.max()) or 1.0
    for i, (family, label) in enumerate(zip(result.families, family_labels(result))):
        if np.min(family.frequencies_hz) > top:
            continue
        ax.plot(result.rpm, family.frequencies_hz, KIND_STYLES.get(family.kind, "-"), color=colours(i % 10),
                marker="o", markersize=2.5, linewidth=1.3, label=label, zorder=3)
    excitation_lines(ax, harmonics, right, top)
    marks = [c for c in crossings(result, harmonics) if c.frequency_hz <= top]
    if marks:
        ax.plot([c.rpm for c in marks], [c.frequency_hz for c in marks], "o", markerfacecolor="none",
                markeredgecolor="black", markersize=6.5, markeredgewidth=0.9, linestyle="none",
                label="crossing with nP (n marked)", zorder=4)
    mark_operating(ax, operating_rpm)
    ax.set_xlim(0.0, right)
    ax.set_ylim(0.0, top)
    finish_axes(ax, title)
    label_crossings(ax, [(c.rpm, c.frequency_hz, c.harmonic) for c in marks])
    return fig


def save_campbell_plot(result: CampbellResult, path: str | Path, title: str = "",
                       operating_rpm: float | tuple[float, float] | None = None,
                       harmonics: Sequence[int] = EXCITATIONS, max_frequency_hz: float | None = None) -> None:
    """Write the Campbell diagram (PNG, PDF or SVG by extension) atomically."""
    save_figure(campbell_figure(result, title, operating_rpm, harmonics, max_frequency_hz), path)
