"""Rotating blade against published tables and exact relations (shared/reference/README.md items 4-7)."""

from __future__ import annotations

import numpy as np
import pytest

from bladefem.assembly import assemble_blade
from bladefem.modal import solve_modes
from bladefem.modal.solve import rpm_to_rad_s
from bladefem.sections import Blade, SectionTable, TipMass, uniform_sections

# omega sqrt(m L^4/EI) of the first three flap modes, R = 0 (Wright et al. 1982; Hodges and Rutkowski 1981)
ROTATING_TABLE = np.array([
    [0, 3.51602, 22.03449, 61.69721], [1, 3.68165, 22.18101, 61.84176], [2, 4.13732, 22.61492, 62.27318],
    [3, 4.79728, 23.32026, 62.98497], [4, 5.58500, 24.27335, 63.96676], [5, 6.44954, 25.44608, 65.20504],
    [6, 7.36037, 26.80908, 66.68391], [7, 8.29964, 28.33408, 68.38595], [8, 9.25684, 29.99538, 70.29296],
    [9, 10.22569, 31.77051, 72.38668], [10, 11.20233, 33.64037, 74.64929], [11, 12.18434, 35.58897, 77.06384],
    [12, 13.17015, 37.60311, 79.61448]])
SOUTHWELL = [1.193336, 6.478225, 17.85952]


def rpm_of(rotor_speed: float) -> float:
    """rpm for a rotor speed in rad/s (the solver's interface takes rpm)."""
    return rotor_speed * 30.0 / np.pi


def omegas(matrices, rotor_speed: float, kind: str, count: int, n_modes: int = 12) -> np.ndarray:
    result = solve_modes(matrices, rpm_of(rotor_speed), n_modes)
    return np.array([2 * np.pi * result.first(kind, n).frequency_hz for n in range(1, count + 1)])


@pytest.fixture(scope="module")
def uniform():
    return assemble_blade(Blade(uniform_sections(1.0, 1.0, 1.0, edge_stiffness=50.0)), elements=120)


@pytest.mark.parametrize("row", ROTATING_TABLE, ids=lambda row: f"lambda={row[0]:g}")
def test_rotating_flap_table(uniform, row):
    # the table is given to 6 significant digits: 1e-4 relative is within its rounding with margin
    np.testing.assert_allclose(omegas(uniform, row[0], "flap", 3), row[1:], rtol=1e-4)


def test_southwell_coefficients(uniform):
    # exact small-speed slope K in omega^2 = omega0^2 + K Omega^2 (reference item 7). By first-order perturbation
    # d(omega^2)/d(Omega^2) = x^T K2 x for M-normalised modes x at rest: the slope exactly, free of the cancellation
    # that a finite difference of nearly equal eigenvalues suffers.
    result = solve_modes(uniform, 0.0, 6)
    flap = [j for j, mode in enumerate(result.modes) if mode.kind == "flap"][:3]
    K2 = uniform.K2[uniform.free][:, uniform.free]
    vectors = result.vectors[:, flap]
    np.testing.assert_allclose(np.einsum("ij,ij->j", vectors, K2 @ vectors), SOUTHWELL, rtol=2e-6)


def tapered_blade(**blade_options) -> Blade:
    x = np.linspace(0.0, 30.0, 7)
    sections = SectionTable(span=x, mass=300.0 - 7.0 * x, flap_stiffness=2e9 * (1 - x / 40.0) ** 3,
                            edge_stiffness=2e9 * (1 - x / 40.0) ** 3)
    return Blade(sections, **blade_options)


@pytest.mark.parametrize("rpm", [5.0, 12.1, 20.0])
def test_lag_frequency_is_flap_minus_rotor_speed(rpm):
    # equal EI, no twist, no precone: omega_lag^2 = omega_flap^2 - Omega^2 exactly, for any m(x), EI(x), hub radius
    # and point tip mass (item 5); same matrices for both, so only round-off separates them
    blade = tapered_blade(hub_radius=2.0, tip_mass=TipMass(150.0))
    result = solve_modes(assemble_blade(blade, 40), rpm, 8)
    flap = [m.frequency_hz for m in result.modes if m.kind == "flap"][:3]
    edge = [m.frequency_hz for m in result.modes if m.kind == "edge"][:3]
    Omega = rpm_to_rad_s(rpm)
    np.testing.assert_allclose((2 * np.pi * np.array(edge)) ** 2,
                               (2 * np.pi * np.array(flap)) ** 2 - Omega**2, rtol=1e-8)


def test_rotating_torsion_relation():
    # omega_T^2 = omega_T0^2 + Omega^2 (k_m2^2 - k_m1^2) / k_m^2 (item 6) at zero pitch: the propeller moment
    i_flap, i_edge, GJ = 2.0e-4, 1.0e-3, 0.01
    blade = Blade(uniform_sections(1.0, 1.0, 1.0, torsion_stiffness=GJ, flap_inertia=i_flap, edge_inertia=i_edge))
    matrices = assemble_blade(blade, 100)
    omega0 = omegas(matrices, 0.0, "torsion", 2)
    # 100 quadratic elements: h^4 error ~ 1e-9 for the second mode
    np.testing.assert_allclose(omega0, np.array([1, 3]) * np.pi / 2 * np.sqrt(GJ / (i_flap + i_edge)), rtol=1e-8)
    for rotor_speed in (3.0, 10.0):
        expected = np.sqrt(omega0**2 + rotor_speed**2 * (i_edge - i_flap) / (i_edge + i_flap))
        np.testing.assert_allclose(omegas(matrices, rotor_speed, "torsion", 2), expected, rtol=1e-8)


def rigid_flap_moments(m: float, L: float, tip: float, tip_offset: float) -> tuple[float, float]:
    """First and second mass moments about the hinge of a uniform blade plus a tip point mass."""
    arm = L + tip_offset
    return m * L**2 / 2 + tip * arm, m * L**3 / 3 + tip * arm**2


@pytest.mark.parametrize("tip,tip_offset", [(0.0, 0.0), (40.0, 0.0), (40.0, 0.5)])
def test_hinged_blade_flaps_at_1P(tip, tip_offset):
    # a hinged blade at zero hub radius has a rigid flap mode at exactly 1P, however flexible it is (w = theta x
    # solves the equations, with the tip mass's own centrifugal force balancing its inertia at the tip): this fails
    # if the tip mass's centrifugal tension is left out, as BModes and pybmodes do. In plane the rigid mode is at 0.
    Omega = 1.3
    blade = Blade(uniform_sections(20.0, 10.0, 1e6), root="hinged",
                  tip_mass=TipMass(tip, offset=[tip_offset, 0.0, 0.0]) if tip else None)
    result = solve_modes(assemble_blade(blade, 20), rpm_of(Omega), 4)
    # eigenvalue round-off is about eps * ||K|| ~ 1e-16 * 12 EI / h^3 ~ 1e-9 in omega^2 (rad/s)^2
    assert (2 * np.pi * result.first("flap").frequency_hz) ** 2 == pytest.approx(Omega**2, abs=1e-8)
    assert (2 * np.pi * result.first("edge").frequency_hz) ** 2 == pytest.approx(0.0, abs=1e-8)


def rigid_rotation(matrices, field: str) -> np.ndarray:
    """The FE vector of a rigid rotation about the hinge (exactly representable by Hermite cubics)."""
    x = np.zeros(matrices.dofs.size)
    x[matrices.dofs.value[field]] = matrices.dofs.nodes
    x[matrices.dofs.slope[field]] = 1.0
    return x


@pytest.mark.parametrize("hub_radius,tip,tip_offset", [(3.0, 0.0, 0.0), (3.0, 40.0, 0.5), (7.5, 12.0, 0.0)])
def test_rigid_hinged_blade_with_hub_radius(hub_radius, tip, tip_offset):
    # rigid hinged blade with hinge offset R: omega^2 = Omega^2 (1 + R S1 / S2) out of plane and Omega^2 R S1 / S2
    # in plane (S1, S2 first and second mass moments about the hinge, tip mass and its axial offset included). The
    # Rayleigh quotient of the exact rigid rotation with K2 and M is that rigid-blade frequency, to round-off.
    m, L = 10.0, 20.0
    blade = Blade(uniform_sections(L, m, 1e6), hub_radius=hub_radius, root="hinged",
                  tip_mass=TipMass(tip, offset=[tip_offset, 0.0, 0.0]) if tip else None)
    matrices = assemble_blade(blade, 10)
    S1, S2 = rigid_flap_moments(m, L, tip, tip_offset)
    for field, expected in (("w", 1 + hub_radius * S1 / S2), ("v", hub_radius * S1 / S2)):
        x = rigid_rotation(matrices, field)
        assert (x @ matrices.K2 @ x) / (x @ matrices.M @ x) == pytest.approx(expected, rel=1e-12)
        assert x @ matrices.K0 @ x == pytest.approx(0.0, abs=1e-9 * abs(x @ matrices.K2 @ x))


@pytest.mark.parametrize("precone_deg", [-5.0, 2.5, 10.0])
def test_precone_rigid_flap(precone_deg):
    # rigid flapping of a hinged coned blade (R = 0) about the undeflected position: omega^2 = Omega^2 cos(2 beta);
    # the rigid lag mode is statically unstable there, omega^2 = -Omega^2 sin^2(beta) (reported as a negative
    # frequency), because the model is linearised about the undeflected, not the coned equilibrium
    Omega, beta = 1.0, np.radians(precone_deg)
    # w = theta x solves the equations exactly for any EI; EI = 1e5 keeps the elastic modes well above 1P while
    # the eigenvalue round-off (eps * ||K||) stays near 1e-10
    blade = Blade(uniform_sections(10.0, 5.0, 1e5), root="hinged", precone=beta)
    result = solve_modes(assemble_blade(blade, 10), rpm_of(Omega), 3)
    assert (2 * np.pi * result.first("flap").frequency_hz) ** 2 == pytest.approx(np.cos(2 * beta), rel=1e-8)
    lag = 2 * np.pi * result.first("edge").frequency_hz
    assert lag < 0
    assert -lag**2 == pytest.approx(-np.sin(beta) ** 2, abs=1e-8)


def test_pitch_rotates_flap_into_edge():
    # turning an untwisted blade by 90 degrees of pitch swaps the roles of flap and edge stiffness at rest
    blade = Blade(uniform_sections(1.0, 1.0, 1.0, edge_stiffness=9.0))
    at_zero = solve_modes(assemble_blade(blade, 30), 0.0, 2)
    at_ninety = solve_modes(assemble_blade(blade.with_(pitch=np.pi / 2), 30), 0.0, 2)
    assert at_zero.kinds == ["flap", "edge"] and at_ninety.kinds == ["edge", "flap"]
    np.testing.assert_allclose(at_zero.frequencies_hz, at_ninety.frequencies_hz, rtol=1e-9)
