"""Campbell diagram with matplotlib: mode families, nP excitation lines, crossings, operating speed."""

from __future__ import annotations

import io
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..modal import CampbellResult

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
    ordinal = {1: "1st", 2: "2nd", 3: "3rd"}
    counts: dict[str, int] = {}
    labels = []
    for family in result.families:
        counts[family.kind] = counts.get(family.kind, 0) + 1
        n = counts[family.kind]
        labels.append(f"{ordinal.get(n, f'{n}th')} {family.kind}")
    return labels


def campbell_figure(result: CampbellResult, title: str = "", operating_rpm: float | None = None,
                    harmonics: Sequence[int] = EXCITATIONS):
    """A matplotlib Figure of the Campbell diagram."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4.6), dpi=150, layout="constrained")
    colours = plt.get_cmap("tab10")
    top = max(float(np.max(f.frequencies_hz)) for f in result.families) * 1.08
    for i, (family, label) in enumerate(zip(result.families, family_labels(result))):
        ax.plot(result.rpm, family.frequencies_hz, KIND_STYLES.get(family.kind, "-"), color=colours(i % 10),
                marker="o", markersize=2.5, linewidth=1.4, label=label)
    speeds = np.array([0.0, float(result.rpm.max()) * 1.02 or 1.0])
    for n in harmonics:
        ax.plot(speeds, n * speeds / 60.0, color="0.55", linewidth=0.8, zorder=0)
        end = speeds[-1] if n * speeds[-1] / 60.0 < top else top * 60.0 / n
        ax.annotate(f"{n}P", (end, n * end / 60.0), textcoords="offset points", xytext=(-14, 2),
                    fontsize=8, color="0.35")
    marks = crossings(result, harmonics)
    if marks:
        ax.plot([c.rpm for c in marks], [c.frequency_hz for c in marks], "o", markerfacecolor="none",
                markeredgecolor="black", markersize=6, linestyle="none", label="crossing with nP")
    if operating_rpm is not None:
        ax.axvline(operating_rpm, color="firebrick", linewidth=1.0, linestyle=":")
        ax.annotate(f"operating {operating_rpm:g} rpm", (operating_rpm, top * 0.97), rotation=90, fontsize=8,
                    ha="right", va="top", color="firebrick")
    ax.set_xlim(0.0, speeds[-1])
    ax.set_ylim(0.0, top)
    ax.set_xlabel("Rotor speed (rpm)")
    ax.set_ylabel("Natural frequency (Hz)")
    if title:
        ax.set_title(title, fontsize=10)
    ax.grid(True, linewidth=0.4, alpha=0.5)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    return fig


def save_campbell_plot(result: CampbellResult, path: str | Path, title: str = "",
                       operating_rpm: float | None = None) -> None:
    """Write the Campbell diagram (PNG, PDF or SVG by extension) atomically."""
    from ..io.results import write_atomic

    fig = campbell_figure(result, title, operating_rpm)
    buffer = io.BytesIO()
    suffix = Path(path).suffix.lower().lstrip(".") or "png"
    fig.savefig(buffer, format=suffix)
    import matplotlib.pyplot as plt
    plt.close(fig)
    write_atomic(path, buffer.getvalue())
