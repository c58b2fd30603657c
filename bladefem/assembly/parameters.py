"""Section parameters at the quadrature points: stiffness, inertia and centrifugal matrices of a blade."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..elements import SectionMotion, gyroscopic_inertia, projected_inertia, rotation_second_order
from ..sections import (
    AxisFrame,
    Blade,
    bending_stiffness,
    extension_bending_stiffness,
    mass_moments,
    shear_flexible_stiffness,
    torsion_stiffness,
    twist_coupling_stiffness,
)

#: Gauss-Legendre rule for the tension integrals (exact to degree 9 on each piece)
_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(5)


def plane_of_rotation(blade: Blade) -> NDArray:
    """Projection P = I - a a^T onto the plane of rotation (a: shaft axis in the blade frame)."""
    a = blade.shaft_axis
    return np.eye(3) - np.outer(a, a)


def _tension_density(blade: Blade, x: NDArray) -> NDArray:
    """Centrifugal force per length along the span axis per Omega^2, e_x^T P int rho r0 dA, N s^2/m^2 (a straight
    blade)."""
    P = plane_of_rotation(blade)
    moments = mass_moments(blade.sections, x, blade.pitch)
    r = blade.hub_radius + x
    return P[0, 0] * moments.m * r + np.einsum("j,j...->...", P[0], moments.S)


def axis_position(blade: Blade, frame: AxisFrame) -> NDArray:
    """The points of a curved reference axis from the rotor apex in the blade frame, m, shape (3, ...)."""
    position = frame.position.copy()
    position[0] += blade.hub_radius
    return position


def _load_density(blade: Blade, x: NDArray) -> NDArray:
    """Centrifugal force per length per Omega^2 on a curved axis, P int rho r0 dA in the blade frame (the sections'
    first moment turned from the local frame), N s^2/m^2, shape (3, ...)."""
    if not blade.curved:
        return np.stack([_tension_density(blade, x), *np.zeros((2,) + np.shape(x))])
    frame = blade.axis_frame(x)
    moments = mass_moments(blade.sections, x, blade.pitch)
    first = moments.m * axis_position(blade, frame) + np.einsum("ij...,j...->i...", frame.rotation, moments.S)
    return np.einsum("ij,j...->i...", plane_of_rotation(blade), first)


def tip_tension(blade: Blade) -> float:
    """The tip mass's own centrifugal force along the span axis per Omega^2, N s^2 (peer tools leave it out)."""
    if blade.tip_mass is None:
        return 0.0
    P = plane_of_rotation(blade)
    position = np.array([blade.tip_radius, 0.0, 0.0]) + blade.tip_mass.offset
    return float(blade.tip_mass.mass * P[0] @ position)


def tip_load(blade: Blade) -> NDArray:
    """The tip mass's centrifugal force per Omega^2 in the blade frame, N s^2 (its offset in the tip's local
    frame on a curved axis)."""
    if not blade.curved:
        return np.array([tip_tension(blade), 0.0, 0.0])
    if blade.tip_mass is None:
        return np.zeros(3)
    frame = blade.axis_frame(np.array(blade.length))
    position = axis_position(blade, frame) + frame.rotation @ blade.tip_mass.offset
    return blade.tip_mass.mass * plane_of_rotation(blade) @ position


def centrifugal_force(blade: Blade, x: NDArray) -> NDArray:
    """The centrifugal force of everything outboard of ``x`` per Omega^2 in the blade frame, N s^2, shape (3, ...):
    integrated from the tip piece by piece between stations, plus the tip mass."""
    x = np.asarray(x, dtype=float)
    stations = blade.sections.span

    def integral(a: NDArray, b: NDArray) -> NDArray:
        half = 0.5 * (b - a)
        xi = (0.5 * (a + b))[..., None] + half[..., None] * _GAUSS_X
        return half * np.sum(_load_density(blade, xi) * _GAUSS_W, axis=-1)

    per_interval = integral(stations[:-1], stations[1:])                         # (3, intervals)
    outboard = np.concatenate([np.cumsum(per_interval[:, ::-1], axis=1)[:, ::-1], np.zeros((3, 1))], axis=1)
    k = np.clip(np.searchsorted(stations, x, side="right"), 1, len(stations) - 1)
    return integral(x, stations[k]) + outboard[:, k] + tip_load(blade).reshape((3,) + (1,) * x.ndim)


def centrifugal_tension(blade: Blade, x: NDArray) -> NDArray:
    """Axial force N(x) per Omega^2 (N s^2) at span positions ``x``: the centrifugal force of everything outboard
    along the axis's tangent (:func:`centrifugal_force`)."""
    force = centrifugal_force(blade, x)
    frame = blade.axis_frame(np.asarray(x, dtype=float))
    return force[0] if frame is None else np.einsum("i...,i...->...", frame.rotation[:, 0], force)


def outboard_mass(blade: Blade, x: NDArray) -> NDArray:
    """The mass outboard of arc length ``x`` (m), kg: the sections' from ``x`` to the tip, piece by piece between
    stations, and the tip mass."""
    x = np.asarray(x, dtype=float)
    stations = blade.sections.span

    def integral(a: NDArray, b: NDArray) -> NDArray:
        half = 0.5 * (b - a)
        xi = (0.5 * (a + b))[..., None] + half[..., None] * _GAUSS_X
        return half * np.sum(mass_moments(blade.sections, xi).m * _GAUSS_W, axis=-1)

    per_interval = integral(stations[:-1], stations[1:])
    outboard = np.concatenate([np.cumsum(per_interval[::-1])[::-1], [0.0]])
    k = np.clip(np.searchsorted(stations, x, side="right"), 1, len(stations) - 1)
    tip = 0.0 if blade.tip_mass is None else blade.tip_mass.mass
    return integral(x, stations[k]) + outboard[k] + tip


def gravity_tension(blade: Blade, x: NDArray) -> NDArray:
    """Axial force N_g(x) of the blade's weight (N) at arc lengths ``x``: the weight of everything outboard along
    the axis's tangent, ``t . g M(x)`` (tension on a blade hanging down, compression on one standing up)."""
    g = blade.gravity_vector
    frame = blade.axis_frame(np.asarray(x, dtype=float))
    along = g[0] if frame is None else np.einsum("i...,i->...", frame.rotation[:, 0], g)
    return along * outboard_mass(blade, x)


@dataclass(frozen=True)
class SectionParameters:
    """Section matrices at quadrature points (trailing axes: elements, points)."""

    bending: NDArray | None          # (2, 2, ...) N m^2 (None for a shear-flexible beam: ``section`` holds it)
    extension_bending: NDArray | None  # (3, 3, ...) when the axial field is present
    torsion: NDArray | None          # GJ, N m^2, when the twist field is present
    inertia: NDArray                 # (6, 6, ...) mass matrix of the slice, kg/m .. kg m
    spin: NDArray                    # (6, 6, ...) spin-softening matrix per Omega^2
    rotation: NDArray                # (3, 3, ...) rotation-second-order matrix per Omega^2
    tension: NDArray                 # N(x) per Omega^2, N s^2
    gyroscopic: NDArray | None = None  # (6, 6, ...) skew Coriolis matrix per Omega, kg/m .. kg m (rotating beams)
    twist_coupling: NDArray | None = None  # (3, ...) phi' with (u', v'', w''), N m, N m^2 (six-by-six sections)
    section: NDArray | None = None   # (6, 6, ...) on (u', gamma_y, gamma_z, phi', v'', w'') (shear-flexible sections)
    curvature: NDArray | None = None  # (4, ...) K2, K3 (1/m) and their rates (1/m^2) of a curved reference axis
    static: SectionMotion | None = None  # the deflection under the centrifugal load per Omega^2 (curved axis)
    gravity_tension: NDArray | None = None  # N_g(x), N: the axial force of the blade's weight (gravity on)
    gravity_static: SectionMotion | None = None  # the deflection under the weight (a prestressed blade, gravity on)

    @property
    def strain_stiffness(self) -> NDArray:
        """The classical section stiffness on (u', v'', w'', phi'), shape (4, 4, ...) (Euler-Bernoulli beams)."""
        shape = np.shape(self.bending)[2:]
        C = np.zeros((4, 4) + shape)
        if self.extension_bending is None:
            C[1:3, 1:3] = self.bending
        else:
            C[:3, :3] = self.extension_bending
        if self.torsion is not None:
            C[3, 3] = self.torsion
        if self.twist_coupling is not None:
            C[3, :3] = C[:3, 3] = self.twist_coupling
        return C

    def stress(self, motion: SectionMotion) -> NDArray:
        """The section's axial force, bending moments and torque conjugate to (u', v'', w'', phi') under a motion,
        shape (4, ...): the classical stiffness on the classical strains, or the six-by-six on all six strains of a
        shear-flexible beam (its transverse shear strains included)."""
        if self.section is None:
            strains = np.stack([motion.u_x, motion.v_xx, motion.w_xx, motion.phi_x])
            return np.einsum("ij...,j...->i...", self.strain_stiffness, strains)
        stress = np.einsum("ij...,j...->i...", self.section, motion.strains)
        return stress[[0, 4, 5, 3]]


def section_parameters(blade: Blade, x: NDArray) -> SectionParameters:
    """Evaluate all section matrices of ``blade`` at span positions ``x`` (m; arc lengths on a curved axis, where
    the centrifugal and gyroscopic matrices take the plane of rotation, the shaft axis and the axis's position in
    each section's local frame)."""
    sections = blade.sections
    moments = mass_moments(sections, x, blade.pitch)
    frame = blade.axis_frame(np.asarray(x, dtype=float))
    Q, shaft, curvature = plane_of_rotation(blade), blade.shaft_axis, None
    node = np.zeros((3,) + np.shape(x))
    node[0] = blade.hub_radius + x
    if frame is not None:
        Q, shaft = frame.tensor_to_local(Q), frame.to_local(shaft)
        node = frame.to_local(axis_position(blade, frame))
        curvature = np.concatenate([frame.curvature, frame.curvature_rate])
    section = shear_flexible_stiffness(sections, x, blade.pitch)
    classical = section is None            # a shear-flexible beam's stiffness is all in ``section``
    return SectionParameters(
        bending=bending_stiffness(sections, x, blade.pitch) if classical else None,
        extension_bending=(extension_bending_stiffness(sections, x, blade.pitch)
                           if classical and sections.axial_stiffness is not None else None),
        torsion=torsion_stiffness(sections, x, blade.pitch) if classical else None,
        inertia=projected_inertia(np.eye(3), moments.m, moments.S, moments.J),
        spin=projected_inertia(Q, moments.m, moments.S, moments.J),
        rotation=rotation_second_order(Q, node, moments.S, moments.J),
        tension=centrifugal_tension(blade, x),
        gyroscopic=gyroscopic_inertia(shaft, moments.m, moments.S, moments.J),
        twist_coupling=twist_coupling_stiffness(sections, x, blade.pitch) if classical else None,
        curvature=curvature,
        section=section,
        gravity_tension=None if blade.gravity is None else gravity_tension(blade, x),
    )


@dataclass(frozen=True)
class AeroParameters:
    """Aerodynamic damping and stiffness of the sections per length on the kinematic vector, (6, 6, ...) at the
    quadrature points (:mod:`bladefem.models.blade_aero`)."""

    damping: NDArray
    stiffness: NDArray
