"""Weak forms of the rotating beam: one physical effect per function.

Each term maps a trial and a test :class:`~bladefem.elements.SectionMotion` and the section parameters at the
quadrature points (:class:`~bladefem.assembly.parameters.SectionParameters`) to the integrand of a bilinear form.
Stiffness terms proportional to Omega^2 are written per unit Omega^2 (they build K2).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from ..elements import SectionMotion
from .parameters import AeroParameters, SectionParameters


def quadratic(a: NDArray, G: NDArray, b: NDArray) -> NDArray:
    """a^T G b over the leading axes, keeping the trailing axes (broadcast: basis-function pairs, elements,
    quadrature points); G b first, which is cheaper than the three-operand product when a and b broadcast."""
    return np.einsum("i...,i...->...", a, np.einsum("ij...,j...->i...", G, b))


def bending_stiffness(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """EI about the tension centre, principal axes turned by twist and pitch: v''EIv'' coupled with w''."""
    return quadratic(test.curvatures, p.bending, trial.curvatures)


def extension_bending_stiffness(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """EA with the tension-centre offset coupling extension u' and the curvatures (replaces bending_stiffness)."""
    return quadratic(test.extension_curvatures, p.extension_bending, trial.extension_curvatures)


def torsion_stiffness(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """St-Venant torsion GJ phi' phi'."""
    return p.torsion * test.phi_x * trial.phi_x


def twist_coupling_stiffness(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """Extension-twist and bend-twist coupling of six-by-six sections: the twist rate phi' against (u', v'', w''),
    both ways (the off-diagonal row and column of the classical stiffness)."""
    g = p.twist_coupling
    return (test.phi_x * np.einsum("i...,i...->...", g, trial.extension_curvatures)
            + trial.phi_x * np.einsum("i...,i...->...", g, test.extension_curvatures))


def section_stiffness(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """The whole six-by-six section of a shear-flexible (Timoshenko) beam on the strains (u', gamma_y, gamma_z, phi',
    v'', w''): extension, both transverse shears, twist and both curvatures with every coupling (replaces the
    bending, torsion and twist-coupling terms)."""
    return quadratic(test.strains, p.section, trial.strains)


def inertia(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """Kinetic energy of the section slice: translation, centre-of-mass offset and rotary inertia."""
    return quadratic(test.kinematic, p.inertia, trial.kinematic)


def axial_force_stiffness(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """Geometric stiffness N(x) v'v' + N(x) w'w' of an axial force acting on the bending slopes: for a blade the
    centrifugal tension per Omega^2 (:func:`~bladefem.assembly.parameters.centrifugal_tension`)."""
    return p.tension * (test.v_x * trial.v_x + test.w_x * trial.w_x)


def axial_force_shear_stiffness(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """What the shear deflections add to :func:`axial_force_stiffness` (shear-flexible beams): the axial force acts
    on Reissner's second-order axial strain ``theta . r' - |theta|^2 / 2``, with the section rotation theta (the
    bending slopes) and the axis slope ``r' = theta + gamma``; its bilinear form is ``N (v'v' + v'v_s' + v_s'v')``
    and the same in flap, of which this is the part with the shear slopes."""
    return p.tension * (test.v_x * trial.v_s_x + test.v_s_x * trial.v_x + test.w_x * trial.w_s_x
                        + test.w_s_x * trial.w_x)


def gravity_axial_force_stiffness(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """The weight's geometric stiffness: :func:`axial_force_stiffness` with the axial force of gravity
    (:func:`~bladefem.assembly.parameters.gravity_tension`, N) in place of the centrifugal tension; it is in K0
    (it does not scale with Omega^2)."""
    return axial_force_stiffness(trial, test, replace(p, tension=p.gravity_tension))


def gravity_axial_force_shear_stiffness(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """What the shear deflections add to :func:`gravity_axial_force_stiffness` (shear-flexible beams)."""
    return axial_force_shear_stiffness(trial, test, replace(p, tension=p.gravity_tension))


def spin_softening(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """Centrifugal softening of motion in the plane of rotation: -int rho |P dr1|^2 (per Omega^2)."""
    return -quadratic(test.kinematic, p.spin, trial.kinematic)


def rotation_second_order(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """Centrifugal work on the second-order displacement of rotated section points (per Omega^2): the propeller
    moment in torsion and the centre-of-mass-offset coupling of twist with the bending slopes."""
    return -quadratic(test.rotation, p.rotation, trial.rotation)


def coriolis(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """Gyroscopic (Coriolis) coupling per Omega, skew: ``2 int rho dr1(test) . (a x dr1(trial))``. It couples
    edge with axial motion (cos beta) and, under precone, edge with flap (sin beta)."""
    return quadratic(test.kinematic, p.gyroscopic, trial.kinematic)


def second_order_strains(a: SectionMotion, b: SectionMotion) -> NDArray:
    """The symmetric bilinear form h(a, b) whose half on (q, q) is the second-order part of the strains
    (u', v'', w'', phi') of a section that bends and then twists about the bent axis (rotation vector ``Theta + 1/2
    Theta_b x Theta_t``, :mod:`bladefem.elements.rigid_slice`): the extension ``1/2 (Theta_2^2 + Theta_3^2)``,
    the curvatures turned by the twist ``phi w''`` and ``-phi v''``, the twist rate ``1/2 (w' v'' - v' w'')``."""
    return np.stack([a.v_x * b.v_x + a.w_x * b.w_x,
                     a.phi * b.w_xx + b.phi * a.w_xx,
                     -(a.phi * b.v_xx + b.phi * a.v_xx),
                     0.5 * (a.w_x * b.v_xx + b.w_x * a.v_xx - a.v_x * b.w_xx - b.v_x * a.w_xx)])


def moment_prestress_stiffness(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """Stiffness per Omega^2 of the static moments and torque under the centrifugal load (``p.static``, the
    deflection per Omega^2, through the section stiffness) on the second-order curvatures: the work that turns a
    prestressed section's bending into twist (the extension's share is :func:`axial_force_stiffness`)."""
    return np.einsum("i...,i...->...", p.stress(p.static)[1:], second_order_strains(test, trial)[1:])


def aerodynamic_damping(trial: SectionMotion, test: SectionMotion, p: AeroParameters) -> NDArray:
    """Quasi-steady aerodynamic damping of the sections, -d(load)/d(velocity) with the induction frozen (not
    symmetric)."""
    return quadratic(test.kinematic, p.damping, trial.kinematic)


def aerodynamic_stiffness(trial: SectionMotion, test: SectionMotion, p: AeroParameters) -> NDArray:
    """Quasi-steady aerodynamic stiffness of the sections, -d(load)/d(displacement): elastic twist changing the
    angle of attack, displaced points turning through other air (not symmetric)."""
    return quadratic(test.kinematic, p.stiffness, trial.kinematic)


def gravity_moment_prestress_stiffness(trial: SectionMotion, test: SectionMotion, p: SectionParameters) -> NDArray:
    """:func:`moment_prestress_stiffness` of the weight's static moments and torque (``p.gravity_static``, the
    deflection under the weight), in K0: on a horizontal blade the edgewise moment turns flap into twist (lateral
    buckling under the weight)."""
    return moment_prestress_stiffness(trial, test, replace(p, static=p.gravity_static))
