"""The turbulent box made for a case (pyconturb, Veers' method) against IEC 61400-1's normal turbulence model in
closed form: the mean power-law profile at every point, the standard deviations sigma_u = I_ref (0.75 U + 5.6),
0.8 and 0.5 of it for v and w (or I U), and the Kaimal spectrum with IEC's length scales, frequency by frequency.

Veers' method gives every point the spectrum's amplitudes with random phases; points whose rows of the coherence
factor are a unit vector (v and w, uncorrelated in IEC's model, and the first u point) carry them exactly, so their
periodograms are the discretized Kaimal spectrum to rounding and their variances sigma^2 exactly (pyconturb scales
with the n / (n - 1) of the sample variance); other u points mix random phases and match only on average.
"""

from __future__ import annotations

import numpy as np
import pytest

from bladefem.aero.turbulence import TurbulenceSpec, turbulent_grid

pytest.importorskip("pyconturb")
SPEC = TurbulenceSpec(speed=11.4, hub_height=90.0, shear_exponent=0.2, duration=120.0, width=140.0,
                      turbulence_class="B", key=7, dt=0.25, points=5)


@pytest.fixture(scope="module")
def box():
    return turbulent_grid(SPEC)


def kaimal(f, sigma, z, component, speed):
    """IEC 61400-1 ed. 3 Kaimal spectrum (one-sided, m^2/s^2/Hz): L_k = (8.1, 2.7, 0.66) Lambda_1,
    Lambda_1 = 0.7 min(z, 60 m)."""
    length = (8.1, 2.7, 0.66)[component] * 0.7 * min(z, 60.0)
    return 4 * sigma**2 * length / speed / (1 + 6 * f * length / speed) ** (5 / 3)


def test_mean_profile_is_the_power_law(box):
    heights = box.z0 + box.dz * np.arange(5)
    expected = SPEC.speed * (heights / SPEC.hub_height) ** SPEC.shear_exponent
    np.testing.assert_allclose(box.velocity[..., 0].mean(axis=0), np.broadcast_to(expected, (5, 5)), rtol=1e-5)
    np.testing.assert_allclose(box.velocity[..., 1:].mean(axis=0), 0.0, atol=1e-5)


def test_standard_deviations_are_iecs(box):
    sigma = 0.14 * (0.75 * 11.4 + 5.6)
    assert SPEC.sigma_u() == pytest.approx(sigma)
    v = box.velocity.astype(float)
    assert v[:, 0, 0, 0].std(ddof=1) == pytest.approx(sigma, rel=1e-5)
    np.testing.assert_allclose(v[..., 1].std(axis=0, ddof=1), 0.8 * sigma, rtol=1e-5)
    np.testing.assert_allclose(v[..., 2].std(axis=0, ddof=1), 0.5 * sigma, rtol=1e-5)
    assert TurbulenceSpec(10.0, 90.0, 0.0, 60.0, 100.0, intensity=0.12).sigma_u() == pytest.approx(1.2)


@pytest.mark.parametrize("point, component", [((0, 0), 0), ((2, 2), 1), ((2, 2), 2), ((1, 0), 1), ((4, 4), 2)])
def test_spectrum_is_kaimal_frequency_by_frequency(box, point, component):
    """The periodogram over the resolved frequencies k / T is the closed-form Kaimal spectrum times one factor
    (pyconturb's scaling to the exact variance), at every frequency, for z below and above 60 m."""
    series = box.velocity[:, point[0], point[1], component].astype(float)
    n = len(series)
    f = np.fft.rfftfreq(n, SPEC.dt)[1:-1]
    periodogram = np.abs(np.fft.rfft(series - series.mean())[1:-1]) ** 2
    z = box.z0 + box.dz * point[1]
    ratio = periodogram / kaimal(f, 1.0, z, component, SPEC.speed)
    np.testing.assert_allclose(ratio, ratio.mean(), rtol=1e-4)


def test_one_key_one_box_and_another_key_another():
    small = TurbulenceSpec(8.0, 90.0, 0.1, 20.0, 100.0, turbulence_class="A", key=1, points=3)
    first, again = turbulent_grid(small), turbulent_grid(small)
    other = turbulent_grid(TurbulenceSpec(8.0, 90.0, 0.1, 20.0, 100.0, turbulence_class="A", key=2, points=3))
    assert np.array_equal(first.velocity, again.velocity)
    assert not np.allclose(first.velocity, other.velocity)
    assert first.periodic and first.x_start == 0.0


def test_a_run_in_a_box_made_for_it(tmp_path):
    """``--turbulence B`` on the shipped deck: the run ends 0, writes its table and the box as a TurbSim file that
    reads back with IEC class B's sigma_u at its corner point (the one point Veers' method gives exact amplitudes)."""
    pytest.importorskip("numba")
    import contextlib
    import io
    from pathlib import Path

    from bladefem.cli import main
    from bladefem.formats.turbsim import read_turbsim

    deck = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"
    box, table = tmp_path / "box.bts", tmp_path / "run.csv"
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        code = main(["turbine", str(deck), "--simulate", "6", "--wind-speed", "9", "--turbulence", "B",
                     "--turbulence-grid", "5", "--turbulence-dt", "0.5", "--turbulence-key", "4",
                     "--turbulence-box", str(box), "--output", str(table), "--quiet"])
    assert code == 0, err.getvalue()
    read = read_turbsim(box)
    u = read.velocity[:, 0, 0, 0].astype(float)
    assert read.periodic and read.velocity.shape == (12, 5, 5, 3) and read.hub_height == 90.0
    sigma = 0.14 * (0.75 * 9.0 * (90.0 / 90.0) ** 0.0 + 5.6)
    assert u.std(ddof=1) == pytest.approx(sigma, rel=2e-3)             # 16-bit counts of the file
    assert len(table.read_text().splitlines()) == 1 + 121


@pytest.mark.parametrize("argv, field", [
    (["--linearize", "--turbulence", "B"], "--turbulence"),
    (["--simulate", "5", "--turbulence", "B", "--turbulence-intensity", "12"], "--turbulence-intensity"),
    (["--simulate", "5", "--turbulence-grid", "5"], "--turbulence-grid"),
    (["--simulate", "5", "--turbulence", "A", "--turbulence-grid", "2"], "--turbulence-grid"),
])
def test_bad_turbulence_options_exit_2(argv, field):
    import contextlib
    import io
    from pathlib import Path

    from bladefem.cli import main
    deck = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        code = main(["turbine", str(deck), *argv, "--quiet"])
    assert code == 2 and f"field '{field}'" in err.getvalue(), err.getvalue()
