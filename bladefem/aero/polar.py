"""A blade section seen from AeroDyn's local polar frame (BEM_Mod 2, its ``APM_BEM_Polar`` projection).

The polar frame of a node (AeroDyn.f90, ``Calculate_MeshOrientation_Rel2Hub``): x_l the shaft axis (downwind),
z_l the node's position projected onto the rotor plane (radial), y_l = z_l x x_l (against the rotation). The
relative wind is resolved there (Vx, Vy), and the section's orientation relative to it is AeroDyn's Euler triple
(``TwistToeCant_FromLocalPolar``): R_sl = R(-theta about z) R(cant about y) R(toe about x), so that the untwisted
section axes in polar components are

    x' = (cos b, sin b sin t, -sin b cos t)    chord normal, downwind       (b the cant, t the toe)
    y' = (0, cos t, sin t)                      towards the trailing edge
    z' = (sin b, -cos b sin t, cos b cos t)     span axis

and twist-plus-pitch theta turns the chord within the x'-y' plane. The BEM works in the polar frame with the
inflow angle phi of (Vx cos b (1 - a), Vy (1 + a')) (``ComputePhiWithInduction``); the airfoil sees that inflow
projected onto its own plane (``computeAirfoilOperatingAOA``): the unit inflow (sin phi_N, cos phi_N, 0),
tan phi_N = tan phi / cos b, without its span component, at the angle :func:`section_angle` from y' about z', so
alpha = section_angle - theta. The momentum equations take the chord-frame coefficients back to the polar frame
(``Transform_ClCdCm_to_CxCyCzCmxCmyCmz``, :func:`polar_coefficients`). With b = t = 0 everything reduces to the
plane formulas (section_angle = phi, cn = cl cos phi + cd sin phi, ct = cl sin phi - cd cos phi).

The frame of each node (:func:`projection`): AeroDyn's two projections (``AeroProjMod``), chosen by ``BEM_Mod``
(``BEMOptions.formulation``).

Legacy (BEM_Mod 1, ``NoSweepPitchTwist``): vx along the section's downwind normal n (the coned blade's i1 turned
by the out-of-plane slope), vy against the rotation e_t; the section is plane in that frame (cant 0, toe 0,
dr/dz 1).

Polar (BEM_Mod 2, ``APM_BEM_Polar``; AeroDyn.f90 ``SetInputsForBEMT``, ``Calculate_MeshOrientation_Rel2Hub``,
``TwistToeCant_FromLocalPolar``): the node's local polar frame x_l = the shaft axis, z_l = the node's position
from the apex projected onto the rotor plane and normalised, y_l = z_l x x_l; vx = V . x_l, vy = V . y_l. The
untwisted section axes (n, -e_t, s; s the deflected span axis) in that frame give AeroDyn's Euler angles
R = R_y(cant) R_x(toe) (above): sin(cant) = s . x_l over the chord-normal's part
(cant = atan2(s . x_l, n . x_l)), toe = atan2(-e_t . z_l, -e_t . y_l) (the node's position off the blade's
radial line: in-plane deflection and the aerodynamic-centre sweep). There is no twist part: e_t is normal to the
shaft, so the section's twist stays ``theta``. The annulus factor dr/dz = |dr_proj| / |dr| of the segment from the
previous node (the first node takes the second's).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ._jit import kernel
from .options import AI_DRAG, TI_DRAG


@kernel
def section_angle(phi, cant, toe):
    """The inflow angle in the untwisted section's own plane (rad): atan2(u . x', u . y') of the polar frame's
    unit inflow u at angle phi, turned by the cant (tan phi_N = tan phi / cos cant); phi itself for cant = toe = 0.
    The angle is taken with atan2 where AeroDyn takes an arccosine and a sign (the same angle, without the
    arccosine's loss of precision near zero)."""
    if cant == 0.0 and toe == 0.0:
        return phi
    return framed_angle(phi, math.sin(phi), math.cos(phi), cant, toe, math.cos(cant), math.sin(cant), math.cos(toe),
                        math.sin(toe))


@kernel
def framed_angle(phi, sin_phi, cos_phi, cant, toe, cb, sb, ct, st):
    """:func:`section_angle` with sin and cos of phi, the cant b and the toe t given (a root solve computes those of
    the section once)."""
    if cant == 0.0 and toe == 0.0:
        return phi
    s, c = sin_phi, cos_phi * cb                              # (sin phi_N, cos phi_N) times a positive factor
    return math.atan2(cb * s + sb * st * c, ct * c)


@kernel
def polar_coefficients(alpha, theta, cant, toe, cl, cd, options):
    """(Cx, Cy): the section's force coefficients along x_l (normal to the rotor plane) and along -y_l (in the
    plane, towards the leading edge) for cl, cd at the angle of attack alpha, the chord turned by theta, drag only
    with AIDrag (normal to the chord) / TIDrag (along it), as AeroDyn's momentum balance takes them."""
    return framed_coefficients(alpha, cl, cd, options, math.cos(theta), math.sin(theta), math.cos(cant),
                               math.sin(cant), math.cos(toe), math.sin(toe))


@kernel
def framed_coefficients(alpha, cl, cd, options, cw, sw, cb, sb, ct, st):
    """:func:`polar_coefficients` with cos and sin of theta (w), the cant (b) and the toe (t) given."""
    cn = cl * math.cos(alpha) + (cd * math.sin(alpha) if options[AI_DRAG] != 0.0 else 0.0)
    ca = -cl * math.sin(alpha) + (cd * math.cos(alpha) if options[TI_DRAG] != 0.0 else 0.0)
    # chord normal x_s = cos(theta) x' - sin(theta) y', chord y_s = sin(theta) x' + cos(theta) y'
    cx = cb * (cn * cw + ca * sw)
    cy = -(cn * (cw * sb * st - sw * ct) + ca * (sw * sb * st + cw * ct))
    return cx, cy


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
    on_axis = np.linalg.norm(radial, axis=-1, keepdims=True) == 0.0   # a node on the shaft (hub radius 0): the
    outward = np.where(on_axis, span - (span @ shaft)[..., None] * shaft, radial)   # section's span axis points out
    z_l = outward / np.linalg.norm(outward, axis=-1, keepdims=True)
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
