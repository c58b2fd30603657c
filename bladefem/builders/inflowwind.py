"""InflowWind input file: steady wind (``WindType`` 1), a uniform wind file (2) or a TurbSim full field (3).

``HWindSpeed`` (m/s) at ``RefHt`` (m) with the power-law exponent ``PLExp``, turned by ``PropagationDir`` (deg,
positive towards -y) and ``VFlowAng`` (deg, upflow); ``FileName_Uni`` with ``RefHt_Uni`` and ``RefLength`` (m);
``FileName_BTS``. The unsteady kinds take their angles from the file alone: a ``PropagationDir`` or ``VFlowAng``
other than 0 with them (InflowWind turns the whole field about the hub) is refused, as are the other wind types
(Bladed, HAWC, user-defined, 4D fields), with the file, line and label.
"""

from __future__ import annotations

import math
import os

import numpy as np

from ..aero.rotor import Inflow
from ..aero.wind import GridWind, UniformWind
from ..errors import InputError
from ..formats._labels import Labels
from ..formats.turbsim import TurbSimBox, read_turbsim
from ..formats.uniform_wind import COLUMNS as UNIFORM_FILE_COLUMNS
from ..formats.uniform_wind import read_uniform_wind
from ..limits import MAX_DIRECTION_DEG, MAX_SHEAR_EXPONENT, MAX_UPFLOW_DEG, MAX_WIND_SPEED

WIND_TYPES = {1: "steady", 2: "uniform time series", 3: "TurbSim full field", 4: "Bladed full field",
              5: "HAWC full field", 6: "user-defined", 7: "native Bladed full field", 8: "4D external"}


def read_inflowwind(path: str | os.PathLike) -> Inflow:
    """The wind of an InflowWind file (SI, rad)."""
    labels = Labels.read(path)
    kind = labels.int("WindType")
    if kind not in (1, 2, 3):
        what = WIND_TYPES.get(kind, "unknown")
        raise labels.error(f"WindType {kind} ({what} wind) is not modelled: bladefem reads steady wind (1), uniform "
                           "wind files (2) and TurbSim full fields (3)", labels.line("WindType"), "WindType")
    direction = math.radians(_within(labels, "PropagationDir", -MAX_DIRECTION_DEG, MAX_DIRECTION_DEG))
    upflow = math.radians(_within(labels, "VFlowAng", -MAX_UPFLOW_DEG, MAX_UPFLOW_DEG))
    if kind != 1:
        for label, value in (("PropagationDir", direction), ("VFlowAng", upflow)):
            if value:
                raise labels.error(f"must be 0 with WindType {kind} (a turned {WIND_TYPES[kind]} field is not "
                                   "modelled): give the angles in the wind file", labels.line(label), label)
    if kind == 2:
        return uniform_inflow(labels)
    if kind == 3:
        return grid_inflow(labels)
    return Inflow(speed=_within(labels, "HWindSpeed", 0.0, MAX_WIND_SPEED, required=True),
                  reference_height=labels.float("RefHt", positive=True),
                  shear_exponent=_within(labels, "PLExp", -MAX_SHEAR_EXPONENT, MAX_SHEAR_EXPONENT,
                                         required=True), direction=direction, upflow=upflow)


def uniform_inflow(labels: Labels) -> Inflow:
    """WindType 2: the table of ``FileName_Uni`` (degrees to rad), ``RefHt_Uni`` and ``RefLength``; the mean speed
    is the first row's (the operating point the run starts from)."""
    record = read_uniform_wind(labels.existing_file("FileName_Uni"))
    rows = record.rows.copy()
    for column, low, high, what in ((1, 0.0, MAX_WIND_SPEED, "speed"),
                                    (5, -MAX_SHEAR_EXPONENT, MAX_SHEAR_EXPONENT, "power-law exponent"),
                                    (8, -MAX_UPFLOW_DEG, MAX_UPFLOW_DEG, "upflow")):
        bad = np.flatnonzero((rows[:, column] < low) | (rows[:, column] > high))
        if bad.size:
            raise InputError(f"the {what} must lie between {low:g} and {high:g}, got {rows[bad[0], column]:g}",
                             record.path, record.lines[bad[0]], UNIFORM_FILE_COLUMNS[column])
    rows[:, 2] = np.radians(rows[:, 2])
    rows[:, 8] = np.radians(rows[:, 8])
    height = labels.float("RefHt_Uni", positive=True)
    table = UniformWind(table=rows, reference_height=height,
                        reference_length=labels.float("RefLength", positive=True))
    return Inflow(speed=float(rows[0, 1]), reference_height=height, shear_exponent=float(rows[0, 5]),
                  direction=float(rows[0, 2]), uniform=table)


def grid_inflow(labels: Labels) -> Inflow:
    """WindType 3: the TurbSim box of ``FileName_BTS`` (its mean speed at its hub height)."""
    box = read_turbsim(labels.existing_file("FileName_BTS", "Filename"))           # v4 and v5 spellings
    if box.mean_speed > MAX_WIND_SPEED:
        raise InputError(f"mean speed {box.mean_speed:g} m/s above {MAX_WIND_SPEED:g}",
                         str(labels.file("FileName_BTS", "Filename")), field="mean_speed")
    return Inflow(speed=box.mean_speed, reference_height=box.hub_height, grid=grid_of(box))


def grid_of(box: TurbSimBox) -> GridWind:
    """The full field a TurbSim box describes (its tower points are not used: the tower carries no aerodynamic
    loads here)."""
    return GridWind(velocity=box.velocity, dt=box.dt, dy=box.dy, dz=box.dz, z0=box.z0, mean_speed=box.mean_speed,
                    periodic=box.periodic)


def _within(labels: Labels, label: str, low: float, high: float, required: bool = False) -> float:
    """The value of ``label`` (0 when absent and not ``required``) within [low, high] (see :mod:`bladefem.limits`)."""
    if not required and not labels.has(label):
        return 0.0
    value = labels.float(label)
    if not low <= value <= high:
        raise labels.error(f"must lie between {low:g} and {high:g}, got {value:g}", labels.line(label), label)
    return value
