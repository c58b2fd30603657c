"""Assumed-mode shapes of a slender beam (tower or blade), sampled at the quadrature points of a 1-D mesh.

A beam carries ``n`` mode shapes; each is a displacement field with two transverse components (blade: in-plane
``y`` and out-of-plane ``z``; tower: fore-aft ``x`` and side-side ``y``) per unit modal amplitude. The axial
shortening of a point at ``x`` from the slopes (ElastoDyn's axial-reduction term) is
``s(x) = 1/2 sum_ij q_i q_j S_ij(x)`` with ``S_ij(x) = int_0^x phi_i' . phi_j' dxi`` (1/m).

Shapes come from nodal values and slopes (cubic Hermite between nodes, as bladefem's finite elements), from
ElastoDyn polynomial coefficients (optionally twisted by the structural twist plus pitch), or directly as arrays.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Literal

import numpy as np
from numpy.typing import NDArray

#: Gauss points per element for the mass and stiffness integrals (exact for Hermite cubics times linear data)
GAUSS_POINTS = 4
#: Gauss points for the partial shortening integrals (exact to degree 11: polynomial shapes of degree 6)
SHORTENING_POINTS = 6

#: how modal damping ratios become damping forces (see :meth:`ModalBeam.damping_matrix`)
DampingConvention = Literal["elastodyn", "end-mass"]
Evaluator = Callable[[NDArray], tuple[NDArray, NDArray, NDArray]]


@dataclass(frozen=True)
class ModalBeam:
    """A beam's assumed modes at its quadrature points ``P`` (the span nodes of the Kane model).

    x : (P,) positions from the root, m
    weight : (P,) quadrature weights, m
    mass : (P,) mass per length, kg/m
    value, slope, curvature : (n, P, 2) transverse displacement (m/m), slope (1/m) and curvature (1/m^2) per unit
        modal amplitude
    stiffness : (P, 2, 2) bending stiffness for the two transverse curvatures, N m^2
    shortening : (n, n, P) S_ij at the quadrature points, 1/m
    tip_value, tip_slope : (n, 2) the shapes at the free end
    tip_shortening : (n, n) S_ij at the free end, 1/m
    length : m
    damping_ratio : (n,) modal structural damping ratios (fraction of critical)
    names : a label per mode
    elastic_stiffness : (n, n) generalized elastic stiffness given directly (ElastoDyn's KBF, KBE, KTFA, KTSS
        with its stiffness tuners), or None for the curvature integral
    damping_mass : (n,) generalized masses of the beam alone that the ElastoDyn damping convention uses (its
        untwisted-polynomial MBF, MBE less the tip mass), or None for the beam's own generalized mass
    """

    x: NDArray
    weight: NDArray
    mass: NDArray
    value: NDArray
    slope: NDArray
    curvature: NDArray
    stiffness: NDArray
    shortening: NDArray
    tip_value: NDArray
    tip_slope: NDArray
    tip_shortening: NDArray
    length: float
    damping_ratio: NDArray
    names: tuple[str, ...]
    elastic_stiffness: NDArray | None = None
    damping_mass: NDArray | None = None

    @property
    def n_modes(self) -> int:
        return self.value.shape[0]

    @property
    def point_mass(self) -> NDArray:
        """Mass lumped at each quadrature point, kg."""
        return self.mass * self.weight

    def generalized_stiffness(self) -> NDArray:
        """Elastic modal stiffness ``K_ij = int kappa_i . D kappa_j dx`` (or the one given), N/m per unit
        amplitudes."""
        if self.elastic_stiffness is not None:
            return self.elastic_stiffness
        return np.einsum("p,ipa,pab,jpb->ij", self.weight, self.curvature, self.stiffness, self.curvature)

    def generalized_mass(self, tip_mass: float = 0.0) -> NDArray:
        """Modal mass ``int m phi_i . phi_j dx`` plus a point mass at the free end, kg."""
        beam = np.einsum("p,ipa,jpa->ij", self.point_mass, self.value, self.value)
        return beam + tip_mass * self.tip_value @ self.tip_value.T

    def damping_matrix(self, convention: DampingConvention = "elastodyn", end_mass: float = 0.0) -> NDArray:
        """Modal damping matrix from the damping ratios, N s/m.

        'elastodyn' (ElastoDyn's CBF, CBE, CTFA, CTSS): ``C_il = 2 zeta_l K_il / w_l`` with ``w_l`` the frequency
        of mode l of the beam alone (``sqrt(K_ll / m_l)``, no end mass, no centrifugal or gravity stiffness);
        'end-mass' (named 'rna' for a tower): diagonal ``c_i = 2 zeta_i sqrt(K_ii m_ii)`` with the modal mass
        including ``end_mass`` at the free end (the rotor-nacelle assembly on a tower, a tip mass on a blade).
        """
        K = self.generalized_stiffness()
        if convention == "elastodyn":
            own = np.diag(self.generalized_mass()) if self.damping_mass is None else self.damping_mass
            return K * (2.0 * self.damping_ratio * np.sqrt(own / np.diag(K)))[None, :]
        if convention == "end-mass":
            m = np.diag(self.generalized_mass(end_mass))
            return np.diag(2.0 * self.damping_ratio * np.sqrt(np.diag(K) * m))
        raise ValueError(f"unknown damping convention '{convention}'")

    def with_damping(self, damping_ratio: NDArray | float) -> ModalBeam:
        """A copy with other modal damping ratios (fraction of critical)."""
        return replace(self, damping_ratio=np.broadcast_to(np.asarray(damping_ratio, float), (self.n_modes,)).copy())


def gauss_rule(edges: NDArray, points: int) -> tuple[NDArray, NDArray]:
    """Gauss-Legendre points and weights on every interval of ``edges``; flattened, in increasing order."""
    xi, w = np.polynomial.legendre.leggauss(points)
    a, b = edges[:-1, None], edges[1:, None]
    x = 0.5 * (a + b) + 0.5 * (b - a) * xi
    return x.ravel(), (0.5 * (b - a) * w).ravel()


def shortening_integrals(evaluate: Evaluator, edges: NDArray, x: NDArray) -> NDArray:
    """``S_ij(x) = int_0^x phi_i' . phi_j'`` at points ``x`` (sorted, inside ``edges``): full elements summed plus
    the partial integral from the element start, each with a Gauss rule exact for the shapes' polynomial degree."""
    def integral(a: NDArray, b: NDArray) -> NDArray:
        xi, w = np.polynomial.legendre.leggauss(SHORTENING_POINTS)
        points = 0.5 * (a[:, None] + b[:, None]) + 0.5 * (b - a)[:, None] * xi
        _, slope, _ = evaluate(points.ravel())
        slope = slope.reshape(slope.shape[0], len(a), SHORTENING_POINTS, 2)
        weights = 0.5 * (b - a)[:, None] * w
        return np.einsum("pg,ipga,jpga->ijp", weights, slope, slope)

    per_element = integral(edges[:-1], edges[1:])
    full = np.concatenate([np.zeros_like(per_element[:, :, :1]), np.cumsum(per_element, axis=2)], axis=2)
    element = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, len(edges) - 2)
    return full[:, :, element] + integral(edges[element], x)


def sample_beam(evaluate: Evaluator, edges: NDArray, mass: Callable[[NDArray], NDArray],
                stiffness: Callable[[NDArray], NDArray], damping_ratio: NDArray | float = 0.0,
                names: tuple[str, ...] | None = None, gauss_points: int = GAUSS_POINTS) -> ModalBeam:
    """Sample shapes given by ``evaluate(x) -> (value, slope, curvature)`` (each (n, len(x), 2)) at the Gauss
    points of the mesh ``edges`` (m; section stations should be edges so the properties are smooth inside).

    mass(x) -> kg/m; stiffness(x) -> (len(x), 2, 2) N m^2; gauss_points per element (4 integrates the mass and
    stiffness of Hermite shapes with linear properties exactly; fewer gives a lighter model for simulation).
    """
    edges = np.asarray(edges, dtype=float)
    x, weight = gauss_rule(edges, gauss_points)
    value, slope, curvature = evaluate(x)
    tip = np.array([edges[-1]])
    tip_value, tip_slope, _ = evaluate(tip)
    n = value.shape[0]
    return ModalBeam(
        x=x, weight=weight, mass=np.asarray(mass(x), dtype=float), value=value, slope=slope,
        curvature=curvature, stiffness=np.asarray(stiffness(x), dtype=float),
        shortening=shortening_integrals(evaluate, edges, x),
        tip_value=tip_value[:, 0], tip_slope=tip_slope[:, 0],
        tip_shortening=shortening_integrals(evaluate, edges, tip)[:, :, 0],
        length=float(edges[-1]),
        damping_ratio=np.broadcast_to(np.asarray(damping_ratio, dtype=float), (n,)).copy(),
        names=names or tuple(f"mode {i + 1}" for i in range(n)),
    )


def hermite_evaluator(nodes: NDArray, values: NDArray, slopes: NDArray) -> Evaluator:
    """Cubic Hermite interpolation of nodal values and slopes, each (n, N, 2), like bladefem's beam elements."""
    nodes = np.asarray(nodes, dtype=float)
    values, slopes = np.asarray(values, dtype=float), np.asarray(slopes, dtype=float)

    def evaluate(x: NDArray) -> tuple[NDArray, NDArray, NDArray]:
        i = np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, len(nodes) - 2)
        h = nodes[i + 1] - nodes[i]
        t = (x - nodes[i]) / h
        basis = (
            (2 * t**3 - 3 * t**2 + 1, 6 * t**2 - 6 * t, 12 * t - 6),
            (h * (t**3 - 2 * t**2 + t), 3 * t**2 - 4 * t + 1, 6 * t - 4),
            (-2 * t**3 + 3 * t**2, -6 * t**2 + 6 * t, -12 * t + 6),
            (h * (t**3 - t**2), 3 * t**2 - 2 * t, 6 * t - 2),
        )
        v0, v1 = values[:, i], values[:, i + 1]
        s0, s1 = slopes[:, i], slopes[:, i + 1]
        hh = h[:, None]
        value = basis[0][0][:, None] * v0 + basis[1][0][:, None] * s0 + basis[2][0][:, None] * v1 \
            + basis[3][0][:, None] * s1
        slope = (basis[0][1][:, None] * v0 + basis[2][1][:, None] * v1) / hh + basis[1][1][:, None] * s0 \
            + basis[3][1][:, None] * s1
        curvature = (basis[0][2][:, None] * v0 + basis[2][2][:, None] * v1) / hh**2 \
            + (basis[1][2][:, None] * s0 + basis[3][2][:, None] * s1) / hh
        return value, slope, curvature

    return evaluate


def polynomial_evaluator(coefficients: NDArray, length: float, directions: NDArray) -> Evaluator:
    """ElastoDyn polynomial shapes ``phi(x) = sum_k c_k (x/L)^k``, k = 2..6, each along a fixed unit direction
    (``directions`` (n, 2), e.g. fore-aft (1, 0) or side-side (0, 1))."""
    c = np.asarray(coefficients, dtype=float)
    powers = np.arange(2, 7)
    directions = np.asarray(directions, dtype=float)

    def evaluate(x: NDArray) -> tuple[NDArray, NDArray, NDArray]:
        xi = np.asarray(x, dtype=float)[None, :, None] / length
        k = powers[None, None, :]
        cc = c[:, None, :]
        value = np.sum(cc * xi**k, axis=2)
        slope = np.sum(cc * k * xi ** (k - 1), axis=2) / length
        curvature = np.sum(cc * k * (k - 1) * xi ** (k - 2), axis=2) / length**2
        d = directions[:, None, :]
        return value[..., None] * d, slope[..., None] * d, curvature[..., None] * d

    return evaluate


def twisted_polynomial_nodes(coefficients: NDArray, length: float, principal: NDArray, nodes: NDArray,
                             angle: Callable[[NDArray], NDArray]) -> tuple[NDArray, NDArray]:
    """Nodal values and slopes (n, N, 2) of ElastoDyn's twisted blade shapes: the polynomial's curvature acts in
    the local principal direction, turned by ``angle(x)`` (structural twist + pitch, rad), and is integrated twice
    from the clamped root (ElastoDyn's TwistedSF).

    principal : (n,) 'flap' or 'edge' per shape. In the blade frame (y in-plane, z out-of-plane) the flapwise
    principal direction is (sin theta, cos theta), the edgewise (chordwise) one (cos theta, -sin theta).
    """
    nodes = np.asarray(nodes, dtype=float)
    plain = polynomial_evaluator(coefficients, length, np.ones((len(coefficients), 2)))

    def curvature(x: NDArray) -> NDArray:
        kappa = plain(x)[2][..., 0]
        theta = angle(x)
        flap = np.stack([np.sin(theta), np.cos(theta)], axis=-1)
        edge = np.stack([np.cos(theta), -np.sin(theta)], axis=-1)
        dirs = np.stack([flap if kind == "flap" else edge for kind in principal])
        return kappa[..., None] * dirs

    xi, w = np.polynomial.legendre.leggauss(SHORTENING_POINTS)
    a, b = nodes[:-1], nodes[1:]
    points = 0.5 * (a[:, None] + b[:, None]) + 0.5 * (b - a)[:, None] * xi
    weights = 0.5 * (b - a)[:, None] * w
    kappa = curvature(points.ravel()).reshape(len(principal), len(a), SHORTENING_POINTS, 2)
    dslope = np.einsum("eg,iega->iea", weights, kappa)
    slope_start = np.concatenate([np.zeros((len(principal), 1, 2)), np.cumsum(dslope, axis=1)], axis=1)
    lever = (b[:, None] - points) * weights
    dvalue = (b - a)[None, :, None] * slope_start[:, :-1] + np.einsum("eg,iega->iea", lever, kappa)
    values = np.concatenate([np.zeros((len(principal), 1, 2)), np.cumsum(dvalue, axis=1)], axis=1)
    return values, slope_start


def closed_form_cantilever(length: float, beta: NDArray, directions: NDArray | None = None) -> Evaluator:
    """Exact mode shapes of a uniform cantilever, bare or with a tip point mass (no rotary inertia), for the roots
    ``beta`` of its frequency equation; normalised to 1 at the tip. The zero-moment tip condition fixes the
    shape's form for any tip mass; the mass enters only through ``beta``."""
    beta = np.asarray(beta, dtype=float)
    directions = np.tile([0.0, 1.0], (len(beta), 1)) if directions is None else np.asarray(directions, float)

    def shape(b: float, x: NDArray, derivative: int) -> NDArray:
        z = b * x / length
        sigma = (np.cosh(b) + np.cos(b)) / (np.sinh(b) + np.sin(b))
        terms = (np.cosh(z) - np.cos(z) - sigma * (np.sinh(z) - np.sin(z)),
                 np.sinh(z) + np.sin(z) - sigma * (np.cosh(z) - np.cos(z)),
                 np.cosh(z) + np.cos(z) - sigma * (np.sinh(z) + np.sin(z)))
        tip = np.cosh(b) - np.cos(b) - sigma * (np.sinh(b) - np.sin(b))
        return terms[derivative] * (b / length) ** derivative / tip

    def evaluate(x: NDArray) -> tuple[NDArray, NDArray, NDArray]:
        x = np.asarray(x, dtype=float)
        out = [np.stack([shape(b, x, k) for b in beta])[..., None] * directions[:, None, :] for k in range(3)]
        return out[0], out[1], out[2]

    return evaluate
