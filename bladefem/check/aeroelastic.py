"""The aeroelastic requirements of a check spec, on a blade model with an ``aerodyn`` file:

- ``standstill_damping``: the parked blade's least total damping ratio (structural + quasi-steady aerodynamic,
  :mod:`bladefem.models.standstill`) over a yaw range and the azimuths asked, per mode, at least ``min_percent``.

The flutter requirement is :mod:`bladefem.check.flutter`.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from ..errors import InputError
from ..sections import Blade
from .models import ModelRun
from .spec import Requirement

if TYPE_CHECKING:
    from ..models.standstill import StandstillResult
    from .evaluate import Outcome

DEFAULT_YAW_POINTS = 73


def blade_of(run: ModelRun, req: Requirement) -> Blade:
    """The model's blade with the requirement's pitch; a tower is refused at the requirement's line."""
    if not run.is_blade:
        raise req.error(f"applies to a blade model; '{run.spec.name}' is a tower")
    blade = run.structure
    pitch = req.parameters.get("pitch_deg")
    return blade if pitch is None else replace(blade, pitch=math.radians(pitch))


def standstill_result(run: ModelRun, req: Requirement) -> StandstillResult:
    """The parked-blade sweep a ``standstill_damping`` requirement asks for."""
    from ..builders.aerodyn_rotor import aerodyn_rotor
    from ..modal import blade_matrices
    from ..models.standstill import standstill_sweep, with_tilt

    p = req.parameters
    blade = blade_of(run, req)
    way = frozenset({"--quasi-steady"})
    try:
        rotor = aerodyn_rotor(run.spec.aerodyn, blade, run.spec.blades, way,
                              way if p.get("quasi_steady", False) else frozenset())
    except InputError as error:
        if "--quasi-steady" in error.message:
            raise req.error(error.message.split("; or --quasi-steady")[0] + " (or quasi_steady: true)",
                            "quasi_steady") from None
        raise
    rotor = with_tilt(rotor, math.radians(p.get("tilt_deg", 0.0)))
    start, stop = p.get("yaw_deg", [-180.0, 180.0])
    if stop < start:
        raise req.error(f"need start <= stop, got {[start, stop]}", "yaw_deg")
    yaws = np.linspace(start, stop, int(p.get("yaw_points", DEFAULT_YAW_POINTS)))
    azimuths = sorted(set(p.get("azimuth_deg", [0.0])))
    structural = dict(zip(("flap", "edge", "torsion"), (v / 100 for v in p.get("structural_damping_percent", []))))
    matrices = blade_matrices(blade, run.spec.elements, run.spec.n_modes, 0.0)
    return standstill_sweep(matrices, rotor, float(p["wind_speed_m_s"]), blade.pitch, yaws, azimuths,
                            run.spec.n_modes, structural, aero_stiffness=not p.get("damping_only", False))


def standstill_verdicts(run: ModelRun, req: Requirement) -> Iterator[Outcome]:
    """One outcome per mode: its least total damping ratio (%) over the sweep against ``min_percent``."""
    from .evaluate import Outcome

    p = req.parameters
    result = standstill_result(run, req)
    limit = float(p.get("min_percent", 0.0))
    names = p.get("modes", list(result.names))
    for name in names:
        if name not in result.names:
            raise req.error(f"no mode '{name}' among the parked blade's modes ({', '.join(result.names)}); raise "
                            "the model's n_modes", "modes")
        total = 100 * result.total(name)
        i, j = np.unravel_index(np.argmin(total), total.shape)
        least = float(total[i, j])
        sectors = "; ".join(f"azimuth {a:g} deg: yaw " + ", ".join(f"{s:.1f} to {e:.1f}" for s, e in spans)
                            for a, spans in ((a, result.negative_sectors(name, k))
                                             for k, a in enumerate(result.azimuth_deg)) if spans)
        detail = (f"least at yaw {result.yaw_deg[i]:g} deg, azimuth {result.azimuth_deg[j]:g} deg, "
                  f"{result.wind_speed:g} m/s, pitch {result.pitch_deg:g} deg"
                  + (f"; negative total damping at {sectors} deg" if sectors else ""))
        yield Outcome(req.name, f"{name} parked, yaw {result.yaw_deg[0]:g} to {result.yaw_deg[-1]:g} deg",
                      least >= limit, least, f">= {limit:g} %", least - limit, "%", detail)
