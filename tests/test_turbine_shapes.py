"""Assumed-mode shapes: sampling, shortening integrals, generalized matrices against closed forms."""

from __future__ import annotations

import math

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


# -- ElastoDyn's discretization (--elastodyn-compatible) ---------------------------------------------------------

def elastodyn_loops(coefficients, fraction, twist, mass, flap, edge, length, nodes, tuners):
    """ElastoDyn.f90's Coeff for one blade, transcribed loop by loop (TwistedSF, AxRedBld, KBF, KBE, MBF, the
    element masses) as an independent check of the vectorised beams: nodes at element midpoints, properties
    linearly interpolated, the twisted shape functions by its running half-element sums."""
    def shp(c, x, d):
        return sum(ci * math.perm(k, d) * x ** (k - d) for ci, k in zip(c, range(2, 7))) / length**d

    dr = length / nodes
    r = (np.arange(nodes) + 0.5) * dr
    theta = np.interp(r / length, fraction, twist)
    m, ef, ee = (np.interp(r / length, fraction, a) for a in (mass, flap, edge))
    kinds = ("flap", "edge", "flap")
    sf = np.zeros((2, 3, nodes + 1, 3))          # (Phi/Psi, mode, node incl. tip, derivative)
    axred = np.zeros((3, 3, nodes + 1))
    old = np.zeros((2, 3, 2))
    ax_old = np.zeros((3, 3))
    for j in range(nodes):
        for i, (c, kind) in enumerate(zip(coefficients, kinds)):
            curv = shp(c, r[j] / length, 2)
            sf[:, i, j, 2] = (curv * np.cos(theta[j]), -curv * np.sin(theta[j])) if kind == "flap" else \
                (curv * np.sin(theta[j]), curv * np.cos(theta[j]))
        new = np.zeros((2, 3, 2))
        new[..., 1] = sf[:, :, j, 2] * 0.5 * dr
        sf[:, :, j, 1] = new[..., 1] + (sf[:, :, j - 1, 1] + old[..., 1] if j else 0.0)
        new[..., 0] = sf[:, :, j, 1] * 0.5 * dr
        sf[:, :, j, 0] = new[..., 0] + (sf[:, :, j - 1, 0] + old[..., 0] if j else 0.0)
        ax = 0.5 * dr * np.einsum("ai,al->il", sf[:, :, j, 1], sf[:, :, j, 1])
        axred[:, :, j] = ax + (axred[:, :, j - 1] + ax_old if j else 0.0)
        old, ax_old = new, ax
    sf[:, :, nodes, 1] = sf[:, :, nodes - 1, 1] + old[..., 1]
    sf[:, :, nodes, 0] = sf[:, :, nodes - 1, 0] + old[..., 0]
    axred[:, :, nodes] = axred[:, :, nodes - 1] + ax_old
    kbf = np.array([[np.sum(ef * dr * shp(a, r / length, 2) * shp(b, r / length, 2)) for b in coefficients[::2]]
                    for a in coefficients[::2]]) * np.sqrt(np.outer(tuners, tuners))
    kbe = np.sum(ee * dr * shp(coefficients[1], r / length, 2) ** 2)
    mbf = [np.sum(m * dr * shp(c, r / length, 0) ** 2) for c in coefficients]
    return sf, axred, kbf, kbe, mbf, m * dr


def test_elastodyn_blade_beam_is_elastodyns_coeff():
    from bladefem.models.turbine.elastodyn_beams import elastodyn_blade_beam
    from bladefem.sections import SectionTable
    rng = np.random.default_rng(2)
    fraction = np.linspace(0.0, 1.0, 9)
    twist, mass = np.radians(np.linspace(13.0, 0.0, 9)), rng.uniform(200, 600, 9)
    flap, edge = rng.uniform(1e9, 5e9, 9), rng.uniform(3e9, 9e9, 9)
    coefficients = {"flap1": [0.1, 1.9, -1.5, 0.8, -0.3], "edge1": [0.4, 0.9, -0.7, 0.5, -0.1],
                    "flap2": [-0.6, 1.6, -7.2, 11.0, -3.8]}
    length, nodes, tuners = 40.0, 11, np.array([1.05, 0.97])
    sections = SectionTable(span=fraction * length, mass=mass, flap_stiffness=flap, edge_stiffness=edge, twist=twist)
    beam = elastodyn_blade_beam(sections, coefficients, nodes, 0.0, tuners)
    c = [coefficients[k] for k in ("flap1", "edge1", "flap2")]
    sf, axred, kbf, kbe, mbf, element = elastodyn_loops(c, fraction, twist, mass, flap, edge, length, nodes, tuners)
    # bladefem's blade frame: y in-plane toward the leading edge = -Psi (ElastoDyn's j2 points to the trailing
    # edge), z out-of-plane = Phi; its edge mode is signed the other way round (curvature toward the leading edge)
    sign = np.array([1.0, -1.0, 1.0])[:, None]
    np.testing.assert_allclose(beam.value[..., 1] * sign, sf[0, :, :-1, 0], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(beam.value[..., 0] * sign, -sf[1, :, :-1, 0], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(beam.tip_value[:, 1] * sign[:, 0], sf[0, :, -1, 0], rtol=1e-12)
    np.testing.assert_allclose(beam.slope[..., 1] * sign, sf[0, :, :-1, 1], rtol=1e-12, atol=1e-15)
    flip = sign @ sign.T
    np.testing.assert_allclose(beam.shortening * flip[..., None], axred[..., :-1], rtol=1e-12, atol=1e-18)
    np.testing.assert_allclose(beam.tip_shortening * flip, axred[..., -1], rtol=1e-12)
    np.testing.assert_allclose(beam.point_mass, element, rtol=1e-12)
    K = beam.generalized_stiffness()
    np.testing.assert_allclose(K[np.ix_([0, 2], [0, 2])], kbf, rtol=1e-12)
    assert K[1, 1] == pytest.approx(kbe, rel=1e-12)
    assert K[0, 1] == K[1, 2] == 0.0
    np.testing.assert_allclose(beam.damping_mass, mbf, rtol=1e-12)


def test_elastodyn_damping_convention_is_cbf():
    """CBF(I,L) = 0.01 BldFDamp(L) KBF(I,L) / (pi FreqBF(L,1)), FreqBF(L,1) = sqrt(KBF(L,L) / MBF(L,L)) / 2 pi
    without the tip mass (ElastoDyn.f90, Coeff)."""
    from bladefem.models.turbine.elastodyn_beams import elastodyn_blade_beam
    from bladefem.sections import uniform_sections
    coefficients = {"flap1": [0.6, 0.6, -0.4, 0.3, -0.1], "edge1": [0.5, 0.8, -0.6, 0.4, -0.1],
                    "flap2": [-0.6, 1.6, -7.2, 11.0, -3.8]}
    beam = elastodyn_blade_beam(uniform_sections(30.0, 300.0, 2e9, edge_stiffness=4e9), coefficients, 15,
                                damping_ratio=np.array([0.01, 0.02, 0.03]))
    K = beam.generalized_stiffness()
    frequency = np.sqrt(np.diag(K) / beam.damping_mass) / (2 * np.pi)
    expected = K * np.array([0.01, 0.02, 0.03])[None, :] / (np.pi * frequency[None, :])
    np.testing.assert_allclose(beam.damping_matrix("elastodyn"), expected, rtol=1e-12)
    assert beam.damping_matrix("elastodyn")[0, 2] != 0.0       # flap 1 - flap 2 coupling, as ElastoDyn's
    rna = beam.damping_matrix("end-mass", 50.0)
    assert np.count_nonzero(rna - np.diag(np.diag(rna))) == 0


def test_elastodyn_tower_beam_uses_the_polynomial_at_the_nodes():
    from bladefem.models.turbine.elastodyn_beams import elastodyn_tower_beam
    from bladefem.sections import uniform_sections
    c = {"fa1": [0.7, 0.3, 0.0, 0.0, 0.0], "fa2": [-20.0, 23.0, -2.0, 0.0, 0.0], "ss1": [1.0, 0.0, 0.0, 0.0, 0.0],
         "ss2": [-10.0, 11.0, 0.0, 0.0, 0.0]}
    beam = elastodyn_tower_beam(uniform_sections(80.0, 4000.0, 5e11), c, 8)
    h = (np.arange(8) + 0.5) * 10.0
    np.testing.assert_allclose(beam.value[0, :, 0], 0.7 * (h / 80) ** 2 + 0.3 * (h / 80) ** 3, rtol=1e-14)
    np.testing.assert_allclose(beam.value[2, :, 1], (h / 80) ** 2, rtol=1e-14)
    assert not beam.value[0, :, 1].any() and not beam.value[2, :, 0].any()
    np.testing.assert_allclose(beam.tip_value[:, 0], [1.0, 1.0, 0.0, 0.0], atol=1e-14)
    # S_ss1 of phi = (h/L)^2: node J holds sum_{j<J} dr s_j^2 + dr s_J^2 / 2 (AxRedTSS), s = 2 h / L^2
    slope2 = (2 * h / 80**2) ** 2
    np.testing.assert_allclose(beam.shortening[2, 2], 10.0 * (np.cumsum(slope2) - slope2 / 2), rtol=1e-12)
    assert beam.generalized_stiffness()[0, 2] == 0.0
