"""Polar interpolation as AeroDyn's InterpOrd: linear, natural cubic spline, angles wrapped into [-pi, pi)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from bladefem.aero import Polar


@pytest.fixture
def polar_data():
    alpha = np.radians(np.array([-180, -90, -20, -5, 0, 4, 8, 12, 20, 90, 180.0]))
    rng = np.random.default_rng(3)
    return alpha, rng.normal(size=(3, alpha.size))


def test_linear_interpolation_is_piecewise_linear(polar_data):
    alpha, (cl, cd, cm) = polar_data
    polar = Polar(alpha, cl, cd, cm)
    x = np.linspace(-np.pi, np.pi - 1e-9, 997)
    got = polar.coefficients(x)
    for value, table in zip(got, (cl, cd, cm)):
        assert np.allclose(value, np.interp(x, alpha, table), rtol=0, atol=1e-13)


def test_cubic_interpolation_is_the_natural_spline(polar_data):
    alpha, (cl, cd, cm) = polar_data
    polar = Polar(alpha, cl, cd, cm, order=3)
    x = np.linspace(-np.pi, np.pi - 1e-9, 997)
    got = polar.coefficients(x)
    for value, table in zip(got, (cl, cd, cm)):
        assert np.allclose(value, CubicSpline(alpha, table, bc_type="natural")(x), rtol=0, atol=1e-12)


def test_angles_wrap_and_hold_end_values(polar_data):
    """alpha + 2 pi k is alpha; a table not reaching +-180 deg holds its end values (AeroDyn warns, then does the
    same)."""
    alpha, (cl, cd, cm) = polar_data
    polar = Polar(alpha, cl, cd, cm)
    x = np.radians([-170.0, -3.0, 7.0, 100.0])
    for shift in (-4 * np.pi, 2 * np.pi, 6 * np.pi):
        assert np.allclose(polar.coefficients(x + shift), polar.coefficients(x), atol=1e-12)
    short = Polar(alpha[3:-3], cl[3:-3], cd[3:-3], cm[3:-3])
    low, high = short.coefficients(np.radians([-60.0, 60.0]))[0]
    assert (low, high) == (cl[3], cl[-4])


def test_polar_refuses_unsorted_angles():
    with pytest.raises(ValueError, match="increase strictly"):
        Polar(np.array([0.0, 0.1, 0.1]), np.zeros(3), np.zeros(3), np.zeros(3))
