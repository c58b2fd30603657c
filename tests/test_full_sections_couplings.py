"""Each coupling of a six-by-six section on its own, on a uniform cantilever (L = 10 m, EA 1e9 N, GJ 3e6 N m^2,
EI 1e7 flap and 2e7 N m^2 edge, k GA 4e8 N, 50 kg/m):

- static tip loads against closed forms: the FE's fields (Hermite cubic bending, quadratic twist and axial) hold
  these solutions exactly, so the tolerance is round-off (1e-9 relative, measured 1e-12 or better);
- natural frequencies against the exact solution of the beam's differential equations (tests/uniform_beam_exact.py,
  its own condensation, no FE), with the FE's h^4 convergence measured;
- turned principal axes against the Euler-Bernoulli closed form (the principal frequencies, mode planes turned);
- shear condensation against the Timoshenko closed form: what it leaves out, sized.
"""

from __future__ import annotations

import numpy as np
import pytest
from test_full_sections import (
    EA,
    EI_EDGE,
    EI_FLAP,
    GA,
    GJ,
    MASS,
    L,
    fe_frequencies,
    fe_tip_static,
    section,
    slice_mass,
    uniform_blade,
)
from uniform_beam_exact import natural_frequencies, tip_deflection

from bladefem.sections import mass_matrix, stiffness_matrix

#: beta_n L of the Euler-Bernoulli cantilever
BETA_L = np.array([1.8751040687119611, 4.6940911329741745, 7.8547574382376126])
F = 1.0e4


def test_static_tension_centre_offset():
    """Axial tip force at the reference axis, tension centre at eta_t: the force's moment about the tension centre
    bends the beam edgewise, v = F eta_t L^2 / (2 EI_edge), and u = F L (1 / EA + eta_t^2 / EI_edge)."""
    eta = 0.3
    tip = fe_tip_static(uniform_blade(section(tension_centre=(eta, 0.0)), slice_mass()), np.array([F, 0, 0, 0, 0, 0]))
    assert tip[1] == pytest.approx(F * eta * L**2 / (2 * EI_EDGE), rel=1e-9)
    assert tip[0] == pytest.approx(F * L * (1 / EA + eta**2 / EI_EDGE), rel=1e-9)
    assert abs(tip[2]) < 1e-12 and abs(tip[3]) < 1e-12


@pytest.mark.parametrize("pitch", [0.0, 0.2])
def test_static_turned_principal_axes(pitch):
    """Flapwise tip force, principal axes turned by alpha (and the section by a pitch): w = F L^3 / 3 (c^2 / EI_f +
    s^2 / EI_e), v = F L^3 / 3 s c (1 / EI_f - 1 / EI_e) with alpha the total angle."""
    alpha = 0.35
    blade = uniform_blade(section(principal_angle=alpha - pitch), slice_mass(), pitch=pitch)
    tip = fe_tip_static(blade, np.array([0, 0, F, 0, 0, 0]))
    c, s = np.cos(alpha), np.sin(alpha)
    assert tip[2] == pytest.approx(F * L**3 / 3 * (c**2 / EI_FLAP + s**2 / EI_EDGE), rel=1e-9)
    assert tip[1] == pytest.approx(F * L**3 / 3 * s * c * (1 / EI_FLAP - 1 / EI_EDGE), rel=1e-9)


def test_static_bend_twist():
    """Flapwise tip force with bend-twist coupling g = K[3, 4] (twist rate with flap curvature): w = F L^3 GJ /
    (3 det), phi = g F L^2 / (2 det), det = GJ EI_f - g^2 (the 2x2 compliance of twist and flap bending)."""
    g = 0.4 * np.sqrt(GJ * EI_FLAP)
    tip = fe_tip_static(uniform_blade(section(flap_twist=g), slice_mass()), np.array([0, 0, F, 0, 0, 0]))
    det = GJ * EI_FLAP - g**2
    assert tip[2] == pytest.approx(F * L**3 * GJ / (3 * det), rel=1e-9)
    assert tip[3] == pytest.approx(g * F * L**2 / (2 * det), rel=1e-9)


def test_static_extension_twist():
    """Axial tip force with extension-twist coupling k = K[0, 3]: u = F L GJ / det, phi = -k F L / det."""
    k = 0.3 * np.sqrt(EA * GJ)
    tip = fe_tip_static(uniform_blade(section(extension_twist=k), slice_mass()), np.array([F, 0, 0, 0, 0, 0]))
    det = EA * GJ - k**2
    assert tip[0] == pytest.approx(F * L * GJ / det, rel=1e-9)
    assert tip[3] == pytest.approx(-k * F * L / det, rel=1e-9)


def fully_coupled() -> np.ndarray:
    return section(tension_centre=(0.25, -0.08), principal_angle=0.2, shear_centre=(0.1, 0.03),
                   extension_twist=0.1 * np.sqrt(EA * GJ), flap_twist=0.3 * np.sqrt(GJ * EI_FLAP),
                   edge_twist=-0.2 * np.sqrt(GJ * EI_EDGE))


def test_static_every_coupling_against_the_integrated_compliance():
    """A fully populated section under every tip load component: the FE equals the classical beam's closed form
    (section compliance integrated along the span, shear left out) to round-off."""
    K = fully_coupled()
    blade = uniform_blade(K, slice_mass())
    for load in np.eye(6) * np.array([F, F, F, F * L, F * L, F * L]):
        fe = fe_tip_static(blade, load)
        exact = tip_deflection(K, L, load, shear=False)
        assert np.allclose(fe, exact, rtol=1e-9, atol=1e-12 * np.max(np.abs(exact))), load


def test_shear_condensation_against_timoshenko():
    """What condensing the shear leaves out, statically: a Timoshenko cantilever's tip deflection is F L^3 / (3 EI)
    + F L / (k GA); the FE has the first term, so it is short by 3 EI / (k GA L^2) of it: 7.5e-4 for this slender
    beam (L / r = 10 / 0.1), 1.9e-2 at a fifth of the length. With the shear centre off the axis the shear force
    twists the beam too (F e / GJ per length), which the classical model also leaves out."""
    K = section()
    blade = uniform_blade(K, slice_mass())
    load = np.array([0, 0, F, 0, 0, 0])
    timoshenko = tip_deflection(K, L, load, shear=True)
    assert timoshenko[2] == pytest.approx(F * L**3 / (3 * EI_FLAP) + F * L / GA, rel=1e-12)
    fe = fe_tip_static(blade, load)
    left_out = 1 - fe[2] / timoshenko[2]
    ratio = 3 * EI_FLAP / (GA * L**2)
    assert left_out == pytest.approx(ratio / (1 + ratio), rel=1e-9)
    assert ratio == pytest.approx(7.5e-4)
    offset = section(shear_centre=(0.1, 0.0))
    twisted = tip_deflection(offset, L, load, shear=True)
    # the force at the reference axis turns about the shear centre 0.1 m toward the leading edge: -F e L / GJ
    assert twisted[3] == pytest.approx(-F * 0.1 * L / GJ, rel=1e-12)
    assert fe_tip_static(uniform_blade(offset, slice_mass()), load)[3] == pytest.approx(0.0, abs=1e-15)


# --- natural frequencies ----------------------------------------------------------------------------------------

def test_turned_principal_axes_frequencies_and_mode_planes():
    """Principal axes turned by alpha: the frequencies are the principal beams' (beta_n L)^2 sqrt(EI / m) / L^2
    and the flapwise modes move along the turned thickness axis (v / w = tan alpha)."""
    alpha = 0.35
    K = stiffness_matrix(EA, GJ, EI_FLAP, EI_EDGE, GA, GA, principal_angle=alpha)
    omega, shapes = fe_frequencies(uniform_blade(K, slice_mass(polar=0.5)), 4)
    flap = BETA_L[:2] ** 2 / L**2 * np.sqrt(EI_FLAP / MASS)
    edge = BETA_L[:2] ** 2 / L**2 * np.sqrt(EI_EDGE / MASS)
    expected = np.sort(np.concatenate([flap, edge]))
    assert omega == pytest.approx(expected, rel=5e-7)        # 40 elements: measured 3.4e-9, 1.3e-7 (second modes)
    v, w = shapes[0].edge[-1], shapes[0].flap[-1]
    assert np.arctan2(v, w) % np.pi == pytest.approx(alpha, abs=1e-8)


def converges_to_the_exact(K: np.ndarray, M: np.ndarray, count: int, upper: float) -> np.ndarray:
    """The FE's relative frequency errors at 40 elements against the exact solution, after checking that they
    fall as h^4 for every mode from 20 elements (so the FE converges to the exact frequencies, not near them)."""
    exact = natural_frequencies(K, M, L, count, upper, samples=1500)
    assert len(exact) == count
    coarse, fine = (np.abs(fe_frequencies(uniform_blade(K, M), count, n)[0] / exact - 1) for n in (20, 40))
    assert np.log2(coarse / fine) == pytest.approx(np.full(count, 4.0), abs=0.15)
    return fine


def test_tension_centre_offset_frequencies():
    """Tension centre at (0.3, -0.1) m, 3 and 1 radii of gyration: extension couples with both bendings."""
    K = section(tension_centre=(0.3, -0.1))
    assert np.max(converges_to_the_exact(K, slice_mass(), 6, 400.0)) < 2e-6     # measured 1.0e-6 (flap 3)


def test_bend_twist_frequencies():
    """Bend-twist couplings of 0.4 sqrt(GJ EI_f) and -0.3 sqrt(GJ EI_e)."""
    K = section(flap_twist=0.4 * np.sqrt(GJ * EI_FLAP), edge_twist=-0.3 * np.sqrt(GJ * EI_EDGE))
    assert np.max(converges_to_the_exact(K, slice_mass(), 6, 300.0)) < 2e-6     # measured 1.0e-6 (flap 3)


def test_centre_of_mass_offset_frequencies():
    """Centre of mass at (0.3, 0.1) m with inertias and a product of inertia: bending-torsion inertial coupling
    (the Dunn/Banerjee coupled bending-torsion beam, here with both bendings and extension)."""
    M = mass_matrix(MASS, (0.3, 0.1), flap_inertia=0.5, edge_inertia=4.0, product_of_inertia=0.3)
    assert np.max(converges_to_the_exact(section(), M, 6, 300.0)) < 2e-6        # measured 9.4e-7


def test_every_coupling_frequencies():
    """Every stiffness coupling and the full mass together."""
    M = mass_matrix(MASS, (0.2, -0.05), flap_inertia=0.5, edge_inertia=4.0, product_of_inertia=0.3)
    assert np.max(converges_to_the_exact(fully_coupled(), M, 4, 200.0)) < 5e-7                 # measured 1.2e-7
