"""Blade and tower beams discretized exactly as ElastoDyn discretizes them (``--elastodyn-compatible``).

ElastoDyn (``SetBladeParameters``, ``SetTowerParameters``, ``Coeff`` in ElastoDyn.f90) evaluates every span
integral at the midpoints of ``BldNodes`` (``TwrNodes``) equal elements, with the section properties linearly
interpolated there (after ``AdjBlMs``, ``AdjFlSt``, ``AdjEdSt``, ``AdjTwMa``, ``AdjFASt``, ``AdjSSSt``), each node
carrying the mass ``m dr`` of its element:

- blade shapes: the polynomial's curvature along the local principal direction (structural twist plus pitch) is
  integrated twice by ElastoDyn's node rule (``TwistedSF``): ``s_J = s_{J-1} + (k_{J-1} dr_{J-1} + k_J dr_J) / 2``
  and likewise the value from the slope; the tip adds half of the last element. Tower shapes are the polynomial
  itself at the nodes (``TwrFASF``, ``TwrSSSF``).
- axial shortening ``S_ij`` (``AxRedBld``, ``AxRedTFA``, ``AxRedTSS``) by the same half-element rule on the slopes.
- elastic stiffness ``K_il = sum EI phi_i'' phi_l'' dr`` (``KBF``, ``KBE``, ``KTFA``, ``KTSS``), times the modal
  stiffness tuners ``sqrt(t_i t_l)``; the mass used by the damping convention is ``sum m phi^2 dr`` of the
  untwisted polynomial (``MBF``, ``MBE``, ``MTFA``, ``MTSS`` less the end mass).

Centrifugal stiffening and gravity softening are not precomputed: as in ElastoDyn they come from the shortening
inside the Kane equations.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from ...modal.elastodyn_integrals import (
    elastodyn_nodes,
    half_element_integral,
    principal_directions,
    twisted_shapes,
)
from ...modal.sextic import polynomial
from ...sections import SectionTable, bending_stiffness
from .shapes import ModalBeam

BLADE_MODES = ("flap1", "edge1", "flap2")
BLADE_KINDS = ("flap", "edge", "flap")
TOWER_MODES = ("fa1", "fa2", "ss1", "ss2")


def shortening(slope: NDArray, tip_slope: NDArray, dr: NDArray) -> tuple[NDArray, NDArray]:
    """``S_ij`` at the nodes (n, n, J) and at the tip (n, n) by the half-element rule on ``phi_i' . phi_j'``;
    slope (n, J, 2)."""
    product = np.einsum("iJa,jJa->ijJ", slope, slope)[..., None]       # (n, n, J, 1): one 'component'
    nodes, tip = half_element_integral(product, dr)
    return nodes[..., 0], tip[..., 0]


def tuned(stiffness: NDArray, tuners: NDArray) -> NDArray:
    """ElastoDyn's modal stiffness tuners: ``K_il sqrt(t_i t_l)``."""
    return stiffness * np.sqrt(np.outer(tuners, tuners))


def elastodyn_blade_beam(sections: SectionTable, coefficients: dict[str, NDArray], nodes: int, pitch: float = 0.0,
                         flap_tuners: Sequence[float] = (1.0, 1.0),
                         damping_ratio: NDArray | float = 0.0) -> ModalBeam:
    """The blade modes flap 1, edge 1, flap 2 of ElastoDyn polynomial ``coefficients`` ('flap1', 'edge1',
    'flap2': c_2..c_6) on ``nodes`` (BldNodes) equal elements; ``sections`` with AdjBlMs/AdjFlSt/AdjEdSt applied;
    ``pitch`` rad; ``flap_tuners`` FlStTunr(1..2)."""
    length = sections.length
    r, dr = _nodes(length, nodes)
    c = np.array([coefficients[name] for name in BLADE_MODES])
    plain = np.stack([[polynomial(ci, r / length, k) / length**k for ci in c] for k in range(3)])   # (3, n, J)
    theta = sections.at(r, "twist") + pitch
    curvature = plain[2][..., None] * principal_directions(BLADE_KINDS, theta)
    value, slope, tip_value, tip_slope = twisted_shapes(curvature, dr)
    S, tip_S = shortening(slope, tip_slope, dr)
    mass = sections.at(r, "mass")
    stiffness = np.moveaxis(bending_stiffness(sections, r, pitch), -1, 0)
    # KBF (flap 1 and 2, with FlStTunr) and KBE from the plain polynomials' curvature; no flap-edge term
    flap = np.array([0, 2])
    elastic = np.zeros((3, 3))
    elastic[np.ix_(flap, flap)] = tuned(np.einsum("p,ip,jp->ij", sections.at(r, "flap_stiffness") * dr,
                                                  plain[2][flap], plain[2][flap]), np.asarray(flap_tuners, float))
    elastic[1, 1] = np.sum(sections.at(r, "edge_stiffness") * dr * plain[2][1] ** 2)
    return ModalBeam(x=r, weight=dr, mass=mass, value=value, slope=slope, curvature=curvature,
                     stiffness=stiffness, shortening=S, tip_value=tip_value, tip_slope=tip_slope, tip_shortening=tip_S,
                     length=float(length), damping_ratio=_ratios(damping_ratio, 3),
                     names=("flap 1", "edge 1", "flap 2"),
                     elastic_stiffness=elastic, damping_mass=np.einsum("J,iJ,iJ->i", mass * dr, plain[0], plain[0]))


def elastodyn_tower_beam(sections: SectionTable, coefficients: dict[str, NDArray], nodes: int,
                         fa_tuners: Sequence[float] = (1.0, 1.0), ss_tuners: Sequence[float] = (1.0, 1.0),
                         damping_ratio: NDArray | float = 0.0) -> ModalBeam:
    """The tower modes FA 1, FA 2 (along x, downwind) and SS 1, SS 2 (along y) of ElastoDyn polynomial
    ``coefficients`` ('fa1', 'fa2', 'ss1', 'ss2') on ``nodes`` (TwrNodes) equal elements of the flexible length;
    ``sections`` (flap = fore-aft, edge = side-side) with AdjTwMa/AdjFASt/AdjSSSt applied; FAStTunr, SSStTunr."""
    length = sections.length
    h, dh = _nodes(length, nodes)
    c = np.array([coefficients[name] for name in TOWER_MODES])
    directions = np.array([[1.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 1.0]])
    value, slope, curvature = (np.stack([polynomial(ci, h / length, k) / length**k for ci in c])[..., None]
                               * directions[:, None, :] for k in range(3))
    tip = np.array([1.0])
    tip_value, tip_slope = (np.stack([polynomial(ci, tip, k)[0] / length**k for ci in c])[:, None] * directions
                            for k in range(2))
    S, tip_S = shortening(slope, tip_slope, dh)
    stiffness = np.zeros((nodes, 2, 2))
    stiffness[:, 0, 0] = sections.at(h, "flap_stiffness")
    stiffness[:, 1, 1] = sections.at(h, "edge_stiffness")
    mass = sections.at(h, "mass")
    elastic = np.einsum("p,ipa,pab,jpb->ij", dh, curvature, stiffness, curvature)
    elastic = tuned(elastic, np.concatenate([fa_tuners, ss_tuners]).astype(float))
    return ModalBeam(x=h, weight=dh, mass=mass, value=value, slope=slope, curvature=curvature, stiffness=stiffness,
                     shortening=S, tip_value=tip_value, tip_slope=tip_slope, tip_shortening=tip_S,
                     length=float(length), damping_ratio=_ratios(damping_ratio, 4),
                     names=("fore-aft 1", "fore-aft 2", "side-side 1", "side-side 2"), elastic_stiffness=elastic)


def _nodes(length: float, count: int) -> tuple[NDArray, NDArray]:
    """ElastoDyn's node positions and element lengths (one per node), m."""
    r, dr = elastodyn_nodes(length, count)
    return r, np.full(count, dr)


def _ratios(value: NDArray | float, n: int) -> NDArray:
    return np.broadcast_to(np.asarray(value, dtype=float), (n,)).copy()
