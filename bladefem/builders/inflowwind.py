"""InflowWind input file: steady wind (``WindType`` 1) only.

``HWindSpeed`` (m/s) at ``RefHt`` (m) with the power-law exponent ``PLExp``, turned by ``PropagationDir`` (deg,
positive towards -y) and ``VFlowAng`` (deg, upflow). Any other wind type (uniform time series, turbulent boxes,
user fields) is refused with the file, line and label of ``WindType``.
"""

from __future__ import annotations

import math
import os

from ..aero.rotor import Inflow
from ..formats._labels import Labels
from ..limits import MAX_DIRECTION_DEG, MAX_SHEAR_EXPONENT, MAX_UPFLOW_DEG, MAX_WIND_SPEED

WIND_TYPES = {1: "steady", 2: "uniform time series", 3: "TurbSim full field", 4: "Bladed full field",
              5: "HAWC full field", 6: "user-defined", 7: "native Bladed full field", 8: "4D external"}


def read_inflowwind(path: str | os.PathLike) -> Inflow:
    """The steady wind of an InflowWind file (SI, rad)."""
    labels = Labels.read(path)
    kind = labels.int("WindType")
    if kind != 1:
        what = WIND_TYPES.get(kind, "unknown")
        raise labels.error(f"WindType {kind} ({what} wind) is not modelled: bladefem reads steady wind "
                           "(WindType 1)", labels.line("WindType"), "WindType")
    return Inflow(speed=_within(labels, "HWindSpeed", 0.0, MAX_WIND_SPEED, required=True),
                  reference_height=labels.float("RefHt", positive=True),
                  shear_exponent=_within(labels, "PLExp", -MAX_SHEAR_EXPONENT, MAX_SHEAR_EXPONENT,
                                         required=True),
                  direction=math.radians(_within(labels, "PropagationDir", -MAX_DIRECTION_DEG, MAX_DIRECTION_DEG)),
                  upflow=math.radians(_within(labels, "VFlowAng", -MAX_UPFLOW_DEG, MAX_UPFLOW_DEG)))


def _within(labels: Labels, label: str, low: float, high: float, required: bool = False) -> float:
    """The value of ``label`` (0 when absent and not ``required``) within [low, high] (see :mod:`bladefem.limits`)."""
    if not required and not labels.has(label):
        return 0.0
    value = labels.float(label)
    if not low <= value <= high:
        raise labels.error(f"must lie between {low:g} and {high:g}, got {value:g}", labels.line(label), label)
    return value
