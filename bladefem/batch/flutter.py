"""The ``flutter`` analysis of a batch plan: the blade's flutter onset (``bladefem flutter``) for each case, one row
per case.

    analysis: {type: flutter, aerodyn: AeroDyn.dat, rpm: [8, 32, 13], wind_speed_m_s: 0, pitch_deg: 0, blades: 3,
               n_modes: 6, elements: 40}
    analysis: {type: flutter, aerodyn: AeroDyn.dat, wind_speed_m_s: [120, 150, 31], rpm: 0, blades: 1}

Exactly one of ``rpm`` and ``wind_speed_m_s`` is a sweep [START, STOP, COUNT] (rpm, m/s); the other is one value
(default 0). A grid may vary ``pitch_deg``, the one that is not swept, and the section properties.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError

#: the plan schema's analysis properties that only this analysis has (``aerodyn`` is the standstill analysis's)
PROPERTIES: dict[str, Any] = {"blades": {"type": "integer", "minimum": 1, "maximum": 10}}
#: every result column of a flutter case (besides the inputs)
COLUMNS = ("swept", "onset", "onset_rpm", "onset_wind_speed_m_s", "onset_frequency_hz", "onset_mode", "flap_share",
           "edge_share", "torsion_share", "least_damping_ratio", "unconverged_roots")
SHARES = ("flap", "edge", "torsion")


def _sweep(value: Any, key: str, refuse: Callable[[str, str], InputError]) -> tuple[float, float, int] | None:
    """[START, STOP, COUNT] -> the sweep (START < STOP, 2 <= COUNT <= 1000, START >= 0); one value -> None."""
    if not isinstance(value, list):
        return None
    start, stop, count = value
    if not (0 <= start < stop and float(count).is_integer() and 2 <= count <= 1000):
        raise refuse(f"need 0 <= START < STOP and 2 <= COUNT <= 1000, got {value}", key)
    return float(start), float(stop), int(count)


def flutter_fields(entry: dict[str, Any], refuse: Callable[[str, str], InputError],
                   input_file: Callable[[str, tuple], Path]) -> dict[str, Any]:
    """The :class:`~bladefem.batch.plan.Analysis` fields of a flutter analysis entry; ``refuse(message, key)``
    makes the error at a key, ``input_file(name, where)`` checks and resolves a file the plan names."""
    for key in ("seconds", "dt", "statistics_from_s", "induction", "spec", "spec_model", "foundation",
                "elastodyn_blades", "quasi_steady", "yaw_deg", "azimuth_deg", "tilt_deg", "structural_damping_percent",
                "damping_only"):
        if key in entry:
            raise refuse("not an input of a flutter analysis", key)
    if "aerodyn" not in entry:
        raise refuse("a flutter analysis needs aerodyn (the AeroDyn primary file)", "type")
    rpm, wind = entry.get("rpm", 0.0), entry.get("wind_speed_m_s", 0.0)
    rpm_sweep, wind_sweep = _sweep(rpm, "rpm", refuse), _sweep(wind, "wind_speed_m_s", refuse)
    if (rpm_sweep is None) == (wind_sweep is None):
        raise refuse("sweep exactly one of rpm and wind_speed_m_s ([START, STOP, COUNT]); the other is one value",
                     "rpm" if rpm_sweep is not None else "type")
    if wind_sweep is not None and rpm > 0 and wind_sweep[0] == 0:
        raise refuse("a turning rotor's wind-speed sweep must start above 0 m/s (the BEM has no operating point "
                      "there with induction)", "wind_speed_m_s")
    return {"aerodyn": input_file(entry["aerodyn"], ("analysis", "aerodyn")),
            "rpm": 0.0 if rpm_sweep is not None else float(rpm), "sweep": rpm_sweep,
            "wind_speed": None if wind_sweep is not None else float(wind), "wind_sweep": wind_sweep,
            "pitch_deg": entry.get("pitch_deg"), "blades": int(entry.get("blades", 3)),
            "n_modes": int(entry.get("n_modes", 6)), "elements": entry.get("elements")}


def check_grid(analysis: Any, grid: dict[str, Any], refuse: Callable[[str], InputError]) -> None:
    """A grid varies the speed that is not swept, never the swept one; ``refuse(key)`` makes the error there."""
    swept = "rpm" if analysis.sweep is not None else "wind_speed_m_s"
    if swept in grid:
        raise refuse(swept)


def conditions(case: Any, pitch: float) -> list[Any]:
    """The case's operating points in sweep order (rotor speed in rad/s, pitch in rad)."""
    from ..models.flutter import OperatingCondition

    analysis = case.analysis
    if analysis.sweep is not None:
        rpm = np.linspace(*analysis.sweep[:2], analysis.sweep[2])
        wind = np.full_like(rpm, float(case.inputs.get("wind_speed_m_s", analysis.wind_speed)))
    else:
        wind = np.linspace(*analysis.wind_sweep[:2], analysis.wind_sweep[2])
        rpm = np.full_like(wind, float(case.inputs.get("rpm", analysis.rpm)))
    return [OperatingCondition(float(u), float(r) * math.pi / 30.0, pitch) for r, u in zip(rpm, wind)]


def rotor_of(analysis: Any, blade: Any) -> Any:
    """The case's rotor: the analysis's AeroDyn file on ``blade`` as the flutter sweep reads it."""
    from ..builders.flutter_inputs import flutter_rotor
    return flutter_rotor(analysis.aerodyn, blade, analysis.blades, False)[0]


def flutter_rows(case: Any, blade: Any) -> list[dict[str, Any]]:
    """One row: the swept speed (``rpm`` or ``wind_speed_m_s``), the onset (rpm, m/s, Hz, tracked mode, flap/edge/torsion shares; None where no mode's damping
    crosses zero), the least damping ratio of the converged roots over the sweep and the count of unconverged
    roots. The numbers of ``bladefem flutter`` on the case's blade."""
    from ..builders.flutter_inputs import flutter_rotor
    from ..models.flutter import flutter_sweep
    from .worker import blade_matrices_cached

    analysis = case.analysis
    if not hasattr(blade, "precone"):
        raise ValueError("a flutter analysis needs a blade")
    if analysis.pitch_deg is not None and "pitch_deg" not in case.inputs:
        blade = blade.with_(pitch=math.radians(analysis.pitch_deg))
    points = conditions(case, blade.pitch)
    rotor, centre, _ = flutter_rotor(analysis.aerodyn, blade, analysis.blades,
                                     all(c.wind_speed == 0.0 for c in points))
    matrices = blade_matrices_cached(case, blade, max(c.rpm for c in points))
    result = flutter_sweep(matrices, rotor, points, analysis.n_modes, centre)
    damping = [float(z) for p in result.points for z, ok in zip(p.damping_ratio, p.converged) if ok]
    row: dict[str, Any] = {
        "swept": "rpm" if analysis.sweep is not None else "wind_speed_m_s", "onset": result.onset is not None, "least_damping_ratio": min(damping) if damping else None,
        "unconverged_roots": sum(int((~p.converged).sum()) for p in result.points)}
    onset = result.onset
    row.update({"onset_rpm": None if onset is None else onset.rpm,
                "onset_wind_speed_m_s": None if onset is None else onset.wind_speed_m_s,
                "onset_frequency_hz": None if onset is None else onset.frequency_hz,
                "onset_mode": None if onset is None else onset.mode,
                **{f"{name}_share": None if onset is None else onset.shares[name] for name in SHARES}})
    return [row]
