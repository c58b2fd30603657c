"""The shear-flexible (Timoshenko) beam of six-by-six sections against closed forms: the uniform cantilever's
frequency equation (solved here, independently of bladefem and of tests/uniform_beam_exact.py), the element's rate
of convergence, and the root conditions that hold the split of the deflection into bending and shear parts.

Frequency equation (uniform cantilever, one bending plane; Huang 1961, "The effect of rotatory inertia and of shear
deformation on the frequency and normal mode equations of uniform beams with simple end conditions"):
``EI psi'' + kGA (w' - psi) + J omega^2 psi = 0`` and ``kGA (w'' - psi') + m omega^2 w = 0`` for the deflection w
and the section rotation psi. Below the cut-off ``omega^2 = kGA / J`` the solutions are ``w = A1 cosh(a x) + A2
sinh(a x) + A3 cos(b x) + A4 sin(b x)``, ``psi = ca (A1 sinh + A2 cosh) + cb (A3 sin - A4 cos)`` with ``a^2`` and
``-b^2`` the roots of ``kGA EI s^2 + (kGA J + m EI) omega^2 s + m omega^2 (J omega^2 - kGA) = 0``,
``ca = (a^2 + m omega^2 / kGA) / a`` and ``cb = (m omega^2 / kGA - b^2) / b``; the clamped root (``w = psi = 0``)
and the free tip (``psi' = 0``, ``w' - psi = 0``) make a 4x4 determinant whose zeros are the frequencies.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from bladefem.assembly import assemble_blade
from bladefem.modal import modes
from bladefem.sections import Blade, FullSections, TipMass, mass_matrix, stiffness_matrix

L = 10.0
MASS = 50.0
EA, GJ = 1e10, 5e6
EI_FLAP, EI_EDGE = 1e7, 4e7
#: shear stiffnesses: 3 EI / (k GA L^2) = 0.03 in flap and 0.12 in edge (a thick, short beam: shear matters)
GA_NORMAL, GA_CHORD = 1e7, 1e7
I_FLAP, I_EDGE = 0.2, 0.8          # rotary inertias per length, kg m (int rho zeta^2, int rho eta^2)


def uniform_blade(shear: bool = True, root: str = "cantilever") -> Blade:
    K = stiffness_matrix(EA, GJ, EI_FLAP, EI_EDGE, GA_CHORD, GA_NORMAL)
    M = mass_matrix(MASS, flap_inertia=I_FLAP, edge_inertia=I_EDGE)
    return Blade(FullSections([0.0, L], [K, K], [M, M], shear_flexible=shear).table(), root=root)


def cantilever_determinant(omega: float, EI: float, kGA: float, m: float, J: float, length: float,
                           tip: float = 0.0) -> float:
    """The frequency equation's 4x4 determinant (module text), columns scaled to order one; with a point mass
    ``tip`` (kg) at the free end the shear condition is ``kGA (w' - psi) = omega^2 tip w``."""
    w2 = omega**2
    s = np.roots([kGA * EI, (kGA * J + m * EI) * w2, m * w2 * (J * w2 - kGA)])
    a, b = np.sqrt(np.max(s)), np.sqrt(-np.min(s))
    ca, cb = (a**2 + m * w2 / kGA) / a, (m * w2 / kGA - b**2) / b
    ch, sh, c, sn = np.cosh(a * length), np.sinh(a * length), np.cos(b * length), np.sin(b * length)
    A = np.array([[1.0, 0.0, 1.0, 0.0],
                  [0.0, ca, 0.0, -cb],
                  [ca * a * ch, ca * a * sh, cb * b * c, cb * b * sn],
                  [(a - ca) * sh, (a - ca) * ch, -(b + cb) * sn, (b + cb) * c]])
    A[3] -= w2 * tip / kGA * np.array([ch, sh, c, sn])
    return float(np.linalg.det(A / np.max(np.abs(A), axis=0)))


def cantilever_frequencies(EI: float, kGA: float, m: float, J: float, length: float, count: int,
                           tip: float = 0.0) -> np.ndarray:
    """The lowest ``count`` roots (rad/s) of the frequency equation, bracketed on a grid and refined by Brent."""
    top = 1.2 * (4 * count * np.pi / 2) ** 2 * np.sqrt(EI / (m * length**4))
    grid = np.linspace(top * 1e-3, top, 4000)
    values = [cantilever_determinant(w, EI, kGA, m, J, length, tip) for w in grid]
    roots = [brentq(cantilever_determinant, grid[i], grid[i + 1], args=(EI, kGA, m, J, length, tip), xtol=1e-14,
                    rtol=1e-15)
             for i in range(len(grid) - 1) if np.sign(values[i]) != np.sign(values[i + 1])]
    return np.array(roots[:count])


def test_the_frequency_equation_tends_to_euler_bernoulli():
    """The closed form's own check: with the shear 1e6 times stiffer and no rotary inertia its first root is the
    Euler-Bernoulli cantilever's 1.87510407^2 sqrt(EI / (m L^4)) (to 3 EI / (k GA L^2) = 3e-8)."""
    first = cantilever_frequencies(EI_FLAP, 1e6 * GA_NORMAL, MASS, 0.0, L, 1)[0]
    assert first == pytest.approx(1.87510407**2 * np.sqrt(EI_FLAP / (MASS * L**4)), rel=1e-7)


def test_uniform_cantilever_against_the_frequency_equation():
    """Flap 1-3 and edge 1-2 of the shear-flexible FE against the closed form to 2e-6 (the FE is refined until
    converged to 1e-6; measured 3e-10 to 9e-8). Shear and rotary inertia lower them by 2.3 % (flap 1) to 34 %
    (edge 2) from the Euler-Bernoulli beam, which the condensed sections give."""
    result = modes(uniform_blade(), 0.0, 8)
    exact = {"flap": cantilever_frequencies(EI_FLAP, GA_NORMAL, MASS, I_FLAP, L, 3),
             "edge": cantilever_frequencies(EI_EDGE, GA_CHORD, MASS, I_EDGE, L, 2)}
    for kind, values in exact.items():
        found = [m.frequency_hz for m in result.modes if m.kind == kind][:len(values)]
        assert 2 * np.pi * np.array(found) == pytest.approx(values, rel=2e-6), kind
    condensed = modes(uniform_blade(shear=False), 0.0, 8)
    flap_eb = [m.frequency_hz for m in condensed.modes if m.kind == "flap"][0]
    assert 2 * np.pi * flap_eb / exact["flap"][0] - 1 > 0.01


def test_tip_mass_moves_with_the_whole_deflection():
    """A point mass of half the beam's mass at the tip: its inertia acts on the deflection, bending plus shear
    (``kGA (w' - psi)(L) = omega^2 M w(L)``): flap 1-2 and edge 1 against the frequency equation with that end
    condition to 2e-6."""
    tip = 0.5 * MASS * L
    result = modes(uniform_blade().with_(tip_mass=TipMass(tip)), 0.0, 8)
    exact = {"flap": cantilever_frequencies(EI_FLAP, GA_NORMAL, MASS, I_FLAP, L, 2, tip),
             "edge": cantilever_frequencies(EI_EDGE, GA_CHORD, MASS, I_EDGE, L, 1, tip)}
    for kind, values in exact.items():
        found = [m.frequency_hz for m in result.modes if m.kind == kind][:len(values)]
        assert 2 * np.pi * np.array(found) == pytest.approx(values, rel=2e-6), kind


def test_convergence_rate_of_the_element():
    """On uniform meshes the frequency error of the third flap mode falls like h^4 (cubic bending, quadratic shear
    deflection: both carry their strain energy to order h^4): measured rates 3.86 and 3.96 between 4, 8 and 16
    elements."""
    exact = cantilever_frequencies(EI_FLAP, GA_NORMAL, MASS, I_FLAP, L, 3)[2]
    errors = []
    for n in (4, 8, 16):
        result = modes(uniform_blade(), 0.0, 8, elements=n)
        errors.append(2 * np.pi * [m.frequency_hz for m in result.modes if m.kind == "flap"][2] / exact - 1)
    assert all(e > 0 for e in errors)                   # a conforming element: from above
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all((rates > 3.7) & (rates < 4.3)), rates


@pytest.mark.parametrize("root", ["cantilever", "hinged", "axial-torsion", "free"])
def test_the_shear_deflection_is_held_at_the_root_under_every_condition(root):
    """A constant moved from the bending to the shear deflection changes no motion (zero mass, zero strain): every
    root condition holds the shear deflection's root value, so the mass matrix on the free DOFs stays positive
    definite; the shear-flexible beam has the shear fields, the condensed one not."""
    matrices = assemble_blade(uniform_blade(root=root), elements=6)
    assert {"v_s", "w_s"} <= set(matrices.dofs.fields)
    M = matrices.free_parts[2].toarray()
    assert np.min(np.linalg.eigvalsh(M)) > 0
    held = set(np.setdiff1d(np.arange(matrices.dofs.size), matrices.free))
    assert {int(matrices.dofs.value[name][0]) for name in ("v_s", "w_s")} <= held
    assert "v_s" not in assemble_blade(uniform_blade(shear=False, root=root), elements=6).dofs.fields
