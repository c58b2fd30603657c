"""A turbulent wind box for a case, made by pyconturb (a maintained generator of IEC 61400-1 turbulence).

The box is IEC 61400-1 (ed. 3) normal turbulence as pyconturb makes it by Veers' method: the Kaimal spectrum of each
component (length scales 8.1, 2.7, 0.66 Lambda_1, Lambda_1 = 0.7 min(z, 60 m)), the IEC exponential coherence of u
(L_c = 340.2 m; v and w uncorrelated between points), standard deviations sigma_u = I_ref (0.75 U + 5.6) for the
turbulence classes A, B, C (I_ref 0.16, 0.14, 0.12) or ``I U`` for a given turbulence intensity I, with sigma_v =
0.8 sigma_u and sigma_w = 0.5 sigma_u; the mean wind follows the power law ``U (z / z_hub)^alpha``. The square grid
is centred on the hub and spans the rotor with a margin; the box repeats in time (the inverse FFT of Veers' method
is periodic), so it is used as TurbSim's periodic files are (:mod:`bladefem.aero.wind`). The three components,
uncorrelated in IEC's model, are made one at a time (random keys ``3 key``, ``3 key + 1``, ``3 key + 2``): the
coherence factorisation per frequency is then of one component's points, not of all three together.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from .wind import GridWind

#: IEC 61400-1 reference turbulence intensities of the turbulence classes
IREF = {"A": 0.16, "B": 0.14, "C": 0.12}
#: sigma_v / sigma_u and sigma_w / sigma_u of IEC 61400-1's normal turbulence model
COMPONENT_RATIOS = (1.0, 0.8, 0.5)


@dataclass(frozen=True)
class TurbulenceSpec:
    """What a turbulent box is made of: mean speed at the hub (m/s), hub height (m), power-law exponent, IEC class
    (``"A"``, ``"B"``, ``"C"``) or turbulence intensity (fraction; one of the two), random key, duration (s), time
    step (s), points per side of the grid, grid width (m)."""

    speed: float
    hub_height: float
    shear_exponent: float
    duration: float
    width: float
    turbulence_class: str | None = None
    intensity: float | None = None
    key: int = 1
    dt: float = 0.25
    points: int = 9

    def sigma_u(self) -> float:
        """Standard deviation of u (m/s): I U, or IEC's normal turbulence model ``I_ref (0.75 U + 5.6)``."""
        if self.intensity is not None:
            return self.intensity * self.speed
        return IREF[self.turbulence_class] * (0.75 * self.speed + 5.6)


def turbulent_grid(spec: TurbulenceSpec) -> GridWind:
    """The box of ``spec`` as a periodic :class:`GridWind` (velocities including the mean profile)."""
    try:
        from pyconturb import gen_spat_grid, gen_turb
    except ImportError:
        from ..errors import InputError
        raise InputError("a turbulent box needs pyconturb: pip install 'bladefem[loads]'", field="--turbulence") \
            from None

    half = spec.width / 2
    y = np.linspace(-half, half, spec.points)
    z = np.linspace(spec.hub_height - half, spec.hub_height + half, spec.points)
    if z[0] <= 0:
        raise ValueError(f"a grid {spec.width:g} m high about a hub at {spec.hub_height:g} m reaches the ground")
    steps = max(int(math.ceil(spec.duration / spec.dt)), 2)
    sigma = spec.sigma_u()

    def sig_func(spat_df, **kwargs):
        k = spat_df.loc["k"].values.astype(int)
        return sigma * np.asarray(COMPONENT_RATIOS)[k]

    velocity = np.empty((steps, spec.points, spec.points, 3), dtype=np.float32)
    for component in range(3):                         # uncorrelated with each other in IEC's model: one at a time
        with warnings.catch_warnings():                # pyconturb's own pandas deprecations, not the user's concern
            warnings.simplefilter("ignore", DeprecationWarning)
            warnings.simplefilter("ignore", FutureWarning)
            frame = gen_turb(gen_spat_grid(y, z, comps=[component]), T=steps * spec.dt, nt=steps, u_ref=spec.speed,
                             z_ref=spec.hub_height, alpha=spec.shear_exponent, sig_func=sig_func,
                             seed=(3 * spec.key + component) % 2**32, nf_chunk=64, verbose=False, dtype=np.float64)
        velocity[..., component] = frame.to_numpy().reshape(steps, spec.points, spec.points)   # iy * nz + iz
    return GridWind(velocity=velocity, dt=spec.dt, dy=float(y[1] - y[0]), dz=float(z[1] - z[0]), z0=float(z[0]),
                    mean_speed=spec.speed, periodic=True)


def rotor_width(radius: float) -> float:
    """Grid width (m) for a rotor of ``radius`` (m): the disk and a tenth of it on each side (a margin for the
    blades' deflection and the rotor's lateral motion)."""
    return 2.2 * radius
