"""Distances of mode frequencies from rotor harmonics and from windows, on piecewise-linear Campbell curves.

A family's frequency ``f(Omega)`` is known at the sweep speeds and taken linear between them. Against the harmonic
``n P = n Omega / 60`` (Hz, Omega in rpm) the relative separation ``(f - nP) / nP`` is, on each interval, a ratio of
two linear functions of Omega and hence monotonic: its smallest magnitude lies at an end of the interval, or is zero
where ``f - nP`` changes sign (a crossing, located by linear interpolation).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray


@dataclass(frozen=True)
class HarmonicMargin:
    """Closest approach of a frequency curve to the harmonic ``n P`` over a speed range.

    margin : least |f - nP| / nP over the range (0 at a crossing)
    rpm : rotor speed where it occurs, rpm
    frequency_hz : the family's frequency there, Hz
    excitation_hz : n P there, Hz
    crossing : True when the curve crosses nP
    """

    margin: float
    rpm: float
    frequency_hz: float
    excitation_hz: float
    crossing: bool


def harmonic_margin(rpm: NDArray, frequency_hz: NDArray, harmonic: int) -> HarmonicMargin:
    """Least relative separation of ``frequency_hz`` (at the speeds ``rpm``, rpm, > 0, increasing) from
    ``harmonic`` x the rotor frequency, with the frequency linear between the speeds."""
    rpm = np.asarray(rpm, dtype=float)
    f = np.asarray(frequency_hz, dtype=float)
    excitation = harmonic * rpm / 60.0
    gap = f - excitation
    for k in range(len(rpm) - 1):
        if gap[k] == 0.0 or gap[k] * gap[k + 1] < 0.0:
            t = gap[k] / (gap[k] - gap[k + 1])
            speed = rpm[k] + t * (rpm[k + 1] - rpm[k])
            return HarmonicMargin(0.0, float(speed), float(harmonic * speed / 60.0), float(harmonic * speed / 60.0),
                                  True)
    if gap[-1] == 0.0:
        return HarmonicMargin(0.0, float(rpm[-1]), float(f[-1]), float(excitation[-1]), True)
    relative = np.abs(gap) / excitation
    k = int(np.argmin(relative))
    return HarmonicMargin(float(relative[k]), float(rpm[k]), float(f[k]), float(excitation[k]), False)


def window_distance(frequency_hz: NDArray, low: float, high: float) -> tuple[float, int]:
    """Least signed distance (Hz) of the frequencies from the edges of the window [low, high] (negative outside)
    and the index where it occurs; on a piecewise-linear curve the extremes lie at the given points."""
    f = np.asarray(frequency_hz, dtype=float)
    distance = np.minimum(f - low, high - f)
    k = int(np.argmin(distance))
    return float(distance[k]), k
