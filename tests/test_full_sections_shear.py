"""What condensing the transverse shear leaves out, on real blade sections: a uniform cantilever made of one
IEA-15-240-RWT BeamDyn station (tests/data/iea15mw_sections), the blade's length (117 m) and a quarter of it,
bladefem's FE (shear condensed) against the exact Timoshenko beam with the whole six-by-six section
(tests/uniform_beam_exact.py). The figures are docs/THEORY.md's table; they bound the effect on the real blade from
above where the section is as thick as this one everywhere."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from uniform_beam_exact import natural_frequencies, timoshenko_frequencies, timoshenko_frequencies_near

from bladefem.builders.section_axes import from_beamdyn_axes
from bladefem.modal import modes
from bladefem.sections import Blade, FullSections

DATA = Path(__file__).resolve().parent / "data" / "iea15mw_sections" / "beamdyn_stations.txt"


def stations() -> dict[float, tuple[np.ndarray, np.ndarray]]:
    """eta -> (stiffness, mass) in bladefem's axes."""
    rows = [[float(v) for v in line.split()] for line in DATA.read_text().splitlines()
            if line.strip() and not line.startswith("#")]
    found = {}
    for i in range(0, len(rows), 13):
        K, M = np.array(rows[i + 1:i + 7]), np.array(rows[i + 7:i + 13])
        found[rows[i][0]] = (from_beamdyn_axes(0.5 * (K + K.T)), from_beamdyn_axes(M))
    return found


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
