"""What condensing the transverse shear leaves out, on the IEA-15-240-RWT's BeamDyn sections
(tests/data/iea15mw_sections): uniform cantilevers of the blade's length (117 m) made of one station, against the
exact Timoshenko beam with the whole six-by-six section (tests/uniform_beam_exact.py), and the whole blade against
a Timoshenko finite-element reference (tests/timoshenko_reference.py). The figures are docs/THEORY.md's table."""

from __future__ import annotations

import numpy as np
import pytest
from iea15_beamdyn import iea15_sections
from timoshenko_reference import timoshenko_blade_frequencies
from uniform_beam_exact import natural_frequencies, timoshenko_frequencies, timoshenko_frequencies_near

from bladefem.builders.section_axes import from_beamdyn_axes
from bladefem.modal import modes
from bladefem.sections import Blade, FullSections

def stations() -> dict[float, tuple[np.ndarray, np.ndarray]]:
    """eta -> (stiffness, mass) of the blade's stations in bladefem's axes."""
    full = iea15_sections()
    return {round(float(x / full.span[-1]), 6): (K, M) for x, K, M in zip(full.span, full.stiffness, full.mass)}


def test_mid_span_section_shear_left_out():
    """Mid-span station (k GA_flap 1.2e8 N, EI_flap 4.9e9 N m^2), 117 m: bladefem's FE equals the condensed beam's
    exact frequencies (2e-6) and lies above the Timoshenko beam's by 0.76 % (first flap), 0.78 % (first edge),
    5.0 % (second flap); the first torsion 0.065 % below it (the shear-torsion coupling K16, K26 condensed into GJ).
    Shear flexibility of the shell is not small on a modern blade: 3 EI / (k GA L^2) = 9.2e-3 here."""
    K, M = stations()[0.5]
    length = 117.0
    condensed = natural_frequencies(K, M, length, 4, 12.0, samples=1500)
    timoshenko = timoshenko_frequencies(K, M, length, 4, 12.0)
    fe = 2 * np.pi * modes(Blade(FullSections([0.0, length], [K, K], [M, M]).table()), 0.0, 4,
                           elements=60).frequencies_hz
    assert fe == pytest.approx(condensed, rel=2e-6)
    left_out = fe / timoshenko - 1
    assert left_out == pytest.approx([0.00757, 0.00784, 0.0501, -0.00065], abs=2e-4)


def test_root_section_shear_left_out():
    """Root station (a near-circular tube: flap and edge within 5e-4 of each other), 117 m: each of the first two
    flap-edge pairs against the Timoshenko pair found on a fine grid around it: 0.38 % and 2.6 % above
    (3 EI / (k GA L^2) = 4.9e-3)."""
    K, M = stations()[0.0]
    length = 117.0
    fe = 2 * np.pi * modes(Blade(FullSections([0.0, length], [K, K], [M, M]).table()), 0.0, 4,
                           elements=60).frequencies_hz
    timoshenko = np.concatenate([timoshenko_frequencies_near(K, M, length, fe[i], 0.05, 1500) for i in (0, 2)])
    assert len(timoshenko) == 4
    assert fe / timoshenko - 1 == pytest.approx([0.00376, 0.00376, 0.0258, 0.0257], abs=2e-4)


def test_timoshenko_reference_tends_to_the_classical_beam():
    """The Timoshenko reference's own check. Scaling the shear rows and columns by s (``T K T``, ``T = diag(1, s,
    s, 1, 1, 1)``) leaves the condensed section as it is and divides the shear compliance by s^2: with s = 1000 the
    Timoshenko frequencies are the condensed beam's (computed by the other solver) to 1e-5 (measured 4.5e-6 on
    the second flap: the stiff limit's conditioning and the root's boundary layer), and the first flap shift
    falls with the shear compliance."""
    K, M = stations()[0.5]
    length = 117.0

    def shear_scaled(s: float) -> np.ndarray:
        T = np.diag([1.0, s, s, 1.0, 1.0, 1.0])
        return T @ K @ T

    condensed = natural_frequencies(K, M, length, 3, 6.0, samples=800)
    rigid = timoshenko_frequencies(shear_scaled(1e3), M, length, 3, 6.0, samples=800)
    assert np.max(np.abs(rigid / condensed - 1)) < 1e-5
    shifts = [1 - timoshenko_frequencies(shear_scaled(s), M, length, 1, 1.2, samples=400)[0] / condensed[0]
              for s in (1.0, np.sqrt(10), 10.0)]
    # measured 7.5e-3, 8.6e-4, 1.2e-4: the shear compliance's share (1 / s^2) and, at the clamped root, a boundary
    # layer of width sqrt(EI / k GA) whose share falls only like 1 / s (5e-7 left at s^2 = 1e6)
    assert shifts[0] > 6 * shifts[1] > 36 * shifts[2] > 0


def test_iea15_blade_shear_left_out():
    """The whole IEA-15-240-RWT BeamDyn blade (straight, parked, every coupling): bladefem's frequencies against a
    Timoshenko beam with the same six-by-six sections (tests/timoshenko_reference.py, converged to 5e-5 between
    40 and 80 elements). The reference with its shear 900 times stiffer gives bladefem's frequencies within 2e-4
    (the shear left in it and the stiff limit's conditioning), an independent check of the FE on the real blade;
    with the real shear bladefem is 2.2 % above on the first flap (0.517 against 0.506 Hz), 1.8 % on the first
    edge, 3.4-8.1 % on the second and third bending modes, 0.7 % on the first torsion."""
    full = iea15_sections()
    result = modes(Blade(full.table()), 0.0, 6)
    assert result.kinds == ["flap", "edge", "flap", "edge", "flap", "torsion"]
    fe = result.frequencies_hz
    T = np.diag([1.0, 30.0, 30.0, 1.0, 1.0, 1.0])
    stiff = timoshenko_blade_frequencies(full.span, T @ full.stiffness @ T, full.mass, full.twist, 6, 40)
    assert np.max(np.abs(stiff / fe - 1)) < 2e-4
    timoshenko = timoshenko_blade_frequencies(full.span, full.stiffness, full.mass, full.twist, 6, 40)
    assert fe / timoshenko - 1 == pytest.approx([0.0220, 0.0177, 0.0502, 0.0344, 0.0808, 0.0071], abs=5e-4)


def test_timoshenko_reference_against_the_exact_uniform_beam():
    """The Timoshenko finite-element reference on the uniform mid-span beam: the exact Timoshenko frequencies to
    2e-6 with 30 elements (measured 1.1e-6)."""
    K, M = stations()[0.5]
    length = 117.0
    exact = timoshenko_frequencies(K, M, length, 4, 12.0) / (2 * np.pi)
    reference = timoshenko_blade_frequencies(np.array([0.0, length]), np.array([K, K]), np.array([M, M]),
                                             np.zeros(2), 4, 30)
    assert np.max(np.abs(reference / exact - 1)) < 2e-6


def test_shear_flexible_fe_is_the_exact_timoshenko_beam_with_every_coupling():
    """The shear-flexible FE (the readers' default for six-by-six sections) on the mid-span station, whose section
    couples the shears with extension and twist (K16 and K26 about the reference axis) and every other strain:
    the exact Timoshenko beam's first four frequencies (tests/uniform_beam_exact.py, an independent solver of the
    whole 6x6 beam) to 2e-6."""
    K, M = stations()[0.5]
    length = 117.0
    sections = FullSections([0.0, length], [K, K], [M, M], shear_flexible=True)
    fe = 2 * np.pi * modes(Blade(sections.table()), 0.0, 4).frequencies_hz
    assert fe == pytest.approx(timoshenko_frequencies(K, M, length, 4, 12.0), rel=2e-6)


def test_shear_flexible_fe_on_the_iea15_blade_against_the_timoshenko_reference():
    """The whole IEA-15-240-RWT BeamDyn blade shear-flexible: the Timoshenko finite-element reference's first six
    frequencies (converged to 5e-5 at 40 elements) to 1e-4 (measured 3-5e-5), kinds in the same order."""
    full = iea15_sections()
    result = modes(Blade(full.with_shear(True).table()), 0.0, 6)
    assert result.kinds == ["flap", "edge", "flap", "edge", "flap", "torsion"]
    reference = timoshenko_blade_frequencies(full.span, full.stiffness, full.mass, full.twist, 6, 40)
    assert result.frequencies_hz == pytest.approx(reference, rel=1e-4)
