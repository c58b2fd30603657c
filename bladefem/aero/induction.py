"""The induction factors of the BEM equations as functions of the inflow angle phi, and the residual whose root is
the BEM solution (Ning 2014), in AeroDyn's two formulations (``BEMOptions.formulation``, AeroDyn's BEM_Mod).

With sigma' = B c / (2 pi r), cn = cl cos phi + cd sin phi and ct = cl sin phi - cd cos phi (drag only with
AIDrag / TIDrag) and F the Prandtl loss factor:

    k = sigma' cn / (4 F sin^2 phi),   k' = sigma' ct / (4 F sin phi cos phi)

Legacy (BEM_Mod 1): a = k / (1 + k) in the momentum region (phi > 0 for vx > 0) up to k = 2/3 (a = 0.4), Buhl's
empirical thrust above (a = (g1 - sqrt(g2)) / g3), a = k / (k - 1) in the propeller brake (phi < 0); a' = k' / (1 -
k'); residual sin phi / (1 - a) - cos phi (1 - k') vx / vy (propeller brake: sin phi (1 - k) - ...).

Polar (BEM_Mod 2): a = k / (1 + k) (vx > 0) up to a_c = min(0.35 / cos chi0, 0.5), above it the quadratic thrust
C_T(a) = c0 + c1 a + c2 a^2 joining 4 a (1 - a) F C1-smoothly at a_c and reaching 2 at a = 1, solved from
4 k F (1 - a)^2 = C_T(a); the tangential k' scaled by H = 4 a (1 - a) F / C_T(a) above a_c; losses only for
phi > 0; residual sin phi / (1 - a) - cos phi / (1 + a') vx / vy.
"""

from __future__ import annotations

import math

from ._jit import kernel
from .options import AI_DRAG, FORMULATION, HIGH_INDUCTION, HUB_LOSS, TAN_IND, TI_DRAG, TIP_LOSS

#: Stand-in for an infinite induction (AeroDyn's InductionLimit).
INDUCTION_LIMIT = 1e6
#: C_T at a = 1 of the polar formulation's empirical thrust.
THRUST_AT_ONE = 2.0


@kernel
def loss_factor(phi, tip_constant, hub_constant, options, cos_cant):
    """Prandtl's tip and hub loss F = F_tip F_hub at inflow angle phi; the constants are B (z_tip - z) / (2 z) and
    B (z - z_hub) / (2 z_hub). Kept above 1e-4 like AeroDyn; the polar formulation applies it only for phi > 0,
    with sin phi_N of the inflow angle in the plane normal to a blade canted by the angle whose cosine is
    ``cos_cant`` (AeroDyn's getNewPhi: tan phi_N = tan phi / cos(cant); 1 for an uncanted section)."""
    return framed_loss(phi, math.sin(phi), math.cos(phi), tip_constant, hub_constant, options, cos_cant)


@kernel
def framed_loss(phi, sin_phi, cos_phi, tip_constant, hub_constant, options, cos_cant):
    """:func:`loss_factor` with sin and cos of phi given."""
    s = abs(sin_phi)
    if cos_cant != 1.0:
        s = s / math.hypot(sin_phi, cos_phi * cos_cant)
    f = 1.0
    if s > 1e-12 and (options[FORMULATION] != 2.0 or phi > 0.0):
        if options[TIP_LOSS] != 0.0:
            f *= prandtl(tip_constant / s)
        if options[HUB_LOSS] != 0.0:
            f *= prandtl(hub_constant / s)
    return max(f, 1e-4)


@kernel
def prandtl(exponent):
    """2/pi acos(exp(-x)); exactly 1.0 in double precision beyond x = 37 (exp(-37) < 1e-16), returned without
    evaluating it."""
    if exponent > 37.0:
        return 1.0
    return 2.0 / math.pi * math.acos(min(1.0, math.exp(-exponent)))


@kernel
def buhl_induction(k, loss, momentum, high_induction):
    """(a, valid) of the legacy formulation: momentum theory, Buhl's thrust above a = 0.4, propeller brake."""
    if momentum:
        if k <= 2.0 / 3.0 or not high_induction:
            if k == -1.0:
                return -INDUCTION_LIMIT, False
            return k / (1.0 + k), k >= -1.0
        twice = 2.0 * loss * k
        g1 = twice - (10.0 / 9.0 - loss)
        g2 = twice - (4.0 / 3.0 - loss) * loss
        g3 = twice - (25.0 / 9.0 - 2.0 * loss)
        if abs(g3) < 1e-6:
            return 1.0 - 0.5 / math.sqrt(g2), True
        return (g1 - math.sqrt(abs(g2))) / g3, True
    if k == 1.0:
        return INDUCTION_LIMIT, False
    return k / (k - 1.0), k > 1.0


@kernel
def empirical_thrust(chi0, loss):
    """(a_c, c0, c1, c2) of the polar formulation's high-thrust curve C_T = c0 + c1 a + c2 a^2."""
    return thrust_curve(critical_induction(chi0), loss)


@kernel
def critical_induction(chi0):
    """a_c of the polar formulation's high-thrust curve in a wake skewed by chi0 (rad)."""
    yaw = abs(chi0)
    if abs(math.cos(yaw)) < 1e-12:
        yaw += 1.5e-8
    return min(0.35 / abs(math.cos(yaw)), 0.5)      # a wake skewed past 90 deg keeps the clipped 0.5


@kernel
def thrust_curve(ac, loss):
    """(a_c, c0, c1, c2) of :func:`empirical_thrust` for a_c given."""
    thrust_c = 4.0 * loss * ac * (1.0 - ac)
    slope_c = 4.0 * loss * (1.0 - 2.0 * ac)
    denom = ac * ac - 2.0 * ac + 1.0
    c0 = (THRUST_AT_ONE * ac * ac - 2.0 * thrust_c * ac + thrust_c + ac * ac * slope_c - ac * slope_c) / denom
    c1 = (-2.0 * THRUST_AT_ONE * ac + 2.0 * thrust_c * ac - ac * ac * slope_c + slope_c) / denom
    c2 = (THRUST_AT_ONE - thrust_c + ac * slope_c - slope_c) / denom
    return ac, c0, c1, c2


@kernel
def polar_axial_induction(phi, vx, k, loss, critical, high_induction):
    """(a, H) of the polar formulation: momentum theory up to a_c (``critical``, :func:`critical_induction`), the
    empirical quadratic thrust above."""
    ac, c0, c1, c2 = thrust_curve(critical, loss)
    if k <= ac / (1.0 - ac) or not high_induction:
        if vx > 0.0:
            return (-INDUCTION_LIMIT if k == -1.0 else k / (k + 1.0)), 1.0
        return (INDUCTION_LIMIT if k == 1.0 else k / (k - 1.0)), 1.0
    big = 4.0 * loss * k
    y1 = 2.0 * big + c1
    y2 = max(4.0 * big * (c2 + c1 + c0) + c1 * c1 - 4.0 * c0 * c2, 0.0)
    y3 = 2.0 * (big - c2)
    if y3 == 0.0:
        a = 1.0 - 1.0 / (2.0 * math.sqrt(y2))
    elif phi >= 0.0:
        a = (y1 - math.sqrt(y2)) / y3
    else:
        a = (y1 + math.sqrt(y2)) / y3
    thrust = c0 + c1 * a + c2 * a * a
    if ac < a <= 1.0:
        return a, 4.0 * a * (1.0 - a) * loss / thrust
    if a > 1.0:
        return a, -4.0 * a * (1.0 - a) * loss / thrust
    return a, 1.0


@kernel
def plane_coefficients(sin_phi, cos_phi, cl, cd, options):
    """(cn, ct): the section's force coefficients normal to the rotor plane and in it (towards the leading edge) at
    the inflow angle phi (its sine and cosine), drag only with AIDrag / TIDrag (AeroDyn's Transform_ClCd_to_CxCy)."""
    s, c = sin_phi, cos_phi
    return cl * c + (cd * s if options[AI_DRAG] != 0.0 else 0.0), cl * s - (cd * c if options[TI_DRAG] != 0.0 else 0.0)


@kernel
def induction(phi, vx, vy, solidity, cn, ct, loss, chi0, options):
    """(residual, a, a', valid) of the BEM equations at inflow angle phi for the force coefficients cn (normal to
    the rotor plane, times dr/dz in the polar formulation) and ct (in the plane)."""
    return framed_induction(phi, math.sin(phi), math.cos(phi), vx, vy, solidity, cn, ct, loss,
                            critical_induction(chi0), options)


@kernel
def framed_induction(phi, s, c, vx, vy, solidity, cn, ct, loss, critical, options):
    """:func:`induction` with sin and cos of phi (s, c) and the polar formulation's a_c (``critical``,
    :func:`critical_induction` of the skew angle) given."""
    k = solidity * cn / (4.0 * loss * s * s)
    polar = options[FORMULATION] == 2.0
    momentum = polar or (phi > 0.0 and vx >= 0.0) or (phi < 0.0 and vx < 0.0)
    if polar:
        a, scale = polar_axial_induction(phi, vx, k, loss, critical, options[HIGH_INDUCTION] != 0.0)
        valid = True
    else:
        a, valid = buhl_induction(k, loss, momentum, options[HIGH_INDUCTION] != 0.0)
        scale = 1.0
    kp, ap = 0.0, 0.0
    if options[TAN_IND] != 0.0:
        if abs(c) < 1e-12:
            kp = math.copysign(INDUCTION_LIMIT, ct * s) * math.copysign(1.0, vx)
            ap = -1.0
        else:
            kp = scale * solidity * ct / (4.0 * loss * s * c)
            if vx < 0.0:
                kp = -kp
            ap = math.copysign(INDUCTION_LIMIT, 1.0 - kp) if kp == 1.0 else kp / (1.0 - kp)
    inverse_speed_ratio = vx / vy
    if not momentum:
        return s * (1.0 - k) - c * inverse_speed_ratio * (1.0 - kp), a, ap, valid
    if a == 1.0:
        return -c * inverse_speed_ratio * (1.0 - kp), a, ap, valid
    return s / (1.0 - a) - c * inverse_speed_ratio * (1.0 - kp), a, ap, valid
