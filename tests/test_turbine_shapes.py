"""Assumed-mode shapes: sampling, shortening integrals, generalized matrices against closed forms."""

from __future__ import annotations

import numpy as np
import pytest

from bladefem.models.turbine.shapes import (
    closed_form_cantilever,
    hermite_evaluator,
    polynomial_evaluator,
    sample_beam,
    twisted_polynomial_nodes,
)

L = 20.0


def uniform(evaluate, edges, mass=3.0, stiffness=5.0):
    return sample_beam(evaluate, edges, lambda x: np.full_like(x, mass),
                       lambda x: np.tile(np.eye(2) * stiffness, (len(x), 1, 1)))


def test_polynomial_shortening_and_stiffness_in_closed_form():
    # phi = (x/L)^2 + (x/L)^3 along z: phi' = 2x/L^2 + 3x^2/L^3, S(x) = int phi'^2, K = EI int phi''^2
    beam = uniform(polynomial_evaluator(np.array([[1.0, 1.0, 0, 0, 0]]), L, np.array([[0.0, 1.0]])),
                   np.linspace(0, L, 5))
    x = beam.x
    exact_S = 4 * x**3 / (3 * L**4) + 3 * x**4 / L**5 + 9 * x**5 / (5 * L**6)
    np.testing.assert_allclose(beam.shortening[0, 0], exact_S, rtol=1e-12)
    np.testing.assert_allclose(beam.tip_shortening[0, 0], 4 / (3 * L) + 3 / L + 9 / (5 * L), rtol=1e-12)
    exact_K = 5.0 * (4 / L**3 + 12 / L**3 + 12 / L**3)   # int (2/L^2 + 6x/L^3)^2 dx
    assert beam.generalized_stiffness()[0, 0] == pytest.approx(exact_K, rel=1e-12)
    exact_M = 3.0 * L * (1 / 5 + 2 / 6 + 1 / 7)
    assert beam.generalized_mass()[0, 0] == pytest.approx(exact_M, rel=1e-12)


def test_hermite_reproduces_a_cubic_exactly():
    nodes = np.linspace(0, L, 4)
    f = lambda x: 0.3 * x**3 / L**3 - 0.1 * x**2 / L**2       # noqa: E731
    df = lambda x: 0.9 * x**2 / L**3 - 0.2 * x / L**2          # noqa: E731
    values = np.stack([np.zeros_like(nodes), f(nodes)], axis=-1)[None]
    slopes = np.stack([np.zeros_like(nodes), df(nodes)], axis=-1)[None]
    x = np.linspace(0, L, 17)
    value, slope, curvature = hermite_evaluator(nodes, values, slopes)(x)
    np.testing.assert_allclose(value[0, :, 1], f(x), atol=1e-14)
    np.testing.assert_allclose(slope[0, :, 1], df(x), atol=1e-14)
    np.testing.assert_allclose(curvature[0, :, 1], 1.8 * x / L**3 - 0.2 / L**2, atol=1e-14)


def test_cantilever_frequency_from_its_exact_shape():
    beta = 1.87510407
    beam = uniform(closed_form_cantilever(L, np.array([beta])), np.linspace(0, L, 21), mass=2.0, stiffness=7.0)
    omega2 = beam.generalized_stiffness()[0, 0] / beam.generalized_mass()[0, 0]
    # Rayleigh quotient of the exact shape, Gauss quadrature of smooth functions on 20 elements: ~1e-10
    assert omega2 == pytest.approx(beta**4 * 7.0 / (2.0 * L**4), rel=1e-8)


def test_twisted_shapes_without_twist_are_the_plain_polynomial():
    c = np.array([[0.0622, 1.7254, -3.2452, 4.7131, -2.2555], [0.3627, 2.5337, -3.5772, 2.376, -0.6952]])
    nodes = np.linspace(0, L, 9)
    values, slopes = twisted_polynomial_nodes(c, L, ("flap", "edge"), nodes, lambda x: np.zeros_like(x))
    plain, plain_slope, _ = polynomial_evaluator(c, L, np.array([[0.0, 1.0], [1.0, 0.0]]))(nodes)
    np.testing.assert_allclose(values, plain, atol=1e-12)
    np.testing.assert_allclose(slopes, plain_slope, atol=1e-12)


def test_twist_turns_the_flap_shape_into_the_rotor_plane():
    c = np.array([[1.0, 0, 0, 0, 0]])
    theta = 0.3
    values, _ = twisted_polynomial_nodes(c, L, ("flap",), np.linspace(0, L, 5), lambda x: np.full_like(x, theta))
    # constant angle: the whole shape along the flap principal direction (sin theta, cos theta)
    np.testing.assert_allclose(values[0, -1], [np.sin(theta), np.cos(theta)], rtol=1e-12)
