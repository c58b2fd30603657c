"""The frame in which each aerodynamic node's relative wind is resolved for the BEM, and the section's orientation
in it: AeroDyn's two projections (``AeroProjMod``), chosen by ``BEM_Mod`` (``BEMOptions.formulation``).

Legacy (BEM_Mod 1, ``NoSweepPitchTwist``): vx along the section's downwind normal n (the coned blade's i1 turned
by the out-of-plane slope), vy against the rotation e_t; the section is plane in that frame (cant 0, toe 0,
dr/dz 1).

Polar (BEM_Mod 2, ``APM_BEM_Polar``; AeroDyn.f90 ``SetInputsForBEMT``, ``Calculate_MeshOrientation_Rel2Hub``,
``TwistToeCant_FromLocalPolar``): the node's local polar frame x_l = the shaft axis, z_l = the node's position
from the apex projected onto the rotor plane and normalised, y_l = z_l x x_l; vx = V . x_l, vy = V . y_l. The
untwisted section axes (n, -e_t, s; s the deflected span axis) in that frame give AeroDyn's Euler angles
R = R_y(cant) R_x(toe) (:mod:`bladefem.aero.polar`): sin(cant) = s . x_l over the chord-normal's part
(cant = atan2(s . x_l, n . x_l)), toe = atan2(-e_t . z_l, -e_t . y_l) (the node's position off the blade's
radial line: in-plane deflection and the aerodynamic-centre sweep). There is no twist part: e_t is normal to the
shaft, so the section's twist stays ``theta``. The annulus factor dr/dz = |dr_proj| / |dr| of the segment from the
previous node (the first node takes the second's).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray


@dataclass(frozen=True)
class Projection:
    """x_axis, y_axis : (B, Na, 3) the unit vectors vx and vy are taken along; cant, toe : (B, Na) rad;
    drdz : (B, Na) the annulus factor."""

    x_axis: NDArray
    y_axis: NDArray
    cant: NDArray
    toe: NDArray
    drdz: NDArray

    def components(self, relative: NDArray) -> tuple[NDArray, NDArray]:
        """(vx, vy) of relative winds (..., B, Na, 3)."""
        return (np.einsum("...k,...k->...", relative, self.x_axis),
                np.einsum("...k,...k->...", relative, self.y_axis))


def projection(polar: bool, arm: NDArray, shaft: NDArray, normal: NDArray, tangent: NDArray,
               span: NDArray) -> Projection:
    """The projection of every node: ``arm`` (B, Na, 3) the nodes from the apex, ``shaft`` (3,) the shaft axis,
    ``normal``, ``tangent`` (direction of rotation), ``span`` (B, Na, 3) the section's untwisted axes."""
    shape = arm.shape[:-1]
    if not polar:
        return Projection(x_axis=normal, y_axis=-np.broadcast_to(tangent, arm.shape), cant=np.zeros(shape),
                          toe=np.zeros(shape), drdz=np.ones(shape))
    radial = arm - (arm @ shaft)[..., None] * shaft
    z_l = radial / np.linalg.norm(radial, axis=-1, keepdims=True)
    x_l = np.broadcast_to(shaft, arm.shape)
    y_l = np.cross(z_l, x_l)
    tangent = np.broadcast_to(tangent, arm.shape)
    cant = np.arctan2(np.einsum("...k,...k", span, x_l), np.einsum("...k,...k", normal, x_l))
    toe = np.arctan2(-np.einsum("...k,...k", tangent, z_l), -np.einsum("...k,...k", tangent, y_l))
    step = np.linalg.norm(np.diff(arm, axis=-2), axis=-1)
    step_projected = np.linalg.norm(np.diff(radial, axis=-2), axis=-1)
    drdz = np.divide(step_projected, step, out=np.zeros_like(step), where=step > 0)
    drdz = np.concatenate([drdz[..., :1], drdz], axis=-1)
    return Projection(x_axis=x_l, y_axis=y_l, cant=cant, toe=toe, drdz=drdz)
