"""The second-order kinematics of a turning section, checked against the exact energy of a rigid turn.

A blade or tower turned rigidly about its root has an exact centrifugal (or gravity) potential. Its second
derivative along the turn must equal the FE stiffness's quadratic form on the DOFs of that turn (Hermite and
quadratic elements hold linear and constant fields exactly). Euler-Bernoulli sections stay normal to the bent axis:
they bend (``Theta_b = (0, -w', v')``) and then twist about the bent axis, so the exact turn is
``expm([Theta_b]x) expm([phi e_x]x)``. A section rotation taken as the plain rotation vector ``(phi, -w', v')`` misses
half of the coupling of twist with the slopes through a centre-of-mass offset; that half is what moved CertTest 01's
rotating frequencies 0.15-0.2 % away from pybmodes (BModes' Hodges-Dowell kinematics have it). The exact energy is
computed from the section table's own columns, so the test also checks the section mass moments (the sign of the
inertia product J_yz enters the turns that combine both slopes).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import expm

from bladefem.assembly import assemble_blade
from bladefem.assembly.supports import rigid_motion
from bladefem.assembly.tower import assemble_tower
from bladefem.elements import skew
from bladefem.sections import Blade, SectionTable, TipMass
from bladefem.sections.tower import Foundation, Supports, TopMass, Tower

#: (w', phi, v') directions of the turns: each alone and in pairs (the pairs hold the couplings)
TURNS = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (0, 1, 1), (1, 0, 1)]
#: fourth-order central difference of the exact energy with step 1e-3: truncation ~1e-12 relative, round-off
#: ~1e-16 / 1e-6 = 1e-10 relative to the energy's size; 1e-8 leaves a margin of 100
RTOL = 1e-8


def gauss_points(sections: SectionTable, order: int = 12) -> tuple[np.ndarray, np.ndarray]:
    """Positions and weights integrating each station interval exactly for polynomials of degree < 2 order."""
    t, w = np.polynomial.legendre.leggauss(order)
    a, b = sections.span[:-1, None], sections.span[1:, None]
    return (0.5 * (a + b) + 0.5 * (b - a) * t).ravel(), (0.5 * (b - a) * w).ravel()


def second_derivative(energy_change, turn) -> float:
    """d^2/dt^2 at 0 of ``energy_change(D(t))``, the energy of the turned body less the unturned one, where
    ``D = R - 1`` and ``R(t)`` is the bend-then-twist turn along ``turn = (w', phi, v')``. Working with ``D`` (each
    factor's ``expm - 1`` is accurate to ~1e-16 absolutely) keeps round-off far below the small second-order
    energy."""
    slope_w, phi, slope_v = turn

    def deviation(t: float) -> np.ndarray:
        bend = expm(skew(t * np.array([0.0, -slope_w, slope_v]))) - np.eye(3)
        twist = expm(skew(t * np.array([phi, 0.0, 0.0]))) - np.eye(3)
        return bend @ twist + bend + twist
    h = 1e-3
    e = [energy_change(deviation(k * h)) if k else 0.0 for k in (-2, -1, 0, 1, 2)]
    return (-e[0] + 16 * e[1] - 30 * e[2] + 16 * e[3] - e[4]) / (12 * h * h)


def raw_moments(sections: SectionTable, x: np.ndarray, pitch: float = 0.0):
    """(m, S, J) per length from the table's own columns (not bladefem.sections.moments): the chord, toward the
    leading edge, is (cos t, -sin t) in (y, z), the thickness direction (sin t, cos t), t = twist + pitch; the
    centre of mass sits ``cm_offset`` along the chord; the inertias are about it."""
    t = sections.at(x, "twist") + pitch
    m, e = sections.at(x, "mass"), sections.at(x, "cm_offset")
    chord = np.stack([np.zeros_like(t), np.cos(t), -np.sin(t)])
    thick = np.stack([np.zeros_like(t), np.sin(t), np.cos(t)])
    S = m * e * chord
    J = (np.einsum("i...,j...->ij...", chord, chord) * (sections.at(x, "edge_inertia") + m * e**2)
         + np.einsum("i...,j...->ij...", thick, thick) * sections.at(x, "flap_inertia"))
    return m, S, J


def twisted_blade() -> Blade:
    sections = SectionTable(span=[0.0, 4.0, 10.0], mass=[30.0, 20.0, 10.0], flap_stiffness=1e6, edge_stiffness=4e6,
                            torsion_stiffness=2e5, axial_stiffness=1e9, twist=[0.4, 0.1, -0.2],
                            flap_inertia=[0.3, 0.2, 0.1], edge_inertia=[1.5, 1.0, 0.4], cm_offset=[0.2, -0.1, 0.15],
                            tension_centre_offset=[0.05, 0.0, 0.02])
    tip = TipMass(2.0, offset=[0.3, 0.2, -0.1], inertia=np.diag([0.2, 0.3, 0.4]))
    return Blade(sections, hub_radius=1.5, precone=0.1, pitch=0.05, tip_mass=tip, root="free")


def body_change(P: np.ndarray, D: np.ndarray, node: np.ndarray, arm: np.ndarray, m: float, S: np.ndarray,
                J: np.ndarray) -> float:
    """Change of int rho |P r|^2 of a body (m, S, J about its node) when ``R = 1 + D`` turns it about the root:
    the node at ``node + R arm``, its points at ``node + R (arm + s)``."""
    p0 = node + arm
    dp = D @ arm
    dPs = P @ D + D.T @ P + D.T @ P @ D                      # R^T P R - P
    return (m * (2 * p0 + dp) @ P @ dp + 2 * (dp @ P @ (S + D @ S) + p0 @ P @ D @ S)
            + np.trace(dPs @ J))


def centrifugal_energy(blade: Blade, D: np.ndarray) -> float:
    """Change of -1/2 int rho |P r|^2 per Omega^2 when the blade turns by ``1 + D`` about its root."""
    P = np.eye(3) - np.outer(blade.shaft_axis, blade.shaft_axis)
    x, w = gauss_points(blade.sections)
    m, S, J = raw_moments(blade.sections, x, blade.pitch)
    hub = np.array([blade.hub_radius, 0.0, 0.0])
    total = sum(w[i] * body_change(P, D, hub, np.array([x[i], 0.0, 0.0]), m[i], S[:, i], J[:, :, i])
                for i in range(len(x)))
    tip = blade.tip_mass
    total += body_change(P, D, hub, np.array([blade.length, 0.0, 0.0]), tip.mass, tip.mass * tip.offset,
                         tip.second_moment)
    return -0.5 * total


@pytest.mark.parametrize("turn", TURNS)
def test_rigid_turn_of_a_rotating_blade_is_exact(turn):
    blade = twisted_blade()
    matrices = assemble_blade(blade, 8)
    dofs = matrices.dofs
    slope_w, phi, slope_v = turn
    x = np.zeros(dofs.size)
    x[dofs.value["v"]], x[dofs.slope["v"]] = dofs.nodes * slope_v, slope_v
    x[dofs.value["w"]], x[dofs.slope["w"]] = dofs.nodes * slope_w, slope_w
    x[dofs.field_dofs["phi"]] = phi
    exact = second_derivative(lambda R: centrifugal_energy(blade, R), turn)
    assert x @ (matrices.K2 @ x) == pytest.approx(exact, rel=RTOL)


def leaning_tower() -> Tower:
    sections = SectionTable(span=[0.0, 30.0, 60.0], mass=[4000.0, 3000.0, 2000.0], flap_stiffness=[4e11, 2e11, 1e11],
                            edge_stiffness=[3e11, 2e11, 1e11], torsion_stiffness=3e11, axial_stiffness=5e11,
                            twist=[0.3, 0.1, 0.0], cm_offset=[0.1, 0.05, 0.2], flap_inertia=100.0,
                            edge_inertia=200.0)
    top = TopMass(2e5, offset=[1.5, 0.3, -0.5], inertia=np.diag([1e6, 2e6, 3e6]))
    return Tower(sections, top_mass=top, supports=Supports(foundation=Foundation(np.zeros((6, 6)))), gravity=9.81)


def gravity_energy(tower: Tower, D: np.ndarray) -> float:
    """Change of the potential g (mass x height of the mass centre) when the tower turns by ``1 + D`` about its
    base."""
    x, w = gauss_points(tower.sections)
    m, S, _ = raw_moments(tower.sections, x)
    total = sum(w[i] * (m[i] * x[i] * D[0, 0] + (D @ S[:, i])[0]) for i in range(len(x)))
    top = tower.top_mass
    total += top.mass * (D @ (np.array([tower.height, 0.0, 0.0]) + top.offset))[0]
    return tower.gravity * total


@pytest.mark.parametrize("turn", TURNS)
def test_rigid_turn_of_a_tower_under_gravity_is_exact(turn):
    # tower frame: x up, v side-side, w fore-aft; the same section kinematics as the blade's
    tower = leaning_tower()
    matrices = assemble_tower(tower, 8)
    slope_w, phi, slope_v = turn
    x = rigid_motion(matrices.dofs, 0.0) @ np.array([0.0, 0.0, 0.0, phi, -slope_w, slope_v])
    exact = second_derivative(lambda R: gravity_energy(tower, R), turn)
    assert x @ (matrices.K_gravity @ x) == pytest.approx(exact, rel=RTOL, abs=RTOL * 1e8)
