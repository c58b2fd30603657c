"""Stall-induced vibration of a parked blade: the quasi-steady aerodynamic damping of each blade mode against the
direction of a steady wind (yaw misalignment and rotor azimuth), and the sectors where a mode's total damping
(structural plus aerodynamic) is negative.

The rotor stands still (no rotation, no induction: the inflow is the wind, as AeroDyn computes a parked rotor with
``WakeMod`` 0). Frames are the BEM's (:mod:`bladefem.aero.rotor`): wind along the inertial x, the nacelle yawed by
``yaw`` (ElastoDyn's ``NacYaw``, positive anticlockwise seen from above), shaft tilt and precone as ElastoDyn's,
blade 1 at ``azimuth`` (0 up). At each AeroDyn node the wind is resolved on the coned blade's out-of-plane normal
(``X``, downwind) and opposite to the direction of rotation (``Y``, from the leading edge); the component along
the pitch axis is left out (independence principle: a yawed section's loads are those of the flow in its own
plane). The section's state is then that of :class:`~bladefem.models.blade_aero.AeroOperatingPoint` with rotor
speed and induction zero, ``alpha = atan2(X, Y) - twist - pitch`` anywhere in -180..180 deg, and its damping and
stiffness are :func:`~bladefem.models.blade_aero.aero_matrices`: a negative lift slope (stall) makes the flapwise
damping ``(rho c W / 2) (cl' cos^2 phi + cd (1 + sin^2 phi) + (cl + cd') sin phi cos phi)`` negative.

Each point solves the quadratic eigenproblem of the blade with those matrices; modes are named after the undamped
modes of the blade (``flap 1``, ``edge 1``, ...) they match best (maximum total MAC). A mode's aerodynamic damping
ratio is that of the solve; its total adds the structural damping ratio of its kind (first order in the damping,
as the modal damping ratios of a lightly damped structure add). Not modelled: unsteady (dynamic-stall) aerodynamics,
the static deflection and gravity of the parked blade, the coupling through hub, tower and the other blades.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from ..aero.kinematics import rigid_rotor
from ..aero.polar import section_angle
from ..aero.rotor import Inflow, Rotor
from ..assembly import BladeMatrices
from ..modal.campbell import TRACKING_MARGIN, best_assignment, mac_from_products
from ..modal.quadratic import solve_quadratic_modes
from ..modal.results import ModalResult
from ..modal.solve import solve_modes
from ..sections import Blade
from .blade_aero import (
    AeroOperatingPoint,
    aero_matrices,
    aerodynamic_centres,
    on_the_axis,
    polar_slopes,
    shaft_axis,
)


@dataclass(frozen=True)
class StandstillMode:
    """One mode of the parked blade at one wind direction.

    name : the undamped mode it continues ('edge 1'); frequency_hz : undamped natural frequency |lambda| / 2 pi
    (negative for a real eigenvalue above zero: a divergence, the motion grows without oscillating)
    aerodynamic, structural, total : damping ratios (fractions of critical; a real eigenvalue gives -1 above zero,
    +1 below); mac : MAC with the undamped mode; shares : kinetic-energy shares of flap, edge, torsion and axial
    """

    name: str
    frequency_hz: float
    aerodynamic: float
    structural: float
    total: float
    mac: float
    shares: dict[str, float]

    @property
    def divergent(self) -> bool:
        """A real eigenvalue above zero: the motion grows without oscillating."""
        return self.frequency_hz < 0


@dataclass(frozen=True)
class StandstillPoint:
    """The modes at one yaw misalignment and azimuth (deg), and the angle-of-attack range along the blade (deg)."""

    yaw_deg: float
    azimuth_deg: float
    modes: tuple[StandstillMode, ...]
    alpha_deg: tuple[float, float]


@dataclass(frozen=True)
class StandstillResult:
    """A sweep over yaw misalignments (rows) and azimuths (columns): ``points[i][j]``; wind speed m/s, pitch deg."""

    wind_speed: float
    pitch_deg: float
    yaw_deg: NDArray
    azimuth_deg: NDArray
    names: tuple[str, ...]
    points: tuple[tuple[StandstillPoint, ...], ...]
    notes: tuple[str, ...] = ()

    def total(self, name: str) -> NDArray:
        """(yaw, azimuth) total damping ratios of the mode ``name``."""
        return np.array([[next(m.total for m in point.modes if m.name == name) for point in row]
                         for row in self.points])

    def minimum(self) -> tuple[float, StandstillMode, StandstillPoint]:
        """The smallest total damping ratio of the sweep, its mode and its point."""
        value, mode, point = min(((m.total, m, p) for row in self.points for p in row for m in p.modes),
                                 key=lambda item: item[0])
        return value, mode, point

    def negative_sectors(self, name: str, azimuth: int = 0) -> list[tuple[float, float]]:
        """Yaw intervals (deg) at the ``azimuth``-th azimuth where the mode's total damping is negative, their ends
        interpolated linearly between the sweep's points (an end of the sweep bounds an open sector)."""
        return negative_intervals(self.yaw_deg, self.total(name)[:, azimuth])


def negative_intervals(x: NDArray, y: NDArray) -> list[tuple[float, float]]:
    """Intervals of ``x`` (increasing) where ``y`` < 0, the crossings interpolated linearly."""
    sectors, start = [], None
    for k in range(len(x)):
        if y[k] < 0 and start is None:
            start = x[k] if k == 0 or y[k - 1] == y[k] else x[k - 1] + (x[k] - x[k - 1]) * y[k - 1] / (y[k - 1] - y[k])
        if y[k] >= 0 and start is not None:
            sectors.append((float(start), float(x[k - 1] + (x[k] - x[k - 1]) * y[k - 1] / (y[k - 1] - y[k]))))
            start = None
    if start is not None:
        sectors.append((float(start), float(x[-1])))
    return sectors


def parked_point(rotor: Rotor, wind_speed: float, yaw: float, azimuth: float, pitch: float,
                 blade: Blade | None = None) -> AeroOperatingPoint:
    """The sections of blade 1 of the parked ``rotor`` (its ``shaft_tilt`` and ``precone``) in a uniform wind of
    ``wind_speed`` (m/s) along the inertial x, nacelle yaw ``yaw``, rotor azimuth ``azimuth`` and pitch ``pitch``
    (rad): in-plane relative velocity, angle of attack and polars there; no rotation, no induction. The pitch
    turns the whole blade, a prebent blade's aerodynamic centres and its sections' cant with it, as AeroDyn
    places them (:func:`bladefem.aero.kinematics.rigid_rotor`), and ``theta`` carries what the pitched canted
    section's orientation adds to its twist and pitch. The aerodynamic centres' arms are taken from ``blade``'s
    reference axis (:func:`~bladefem.models.blade_aero.aerodynamic_centres`)."""
    height = rotor.hub_height if math.isfinite(rotor.hub_height) else 1.0
    kinematics = rigid_rotor(rotor, Inflow(wind_speed, height), 0.0, np.array([azimuth]), yaw, pitch)
    cant, toe = kinematics.cant[0, 0], kinematics.toe[0, 0]
    x, y = kinematics.vx[0, 0] * np.cos(cant), kinematics.vy[0, 0]
    # the inflow in the section's own plane (bladefem.aero.section.section_loads, no induction): the polar
    # projection's canted or toed section sees its own angle; the legacy projection's, atan2(vx, vy)
    inflow = np.vectorize(section_angle, otypes=[float])(np.arctan2(x, y), cant, toe)
    X, Y = np.hypot(x, y) * np.sin(inflow), np.hypot(x, y) * np.cos(inflow)
    theta = rotor.twist + pitch + kinematics.twist[0, 0]
    alpha = np.angle(np.exp(1j * (inflow - theta)))                     # wrapped into (-pi, pi]
    coefficients = np.array([rotor.polars[airfoil].coefficients(angle)
                             for angle, airfoil in zip(alpha, rotor.airfoil)])[:, :, 0].T
    slopes = polar_slopes(rotor, alpha)
    cm = coefficients[2] if rotor.options.pitching_moment else np.zeros_like(alpha)
    zero = np.zeros_like(alpha)
    return on_the_axis(AeroOperatingPoint(
        span=rotor.span, chord=rotor.chord, centre=aerodynamic_centres(rotor, pitch), X=X, Y=Y, theta=theta,
        alpha=alpha,
        cl=coefficients[0], cd=coefficients[1], cm=cm, dcl=slopes[0], dcd=slopes[1], dcm=slopes[2], a=zero,
        ap=zero, air_density=rotor.air_density, rotor_speed=0.0, shaft_axis=shaft_axis(rotor),
        wind_speed=wind_speed, pitch=pitch), rotor, blade)


def mode_names(result: ModalResult, pitch: float) -> tuple[str, ...]:
    """'flap 1', 'edge 1', 'flap 2', ...: each mode's kind and its number among the modes of that kind. Bending is
    named in the frame pitched by ``pitch`` (rad), where the chord of an untwisted section lies: flapwise is
    ``v sin(pitch) + w cos(pitch)``, edgewise ``v cos(pitch) - w sin(pitch)`` (so a feathered blade's flapwise mode,
    which moves in the rotor plane, is still 'flap'); torsion and axial modes keep their kind."""
    c, s = math.cos(pitch), math.sin(pitch)
    counts: dict[str, int] = {}
    names = []
    for mode in result.modes:
        kind = mode.kind
        if kind in ("flap", "edge"):
            shape = mode.shape
            flapwise = np.sum((shape.edge * s + shape.flap * c) ** 2)
            edgewise = np.sum((shape.edge * c - shape.flap * s) ** 2)
            kind = "flap" if flapwise >= edgewise else "edge"
        counts[kind] = counts.get(kind, 0) + 1
        names.append(f"{kind} {counts[kind]}")
    return tuple(names)


def standstill_sweep(matrices: BladeMatrices, rotor: Rotor, wind_speed: float, pitch: float,
                     yaw_deg: Sequence[float], azimuth_deg: Sequence[float], n_modes: int = 6,
                     structural: Mapping[str, float] | None = None, notes: tuple[str, ...] = (),
                     progress: Callable[[Iterable], Iterable] | None = None,
                     aero_stiffness: bool = True) -> StandstillResult:
    """The parked blade's modes at every (yaw, azimuth) in degrees, pitch ``pitch`` (rad, as the blade's
    structure is pitched). ``structural`` gives the structural damping ratio of each kind ('flap', 'edge',
    'torsion'; absent kinds: zero). ``aero_stiffness`` False leaves out the aerodynamic stiffness (the loads of
    the elastic twist), keeping the damping alone."""
    structural = dict(structural or {})
    reference = solve_modes(matrices, 0.0, n_modes)
    names = mode_names(reference, pitch)
    M = matrices.free_parts[2]
    weighted = M @ reference.vectors
    yaws, azimuths = np.asarray(yaw_deg, dtype=float), np.asarray(azimuth_deg, dtype=float)
    grid = [(y, a) for y in yaws for a in azimuths]
    points = []
    for yaw, azimuth in (progress or iter)(grid):
        op = parked_point(rotor, wind_speed, math.radians(yaw), math.radians(azimuth), pitch, matrices.blade)
        damping, stiffness = aero_matrices(matrices, op)
        result = solve_quadratic_modes(matrices, 0.0, n_modes + TRACKING_MARGIN, damping=damping,
                                       stiffness=stiffness if aero_stiffness else None, coriolis=False)
        mac = mac_from_products(reference.vectors, weighted, result.vectors, M @ result.vectors)
        rows, cols = best_assignment(mac)
        modes = []
        for row, col in sorted(zip(rows, cols)):
            mode = result.modes[col]
            extra = structural.get(names[row].split()[0], 0.0)
            modes.append(StandstillMode(names[row], mode.frequency_hz, float(mode.damping_ratio), extra,
                                        float(mode.damping_ratio) + extra, float(mac[row, col]),
                                        dict(mode.energy_fractions)))
        span = np.degrees(op.alpha)
        points.append(StandstillPoint(float(yaw), float(azimuth), tuple(modes), (float(span.min()),
                                                                               float(span.max()))))
    table = tuple(tuple(points[i * len(azimuths):(i + 1) * len(azimuths)]) for i in range(len(yaws)))
    return StandstillResult(wind_speed, math.degrees(pitch), yaws, azimuths, names, table, notes)


def with_tilt(rotor: Rotor, tilt: float) -> Rotor:
    """The rotor with shaft tilt ``tilt`` (rad, ElastoDyn's ShftTilt sign)."""
    return replace(rotor, shaft_tilt=tilt)
