"""Six-by-six sections (bladefem.sections.full_section) in the finite elements, one coupling at a time, against
closed forms: the section algebra by hand, static tip loads on a uniform cantilever (Hermite cubics and quadratic
twist and axial fields hold these solutions exactly, so the FE must reproduce them to round-off), and natural
frequencies against the exact solution of the uniform beam's differential equations (tests/uniform_beam_exact.py).
A section without couplings reproduces the column model (SectionTable) to round-off."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from uniform_beam_exact import natural_frequencies, tip_deflection

from bladefem.assembly.blade import assemble_blade
from bladefem.errors import InputError
from bladefem.builders.case import read_case
from bladefem.modal import modes
from bladefem.sections import (
    Blade,
    FullSections,
    SectionTable,
    full_sections_from_table,
    mass_matrix,
    stiffness_matrix,
)
from bladefem.sections.full_section import condensed

CASES = Path(__file__).resolve().parent.parent / "cases"
L = 10.0
EA, GJ, EI_FLAP, EI_EDGE, GA = 1e9, 3e6, 1e7, 2e7, 4e8
MASS = 50.0


def section(**couplings: object) -> np.ndarray:
    return stiffness_matrix(EA, GJ, EI_FLAP, EI_EDGE, GA, GA, **couplings)


def slice_mass(polar: float = 2.0, **kwargs: object) -> np.ndarray:
    """Section mass with no rotary inertia in bending unless asked, and a polar inertia (kg m)."""
    M = mass_matrix(MASS, **kwargs)
    M[3, 3] += polar
    return M


def uniform_blade(K: np.ndarray, M: np.ndarray, twist: float = 0.0, pitch: float = 0.0) -> Blade:
    return Blade(FullSections(span=[0.0, L], stiffness=[K, K], mass=[M, M], twist=twist).table(), pitch=pitch)


def fe_frequencies(blade: Blade, count: int, elements: int = 40) -> tuple[np.ndarray, list]:
    """Lowest natural frequencies (rad/s) and mode shapes of the parked blade (bladefem's modal solve: its
    Rayleigh-quotient refinement keeps the digits that a dense solve of the assembled matrices loses, 1e-7 at 40
    elements)."""
    result = modes(blade, 0.0, count, elements=elements)
    return 2 * np.pi * result.frequencies_hz, [mode.shape for mode in result.modes]


def fe_tip_static(blade: Blade, load: np.ndarray, elements: int = 8) -> np.ndarray:
    """Tip (u, v, w, phi, v', w') under a tip load (F_x, F_y, F_z, M_x, M_y, M_z) at the reference axis."""
    matrices = assemble_blade(blade, elements)
    T = matrices.dofs.kinematic_selector(len(matrices.dofs.nodes) - 1)
    force = T.T @ load
    K = matrices.free_parts[0].toarray()
    x = np.zeros(matrices.dofs.size)
    x[matrices.free] = np.linalg.solve(K, force[matrices.free])
    d = T @ x
    return np.array([d[0], d[1], d[2], d[3], d[5], -d[4]])


# --- the section algebra ---------------------------------------------------------------------------------------

def test_condensation_is_the_inverse_of_the_classical_compliance():
    rng = np.random.default_rng(7)
    A = rng.normal(size=(6, 6))
    K = A @ A.T + 6 * np.eye(6)
    C = condensed(K)
    assert np.allclose(C, np.linalg.inv(np.linalg.inv(K)[np.ix_([0, 3, 4, 5], [0, 3, 4, 5])]), rtol=1e-12)
    # a shear centre off the axis only couples shear and twist: condensed out, GJ is what remains
    assert np.allclose(condensed(section(shear_centre=(0.2, -0.1))), condensed(section()), rtol=1e-12)
    assert section(shear_centre=(0.2, -0.1))[3, 3] == pytest.approx(GJ + GA * (0.2**2 + 0.1**2))


def test_tension_centre_and_principal_axes_by_hand():
    eta, zeta, alpha = 0.3, -0.1, 0.25
    C = condensed(section(tension_centre=(eta, zeta)))
    # fibre strain eps + zeta kappa_eta - eta kappa_zeta at the tension centre: EA-weighted parallel axes
    assert C[0, 2] == pytest.approx(EA * zeta) and C[0, 3] == pytest.approx(-EA * eta)
    assert C[2, 2] == pytest.approx(EI_FLAP + EA * zeta**2) and C[3, 3] == pytest.approx(EI_EDGE + EA * eta**2)
    assert C[2, 3] == pytest.approx(-EA * eta * zeta)
    turned = condensed(section(principal_angle=alpha))[2:, 2:]
    c, s = np.cos(alpha), np.sin(alpha)
    assert turned[0, 0] == pytest.approx(EI_FLAP * c**2 + EI_EDGE * s**2)
    assert turned[0, 1] == pytest.approx((EI_EDGE - EI_FLAP) * s * c)
    assert np.allclose(np.linalg.eigvalsh(turned), [EI_FLAP, EI_EDGE], rtol=1e-12)
    summary = FullSections([0.0, L], [section(tension_centre=(eta, zeta))] * 2, [slice_mass()] * 2).summary()
    assert summary["tension_centre_offset"] == pytest.approx([eta, eta])
    assert summary["flap_stiffness"] == pytest.approx([EI_FLAP, EI_FLAP])


def test_mass_moments_in_the_blade_frame_by_hand():
    eta, zeta, i_flap, i_edge, i_product, theta = 0.4, 0.15, 3.0, 7.0, 0.8, 0.3
    M = mass_matrix(MASS, (eta, zeta), i_flap, i_edge, i_product)
    sections = FullSections([0.0, L], [section()] * 2, [M] * 2, twist=theta - 0.1)
    moments = sections.mass_moments(np.array([2.0]), pitch=0.1)
    c, s = np.cos(theta), np.sin(theta)
    e_eta, e_zeta = np.array([0.0, c, -s]), np.array([0.0, s, c])
    centre = eta * e_eta + zeta * e_zeta
    J = (i_edge * np.outer(e_eta, e_eta) + i_flap * np.outer(e_zeta, e_zeta)
         + i_product * (np.outer(e_eta, e_zeta) + np.outer(e_zeta, e_eta)) + MASS * np.outer(centre, centre))
    assert np.allclose(moments.S[:, 0], MASS * centre, rtol=1e-14, atol=1e-12)
    assert np.allclose(moments.J[:, :, 0], J, rtol=1e-14, atol=1e-12)
    # and the polar inertia is what the matrix holds: I_xx = J_yy + J_zz
    assert M[3, 3] == pytest.approx(i_flap + i_edge + MASS * (eta**2 + zeta**2))


def test_bad_matrices_are_refused_with_the_station():
    K = section()
    with pytest.raises(InputError, match="not symmetric.*station 2"):
        bad = K.copy()
        bad[0, 4] += 1e-3 * np.sqrt(K[0, 0] * K[4, 4])
        FullSections([0.0, L], [K, bad], [slice_mass()] * 2)
    with pytest.raises(InputError, match="not positive definite"):
        FullSections([0.0, L], [K, K - 2 * EA * np.outer(np.eye(6)[0], np.eye(6)[0])], [slice_mass()] * 2)
    with pytest.raises(InputError, match="section mass matrix"):
        bad = slice_mass()
        bad[0, 1] = bad[1, 0] = 1.0
        FullSections([0.0, L], [K, K], [slice_mass(), bad])


def test_a_column_changed_alone_is_refused():
    table = FullSections([0.0, L], [section(tension_centre=(0.2, 0.0))] * 2, [slice_mass()] * 2).table()
    with pytest.raises(InputError, match="change the matrices"):
        replace(table, tension_centre_offset=np.zeros(2))


# --- a diagonal section reproduces the column model -------------------------------------------------------------

@pytest.mark.parametrize("rpm,pitch_deg", [(0.0, 0.0), (12.1, 0.0), (12.1, 8.0)])
def test_nrel5mw_diagonal_sections_give_the_column_model(rpm, pitch_deg):
    """The NREL 5MW blade with GJ, EA and constant offsets (so that the columns' and the matrices' interpolation
    agree): matrices to round-off, frequencies to 1e-10 (measured 2.6e-11: the eigensolver's own tolerance)."""
    blade = read_case(CASES / "nrel5mw_blade.yaml")
    s = blade.sections
    table = replace(s, torsion_stiffness=0.2 * s.flap_stiffness, axial_stiffness=300.0 * s.flap_stiffness,
                    tension_centre_offset=0.1, cm_offset=-0.05, flap_inertia=0.002 * s.mass,
                    edge_inertia=0.01 * s.mass)
    columns = replace(blade, sections=table, pitch=np.radians(pitch_deg))
    full = replace(columns, sections=full_sections_from_table(table).table())
    a, b = assemble_blade(columns), assemble_blade(full)
    for name in ("K0", "K2", "M"):
        X, Y = getattr(a, name), getattr(b, name)
        assert abs(X - Y).max() <= 1e-14 * abs(X).max(), name
    fa, fb = (modes(x, rpm, 8).frequencies_hz for x in (columns, full))
    assert np.max(np.abs(fb / fa - 1)) < 1e-10


def test_uniform_case_diagonal_sections_give_the_column_model():
    blade = read_case(CASES / "uniform_blade.yaml")
    s = blade.sections
    assert s.torsion_stiffness is not None and s.axial_stiffness is None
    table = replace(s, axial_stiffness=500.0 * s.flap_stiffness)
    columns = replace(blade, sections=table)
    full = replace(columns, sections=full_sections_from_table(table).table())
    for rpm in (0.0, 60.0):
        fa, fb = (modes(x, rpm, 6).frequencies_hz for x in (columns, full))
        assert np.max(np.abs(fb / fa - 1)) < 1e-10


def test_turning_the_section_frame_changes_nothing():
    """The same sections written in a frame turned by beta (matrices Q^T K Q, twist + beta) are the same blade:
    every matrix, the gyroscopic one included, to round-off, rotating with hub radius, precone and pitch."""
    from bladefem.sections.full_section import frame_rotation

    K = stiffness_matrix(EA, GJ, EI_FLAP, EI_EDGE, GA, 0.5 * GA, tension_centre=(0.3, -0.1), principal_angle=0.2,
                         shear_centre=(0.1, 0.05), extension_twist=1e5, flap_twist=2e6, edge_twist=-1e6)
    M = mass_matrix(MASS, (0.3, 0.1), 0.5, 4.0, 0.3)
    beta = 0.7
    Q = np.zeros((6, 6))
    Q[:3, :3] = Q[3:, 3:] = frame_rotation(beta)
    geometry = dict(hub_radius=2.0, precone=np.radians(-3), pitch=0.1)
    blades = [Blade(FullSections([0.0, L], [k, 0.7 * k], [m, 0.8 * m], twist=[t + 0.4, t]).table(), **geometry)
              for k, m, t in [(K, M, 0.0), (Q.T @ K @ Q, Q.T @ M @ Q, beta)]]
    a, b = (assemble_blade(blade, 20) for blade in blades)
    for name in ("K0", "K2", "M", "G"):
        X, Y = getattr(a, name), getattr(b, name)
        assert abs(X - Y).max() <= 1e-13 * abs(X).max(), name


def test_scaling_six_by_six_sections():
    """Mass x k divides the frequencies by sqrt(k), stiffness x k multiplies them by sqrt(k) (SectionTable.scaled
    on the matrices); scaling flap or edge alone is refused (the matrices have no such split)."""
    table = FullSections([0.0, L], [section(tension_centre=(0.2, 0.1), flap_twist=1e6)] * 2,
                         [mass_matrix(MASS, (0.1, 0.05), 0.5, 4.0, 0.2)] * 2, twist=[0.3, 0.0]).table()
    base = modes(Blade(table), 0.0, 6, elements=30).frequencies_hz
    heavy = modes(Blade(table.scaled(mass=4.0)), 0.0, 6, elements=30).frequencies_hz
    stiff = modes(Blade(table.scaled(stiffness=4.0)), 0.0, 6, elements=30).frequencies_hz
    np.testing.assert_allclose(heavy, base / 2, rtol=1e-9)
    np.testing.assert_allclose(stiff, base * 2, rtol=1e-9)
    with pytest.raises(InputError, match="flap or edge alone"):
        table.scaled(flap_stiffness=2.0)
