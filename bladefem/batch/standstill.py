"""The ``standstill`` analysis of a batch plan: the parked blade's damping against yaw (``bladefem standstill``) for
each case, one row per yaw misalignment, azimuth and mode.

    analysis: {type: standstill, aerodyn: AeroDyn.dat, wind_speed_m_s: 50, pitch_deg: 90, yaw_deg: [-180, 180, 73],
               azimuth_deg: [0], tilt_deg: 0, structural_damping_percent: [0.5, 0.5], quasi_steady: false,
               damping_only: false, n_modes: 6, elements: 40}

A grid may vary ``wind_speed_m_s`` and ``pitch_deg`` (and the section properties, as for the modal analyses).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError

_ANGLE = {"type": "number", "minimum": -360, "maximum": 360}
#: the plan schema's analysis properties that only this analysis has
PROPERTIES: dict[str, Any] = {
    "aerodyn": {"type": "string", "description": "AeroDyn primary file, relative to the plan"},
    "yaw_deg": {"type": "array", "items": _ANGLE, "minItems": 3, "maxItems": 3,
                "description": "yaw misalignments [START, STOP, COUNT], deg"},
    "azimuth_deg": {"type": "array", "items": _ANGLE, "minItems": 1},
    "tilt_deg": {"type": "number", "minimum": -45, "maximum": 45},
    "structural_damping_percent": {"type": "array", "items": {"type": "number", "minimum": 0, "maximum": 100},
                                   "minItems": 2, "maxItems": 3},
    "damping_only": {"type": "boolean"},
}
#: every key of a standstill analysis besides type, n_modes and elements
OWN = (*PROPERTIES, "wind_speed_m_s", "pitch_deg", "quasi_steady")
WAY = frozenset({"--quasi-steady"})


def standstill_fields(entry: dict[str, Any], refuse: Callable[[str, str], InputError],
                      input_file: Callable[[str, tuple], Path]) -> dict[str, Any]:
    """The :class:`~bladefem.batch.plan.Analysis` fields of a standstill analysis entry; ``refuse(message, key)``
    makes the error at a key, ``input_file(name, where)`` checks and resolves a file the plan names."""
    for key in ("seconds", "dt", "statistics_from_s", "induction", "spec", "spec_model", "rpm", "foundation",
                "elastodyn_blades"):
        if key in entry:
            raise refuse("not an input of a standstill analysis", key)
    for key in ("aerodyn", "wind_speed_m_s"):
        if key not in entry:
            raise refuse(f"a standstill analysis needs {key}", "type")
    start, stop, count = entry.get("yaw_deg", [-180.0, 180.0, 73])
    if not (start <= stop and float(count).is_integer() and 1 <= count <= 1000):
        raise refuse(f"need START <= STOP and 1 <= COUNT <= 1000, got {entry['yaw_deg']}", "yaw_deg")
    return {"aerodyn": input_file(entry["aerodyn"], ("analysis", "aerodyn")),
            "wind_speed": float(entry["wind_speed_m_s"]), "pitch_deg": entry.get("pitch_deg"),
            "yaw_sweep": (float(start), float(stop), int(count)),
            "azimuths": tuple(sorted({float(a) for a in entry.get("azimuth_deg", [0.0])})),
            "tilt_deg": float(entry.get("tilt_deg", 0.0)),
            "structural": tuple(float(v) for v in entry.get("structural_damping_percent", ())),
            "damping_only": bool(entry.get("damping_only", False)),
            "leave_out": ("--quasi-steady",) if entry.get("quasi_steady", False) else (),
            "n_modes": int(entry.get("n_modes", 6)), "elements": entry.get("elements")}


def rotor_of(analysis: Any, blade: Any) -> Any:
    """The case's rotor: the analysis's AeroDyn file on ``blade``, tilted."""
    from ..builders.aerodyn_rotor import aerodyn_rotor
    from ..models.standstill import with_tilt
    rotor = aerodyn_rotor(analysis.aerodyn, blade, 3, WAY, frozenset(analysis.leave_out))
    return with_tilt(rotor, math.radians(analysis.tilt_deg))


def standstill_rows(case: Any, blade: Any) -> list[dict[str, Any]]:
    """One row per (yaw, azimuth, mode): frequency (Hz), aerodynamic and total damping ratios."""
    from ..models.standstill import standstill_sweep
    from .worker import blade_matrices_cached

    analysis = case.analysis
    if not hasattr(blade, "precone"):
        raise ValueError("a standstill analysis needs a blade")
    if analysis.pitch_deg is not None and "pitch_deg" not in case.inputs:
        blade = blade.with_(pitch=math.radians(analysis.pitch_deg))
    wind_speed = float(case.inputs.get("wind_speed_m_s", analysis.wind_speed))
    start, stop, count = analysis.yaw_sweep
    structural = dict(zip(("flap", "edge", "torsion"), (v / 100 for v in analysis.structural)))
    matrices = blade_matrices_cached(case, blade, 0.0)
    result = standstill_sweep(matrices, rotor_of(analysis, blade), wind_speed, blade.pitch,
                              np.linspace(start, stop, count), analysis.azimuths, analysis.n_modes, structural,
                              aero_stiffness=not analysis.damping_only)
    return [{"wind_speed_m_s": wind_speed, "yaw_deg": p.yaw_deg, "azimuth_deg": p.azimuth_deg, "name": m.name,
             "frequency_hz": m.frequency_hz, "aerodynamic_damping_ratio": m.aerodynamic,
             "total_damping_ratio": m.total}
            for row in result.points for p in row for m in p.modes]
