"""Fatigue and extreme loads of a DLC 1.2 batch (IEC 61400-1: power production in normal turbulence, wind speeds
across the operating range, several turbulence boxes per speed).

Per case and channel, the damage-equivalent load over the statistics window (ASTM E1049-85 rainflow counting by the
``rainflow`` package, the residue's ranges counted as half cycles):

    DEL = (sum_i n_i S_i^m / N_eq)^(1/m),     N_eq = f_eq T (1 Hz equivalent cycles over the window of T s)

with the S-N slope ``m`` of the channel (steel 4 for the tower, composite 10 for the blades, 4 otherwise by
default). Across the plan, the lifetime DEL weights each wind speed by its Weibull probability (the IEC class's
annual mean speed at the hub, shape 2: a Rayleigh distribution), averaging damage over the boxes of one speed:

    DEL_life = (sum_j p_j <DEL_j^m>_boxes)^(1/m),     p_j = F(v_j + dv/2) - F(v_j - dv/2),  F = 1 - exp(-(v/A)^k)

with the bins between the midpoints of the plan's speeds (the outer bins as wide as their neighbours' halves),
``p`` normalised over the plan's speeds (the weight of the operating range), and the extremes the largest
maximum and smallest minimum over every case.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

#: IEC 61400-1 annual mean wind speed at the hub (m/s) of the wind turbine classes
IEC_MEAN_SPEED = {"I": 10.0, "II": 8.5, "III": 7.5}
#: default S-N (Woehler) slopes by channel: composite blades 10, steel elsewhere 4
WOHLER = {"RootMOoP1": 10.0, "RootMIP1": 10.0, "OoPDefl1": 10.0, "IPDefl1": 10.0}
DEFAULT_WOHLER = 4.0


def wohler_slope(channel: str) -> float:
    return WOHLER.get(channel, DEFAULT_WOHLER)


def rainflow_cycles(series: NDArray) -> tuple[NDArray, NDArray]:
    """Ranges and counts (1 for a closed cycle, 1/2 for the residue's) of ``series`` by ASTM E1049-85 rainflow
    counting (the ``rainflow`` package)."""
    import rainflow

    series = np.asarray(series, dtype=float)
    if series.size < 3 or np.ptp(series) == 0:
        return np.zeros(0), np.zeros(0)
    found = np.array([(rng, count) for rng, _, count, _, _ in rainflow.extract_cycles(series)]).reshape(-1, 2)
    return found[:, 0], found[:, 1]


def damage_equivalent_load(series: NDArray, m: float, duration: float, frequency: float = 1.0) -> float:
    """DEL (the series' unit) of ``series`` over ``duration`` s for S-N slope ``m`` at ``frequency`` Hz
    equivalent cycles."""
    ranges, counts = rainflow_cycles(series)
    return float((np.sum(counts * ranges**m) / (frequency * duration)) ** (1.0 / m))


def weibull_weights(speeds: NDArray, mean_speed: float, shape: float = 2.0) -> NDArray:
    """Probabilities of the wind-speed bins about ``speeds`` (sorted, m/s) for a Weibull distribution of mean
    ``mean_speed`` and ``shape``, normalised to sum 1 over the bins."""
    speeds = np.asarray(speeds, dtype=float)
    edges = bin_edges(speeds)
    scale = mean_speed / math.gamma(1.0 + 1.0 / shape)
    cdf = 1.0 - np.exp(-(np.maximum(edges, 0.0) / scale) ** shape)
    weights = np.diff(cdf)
    return weights / weights.sum()


def bin_edges(speeds: NDArray) -> NDArray:
    """Bin edges about sorted ``speeds``: midpoints between neighbours, the outer edges half a neighbour gap out
    (a single speed: +-1 m/s)."""
    if speeds.size == 1:
        return np.array([speeds[0] - 1.0, speeds[0] + 1.0])
    middle = 0.5 * (speeds[1:] + speeds[:-1])
    return np.concatenate([[speeds[0] - (middle[0] - speeds[0])], middle, [speeds[-1] + (speeds[-1] - middle[-1])]])


@dataclass(frozen=True)
class ChannelLoads:
    """One channel over the plan: per wind speed (m/s) the box-averaged DEL, its Weibull weight; the lifetime
    DEL, the S-N slope, and the extremes (largest maximum, smallest minimum) with the wind speed of each."""

    channel: str
    unit: str
    wohler: float
    speeds: NDArray
    dels: NDArray
    weights: NDArray
    lifetime_del: float
    maximum: float
    maximum_speed: float
    minimum: float
    minimum_speed: float


def lifetime_loads(rows: list[dict], mean_speed: float) -> list[ChannelLoads]:
    """The :class:`ChannelLoads` of every channel of a DLC batch's rows (each with ``channel``, ``unit``,
    ``wind_speed_m_s``, ``del``, ``wohler_m``, ``min``, ``max``)."""
    out = []
    for channel in dict.fromkeys(r["channel"] for r in rows):
        mine = [r for r in rows if r["channel"] == channel and r.get("del") is not None]
        if not mine:
            continue
        m = float(mine[0]["wohler_m"])
        speeds = np.array(sorted({float(r["wind_speed_m_s"]) for r in mine}))
        dels = np.array([np.mean([r["del"] ** m for r in mine if float(r["wind_speed_m_s"]) == v]) ** (1 / m)
                         for v in speeds])
        weights = weibull_weights(speeds, mean_speed)
        high = max(mine, key=lambda r: r["max"])
        low = min(mine, key=lambda r: r["min"])
        out.append(ChannelLoads(channel=channel, unit=mine[0]["unit"], wohler=m, speeds=speeds, dels=dels,
                                weights=weights, lifetime_del=float(np.sum(weights * dels**m) ** (1 / m)),
                                maximum=float(high["max"]), maximum_speed=float(high["wind_speed_m_s"]),
                                minimum=float(low["min"]), minimum_speed=float(low["wind_speed_m_s"])))
    return out
