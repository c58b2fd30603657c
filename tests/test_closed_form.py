"""FE against closed-form solutions: cantilever bending, torsion and axial rods, tip mass, h^4 convergence."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from bladefem.errors import InputError
from bladefem.modal import modes
from bladefem.sections import Blade, SectionTable, TipMass, uniform_sections

# roots of 1 + cos b cosh b = 0 (shared/reference/README.md, item 1)
CANTILEVER_B = np.array([1.87510407, 4.69409113, 7.85475744, 10.99554073, 14.13716839])


def omega(result, kind: str, count: int) -> np.ndarray:
    """Circular frequencies (rad/s) of the first ``count`` modes of a kind."""
    return np.array([2 * np.pi * result.first(kind, n).frequency_hz for n in range(1, count + 1)])


def test_uniform_cantilever_bending_five_modes():
    # m = EI = L = 1: omega_n = b_n^2. 400 elements: h^4 error ~ 1e-12 for mode 5, far below the 1e-6 asked.
    blade = Blade(uniform_sections(1.0, 1.0, 1.0, edge_stiffness=16.0))
    result = modes(blade, n_modes=12, elements=400)
    np.testing.assert_allclose(omega(result, "flap", 5), CANTILEVER_B**2, rtol=1e-6)
    np.testing.assert_allclose(omega(result, "edge", 2), 4 * CANTILEVER_B[:2] ** 2, rtol=1e-6)


def test_bending_converges_as_h4():
    # Hermite cubics: frequency error ~ h^4; fit the slope of log(error) against log(h) for modes 2 and 3
    blade = Blade(uniform_sections(1.0, 1.0, 1.0, edge_stiffness=100.0))
    counts = np.array([4, 8, 16, 32])
    for mode in (2, 3):
        errors = [abs(omega(modes(blade, n_modes=4, elements=n), "flap", mode)[-1] / CANTILEVER_B[mode - 1] ** 2 - 1)
                  for n in counts]
        slope = np.polyfit(np.log(1.0 / counts), np.log(errors), 1)[0]
        assert 3.5 < slope < 4.5, (mode, slope, errors)


def test_torsion_and_axial_rods():
    # clamped-free rods: omega_n = (2n-1) pi/2 sqrt(GJ/(I_p L^2)) and (2n-1) pi/2 sqrt(EA/(m L^2))
    GJ, i_flap, i_edge, EA, m, L = 2.0e5, 0.3, 0.7, 5.0e5, 2.0, 3.0   # torsion and axial modes interleave
    sections = SectionTable(span=[0.0, L], mass=m, flap_stiffness=1e9, edge_stiffness=1e9, torsion_stiffness=GJ,
                            axial_stiffness=EA, flap_inertia=i_flap, edge_inertia=i_edge)
    result = modes(Blade(sections), n_modes=8, elements=200)
    n = np.arange(1, 4)
    np.testing.assert_allclose(omega(result, "torsion", 3), (2 * n - 1) * np.pi / 2 * np.sqrt(GJ / (i_flap + i_edge))
                               / L, rtol=1e-8)
    np.testing.assert_allclose(omega(result, "axial", 3), (2 * n - 1) * np.pi / 2 * np.sqrt(EA / m) / L, rtol=1e-8)


def tip_mass_equation(b: float, mu: float) -> float:
    return 1 + np.cos(b) * np.cosh(b) + mu * b * (np.cos(b) * np.sinh(b) - np.sin(b) * np.cosh(b))


def test_cantilever_with_tip_mass():
    # reference README item 3: mu = 1 gives w = 1.557298, 16.25009, 50.89584 (roots of the frequency equation)
    blade = Blade(uniform_sections(1.0, 1.0, 1.0, edge_stiffness=100.0), tip_mass=TipMass(1.0))
    result = modes(blade, n_modes=4, elements=60)
    np.testing.assert_allclose(omega(result, "flap", 3), [1.557298, 16.25009, 50.89584], rtol=2e-6)
    roots = [brentq(tip_mass_equation, a, b, args=(1.0,), xtol=1e-14) for a, b in [(1.0, 1.5), (3.5, 4.5)]]
    # 60 elements: discretisation error ~1e-9 (h^4); the lowest eigenvalue's round-off is eps times the
    # condition number (~1e-16 * 60^4 * 1e3), so 1e-7 is the honest bound
    np.testing.assert_allclose(omega(result, "flap", 2), np.square(roots), rtol=1e-7)


def test_result_reports_small_residuals_and_pure_kinds():
    blade = Blade(uniform_sections(2.0, 3.0, 5.0, edge_stiffness=20.0, torsion_stiffness=7.0, flap_inertia=0.01,
                                   edge_inertia=0.02))
    result = modes(blade, n_modes=6, elements=40)
    assert max(mode.residual for mode in result.modes) < 1e-6
    for mode in result.modes:
        assert mode.energy_fractions[mode.kind] == pytest.approx(1.0, abs=1e-12)   # untwisted: fields decouple
        assert sum(mode.energy_fractions.values()) == pytest.approx(1.0)


def test_tension_centre_offset_equals_moving_the_axis():
    # a beam whose tension centre sits e off the reference axis (stiff EA, mass on the axis) is, at rest, the same
    # beam described about its tension centre with the mass offset by -e and no axial DOF: two independent routes
    # through the extension-bending coupling and the centre-of-mass terms. The stiff axial spring leaves a
    # difference of order EI / (EA L^2) = 2e-6; 1e-5 allows for it.
    e, L = 0.3, 10.0
    offset_tension = SectionTable(span=[0.0, L], mass=50.0, flap_stiffness=1e7, edge_stiffness=2e7, twist=0.2,
                                  axial_stiffness=1e11, tension_centre_offset=e)
    offset_mass = SectionTable(span=[0.0, L], mass=50.0, flap_stiffness=1e7, edge_stiffness=2e7, twist=0.2,
                               cm_offset=-e)
    a, b = modes(Blade(offset_tension), n_modes=4, elements=40), modes(Blade(offset_mass), n_modes=4, elements=40)
    np.testing.assert_allclose(a.frequencies_hz, b.frequencies_hz, rtol=1e-5)
    # and the offset matters: on the axis the edge modes are 0.2 % and 1.5 % higher
    on_axis = modes(Blade(SectionTable(span=[0.0, L], mass=50.0, flap_stiffness=1e7, edge_stiffness=2e7, twist=0.2)),
                    n_modes=4, elements=40)
    assert on_axis.frequencies_hz[1] > a.frequencies_hz[1] * 1.001


def test_tension_centre_offset_without_axial_stiffness_is_refused():
    with pytest.raises(InputError, match="tension-centre offset needs the axial stiffness"):
        SectionTable(span=[0.0, 1.0], mass=1.0, flap_stiffness=1.0, edge_stiffness=1.0, tension_centre_offset=0.1)
