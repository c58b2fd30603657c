"""Figures of a DLC 1.2 batch's loads: the damage-equivalent load over wind speed per channel (with the lifetime
DEL and the Weibull weights), and the extremes."""

from __future__ import annotations

from pathlib import Path

import numpy as np

#: channels drawn, when present: blade root and tower-base-like moments, thrust, deflections, power
SHOWN = ("RootMOoP1", "RootMIP1", "RotThrust", "RotTorq", "OoPDefl1", "TTDspFA", "GenPwr", "RtAeroFxh")


def plot_loads(channels, folder: str | Path, mean_speed: float, title: str = "") -> list[Path]:
    """``del.png`` and ``extremes.png`` in ``folder`` (written whole or not at all); the files written."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..files import atomic_path
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    chosen = [c for c in channels if c.channel in SHOWN] or list(channels)[:6]
    columns = min(3, len(chosen))
    rows = (len(chosen) + columns - 1) // columns
    figure, axes = plt.subplots(rows, columns, figsize=(4.2 * columns, 3.2 * rows + 0.6), squeeze=False)
    for axis, c in zip(axes.flat, chosen):
        axis.plot(c.speeds, c.dels, "o-", color="#4c72b0", label="DEL (boxes averaged)")
        axis.axhline(c.lifetime_del, color="black", linestyle="--", linewidth=1, label="lifetime DEL")
        axis.set_title(f"{c.channel} (m = {c.wohler:g})", fontsize=9)
        axis.set_xlabel("wind speed at hub [m/s]")
        axis.set_ylabel(f"DEL [{c.unit}]")
        twin = axis.twinx()
        twin.bar(c.speeds, c.weights, width=0.4 * np.min(np.diff(c.speeds)) if len(c.speeds) > 1 else 0.5,
                 color="#dd8452", alpha=0.35)
        twin.set_ylabel("Weibull weight", fontsize=8)
    for axis in list(axes.flat)[len(chosen):]:
        axis.set_visible(False)
    axes.flat[0].legend(fontsize=7)
    figure.suptitle(f"{title + ': ' if title else ''}damage-equivalent loads (1 Hz), Weibull mean {mean_speed:g} m/s",
                    fontsize=10)
    figure.tight_layout()
    written = []
    with atomic_path(folder / "del.png") as path:
        figure.savefig(path, format="png", dpi=110)
    written.append(folder / "del.png")
    plt.close(figure)
    figure, axis = plt.subplots(figsize=(7, 3.5))
    names = [c.channel for c in chosen]
    spans = [max(abs(c.maximum), abs(c.minimum)) or 1.0 for c in chosen]
    axis.barh(names, [c.maximum / s for c, s in zip(chosen, spans)], color="#4c72b0", label="max / largest |extreme|")
    axis.barh(names, [c.minimum / s for c, s in zip(chosen, spans)], color="#c44e52", label="min / largest |extreme|")
    for i, c in enumerate(chosen):
        axis.text(1.02, i, f"{c.minimum:.4g} .. {c.maximum:.4g} {c.unit}", va="center", fontsize=7)
    axis.set_xlim(-1.1, 2.2)
    axis.legend(fontsize=7, loc="lower right")
    axis.set_title(f"{title + ': ' if title else ''}extremes over every case", fontsize=10)
    figure.tight_layout()
    with atomic_path(folder / "extremes.png") as path:
        figure.savefig(path, format="png", dpi=110)
    written.append(folder / "extremes.png")
    plt.close(figure)
    return written
