"""The ``flutter`` requirement of a check spec: no flutter onset below ``factor`` times the rated rotor speed.

The blade model's flutter sweep (:func:`bladefem.models.flutter.flutter_sweep`, six tracked modes) runs over
``points`` rotor speeds from rated to ``factor x rated`` at ``wind_speed`` (default 0: still air, no induction),
with the spec's AeroDyn primary file. The outcome's measured value is the onset's rotor speed over rated (the top of
the sweep when there is none); its margin is that ratio minus ``factor``.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from .evaluate import Outcome
from .models import ModelRun
from .spec import Requirement

DEFAULT_POINTS = 16
TRACKED_MODES = 6


def flutter_verdict(run: ModelRun, req: Requirement) -> Outcome:
    """The flutter margin of ``run``'s blade (module docstring)."""
    from ..builders.aerodyn_rotor import aerodyn_rotor
    from ..builders.flutter_inputs import REPLACED, chordwise_centre
    from ..modal import blade_matrices
    from ..models.flutter import OperatingCondition, flutter_sweep

    if not run.is_blade:
        raise req.error(f"applies to a blade model; '{run.spec.name}' is a tower")
    p = req.parameters
    blade, rated, factor = run.structure, float(p["rated_rpm"]), float(p["factor"])
    wind = float(p.get("wind_speed", 0.0))
    rotor = aerodyn_rotor(p["aero"], blade, run.spec.blades, replaced=REPLACED)
    if rotor.hub_radius + rotor.span[0] <= 0.0:
        raise req.error("the first AeroDyn node sits on the rotor axis: give the model's hub_radius_m", "aero")
    if wind == 0.0:
        rotor = replace(rotor, options=replace(rotor.options, induction=False))
    rpm = np.linspace(rated, factor * rated, int(p.get("points", DEFAULT_POINTS)))
    conditions = [OperatingCondition(wind, r * math.pi / 30, blade.pitch) for r in rpm]
    matrices = blade_matrices(blade, run.spec.elements, TRACKED_MODES, float(rpm[-1]))
    result = flutter_sweep(matrices, rotor, conditions, TRACKED_MODES, chordwise_centre(blade, rotor, []))
    onset = result.onset
    ratio = onset.rpm / rated if onset is not None else factor
    passed = onset is None
    if onset is None:
        detail = f"no onset from {rated:g} to {factor * rated:.4g} rpm at {wind:g} m/s"
    else:
        shares = ", ".join(f"{name} {share:.2f}" for name, share in onset.shares.items())
        detail = (f"mode {onset.mode} at {onset.rpm:.4g} rpm ({ratio:.3g} x rated), {onset.frequency_hz:.4g} Hz, "
                  f"{shares}; {wind:g} m/s")
    return Outcome(req.name, f"flutter onset >= {factor:g} x {rated:g} rpm", passed, ratio,
                   f">= {factor:g} x rated", ratio - factor, "x rated", detail)
