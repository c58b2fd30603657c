"""Statistics of a batch's results: per mode (or family and speed, or requirement) the mean, standard deviation
and 5/95 % quantiles, and the sensitivity of each to each varied input (Pearson correlation and the linear swing
over the input's 5-95 % range); histograms and a tornado chart."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

RESULT_COLUMNS = {"case_index", "case_hash", "status", "error", "mode", "name", "kind", "frequency_hz",
                  "residual", "damping_ratio", "requirement", "check", "passed", "measured", "margin", "rpm",
                  "channel", "unit", "mean", "std", "min", "max", "del", "wohler_m", "swept", "onset", "onset_rpm",
                  "onset_wind_speed_m_s", "onset_frequency_hz", "onset_mode", "flap_share", "edge_share",
                  "torsion_share", "least_damping_ratio", "unconverged_roots"}
#: a flutter batch's summarised quantities: result column -> label, unit
FLUTTER = {"onset_rpm": ("flutter onset rotor speed", "rpm"),
           "onset_wind_speed_m_s": ("flutter onset wind speed", "m/s"),
           "onset_frequency_hz": ("flutter onset frequency", "Hz")}


@dataclass(frozen=True)
class Quantity:
    """One summarised quantity over the cases: its label, unit, values (by case), and per input the correlation
    and the linear swing (value change over the input's 5-95 % range, same unit as the values); ``meaning`` says
    what the values are (a frequency, a channel's mean over the window, a check's measured value)."""

    label: str
    unit: str
    values: NDArray[np.float64]
    correlation: dict[str, float]
    swing: dict[str, float]
    meaning: str = "value"

    @property
    def statistics(self) -> dict[str, float]:
        v = self.values
        return {"count": len(v), "mean": float(np.mean(v)), "std": float(np.std(v, ddof=1)) if len(v) > 1 else 0.0,
                "q05": float(np.quantile(v, 0.05)), "q95": float(np.quantile(v, 0.95))}


@dataclass(frozen=True)
class BatchSummary:
    cases: int
    failed: int
    inputs: tuple[str, ...]
    quantities: list[Quantity]


def _columns(table: Any) -> dict[str, list]:
    return {name: table[name].to_pylist() for name in table.column_names}


def _varied_inputs(data: dict[str, list], ok: NDArray[np.bool_]) -> list[str]:
    names = []
    for name, values in data.items():
        if name in RESULT_COLUMNS - {"rpm"} or name.endswith("_stations") or name == "file":
            continue
        column = np.array([np.nan if v is None else v for v in values], dtype=float)[ok]
        if column.size and np.all(np.isfinite(column)) and np.ptp(column) > 0:
            names.append(name)
    return names


def _sensitivity(x: NDArray, y: NDArray) -> tuple[float, float]:
    if np.ptp(x) == 0 or np.ptp(y) == 0 or len(x) < 3:
        return 0.0, 0.0
    correlation = float(np.corrcoef(x, y)[0, 1])
    slope = np.polyfit(x, y, 1)[0]
    return correlation, float(slope * (np.quantile(x, 0.95) - np.quantile(x, 0.05)))


def summarize(table: Any) -> BatchSummary:
    """The summary of a results table (see :class:`bladefem.batch.store.ResultStore.table`)."""
    data = _columns(table)
    status = np.array(data.get("status", []))
    ok = status == "ok"
    hashes = np.array(data.get("case_hash", []))
    failed = len(set(hashes[~ok]))
    if "onset_rpm" in data:
        return _flutter_summary(data, ok, failed, len(set(hashes)))
    checks = "measured" in data and "frequency_hz" not in data
    channels = "channel" in data
    value_name = "mean" if channels else "measured" if checks else "frequency_hz"
    values = np.array([np.nan if v is None else v for v in data.get(value_name, [])], dtype=float)
    inputs = [name for name in _varied_inputs(data, ok) if not (name == "rpm" and _rpm_is_sweep(data, ok))]
    units: dict[str, str] = {}
    if channels:                                  # turbine simulations: each channel's mean over the window
        labels = [f"{c} mean" for c in data["channel"]]
        units = {f"{c} mean": u for c, u in zip(data["channel"], data["unit"]) if c is not None}
        meaning = "mean over the window"
    elif checks:                                  # the unit of each check's measured value (older results: none)
        labels = [f"{r} / {c}" for r, c in zip(data["requirement"], data["check"])]
        units = {label: u for label, u in zip(labels, data.get("unit", [None] * len(labels))) if u is not None}
        meaning = "measured value"
    else:
        meaning = "frequency"
    if not channels and not checks and _rpm_is_sweep(data, ok):
        labels = [f"{n} at {r:g} rpm" for n, r in zip(data["name"], data["rpm"])]
    elif not channels and not checks:
        labels = list(data.get("name", []))
    quantities = []
    for label in dict.fromkeys(label for label, good in zip(labels, ok) if good):
        rows = np.array([good and this == label for this, good in zip(labels, ok)])
        y = values[rows]
        correlation, swing = {}, {}
        for name in inputs:
            x = np.array(data[name], dtype=float)[rows]
            correlation[name], swing[name] = _sensitivity(x, y)
        unit = units.get(label, "") if channels or checks else "Hz"
        quantities.append(Quantity(label, unit, y, correlation, swing, meaning))
    return BatchSummary(len(set(hashes)), failed, tuple(inputs), quantities)


def _flutter_summary(data: dict[str, list], ok: NDArray[np.bool_], failed: int, cases: int) -> BatchSummary:
    """The flutter onset's swept speed (rotor or wind) and frequency over the cases that have one (a case without
    onset in its sweep is left out of the statistics: ``n`` counts those with one)."""
    inputs = _varied_inputs(data, ok)
    onset = ok & np.array([bool(v) for v in data["onset"]])
    swept = {f"onset_{s}" for s, good in zip(data["swept"], ok) if good}
    quantities = []
    for column, (label, unit) in FLUTTER.items():
        if column != "onset_frequency_hz" and column not in swept:
            continue
        y = np.array(data[column], dtype=float)[onset] if onset.any() else np.zeros(0)
        correlation, swing = {}, {}
        for name in inputs:
            correlation[name], swing[name] = _sensitivity(np.array(data[name], dtype=float)[onset], y)
        quantities.append(Quantity(label, unit, y, correlation, swing, "flutter onset"))
    return BatchSummary(cases, failed, tuple(inputs), [q for q in quantities if len(q.values)])


def _rpm_is_sweep(data: dict[str, list], ok: NDArray[np.bool_]) -> bool:
    """True when one case holds several speeds (a Campbell analysis)."""
    if "rpm" not in data or "name" not in data:
        return False
    seen: dict[tuple, set] = {}
    for case, name, rpm, good in zip(data["case_hash"], data["name"], data["rpm"], ok):
        if good:
            seen.setdefault((case, name), set()).add(rpm)
    return any(len(speeds) > 1 for speeds in seen.values())


def format_summary(summary: BatchSummary) -> str:
    """Statistics per quantity, then the correlation of each with each varied input."""
    meanings = ", ".join(dict.fromkeys(q.meaning for q in summary.quantities)) or "-"
    lines = [f"# {summary.cases} cases, {summary.failed} failed; varied inputs: {', '.join(summary.inputs) or '-'}",
             f"# statistics over the cases of each quantity ({meanings}), in its unit",
             f"{'quantity':<28} {'unit':<8} {'n':>5} {'mean':>12} {'std':>11} {'q05':>12} {'q95':>12}"]
    for q in summary.quantities:
        s = q.statistics
        lines.append(f"{q.label:<28} {q.unit or '-':<8} {s['count']:>5d} {s['mean']:>12.6g} {s['std']:>11.4g} "
                     f"{s['q05']:>12.6g} {s['q95']:>12.6g}")
    if summary.inputs:
        lines += ["", "# correlation with each varied input (linear swing over its 5-95 % range in brackets)",
                  f"{'quantity':<28} " + " ".join(f"{name:>26}" for name in summary.inputs)]
        for q in summary.quantities:
            cells = [f"{q.correlation[n]:+.3f} ({q.swing[n]:+.3g} {q.unit})".rjust(26) for n in summary.inputs]
            lines.append(f"{q.label:<28} " + " ".join(cells))
    return "\n".join(lines)


def _axis_label(q: Quantity) -> str:
    return f"{q.meaning} ({q.unit})" if q.unit else q.meaning


def plot_summary(summary: BatchSummary, folder: str | Path, most: int = 6, title: str | None = None) -> list[Path]:
    """``histograms.png`` (one panel per quantity: how many cases gave each value, with the mean and the 5/95 %
    quantiles) and, when inputs vary, ``tornado.png`` (per quantity the linear swing of each input, largest first);
    written whole or not at all; ``title`` names the batch (e.g. its results folder). Returns the files written."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import MaxNLocator

    from ..files import atomic_path
    folder = Path(folder)
    shown = summary.quantities[:most]
    written = []
    columns = min(3, len(shown)) or 1
    rows = (len(shown) + columns - 1) // columns or 1
    batch = f"{title}: " if title else ""
    failed = f", {summary.failed} failed" if summary.failed else ""
    more = f"; the first {len(shown)} of {len(summary.quantities)} quantities" if len(summary.quantities) > most else ""
    figure, axes = plt.subplots(rows, columns, figsize=(4 * columns, 3 * rows + 0.5), squeeze=False)
    for axis, q in zip(axes.flat, shown):
        values = np.asarray(q.values, dtype=float)
        spread = np.ptp(values) > 1e-9 * np.max(np.abs(values))     # else constant but for round-off: one bin
        axis.hist(values, bins="auto" if spread else 1, color="#4c72b0", edgecolor="white")
        s = q.statistics
        axis.axvline(s["mean"], color="black", linewidth=1.2, label="mean")
        for quantile in (s["q05"], s["q95"]):
            axis.axvline(quantile, color="#c44e52", linewidth=1, linestyle="--",
                         label="5 and 95 % quantiles" if quantile == s["q05"] else None)
        axis.set_title(q.label, fontsize=9)
        axis.set_xlabel(_axis_label(q))
        axis.set_ylabel("cases")
        axis.yaxis.set_major_locator(MaxNLocator(integer=True))
    handles, names = axes.flat[0].get_legend_handles_labels()
    figure.legend(handles, names, loc="upper right", ncol=2, fontsize=8, frameon=False)
    for axis in list(axes.flat)[len(shown):]:
        axis.set_visible(False)
    figure.suptitle(f"{batch}each quantity over {summary.cases} cases{failed}{more}", fontsize=11, x=0.01,
                    ha="left")
    figure.tight_layout(rect=(0, 0, 1, 0.97))
    with atomic_path(folder / "histograms.png") as temporary:
        figure.savefig(temporary, dpi=120)
    written.append(folder / "histograms.png")
    plt.close(figure)
    if summary.inputs:
        figure, axes = plt.subplots(rows, columns, figsize=(4.5 * columns, 2.2 + 0.4 * len(summary.inputs) * rows),
                                    squeeze=False)
        for axis, q in zip(axes.flat, shown):
            order = sorted(summary.inputs, key=lambda n: abs(q.swing[n]))
            axis.barh(order, [q.swing[n] for n in order], color=["#c44e52" if q.swing[n] < 0 else "#55a868"
                                                                  for n in order])
            axis.axvline(0, color="black", linewidth=0.8)
            axis.set_title(q.label, fontsize=9)
            axis.set_xlabel(f"swing over the input's 5-95 % range ({q.unit})" if q.unit else
                            "swing over the input's 5-95 % range")
            axis.xaxis.set_major_locator(MaxNLocator(nbins=5))
        for axis in list(axes.flat)[len(shown):]:
            axis.set_visible(False)
        figure.suptitle(f"{batch}sensitivity of each quantity to each varied input ({summary.cases} cases{failed}"
                        f"{more})", fontsize=11, x=0.01, ha="left")
        figure.tight_layout(rect=(0, 0, 1, 0.95))
        with atomic_path(folder / "tornado.png") as temporary:
            figure.savefig(temporary, dpi=120)
        written.append(folder / "tornado.png")
        plt.close(figure)
    return written
