"""Rigid-rotor inputs of the BEM: blade planform and polars, rotor geometry, steady wind.

Frames follow ElastoDyn and InflowWind: inertial x downwind (at zero wind direction), z up, y to the left looking
downwind. The shaft axis is x_s = (cos tilt cos yaw, cos tilt sin yaw, sin tilt) with ElastoDyn's ShftTilt sign
(the NREL 5MW's -5 deg lifts the upwind rotor end); the rotor turns positively about x_s (clockwise seen from
upwind); azimuth 0 is blade 1 pointing up. A blade coned by PreCone (negative: tips upwind) has its pitch axis
i3 = sin(precone) x_s + cos(precone) e_r and its out-of-plane normal i1 = cos(precone) x_s - sin(precone) e_r,
e_r the radial direction in the plane of rotation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from .dynamic_wake import DynamicWake
from .options import BEMOptions
from .polars import Polar
from .wind import GridWind, UniformWind, velocities, wind_arrays


@dataclass(frozen=True)
class Rotor:
    """Everything the BEM needs except the operating point (SI, rad); every blade alike.

    n_blades : number of blades
    hub_radius : rotor centre to blade root along the pitch axis (ElastoDyn HubRad), m
    span : blade nodes from the root along the pitch axis (AeroDyn BlSpn), m, increasing
    chord : m; twist : aerodynamic twist (BlTwist), rad, positive towards feather (reduces the angle of attack)
    airfoil : 0-based index into ``polars`` for each node (BlAFID - 1)
    polars : the airfoil tables
    curve, sweep : offsets of the aerodynamic centre from the pitch axis at zero pitch (BlCrvAC positive downwind,
        BlSwpAC positive opposite to the rotation), m; zero when not given
    curve_angle : the sections' cant from the pitch axis (BlCrvAng, positive toward downwind: the local slope of a
        prebent blade), rad; zero when not given
    precone : ElastoDyn PreCone, rad; shaft_tilt : ElastoDyn ShftTilt, rad
    hub_height : height of the rotor centre above the ground (for shear), m
    air_density : kg/m^3; kinematic_viscosity : m^2/s (kept for reference: the polars do not depend on Re)
    options : the BEM switches
    dynamic_wake : AeroDyn's dynamic wake (DBEMT_Mod 1-3, :mod:`bladefem.aero.dynamic_wake`) for time simulations,
        None for quasi-steady induction (steady and linear analyses are quasi-steady either way: the filters' rest
        state is the quasi-steady induction)
    notes : where the data came from
    """

    n_blades: int
    hub_radius: float
    span: NDArray[np.float64]
    chord: NDArray[np.float64]
    twist: NDArray[np.float64]
    airfoil: NDArray[np.int64]
    polars: tuple[Polar, ...]
    curve: NDArray[np.float64] | None = None
    sweep: NDArray[np.float64] | None = None
    curve_angle: NDArray[np.float64] | None = None
    precone: float = 0.0
    shaft_tilt: float = 0.0
    hub_height: float = math.nan
    air_density: float = 1.225
    kinematic_viscosity: float = 1.464e-5
    options: BEMOptions = field(default_factory=BEMOptions)
    notes: tuple[str, ...] = ()
    dynamic_wake: DynamicWake | None = None

    def __post_init__(self) -> None:
        n = len(self.span)
        for name in ("span", "chord", "twist", "curve", "sweep", "curve_angle"):
            value = getattr(self, name)
            value = np.zeros(n) if value is None else np.asarray(value, dtype=float)
            if value.shape != (n,):
                raise ValueError(f"{name} must have one value per node ({n}), got shape {value.shape}")
            object.__setattr__(self, name, value)
        object.__setattr__(self, "airfoil", np.asarray(self.airfoil, dtype=np.int64))
        if self.n_blades < 1:
            raise ValueError(f"n_blades must be at least 1, got {self.n_blades}")
        if n < 2 or np.any(np.diff(self.span) <= 0):
            raise ValueError("span needs at least two strictly increasing nodes")
        if np.any(self.chord <= 0):
            raise ValueError("chord must be positive")
        if self.airfoil.shape != (n,) or self.airfoil.min() < 0 or self.airfoil.max() >= len(self.polars):
            raise ValueError(f"airfoil indices must lie in 0..{len(self.polars) - 1}, one per node")

    @property
    def tip_radius(self) -> float:
        """Hub radius plus the last span node (ElastoDyn's TipRad for a matching AeroDyn blade), m."""
        return self.hub_radius + float(self.span[-1])


@dataclass(frozen=True)
class Inflow:
    """The wind: horizontal speed ``speed`` (m/s) at ``reference_height`` (m), power-law shear exponent, propagation
    direction (rad, positive turns the wind towards -y) and upflow angle (rad) of steady wind (InflowWind WindType
    1); with a ``uniform`` table (WindType 2) or a full-field ``grid`` (WindType 3, :mod:`bladefem.aero.wind`)
    the wind varies in time and space and ``speed`` is its mean at the reference height (the operating point the
    simulation starts from)."""

    speed: float
    reference_height: float
    shear_exponent: float = 0.0
    direction: float = 0.0
    upflow: float = 0.0
    uniform: UniformWind | None = field(default=None, compare=False, repr=False)
    grid: GridWind | None = field(default=None, compare=False, repr=False)

    @property
    def kind(self) -> str:
        return "grid" if self.grid is not None else "uniform" if self.uniform is not None else "steady"

    def arrays(self) -> tuple[NDArray, NDArray, NDArray]:
        """The arrays of :func:`bladefem.aero.wind.point_wind` for this wind."""
        return wind_arrays(self.speed, self.reference_height, self.shear_exponent, self.direction, self.upflow,
                           self.uniform, self.grid)

    def velocity_at(self, points: NDArray, t: float) -> NDArray:
        """Wind velocity (..., 3), m/s, at the inertial ``points`` (..., 3), m, and time t (s)."""
        if self.kind == "steady":
            return self.velocity(np.asarray(points)[..., 2])
        return velocities(points, t, self.arrays())

    def check_covers(self, hub_height: float, radius: float, duration: float) -> None:
        """Refuse (:class:`bladefem.errors.InputError`, field ``FileName_BTS``) a full-field grid that does not hold
        the rotor disk of ``radius`` (m) about ``hub_height`` (m) or runs out of wind before ``duration`` (s)."""
        grid = self.grid
        if grid is None:
            return
        from ..errors import InputError
        if radius > grid.half_width or hub_height - radius < grid.z0 or hub_height + radius > grid.top:
            raise InputError(f"the wind grid (y within +-{grid.half_width:g} m, z from {grid.z0:g} to {grid.top:g} m) "
                             f"does not hold the rotor disk ({radius:g} m about the hub at {hub_height:g} m)",
                             field="FileName_BTS")
        needed = duration + (grid.x_start + radius) / grid.mean_speed
        if not grid.periodic and needed > grid.time_span():
            raise InputError(f"the wind grid holds {grid.time_span():g} s of wind, a run of {duration:g} s reaches "
                             f"{needed:g} s into it (Taylor's frozen turbulence from half the grid width upwind)",
                             field="FileName_BTS")

    def velocity(self, height: NDArray) -> NDArray:
        """Wind velocity (..., 3) at the heights ``height`` (m above ground): V (z / RefHt)^PLExp along the
        propagation direction; zero at and below the ground."""
        height = np.asarray(height, dtype=float)
        ratio = np.where(height > 0, height, 0.0) / self.reference_height
        speed = self.speed * ratio ** self.shear_exponent if self.shear_exponent else np.full(height.shape,
                                                                                               self.speed)
        direction = np.array([math.cos(self.upflow) * math.cos(self.direction),
                              -math.cos(self.upflow) * math.sin(self.direction), math.sin(self.upflow)])
        return speed[..., None] * direction
