"""Section parameters at the quadrature points: stiffness, inertia and centrifugal matrices of a blade."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..elements import gyroscopic_inertia, projected_inertia, rotation_second_order
from ..sections import (
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
    """Centrifugal force per length along the span axis per Omega^2, e_x^T P int rho r0 dA, N s^2/m^2."""
    P = plane_of_rotation(blade)
    moments = mass_moments(blade.sections, x, blade.pitch)
    r = blade.hub_radius + x
    return P[0, 0] * moments.m * r + np.einsum("j,j...->...", P[0], moments.S)


def tip_tension(blade: Blade) -> float:
    """The tip mass's own centrifugal force along the span axis per Omega^2, N s^2 (peer tools leave it out)."""
    if blade.tip_mass is None:
        return 0.0
    P = plane_of_rotation(blade)
    position = np.array([blade.tip_radius, 0.0, 0.0]) + blade.tip_mass.offset
    return float(blade.tip_mass.mass * P[0] @ position)


def centrifugal_tension(blade: Blade, x: NDArray) -> NDArray:
    """Axial force N(x) per Omega^2 (N s^2) at span positions ``x``: the centrifugal force of everything outboard,
    integrated from the tip to ``x`` piece by piece between stations, plus the tip mass."""
    x = np.asarray(x, dtype=float)
    stations = blade.sections.span

    def integral(a: NDArray, b: NDArray) -> NDArray:
        half = 0.5 * (b - a)
        xi = (0.5 * (a + b))[..., None] + half[..., None] * _GAUSS_X
        return half * np.sum(_tension_density(blade, xi) * _GAUSS_W, axis=-1)

    per_interval = integral(stations[:-1], stations[1:])
    outboard = np.concatenate([np.cumsum(per_interval[::-1])[::-1], [0.0]])   # from each station to the tip
    k = np.clip(np.searchsorted(stations, x, side="right"), 1, len(stations) - 1)
    return integral(x, stations[k]) + outboard[k] + tip_tension(blade)


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


def section_parameters(blade: Blade, x: NDArray) -> SectionParameters:
    """Evaluate all section matrices of ``blade`` at span positions ``x`` (m)."""
    sections = blade.sections
    moments = mass_moments(sections, x, blade.pitch)
    P = plane_of_rotation(blade)
    node = np.zeros((3,) + np.shape(x))
    node[0] = blade.hub_radius + x
    section = shear_flexible_stiffness(sections, x, blade.pitch)
    classical = section is None            # a shear-flexible beam's stiffness is all in ``section``
    return SectionParameters(
        bending=bending_stiffness(sections, x, blade.pitch) if classical else None,
        extension_bending=(extension_bending_stiffness(sections, x, blade.pitch)
                           if classical and sections.axial_stiffness is not None else None),
        torsion=torsion_stiffness(sections, x, blade.pitch) if classical else None,
        inertia=projected_inertia(np.eye(3), moments.m, moments.S, moments.J),
        spin=projected_inertia(P, moments.m, moments.S, moments.J),
        rotation=rotation_second_order(P, node, moments.S, moments.J),
        tension=centrifugal_tension(blade, x),
        gyroscopic=gyroscopic_inertia(blade.shaft_axis, moments.m, moments.S, moments.J),
        twist_coupling=twist_coupling_stiffness(sections, x, blade.pitch) if classical else None,
        section=section,
    )


@dataclass(frozen=True)
class AeroParameters:
    """Aerodynamic damping and stiffness of the sections per length on the kinematic vector, (6, 6, ...) at the
    quadrature points (:mod:`bladefem.models.blade_aero`)."""

    damping: NDArray
    stiffness: NDArray
