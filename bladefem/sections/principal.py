"""Principal bending axes of a section, and the sections ElastoDyn can hold.

ElastoDyn's blade (OpenFAST docs/source/user/elastodyn/input.rst, "Blade Input File") has per station the mass
per length, the flapwise and edgewise stiffnesses ``FlpStff``, ``EdgStff`` about its principal axes and the
structural twist ``StrcTwst`` that turns them; no offsets (centre of mass, tension and shear centres on the pitch
axis), no torsion, no couplings. :func:`elastodyn_sections` is the reduction bladefem documents for fitting its
polynomials to a blade with six-by-six sections: the bending stiffness about the tension centre (extension and
twist free) turned to its principal axes, the turn added to the twist, the mass on the axis; ``twisted=False``
also drops the twist (OpenFAST's guidance for the BModes/ElastoDyn mode-shape fit: no pretwist, no offsets).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from .table import SectionTable


def principal_axes(B: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """(angle, flap, edge) of 2x2 bending stiffnesses ``B`` (..., 2, 2) over the curvatures ``(kappa_eta,
    kappa_zeta)``: the axes turned by ``angle`` (rad, positive like the twist, at most 45 deg) make ``B``
    diagonal, ``flap`` about the turned chordwise axis and ``edge`` about the turned thickness axis (N m^2).
    ``B = Q diag(flap, edge) Q^T`` with ``Q = [[cos, sin], [-sin, cos]]``."""
    B = np.asarray(B, dtype=float)
    difference = B[..., 1, 1] - B[..., 0, 0]
    angle = 0.5 * np.arctan2(2 * B[..., 0, 1], np.abs(difference)) * np.where(difference < 0, -1.0, 1.0)
    c, s = np.cos(angle), np.sin(angle)
    flap = c**2 * B[..., 0, 0] - 2 * c * s * B[..., 0, 1] + s**2 * B[..., 1, 1]
    edge = s**2 * B[..., 0, 0] + 2 * c * s * B[..., 0, 1] + c**2 * B[..., 1, 1]
    return angle, flap, edge


def elastodyn_sections(sections: SectionTable, twisted: bool = True) -> SectionTable:
    """What ElastoDyn holds of ``sections``: mass per length, principal flap and edge stiffnesses about the tension
    centre, the twist plus the principal angle (zero with ``twisted=False``); no offsets, no inertias, no torsion,
    no axial stiffness. A column table keeps its stiffnesses and twist."""
    if sections.full is not None:
        angle, flap, edge = principal_axes(sections.full.bending())
        twist = sections.twist + angle
    else:
        flap, edge, twist = sections.flap_stiffness, sections.edge_stiffness, sections.twist
    zero = np.zeros_like(sections.span)
    return replace(sections, full=None, flap_stiffness=flap, edge_stiffness=edge,
                   twist=twist if twisted else zero, cm_offset=zero, tension_centre_offset=None,
                   shear_centre_offset=None, flap_inertia=zero, edge_inertia=zero, torsion_stiffness=None,
                   axial_stiffness=None, inertia_per_mass=False)
