"""Full-system Campbell diagram: the linearized turbine's modes (multi-blade coordinates, azimuth-averaged when
the rotor turns, parked at one azimuth at 0 rpm) over rotor speed, followed by their names."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .kane import TurbineModel
from .linearize import LinearModel, linearize


@dataclass(frozen=True)
class TurbineCampbell:
    """Modes over rotor speed.

    rpm : (S,) rotor speeds, rpm
    names : mode names (in order of first appearance, by frequency at the first speed)
    frequencies_hz, damping_ratios : (len(names), S), NaN where a name does not occur at a speed
    linearizations : the linear model at each speed
    """

    rpm: NDArray
    names: list[str]
    frequencies_hz: NDArray
    damping_ratios: NDArray
    linearizations: list[LinearModel]


def campbell(model: TurbineModel, free: NDArray, rpm: Sequence[float], azimuths: int = 8, azimuth: float = 0.0,
             yaw: float = 0.0, progress: Callable[[Iterable[float]], Iterable[float]] | None = None
             ) -> TurbineCampbell:
    """Linearize at each rotor speed (rpm; parked at ``azimuth``, rad, at 0 rpm) with the nacelle at ``yaw`` (rad)
    and gather the modes by name; ``progress`` optionally wraps the loop over speeds (e.g. a progress bar)."""
    results: list[LinearModel] = [linearize(model, free, float(speed), azimuth, azimuths, yaw=yaw)
                                  for speed in (progress or iter)(list(rpm))]
    spinning = any(speed > 0 for speed in rpm)
    labels = [whirl_names(result) if spinning and result.rpm == 0 else [m.name for m in result.modes]
              for result in results]
    names: list[str] = []
    for row in labels:
        names += [name for name in row if name not in names]
    frequencies = np.full((len(names), len(results)), np.nan)
    damping = np.full_like(frequencies, np.nan)
    for j, (result, row) in enumerate(zip(results, labels)):
        for mode, name in zip(result.modes, row):
            i = names.index(name)
            frequencies[i, j], damping[i, j] = mode.frequency_hz, mode.damping_ratio
    return TurbineCampbell(rpm=np.asarray(rpm, dtype=float), names=names, frequencies_hz=frequencies,
                           damping_ratios=damping, linearizations=results)


def whirl_names(result: LinearModel) -> list[str]:
    """The names of a parked linearization with each asymmetric pair ('... (pitch)', '... (yaw)') renamed as the
    whirls it becomes when the rotor starts turning: the lower backward, the higher forward (they split by
    -+ Omega from there), so that a Campbell diagram's curves start at 0 rpm."""
    names = [mode.name for mode in result.modes]
    for family in {name.rsplit(" (", 1)[0] for name in names if name.endswith(("(pitch)", "(yaw)"))}:
        pair = [i for i, name in enumerate(names) if name in (f"{family} (pitch)", f"{family} (yaw)")]
        for i, whirl in zip(sorted(pair, key=lambda i: result.modes[i].frequency_hz), ("backward", "forward")):
            names[i] = f"{family} ({whirl} whirl)"
    return names


def campbell_text(result: TurbineCampbell) -> str:
    """CSV: one row per rotor speed, a frequency (Hz) column per mode."""
    header = "rpm," + ",".join(f"{name} [Hz]" for name in result.names)
    rows = [f"{speed:.6g}," + ",".join("" if np.isnan(value) else f"{value:.6g}" for value in column)
            for speed, column in zip(result.rpm, result.frequencies_hz.T)]
    return "\n".join([header] + rows) + "\n"
