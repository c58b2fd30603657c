"""Campbell diagram with matplotlib: mode families, nP excitation lines, crossings, operating speed."""

from __future__ import annotations

import io
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..modal import CampbellResult
from .modes3d import ordinal

EXCITATIONS: tuple[int, ...] = (1, 3, 6, 9)
KIND_STYLES = {"flap": "-", "edge": "--", "torsion": "-.", "axial": ":"}


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
    counts: dict[str, int] = {}
    labels = []
    for family in result.families:
        counts[family.kind] = counts.get(family.kind, 0) + 1
        labels.append(f"{ordinal(counts[family.kind])} {family.kind}")
    return labels


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


def excitation_lines(ax, harmonics: Sequence[int], right: float, top: float) -> None:
    """The nP lines, labelled just outside the right edge of the axes (or above the top where a line leaves
    there), the right-edge labels spread so that they never overlap."""
    speeds = np.array([0.0, right])
    at_edge = []
    for n in harmonics:
        ax.plot(speeds, n * speeds / 60.0, color="0.5", linewidth=0.8, zorder=1)
        end = n * right / 60.0
        if end <= top:
            at_edge.append((n, end))
        else:
            ax.annotate(f"{n}P", (top * 60.0 / n, top), textcoords="offset points", xytext=(0, 2), ha="center",
                        va="bottom", fontsize=8, color="0.3", annotation_clip=False)
    labels = spread([y for _, y in at_edge], 0.045 * top)
    for (n, y), y_label in zip(at_edge, labels):
        ax.annotate(f"{n}P", (right, y_label), xytext=(5, 0), textcoords="offset points", ha="left",
                    va="center", fontsize=8, color="0.3", annotation_clip=False)


def campbell_figure(result: CampbellResult, title: str = "", operating_rpm: float | None = None,
                    harmonics: Sequence[int] = EXCITATIONS, max_frequency_hz: float | None = None):
    """A matplotlib Figure of the Campbell diagram: families (MAC-tracked) against rotor speed, nP lines,
    crossings circled, the operating speed as a dotted line (in the legend)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import AutoMinorLocator

    fig, ax = plt.subplots(figsize=(6.5, 4.2), dpi=200, layout="constrained")
    colours = plt.get_cmap("tab10")
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
                label="crossing with nP", zorder=4)
    if operating_rpm is not None:
        ax.axvline(operating_rpm, color="firebrick", linewidth=1.0, linestyle=":", zorder=2,
                   label=f"operating speed ({operating_rpm:g} rpm)")
    ax.set_xlim(0.0, right)
    ax.set_ylim(0.0, top)
    ax.set_xlabel("Rotor speed (rpm)")
    ax.set_ylabel("Natural frequency (Hz)")
    ax.xaxis.set_minor_locator(AutoMinorLocator())
    ax.yaxis.set_minor_locator(AutoMinorLocator())
    ax.tick_params(which="both", direction="in", top=True, right=True)
    if title:
        ax.set_title(title, fontsize=10)
    ax.grid(True, linewidth=0.4, alpha=0.5)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.07, 1.0), frameon=False, borderaxespad=0.0)
    return fig


def save_campbell_plot(result: CampbellResult, path: str | Path, title: str = "",
                       operating_rpm: float | None = None, harmonics: Sequence[int] = EXCITATIONS,
                       max_frequency_hz: float | None = None) -> None:
    """Write the Campbell diagram (PNG, PDF or SVG by extension) atomically."""
    from ..io.results import write_atomic

    fig = campbell_figure(result, title, operating_rpm, harmonics, max_frequency_hz)
    buffer = io.BytesIO()
    suffix = Path(path).suffix.lower().lstrip(".") or "png"
    fig.savefig(buffer, format=suffix)
    import matplotlib.pyplot as plt
    plt.close(fig)
    write_atomic(path, buffer.getvalue())
