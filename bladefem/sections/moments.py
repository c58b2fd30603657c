"""Section mass moments and stiffness matrices in the blade frame, at any span positions.

A section point at chord coordinate ``eta`` and thickness coordinate ``zeta`` sits, for a total angle
``theta`` = structural twist + pitch, at ``y = eta cos(theta) + zeta sin(theta)`` (in-plane) and
``z = -eta sin(theta) + zeta cos(theta)`` (out-of-plane): positive twist turns the leading edge upwind.

Mass moments per unit length about the reference axis:
``m``, ``S = int rho (0, y, z) dA`` and ``J = int rho s s^T dA`` (3x3, zero x row and column).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .table import SectionTable

#: positions of (u', v'', w'') and of phi' in the classical strains (u', phi', v'', w'')
EXTENSION_BENDING = (0, 2, 3)
TWIST = 1


def chord_direction(theta: NDArray) -> tuple[NDArray, NDArray]:
    """(y, z) components of the unit vector along the chord toward the leading edge."""
    return np.cos(theta), -np.sin(theta)


@dataclass(frozen=True)
class MassMoments:
    """Mass moments per length at a set of points (arrays of the points' shape; S: (3, ...), J: (3, 3, ...))."""

    m: NDArray
    S: NDArray
    J: NDArray


def total_angle(sections: SectionTable, x: NDArray, pitch: float) -> NDArray:
    """Structural twist plus pitch at span positions ``x``, rad."""
    return sections.at(x, "twist") + pitch


def mass_moments(sections: SectionTable, x: NDArray, pitch: float = 0.0) -> MassMoments:
    """Mass per length (kg/m), first moments (kg) and second moments (kg m) about the reference axis."""
    if sections.full is not None:
        return sections.full.mass_moments(x, pitch)
    theta = total_angle(sections, x, pitch)
    c, s = np.cos(theta), np.sin(theta)
    m = sections.at(x, "mass")
    e = sections.at(x, "cm_offset")
    i_chord = sections.at(x, "edge_inertia")   # int rho eta^2 about the centre of mass
    i_thick = sections.at(x, "flap_inertia")   # int rho zeta^2 about the centre of mass
    cy, cz = chord_direction(theta)
    zero = np.zeros_like(m)
    S = np.stack([zero, m * e * cy, m * e * cz])
    J = np.zeros((3, 3) + m.shape)
    J[1, 1] = i_chord * c**2 + i_thick * s**2 + m * (e * cy) ** 2
    J[2, 2] = i_chord * s**2 + i_thick * c**2 + m * (e * cz) ** 2
    J[1, 2] = J[2, 1] = (i_thick - i_chord) * s * c + m * e**2 * cy * cz
    return MassMoments(m=m, S=S, J=J)


def bending_stiffness(sections: SectionTable, x: NDArray, pitch: float = 0.0) -> NDArray:
    """2x2 bending stiffness about the tension centre for curvatures (v'', w''), N m^2, shape (2, 2, ...).

    The principal stiffnesses (edge about the thickness axis, flap about the chord axis) are rotated by the
    structural twist plus pitch: this is what couples flap and edge bending in a twisted blade. For six-by-six
    sections: the bending block with extension and twist free (axial force and torque zero).
    """
    if sections.full is not None:
        D = np.moveaxis(sections.full.blade_stiffness(x, pitch), (0, 1), (-2, -1))
        B = D[..., 2:, 2:] - D[..., 2:, :2] @ np.linalg.solve(D[..., :2, :2], D[..., :2, 2:])
        return np.moveaxis(B, (-2, -1), (0, 1))
    theta = total_angle(sections, x, pitch)
    c, s = np.cos(theta), np.sin(theta)
    flap = sections.at(x, "flap_stiffness")
    edge = sections.at(x, "edge_stiffness")
    D = np.empty((2, 2) + flap.shape)
    D[0, 0] = edge * c**2 + flap * s**2
    D[1, 1] = edge * s**2 + flap * c**2
    D[0, 1] = D[1, 0] = (flap - edge) * s * c
    return D


def extension_bending_stiffness(sections: SectionTable, x: NDArray, pitch: float = 0.0) -> NDArray:
    """3x3 stiffness for the strains (u', v'', w'') of the reference axis, with the tension-centre offset.

    The axial strain of a fibre at (y, z) is ``u' - y v'' - z w''``; integrating ``E`` times its square over the
    section about the reference axis gives EA, the offset coupling ``-EA y_t`` and the parallel-axis terms.
    Six-by-six sections give their classical stiffness's block (offsets in both directions, turned principal
    axes).
    """
    if sections.full is not None:
        return sections.full.blade_stiffness(x, pitch)[np.ix_(EXTENSION_BENDING, EXTENSION_BENDING)]
    theta = total_angle(sections, x, pitch)
    EA = sections.at(x, "axial_stiffness")
    e_t = sections.at(x, "tension_centre_offset")
    cy, cz = chord_direction(theta)
    offset = np.stack([-e_t * cy, -e_t * cz])          # d(strain)/d(v'', w'') at the tension centre
    D = np.empty((3, 3) + EA.shape)
    D[0, 0] = EA
    D[0, 1:] = D[1:, 0] = EA * offset
    D[1:, 1:] = bending_stiffness(sections, x, pitch) + EA * offset[:, None] * offset[None, :]
    return D


def torsion_stiffness(sections: SectionTable, x: NDArray, pitch: float = 0.0) -> NDArray | None:
    """GJ at ``x``, N m^2 (None for a torsionally rigid table); six-by-six sections: the classical twist entry."""
    if sections.full is not None:
        return sections.full.blade_stiffness(x, pitch)[TWIST, TWIST]
    return None if sections.torsion_stiffness is None else sections.at(x, "torsion_stiffness")


def twist_coupling_stiffness(sections: SectionTable, x: NDArray, pitch: float = 0.0) -> NDArray | None:
    """The classical stiffness's coupling of the twist rate phi' with (u', v'', w''), shape (3, ...): extension-
    twist and bend-twist, N m and N m^2; None where there is none (every column table)."""
    if sections.full is None:
        return None
    D = sections.full.blade_stiffness(x, pitch)[TWIST, list(EXTENSION_BENDING)]
    return D if np.any(D != 0) else None


def shear_flexible_stiffness(sections: SectionTable, x: NDArray, pitch: float = 0.0) -> NDArray | None:
    """The whole six-by-six stiffness on the blade-frame strains (u', gamma_y, gamma_z, phi', v'', w''), shape
    (6, 6, ...), for sections the FE takes shear-flexible (:attr:`~bladefem.sections.FullSections.shear_flexible`);
    None for every other table (the beam is Euler-Bernoulli)."""
    if sections.full is None or not sections.full.shear_flexible:
        return None
    return sections.full.blade_section_stiffness(x, pitch)
