"""Quasi-steady blade-element momentum theory at one blade node, solved in the inflow angle.

Ning's one-equation method (S. A. Ning, "A simple solution method for the blade element momentum equations with
guaranteed convergence", Wind Energy 17:1327-1345, 2014), as AeroDyn's BEMT uses it. For the local velocity
components ``vx`` (normal to the rotor plane of the coned blade, positive downwind) and ``vy`` (in the plane of
rotation, positive from the leading towards the trailing edge, i.e. opposite to the blade motion), the induction
factors follow from the inflow angle phi alone:

    sigma' = B c / (2 pi r)                          local solidity
    cn = cl cos phi + cd sin phi,  ct = cl sin phi - cd cos phi     (drag only if AIDrag / TIDrag)
    F = F_tip F_hub,  F_tip = 2/pi acos(exp(-B (z_tip - z) / (2 z |sin phi|))),
                      F_hub = 2/pi acos(exp(-B (z - z_hub) / (2 z_hub |sin phi|)))    Prandtl
    k = sigma' cn / (4 F sin^2 phi),  k' = sigma' ct / (4 F sin phi cos phi)
    a = k / (1 + k)                                  momentum region, k <= 2/3 (a <= 0.4)
    a = (g1 - sqrt(g2)) / g3                         Buhl's high-induction thrust curve, k > 2/3
    a = k / (k - 1)                                  propeller-brake region (phi < 0 for vx > 0)
    a' = k' / (1 - k')                               tangential induction (TanInd)

and the residual  R(phi) = sin phi / (1 - a) - cos phi (1 - k') vx / vy  (propeller brake:
sin phi (1 - k) - cos phi (1 - k') vx / vy) has a sign change on one of the intervals (0, pi/2], [-pi/4, 0),
(pi/2, pi) (mirrored for vx < 0), where Brent's method finds it: the solve cannot fail to converge.

After the solve the axial induction is redistributed for a skewed wake (Glauert/Pitt-Peters, AeroDyn's SkewMod 2 /
Skew_Mod 1):  a <- a (1 + K tan(chi / 2) (r / R) cos psi),  chi = (1 + 0.6 a) chi0,  K = 15 pi / 32, psi the angle
between the blade and the most downwind direction of the rotor plane. The loads then follow from the induced
velocities: W^2 = (vx (1 - a))^2 + (vy (1 + a'))^2, phi = atan2(vx (1 - a), vy (1 + a')), alpha = phi - theta.
"""

from __future__ import annotations

import math

import numpy as np

from ._jit import kernel
from .induction import critical_induction, framed_induction, framed_loss, loss_factor, plane_coefficients
from .options import (
    FORMULATION,
    HUB_LOSS,
    INDUCTION,
    MAX_ITER,
    SKEW_FACTOR,
    SKEW_REDISTRIBUTION,
    TIP_LOSS,
    TOLERANCE,
)
from .polar import framed_coefficients, section_inflow
from .section import framed_section_loads
from .polars import polar_lookup

#: A velocity component below this counts as zero (AeroDyn's VelocityIsZero), m/s.
ZERO_VELOCITY = 1e-3
#: Distance of the bracket ends from the singular angles 0 and pi/2, rad.
EDGE = 1e-6
#: AeroDyn's limits on the induction factors (BEMT_MinInduction, BEMT_MaxInduction).
A_MIN, A_MAX, AP_MIN, AP_MAX = -1.0, 1.5, -1.0, 1.0
#: Brent's first trial point in the momentum region is atan2(vx cos(cant) PREDICTED_FACTOR, vy), the inflow angle at
#: the axial induction a = 1/3 of an ideal rotor (Betz), without tangential induction.
PREDICTED_FACTOR = 2.0 / 3.0
#: The search next to a node's previous root (:func:`local_root`): its first step is this many times the Newton step
#: of a unit slope (the residual's slope dR/dphi at the NREL 5MW's roots from cut-in to cut-out: 0.89 to 6.95,
#: median 1.27, so the step mostly overshoots the root and brackets it), and so is each secant step after it, at
#: most :data:`LOCAL_GROWTH` times the step before, in at most :data:`LOCAL_TRIALS` trials.
LOCAL_OVERSHOOT = 1.5
LOCAL_GROWTH = 4.0
LOCAL_TRIALS = 4
#: Number of values :func:`node_loads` returns.
NODE_OUTPUTS = 13


@kernel
def residual(phi, vx, vy, solidity, theta, tip_constant, hub_constant, chi0, airfoil, knots, values, coefs, start,
             count, options, geometry):
    """(residual, a, a', valid) at phi with the polar looked up at alpha = phi - theta; in the polar formulation
    at the section's own angle (:mod:`bladefem.aero.polar`) with the momentum balance on vx cos(cant) and the
    normal coefficient times dr/dz. ``geometry`` = (cant, toe, dr/dz) of the node (0, 0, 1: a plane section)."""
    return framed_residual(phi, vx, vy, solidity, theta, tip_constant, hub_constant, chi0, airfoil, knots, values,
                           coefs, start, count, options, section_frame(theta, chi0, angle_geometry(*geometry)))


@kernel
def angle_geometry(cant, toe, drdz):
    """A node's geometry as the solve takes it, (cos and sin of the cant, cos and sin of the toe, dr/dz), from its
    angles (rad): the cant and the toe enter the BEM only through their cosines and sines, which the compiled loads
    take from the section's axes without an angle (:func:`bladefem.aero.polar.euler_frame`)."""
    return math.cos(cant), math.sin(cant), math.cos(toe), math.sin(toe), drdz


@kernel
def section_frame(theta, chi0, geometry):
    """What the residual of one node takes at every angle, computed once a solve, for its ``geometry``
    (:func:`angle_geometry`): (cos and sin of the cant and the toe, dr/dz, cos and sin of theta, a_c of the polar
    formulation's thrust curve)."""
    cb, sb, ct, st, drdz = geometry
    return cb, sb, ct, st, drdz, math.cos(theta), math.sin(theta), critical_induction(chi0)


@kernel
def framed_residual(phi, vx, vy, solidity, theta, tip_constant, hub_constant, chi0, airfoil, knots, values, coefs,
                    start, count, options, frame):
    """:func:`residual` with the node's :func:`section_frame`."""
    s, c = math.sin(phi), math.cos(phi)
    if options[FORMULATION] != 2.0:
        cl, cd, _ = polar_lookup(phi - theta, airfoil, knots, values, coefs, start, count)
        cn, ct = plane_coefficients(s, c, cl, cd, options)
        loss = framed_loss(phi, s, c, tip_constant, hub_constant, options, 1.0)
        return framed_induction(phi, s, c, vx, vy, solidity, cn, ct, loss, frame[7], options)
    cb, sb, ct_, st, drdz, cw, sw, critical = frame
    inflow, sin_inflow, cos_inflow = section_inflow(phi, s, c, cb, sb, ct_, st)
    cl, cd, _ = polar_lookup(inflow - theta, airfoil, knots, values, coefs, start, count)
    cn, ct = framed_coefficients(cos_inflow * cw + sin_inflow * sw, sin_inflow * cw - cos_inflow * sw, cl, cd,
                                 options, cw, sw, cb, sb, ct_, st)
    loss = framed_loss(phi, s, c, tip_constant, hub_constant, options, cb)
    return framed_induction(phi, s, c, vx * cb, vy, solidity, cn * drdz, ct, loss, critical, options)


@kernel
def brent(lo, hi, f_lo, f_hi, vx, vy, solidity, theta, tip_constant, hub_constant, chi0, airfoil, knots, values,
          coefs, start, count, options, frame, first):
    """Root of the residual in [lo, hi] (f_lo, f_hi of opposite signs) by Brent's method (inverse quadratic
    interpolation, secant and bisection); stops at |R| <= tolerance or a bracket narrower than 1e-13 rad.
    ``frame``: the node's :func:`section_frame`; ``first``: the first trial point, inside (lo, hi) (nan: Brent's
    own step from the ends). Returns (phi, a, a', valid) at the root."""
    args = (vx, vy, solidity, theta, tip_constant, hub_constant, chi0, airfoil, knots, values, coefs, start, count,
            options, frame)
    tolerance = options[TOLERANCE]
    a, b, fa, fb = lo, hi, f_lo, f_hi
    c, fc = b, fb
    d = e = b - a
    at_b, induced_a, induced_ap, valid = False, 0.0, 0.0, False
    for _ in range(int(options[MAX_ITER])):
        if (fb > 0.0) == (fc > 0.0):
            c, fc = a, fa
            d = e = b - a
        if abs(fc) < abs(fb):
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
            at_b = False
        step_tolerance = 4.0e-16 * abs(b) + 0.5e-13
        half = 0.5 * (c - b)
        if abs(half) <= step_tolerance or abs(fb) <= tolerance:
            break
        if math.isfinite(first):
            d = e = first - b
        elif abs(e) >= step_tolerance and abs(fa) > abs(fb):
            s = fb / fa
            if a == c:
                p, q = 2.0 * half * s, 1.0 - s
            else:
                q, r = fa / fc, fb / fc
                p = s * (2.0 * half * q * (q - r) - (b - a) * (r - 1.0))
                q = (q - 1.0) * (r - 1.0) * (s - 1.0)
            if p > 0.0:
                q = -q
            p = abs(p)
            if 2.0 * p < min(3.0 * half * q - abs(step_tolerance * q), abs(e * q)):
                e, d = d, p / q
            else:
                d = e = half
        else:
            d = e = half
        a, fa = b, fb
        b += d if abs(d) > step_tolerance else math.copysign(step_tolerance, half)
        fb, induced_a, induced_ap, valid = framed_residual(b, *args)
        first = math.nan
        at_b = True
    if not at_b:
        _, induced_a, induced_ap, valid = framed_residual(b, *args)
    return b, induced_a, induced_ap, valid


@kernel
def local_root(guess, lo, hi, rising, tolerance, args):
    """(phi, a, a', found): a root of the residual (|R| <= ``tolerance``, or Brent's bracket) next to ``guess``
    (a node's root at the previous right-hand side, inside the momentum interval (lo, hi), rad), ``args`` those of
    :func:`framed_residual` after phi.

    The guess is evaluated and kept if it solves the equations; else a step of :data:`LOCAL_OVERSHOOT` times the
    Newton step of a unit slope (``rising``: +1 where the residual rises with phi through its root, vx > 0; -1 for
    the mirrored interval) looks for a sign change, then secant steps (each at most :data:`LOCAL_GROWTH` times the
    one before, within (lo, hi)), :data:`LOCAL_TRIALS` trials in all; Brent's method solves the bracket found. Not
    found (no bracket, or an invalid root): ``found`` False, the solve starts from scratch."""
    f_p, a_p, ap_p, valid_p = framed_residual(guess, *args)
    if abs(f_p) <= tolerance:
        return guess, a_p, ap_p, valid_p
    p = guess
    step = -LOCAL_OVERSHOOT * rising * f_p
    for _ in range(LOCAL_TRIALS):
        q = min(max(p + step, lo), hi)
        if q == p:
            break
        f_q, a_q, ap_q, valid_q = framed_residual(q, *args)
        if abs(f_q) <= tolerance:
            return q, a_q, ap_q, valid_q
        if (f_q > 0.0) != (f_p > 0.0):
            low, high, f_low, f_high = (p, q, f_p, f_q) if p < q else (q, p, f_q, f_p)
            return brent(low, high, f_low, f_high, *args, math.nan)
        if f_q == f_p:
            break
        secant = -LOCAL_OVERSHOOT * f_q * (q - p) / (f_q - f_p)
        growth = LOCAL_GROWTH * abs(q - p)
        step = min(max(secant, -growth), growth)
        p, f_p = q, f_q
    return guess, 0.0, 0.0, False


@kernel
def search_intervals(vx, angle):
    """The three phi intervals of Ning's method in AeroDyn's order (lower ends, upper ends): the momentum region
    first, then the propeller brake and the region beyond pi/2 (the one nearer ``angle`` first, rad)."""
    q, h = math.pi / 4.0, math.pi / 2.0
    near_zero = -q < angle < q
    if vx > 0.0:
        first = (EDGE, h - EDGE)
        brake, beyond = (-q, -EDGE), (h + EDGE, math.pi - EDGE)
    else:
        first = (-EDGE, -h + EDGE)
        brake, beyond = (q, EDGE), (-h - EDGE, -math.pi + EDGE)
    if near_zero:
        return (first[0], brake[0], beyond[0]), (first[1], brake[1], beyond[1])
    return (first[0], beyond[0], brake[0]), (first[1], beyond[1], brake[1])


@kernel
def solve_inflow_angle(vx, vy, solidity, theta, tip_constant, hub_constant, chi0, airfoil, knots, values, coefs,
                       start, count, options, guess, geometry):
    """(phi, valid, a, a'): the inflow angle solving the BEM equations (rad) and the induction there.

    A finite ``guess`` inside the momentum interval (the node's valid root at the previous right-hand side) is
    searched from first (:func:`local_root`): the root bracketed next to it, in the momentum region only, 3.44
    residual evaluations a solve over the NREL 5MW's 100 s torque-law run against 5.31 from the interval's ends
    (docs/turbine-aero.md#speed). As AeroDyn keeps a previous solution that still solves the equations, this keeps
    a momentum-region root next to the previous one where the region holds several (stall: a stalled section keeps
    its branch). A guess elsewhere is not searched from (a bracket next to a propeller-brake root kept BEM_Mod 1's
    nodes there though the momentum region had a root, and lost 14-29 % of the NREL 5MW's loads).
    Without a guess, or without a root next to it, the solve starts from scratch as AeroDyn's
    ``BEMT_UnCoupledSolve``: Ning's three intervals are searched (ordered by the geometric angle) and Brent's
    method runs on the first with a sign change, in the momentum region from the inflow angle of a Betz rotor
    (:data:`PREDICTED_FACTOR`, a point computed from the node's inputs alone: the secant from the ends lands near
    pi/2 and bisections follow). Without a valid BEM solution: the geometric angle atan2(vx cos(cant), vy), valid
    False and zero induction (as AeroDyn)."""
    if abs(vx) < ZERO_VELOCITY:
        return 0.0, True, 0.0, 0.0
    if abs(vy) < ZERO_VELOCITY:
        return math.copysign(math.pi / 2.0, vx), True, 0.0, 0.0
    frame = section_frame(theta, chi0, geometry)
    cos_cant = frame[0]
    args = (vx, vy, solidity, theta, tip_constant, hub_constant, chi0, airfoil, knots, values, coefs, start, count,
            options, frame)
    tolerance = options[TOLERANCE]
    momentum_lo, momentum_hi = (EDGE, math.pi / 2.0 - EDGE) if vx > 0.0 else (EDGE - math.pi / 2.0, -EDGE)
    if momentum_lo < guess < momentum_hi:         # the momentum region of search_intervals (its first)
        phi, a, ap, found = local_root(guess, momentum_lo, momentum_hi, math.copysign(1.0, vx), tolerance, args)
        if found:
            return phi, True, a, ap
    lows, highs = search_intervals(vx, math.atan2(vx, vy))
    for i in range(3):
        lo, hi = lows[i], highs[i]
        f_lo, a_lo, ap_lo, valid_lo = framed_residual(lo, *args)
        f_hi, a_hi, ap_hi, valid_hi = framed_residual(hi, *args)
        if abs(f_lo) < tolerance:                      # an end of the interval is already a root
            if abs(f_hi) < abs(f_lo) and valid_hi:
                return hi, True, a_hi, ap_hi
            if valid_lo:
                return lo, True, a_lo, ap_lo
        elif abs(f_hi) < tolerance and valid_hi:
            return hi, True, a_hi, ap_hi
        if (f_lo > 0.0) != (f_hi > 0.0):
            first = math.atan2(vx * cos_cant * PREDICTED_FACTOR, vy) if i == 0 else math.nan
            if not min(lo, hi) < first < max(lo, hi):
                first = math.nan
            phi, a, ap, valid = brent(lo, hi, f_lo, f_hi, *args, first)
            if valid:
                return phi, True, a, ap
    return math.atan2(vx * cos_cant, vy), False, 0.0, 0.0


@kernel
def skewed_wake(a, loss, chi0, tip_ratio, skew_cos, options):
    """Axial induction redistributed over the azimuth for a wake skewed by chi0 (Glauert/Pitt-Peters)."""
    chi = (0.6 * a + 1.0) * abs(chi0)
    chi = chi - 2.0 * math.pi * math.floor((chi + math.pi) / (2.0 * math.pi))
    half_tangent = math.copysign(1.0, chi) if abs(chi) > math.pi / 2.0 else math.tan(0.5 * chi)
    weight = loss if options[FORMULATION] == 2.0 else 1.0
    return a * (1.0 + options[SKEW_FACTOR] * weight * half_tangent * tip_ratio * skew_cos)


@kernel
def node_loads(vx, vy, r_local, chord, theta, tip_constant, hub_constant, n_blades, tip_ratio, chi0, skew_cos,
               induction_weight, airfoil, knots, values, coefs, start, count, options, air_density, guess, cant, toe,
               drdz):
    """Quasi-steady BEM loads at one blade node.

    Inputs (SI, rad): vx, vy the relative velocity of the air at the node without induction (wind minus structural
    velocity) normal to the coned rotor plane (downwind) and in the plane of rotation (towards the trailing edge);
    r_local distance from the rotor axis; chord; theta local twist plus pitch (alpha = phi - theta);
    tip_constant B (z_tip - z) / (2 z) and hub_constant B (z - z_hub) / (2 z_hub) with z the distance from the rotor
    centre along the blade; n_blades; tip_ratio r_local / R_tip, chi0 the wake skew angle and skew_cos the cosine of
    the angle between the blade and the most downwind direction (skewed-wake model); induction_weight (1, or
    AeroDyn's low-tip-speed-ratio blend); airfoil the polar index; the packed polars; the option vector;
    air_density; guess the previous phi (nan for none); in the polar formulation (BEM_Mod 2, vx and vy then in
    AeroDyn's local polar frame) the section's cant and toe (rad) and dr/dz of the annulus (0, 0, 1 otherwise;
    :mod:`bladefem.aero.polar`).

    Returns (phi_solved, a, a', phi, alpha, W, cl, cd, cm, fn, ft, m, valid): fn the force per unit length along
    +x (downwind normal), ft along the direction of rotation (-y), m the pitching moment per unit length (N m/m,
    nose up) — in the polar formulation fn along the untwisted section's chord normal x' and ft along -y' —;
    phi_solved is the root of the BEM equations (keep it as the next guess), phi the inflow angle after the skew
    correction.
    """
    return framed_node_loads(vx, vy, r_local, chord, theta, tip_constant, hub_constant, n_blades, tip_ratio, chi0,
                             skew_cos, induction_weight, airfoil, knots, values, coefs, start, count, options,
                             air_density, guess, angle_geometry(cant, toe, drdz))


@kernel
def framed_node_loads(vx, vy, r_local, chord, theta, tip_constant, hub_constant, n_blades, tip_ratio, chi0,
                      skew_cos, induction_weight, airfoil, knots, values, coefs, start, count, options, air_density,
                      guess, geometry):
    """:func:`node_loads` for the node's :func:`angle_geometry`."""
    phi_solved, valid, fixed, a, ap = node_induction(vx, vy, r_local, chord, theta, tip_constant, hub_constant,
                                                     n_blades, chi0, airfoil, knots, values, coefs, start, count,
                                                     options, guess, geometry)
    a, ap, phi, alpha, w, cl, cd, cm, fn, ft, m = induced_loads(
        vx, vy, a, ap, phi_solved, valid, fixed, chord, theta, tip_constant, hub_constant, tip_ratio, chi0,
        skew_cos, induction_weight, airfoil, knots, values, coefs, start, count, options, air_density, geometry)
    return phi_solved, a, ap, phi, alpha, w, cl, cd, cm, fn, ft, m, valid


@kernel
def node_induction(vx, vy, r_local, chord, theta, tip_constant, hub_constant, n_blades, chi0, airfoil, knots,
                   values, coefs, start, count, options, guess, geometry):
    """The quasi-steady induction of one node (its :func:`angle_geometry`) before the skew redistribution and the
    low tip-speed-ratio blend (the dynamic wake's input, AeroDyn's ``calculate_Inductions_from_BEMT``):
    (phi_solved, valid, fixed, a, a'), a and a' within AeroDyn's limits; ``fixed``: a node at the tip or hub with
    loss (no flow through it, a = 1)."""
    solidity = n_blades * chord / (2.0 * math.pi * r_local)
    fixed = ((options[TIP_LOSS] != 0.0 and tip_constant == 0.0)
             or (options[HUB_LOSS] != 0.0 and hub_constant == 0.0))
    if options[INDUCTION] == 0.0:
        return math.atan2(vx * geometry[0], vy), True, False, 0.0, 0.0
    if fixed:
        return math.atan2(vx * geometry[0], vy), True, True, 1.0, 0.0
    phi_solved, valid, a, ap = solve_inflow_angle(vx, vy, solidity, theta, tip_constant, hub_constant, chi0,
                                                  airfoil, knots, values, coefs, start, count, options, guess,
                                                  geometry)
    return phi_solved, valid, False, min(max(a, A_MIN), A_MAX), min(max(ap, AP_MIN), AP_MAX)


@kernel
def induced_loads(vx, vy, a, ap, phi_solved, valid, fixed, chord, theta, tip_constant, hub_constant, tip_ratio,
                  chi0, skew_cos, induction_weight, airfoil, knots, values, coefs, start, count, options, air_density,
                  geometry):
    """The loads of a node (its :func:`angle_geometry`) with the induction a, a' (quasi-steady or filtered by the
    dynamic wake) after the skewed-wake redistribution (for a valid solution with both velocities nonzero) and
    the low tip-speed-ratio blend (a fixed node keeps a = 1): (a, a', phi, alpha, W, cl, cd, cm, fn, ft, m) as
    :func:`node_loads`."""
    if options[INDUCTION] != 0.0 and not fixed:
        if valid and abs(vx) >= ZERO_VELOCITY and abs(vy) >= ZERO_VELOCITY:
            if options[SKEW_REDISTRIBUTION] != 0.0:
                loss = loss_factor(phi_solved, tip_constant, hub_constant, options, geometry[0])
                a = skewed_wake(a, loss, chi0, tip_ratio, skew_cos, options)
        a, ap = a * induction_weight, ap * induction_weight
    phi, alpha, w, cl, cd, cm, fn, ft, m = framed_section_loads(
        vx, vy, a, ap, chord, theta, airfoil, knots, values, coefs, start, count, options, air_density, geometry[0],
        geometry[1], geometry[2], geometry[3])
    return a, ap, phi, alpha, w, cl, cd, cm, fn, ft, m


@kernel
def filtered_induction(vx, vy, axial, tangential):
    """a, a' of the dynamic wake's induced velocities (m/s; ``axial`` slows vx, ``tangential`` adds to vy), zero
    where the velocity is zero, within AeroDyn's limits (``calculate_Inductions_from_DBEMT``)."""
    a = axial / vx if vx != 0.0 else 0.0
    ap = tangential / vy if vy != 0.0 else 0.0
    return min(max(a, A_MIN), A_MAX), min(max(ap, AP_MIN), AP_MAX)


@kernel
def solve_nodes(vx, vy, r_local, chord, theta, tip_constant, hub_constant, n_blades, tip_ratio, chi0, skew_cos,
                induction_weight, airfoil, knots, values, coefs, start, count, options, air_density, guess, cant, toe,
                drdz, out):
    """:func:`node_loads` at every node of flat arrays (scalars n_blades, induction_weight, air_density shared);
    row i of ``out`` (n, NODE_OUTPUTS) receives node i's outputs in :func:`node_loads` order (valid as 1.0/0.0)."""
    for i in range(vx.shape[0]):
        phi_solved, a, ap, phi, alpha, w, cl, cd, cm, fn, ft, m, valid = node_loads(
            vx[i], vy[i], r_local[i], chord[i], theta[i], tip_constant[i], hub_constant[i], n_blades, tip_ratio[i],
            chi0[i], skew_cos[i], induction_weight, airfoil[i], knots, values, coefs, start, count, options,
            air_density, guess[i], cant[i], toe[i], drdz[i])
        out[i, 0], out[i, 1], out[i, 2], out[i, 3], out[i, 4] = phi_solved, a, ap, phi, alpha
        out[i, 5], out[i, 6], out[i, 7], out[i, 8] = w, cl, cd, cm
        out[i, 9], out[i, 10], out[i, 11], out[i, 12] = fn, ft, m, 1.0 if valid else 0.0


def plane_geometry(n: int) -> tuple:
    """(cant, toe, dr/dz) arrays of ``n`` plane sections (0, 0, 1) for :func:`solve_nodes`: the legacy
    projection, and the polar one for sections normal to the rotor plane."""
    return np.zeros(n), np.zeros(n), np.ones(n)
