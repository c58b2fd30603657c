"""The flutter diagram: the damped frequency (top) and damping ratio (bottom) of each tracked blade mode against
the swept speed (rotor speed, or wind speed when the rotor speed is fixed), the onset marked in both panels."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .style import DPI, colormap, finish_axes, pyplot, save_figure

if TYPE_CHECKING:
    from ..models.flutter import FlutterResult

__all__ = ["flutter_figure", "save_flutter_plot"]


def swept(result: FlutterResult) -> tuple[np.ndarray, str, float | None]:
    """The swept values, their axis label and the onset's value on that axis (None without onset)."""
    rpm = np.array([p.condition.rpm for p in result.points])
    if np.ptp(rpm) > 0:
        return rpm, "Rotor speed (rpm)", None if result.onset is None else result.onset.rpm
    wind = np.array([p.condition.wind_speed for p in result.points])
    return wind, "Wind speed (m/s)", None if result.onset is None else result.onset.wind_speed_m_s


def flutter_figure(result: FlutterResult, title: str = "Blade flutter (p-k, Theodorsen)"):
    """The two-panel figure."""
    x, label, at = swept(result)
    frequency = np.array([p.frequency_hz for p in result.points])
    damping = 100 * np.array([p.damping_ratio for p in result.points])
    fig, (top, bottom) = pyplot().subplots(2, 1, figsize=(7.5, 6.5), dpi=DPI, sharex=True, layout="constrained")
    colours = colormap("tab10")
    for j in range(frequency.shape[1]):
        share = result.points[0].shares[j]
        name = f"mode {j + 1} ({max(share, key=share.get)})"
        top.plot(x, frequency[:, j], color=colours(j % 10), label=name)
        bottom.plot(x, damping[:, j], color=colours(j % 10), label=name)
    bottom.axhline(0.0, color="0.2", linewidth=0.8)
    if at is not None:
        onset = result.onset
        for ax in (top, bottom):
            ax.axvline(at, color="crimson", linestyle=":", linewidth=1.0)
        top.plot([at], [onset.frequency_hz], "o", color="crimson", label=f"onset {at:.4g}")
        bottom.plot([at], [0.0], "o", color="crimson")
    finish_axes(top, title, xlabel="", ylabel="Damped frequency (Hz)")
    finish_axes(bottom, xlabel=label, ylabel="Damping ratio (%)", legend=False)
    return fig


def save_flutter_plot(result: FlutterResult, path: str | Path) -> None:
    """Write the diagram (PNG, PDF or SVG by extension) atomically."""
    save_figure(flutter_figure(result), path)
