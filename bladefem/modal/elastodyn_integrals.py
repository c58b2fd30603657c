"""ElastoDyn's span integrals of its polynomial modes (``SetBladeParameters``, ``SetTowerParameters`` and ``Coeff``
in ElastoDyn.f90): the node rule, the twisted blade shapes, and a mode's generalized stiffness and mass.

ElastoDyn evaluates its span integrals at the midpoints of ``BldNodes`` (``TwrNodes``) equal elements, with the
section properties linearly interpolated there, each node carrying its element's mass ``m dr``. A blade mode's
curvature lies along the local principal direction (structural twist plus pitch) and is integrated twice from the
clamped root by the half-element rule ``I_J = I_{J-1} + (f_{J-1} dr_{J-1} + f_J dr_J) / 2`` (``TwistedSF``); the tip
adds half of the last element. Those twisted shapes carry the mass in its equations of motion; the elastic
stiffness is ``sum EI phi''^2 dr`` of the plain polynomial.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import scipy.linalg
from numpy.typing import NDArray

from ..sections import SectionTable
from .sextic import monomials


def elastodyn_nodes(length: float, count: int) -> tuple[NDArray, float]:
    """ElastoDyn's analysis nodes: midpoints of ``count`` equal elements over ``length``; (positions m, dr m)."""
    dr = length / count
    return (np.arange(count) + 0.5) * dr, dr


def half_element_integral(rate: NDArray, dr: NDArray) -> tuple[NDArray, NDArray]:
    """ElastoDyn's running integral of ``rate`` (..., J, k) given at the J nodes (axis -2):
    ``I_1 = rate_1 dr_1 / 2``, ``I_J = I_{J-1} + (rate_{J-1} dr_{J-1} + rate_J dr_J) / 2``; and its value at the
    tip, ``I_J + rate_J dr_J / 2``."""
    half = 0.5 * rate * np.asarray(dr)[:, None]
    running = 2.0 * np.cumsum(half, axis=-2) - half
    return running, running[..., -1, :] + half[..., -1, :]


def principal_directions(kinds: Sequence[str], theta: NDArray) -> NDArray:
    """Unit curvature directions (n, J, 2) in the blade frame (y in-plane toward the leading edge, z out-of-plane):
    flapwise (sin theta, cos theta), edgewise (cos theta, -sin theta), theta = structural twist + pitch."""
    flap = np.stack([np.sin(theta), np.cos(theta)], axis=-1)
    edge = np.stack([np.cos(theta), -np.sin(theta)], axis=-1)
    return np.stack([flap if kind == "flap" else edge for kind in kinds])


def twisted_shapes(curvature: NDArray, dr: NDArray) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """Slopes and values (n, J, 2) at the nodes, and at the tip (n, 2), of curvatures (n, J, 2) integrated twice
    from a clamped root by the half-element rule."""
    slope, tip_slope = half_element_integral(curvature, dr)
    value, tip_value = half_element_integral(slope, dr)
    return value, slope, tip_value, tip_slope


def centrifugal_load(sections: SectionTable, nodes: NDArray, dr: float, hub_radius: float, tip_mass: float,
                     omega: float, precone: float) -> NDArray:
    """Axial load N (N) at each node from the node masses outboard of it, lumped as ElastoDyn lumps them (the
    outer half of a node's own element sits at r + dr/4), plus the tip mass at the tip."""
    element = sections.at(nodes, "mass") * dr
    moments = element * (hub_radius + nodes)
    outboard = np.cumsum(moments[::-1])[::-1] - moments
    own = 0.5 * element * (hub_radius + nodes + dr / 4)
    tip = tip_mass * (hub_radius + sections.length)
    return omega**2 * math.cos(precone) ** 2 * (outboard + own + tip)


def gravity_load(sections: SectionTable, nodes: NDArray, dr: float, top_mass: float, gravity: float) -> NDArray:
    """Compressive axial load (N) at each tower node: the weight of the node masses above it (the upper half of
    its own element included) and of the top mass."""
    element = sections.at(nodes, "mass") * dr
    above = np.cumsum(element[::-1])[::-1] - element / 2
    return gravity * (above + top_mass)


def elastodyn_forms(sections: SectionTable, stiffness: str, nodes: int, *, tip_mass: float = 0.0,
                    omega: float = 0.0, hub_radius: float = 0.0, precone: float = 0.0, in_plane: bool = False,
                    gravity: float = 0.0, twist_pitch: float | None = None) -> tuple[NDArray, NDArray]:
    """ElastoDyn's generalized stiffness and mass of a polynomial mode as quadratic forms over c_2..c_6 (5 x 5):
    ``K(c) = c^T K c``, ``M(c) = c^T M c`` over its own ``nodes``, ``stiffness`` the EI column ('flap_stiffness' or
    'edge_stiffness'), with the centrifugal tension ``N`` at rotor speed ``omega`` (rad/s) and for a tower the
    gravity load ``P`` (``gravity``, m/s^2): ``K = sum EI phi''^2 dr + sum (N - P) phi' . phi' dr``.

    ``twist_pitch`` None (towers): the plain polynomial at the nodes, ``M = sum m phi^2 dr + M_tip (sum c)^2``,
    ``in_plane`` subtracts the spin softening ``omega^2 M``. ``twist_pitch`` given (blades, rad): the shape is
    twisted by the structural twist plus this pitch and integrated by ElastoDyn's rule (:func:`twisted_shapes`),
    as in its equations of motion; the mass and the centrifugal term follow the twisted shape and the spin
    softening acts on its in-plane component.
    """
    length = sections.length
    r, dr = elastodyn_nodes(length, nodes)
    x = r / length
    load = centrifugal_load(sections, r, dr, hub_radius, tip_mass, omega, precone)
    load = load - gravity_load(sections, r, dr, tip_mass, gravity)
    mass_per_node = sections.at(r, "mass") * dr
    curvature = monomials(x, 2).T / length**2                                    # (5, J)
    K = dr * np.einsum("p,ip,jp->ij", sections.at(r, stiffness), curvature, curvature)
    if twist_pitch is None:
        phi, phi1 = (monomials(x, k).T / length**k for k in (0, 1))
        M = np.einsum("p,ip,jp->ij", mass_per_node, phi, phi) + tip_mass * np.ones((5, 5))
        K = K + dr * np.einsum("p,ip,jp->ij", load, phi1, phi1)
        return (K - omega**2 * M if in_plane else K), M
    kind = "edge" if stiffness.startswith("edge") else "flap"
    theta = sections.at(r, "twist") + twist_pitch
    directions = principal_directions([kind] * 5, theta)
    value, slope, tip_value, _ = twisted_shapes(curvature[..., None] * directions, np.full(nodes, dr))
    M = np.einsum("p,ipa,jpa->ij", mass_per_node, value, value) + tip_mass * tip_value @ tip_value.T
    K = K + dr * np.einsum("p,ipa,jpa->ij", load, slope, slope)
    in_plane_mass = np.einsum("p,ip,jp->ij", mass_per_node, value[..., 0], value[..., 0]) \
        + tip_mass * np.outer(tip_value[:, 0], tip_value[:, 0])
    return K - omega**2 * in_plane_mass, M


def elastodyn_frequency(coefficients: NDArray, sections: SectionTable, stiffness: str, nodes: int,
                        **options: float) -> float:
    """Frequency (Hz) ElastoDyn derives for a polynomial mode from its generalized mass and stiffness
    (:func:`elastodyn_forms`, same options)."""
    K, M = elastodyn_forms(sections, stiffness, nodes, **options)
    c = np.asarray(coefficients, dtype=float)
    return math.sqrt(max(float(c @ K @ c), 0.0) / float(c @ M @ c)) / (2 * math.pi)


#: ElastoDyn's blade degrees of freedom in its order (DOF_BF(K,1), DOF_BF(K,2), DOF_BE(K,1)) and their kinds
BLADE_DOFS = (("flap1", "flap"), ("flap2", "flap"), ("edge1", "edge"))


def elastodyn_blade_matrices(coefficients: dict[str, NDArray], sections: SectionTable, nodes: int, *,
                             tip_mass: float = 0.0, omega: float = 0.0, hub_radius: float = 0.0,
                             precone: float = 0.0, twist_pitch: float = 0.0) -> tuple[NDArray, NDArray]:
    """ElastoDyn's coupled stiffness and mass (3 x 3, in the order of :data:`BLADE_DOFS`) of one blade's polynomial
    modes, as its equations of motion hold them: the elastic stiffness couples the two flap modes
    (``KBF(K,1,2)``, the flap EI) and not flap with edge; the mass, the centrifugal stiffening and the spin
    softening act on the twisted shapes (``TwistedSF``), so every pair of modes couples through them. Options as
    :func:`elastodyn_forms` (rad/s, m, rad, kg)."""
    r, dr = elastodyn_nodes(sections.length, nodes)
    x = r / sections.length
    curvature = monomials(x, 2).T / sections.length**2                                    # (5, J)
    load = centrifugal_load(sections, r, dr, hub_radius, tip_mass, omega, precone)
    mass_per_node = sections.at(r, "mass") * dr
    theta = sections.at(r, "twist") + twist_pitch
    values, slopes, tips, elastic = [], [], [], []
    for name, kind in BLADE_DOFS:
        c = np.asarray(coefficients[name], dtype=float)
        direction = principal_directions([kind], theta)[0]                                  # (J, 2)
        value, slope, tip_value, _ = twisted_shapes((c @ curvature)[None, :, None] * direction, np.full(nodes, dr))
        values.append(value[0])
        slopes.append(slope[0])
        tips.append(tip_value[0])
        elastic.append((kind, c @ curvature))
    count = len(BLADE_DOFS)
    K, M = np.zeros((count, count)), np.zeros((count, count))
    for i in range(count):
        for j in range(count):
            if elastic[i][0] == elastic[j][0]:
                stiffness = sections.at(r, f"{elastic[i][0]}_stiffness")
                K[i, j] = dr * np.sum(stiffness * elastic[i][1] * elastic[j][1])
            K[i, j] += dr * np.sum(load * np.einsum("pa,pa->p", slopes[i], slopes[j]))
            in_plane = np.sum(mass_per_node * values[i][:, 0] * values[j][:, 0]) + tip_mass * tips[i][0] * tips[j][0]
            K[i, j] -= omega**2 * in_plane
            M[i, j] = np.sum(mass_per_node * np.einsum("pa,pa->p", values[i], values[j])) + tip_mass * tips[i] @ tips[j]
    return K, M


def elastodyn_coupled_frequencies(coefficients: dict[str, NDArray], sections: SectionTable, nodes: int,
                                  **options: float) -> dict[str, float]:
    """The blade frequencies (Hz) ElastoDyn's linearization finds for these polynomial modes together
    (:func:`elastodyn_blade_matrices`), each named after the mode whose generalized coordinate leads its
    eigenvector."""
    K, M = elastodyn_blade_matrices(coefficients, sections, nodes, **options)
    eigenvalues, vectors = scipy.linalg.eigh(K, M)
    scaled = np.abs(vectors) * np.sqrt(np.diag(M))[:, None]
    named = {}
    for k in np.argsort(eigenvalues):
        name = BLADE_DOFS[int(np.argmax(scaled[:, k]))][0]
        named.setdefault(name, math.sqrt(max(float(eigenvalues[k]), 0.0)) / (2 * math.pi))
    return named
