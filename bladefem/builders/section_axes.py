"""Six-by-six sections in BeamDyn's axes onto bladefem's section frame (:class:`~bladefem.sections.FullSections`).

BeamDyn (OpenFAST docs/source/user/beamdyn/input_files.rst, "Blade Input File" and "Distributed Properties"; the
same axes in windIO and in HAWC2 FPM data converted for BeamDyn): the matrices are given in the local blade frame
turned with the section, ``X`` toward the suction side (downwind for an upwind rotor), ``Y`` toward the trailing
edge, ``Z`` along the reference axis; rows and columns ``(F_X, F_Y, F_Z, M_X, M_Y, M_Z)`` (stiffness: shear X, shear
Y, extension, bending about X = edgewise, bending about Y = flapwise, torsion) and the mass likewise on
``(u_X, u_Y, u_Z, omega_X, omega_Y, omega_Z)``. BeamDyn's ``initial_twist`` follows the IEC convention, a rotation
about ``-Z`` (input_files.rst, "Blade key points"; in the source BeamDyn_IO.f90 negates the value as it reads it
and BD_ComputeIniNodalCrv turns the section by that about the tangent), which turns the leading edge upwind for
positive values: the sense of bladefem's twist, so it is taken as it is.

bladefem's section frame (:mod:`bladefem.sections.full_section`): ``x = Z`` along the span, ``eta = -Y`` toward the
leading edge, ``zeta = X``; a proper rotation (determinant +1), so forces and moments (strains and curvatures)
map alike: ``K = P K_BeamDyn P^T``, ``M = P M_BeamDyn P^T``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..sections import FullSections

#: bladefem's row i is BeamDyn's row ``BEAMDYN_INDEX[i]`` times ``BEAMDYN_SIGN[i]``
BEAMDYN_INDEX = (2, 1, 0, 5, 4, 3)
BEAMDYN_SIGN = (1.0, -1.0, 1.0, 1.0, -1.0, 1.0)


def beamdyn_permutation() -> NDArray[np.float64]:
    """P (6x6) with bladefem's components ``= P`` BeamDyn's."""
    P = np.zeros((6, 6))
    P[np.arange(6), BEAMDYN_INDEX] = BEAMDYN_SIGN
    return P


def from_beamdyn_axes(matrices: NDArray[np.float64]) -> NDArray[np.float64]:
    """Section matrices (..., 6, 6) in BeamDyn's axes and order, in bladefem's."""
    P = beamdyn_permutation()
    return P @ np.asarray(matrices, dtype=float) @ P.T


def to_beamdyn_axes(matrices: NDArray[np.float64]) -> NDArray[np.float64]:
    """Section matrices (..., 6, 6) in bladefem's axes and order, in BeamDyn's (the inverse of
    :func:`from_beamdyn_axes`)."""
    P = beamdyn_permutation()
    return P.T @ np.asarray(matrices, dtype=float) @ P


def full_sections_from_beamdyn(span: NDArray[np.float64], stiffness: NDArray[np.float64],
                               mass: NDArray[np.float64], twist: NDArray[np.float64],
                               source: str = "", chord: NDArray[np.float64] | None = None) -> FullSections:
    """Six-by-six sections from BeamDyn-axes matrices: ``span`` in m along the reference axis from the root,
    ``stiffness`` and ``mass`` of shape (stations, 6, 6) in SI, ``twist`` BeamDyn's initial twist at the stations
    in rad; ``chord`` (m, for drawing) at the stations."""
    return FullSections(span=span, stiffness=from_beamdyn_axes(stiffness), mass=from_beamdyn_axes(mass),
                        twist=np.asarray(twist, dtype=float), chord=chord, source=source)
