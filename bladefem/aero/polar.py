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
"""

from __future__ import annotations

import math

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
    cb, sb, ct, st = math.cos(cant), math.sin(cant), math.cos(toe), math.sin(toe)
    s, c = math.sin(phi), math.cos(phi) * cb                  # (sin phi_N, cos phi_N) times a positive factor
    return math.atan2(cb * s + sb * st * c, ct * c)


@kernel
def polar_coefficients(alpha, theta, cant, toe, cl, cd, options):
    """(Cx, Cy): the section's force coefficients along x_l (normal to the rotor plane) and along -y_l (in the
    plane, towards the leading edge) for cl, cd at the angle of attack alpha, the chord turned by theta, drag only
    with AIDrag (normal to the chord) / TIDrag (along it), as AeroDyn's momentum balance takes them."""
    cn = cl * math.cos(alpha) + (cd * math.sin(alpha) if options[AI_DRAG] != 0.0 else 0.0)
    ca = -cl * math.sin(alpha) + (cd * math.cos(alpha) if options[TI_DRAG] != 0.0 else 0.0)
    cw, sw = math.cos(theta), math.sin(theta)
    cb, sb, ct, st = math.cos(cant), math.sin(cant), math.cos(toe), math.sin(toe)
    # chord normal x_s = cos(theta) x' - sin(theta) y', chord y_s = sin(theta) x' + cos(theta) y'
    cx = cb * (cn * cw + ca * sw)
    cy = -(cn * (cw * sb * st - sw * ct) + ca * (sw * sb * st + cw * ct))
    return cx, cy
