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
    return Inflow(speed=labels.float("HWindSpeed", non_negative=True),
                  reference_height=labels.float("RefHt", positive=True),
                  shear_exponent=labels.float("PLExp"),
                  direction=math.radians(labels.float("PropagationDir")) if labels.has("PropagationDir") else 0.0,
                  upflow=math.radians(labels.float("VFlowAng")) if labels.has("VFlowAng") else 0.0)
