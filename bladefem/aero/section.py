"""The loads of a blade section for given induction factors (no solve): the inflow with the induced velocities, the
angle of attack at the section's own plane, the polar's coefficients and the forces per unit length they give.
:func:`bladefem.aero.bem.node_loads` ends with them after its solve; a right-hand side between two solves (the
induction held) takes them alone.
"""

from __future__ import annotations

import math

from ._jit import kernel
from .options import USE_CM
from .polar import section_inflow
from .polars import polar_lookup


@kernel
def section_loads(vx, vy, a, ap, chord, theta, airfoil, knots, values, coefs, start, count, options, air_density,
                  cant, toe):
    """Loads of a blade section for given induction factors a, a' (no solve): (phi, alpha, W, cl, cd, cm, fn, ft, m)
    as in :func:`bladefem.aero.bem.node_loads`; drag always included. About a tenth of a node solve: for right-hand
    sides evaluated between two solves with the induction held. A canted or toed section (cant, toe in rad, polar
    formulation) sees W from (vx cos(cant) (1 - a), vy (1 + a')) at its own angle
    (:func:`bladefem.aero.polar.section_angle`), and fn, ft act along its untwisted chord normal and against y'
    (AeroDyn's loads in the airfoil frame turned back by the section's orientation)."""
    return framed_section_loads(vx, vy, a, ap, chord, theta, airfoil, knots, values, coefs, start, count, options,
                                air_density, math.cos(cant), math.sin(cant), math.cos(toe), math.sin(toe))


@kernel
def framed_section_loads(vx, vy, a, ap, chord, theta, airfoil, knots, values, coefs, start, count, options,
                         air_density, cb, sb, ct, st):
    """:func:`section_loads` with the cosines and sines of the cant (b) and the toe (t) given."""
    x, y = vx * cb * (1.0 - a), vy * (1.0 + ap)
    phi = math.atan2(x, y) if (x != 0.0 or y != 0.0) else 0.0
    inflow, s, c = section_inflow(phi, x, y, cb, sb, ct, st)
    alpha = inflow - theta
    cl, cd, cm = polar_lookup(alpha, airfoil, knots, values, coefs, start, count)
    w = math.sqrt(x * x + y * y)
    q = 0.5 * air_density * w * w
    fn = q * chord * (cl * c + cd * s)
    ft = q * chord * (cl * s - cd * c)
    m = q * chord * chord * cm if options[USE_CM] != 0.0 else 0.0
    return phi, alpha, w, cl, cd, cm, fn, ft, m
