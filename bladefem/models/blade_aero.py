"""Quasi-steady aerodynamic damping and stiffness of the rotating blade's sections, with the induction frozen at the
operating point (the induced velocities held, as OpenFAST's linearization with a frozen wake).

At an operating point (wind speed, rotor speed, pitch) the BEM of :mod:`bladefem.aero` gives, at each AeroDyn node,
the relative velocity normal to the coned rotor plane ``X = vx (1 - a)`` (downwind) and in it ``Y = vy (1 + a')``
(towards the trailing edge), the angle of attack and the polar there. A section's loads per length are the force
``(0, ft, fn)`` at its aerodynamic centre ``s_ac`` (``(0, -BlSwpAC, BlCrvAC)`` pitched, from the reference axis:
:func:`aerodynamic_centres`) and the pitching moment ``m`` about the
span axis (:func:`bladefem.aero.bem.node_loads`):

    fn = q c (cl cos phi + cd sin phi),  ft = q c (cl sin phi - cd cos phi),  m = q c^2 cm,
    q = rho W^2 / 2,  W^2 = X^2 + Y^2,  phi = atan2(X, Y),  alpha = phi - theta + phi_e

with ``phi_e`` the elastic twist (positive turns the leading edge downwind, raising alpha). The motion ``d`` of the
section (kinematic vector) moves the centre by ``N_ac d``, ``N_ac = [I, -[s_ac]x]``; its air velocity changes by
``-(N_ac dd/dt + Omega a x N_ac d)`` (own velocity, and the rotation of the displaced point), so that
``(dX, dY) = -E (N_ac dd/dt + Omega [a]x N_ac d)`` with ``X = V.e_z``, ``Y = -V.e_y``. Linearized, the generalized
forces ``Q = [N_ac; e_phi]^T (F, m)`` give the damping ``D = -dQ/d(dd/dt)`` and stiffness ``K_a = -dQ/dd`` per
length; they enter the quadratic eigenproblem as ``lambda D`` and ``K_a``. Neglected: the tilt of the section plane
by the bending slopes (the wind's span component ``U sin(beta)`` and the turning of the load direction), unsteady
aerodynamics and the change of induction (frozen).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from skfem import Basis

from ..aero.performance import performance_at
from ..aero.polar import pitched_offsets
from ..aero.rotor import Inflow, Rotor
from ..assembly import BladeMatrices, span_mesh
from ..assembly.blade import QUADRATURE_ORDER
from ..assembly.forms import assemble_terms
from ..assembly.parameters import AeroParameters
from ..assembly.terms import aerodynamic_damping, aerodynamic_stiffness
from ..elements import beam_element, skew
from ..sections import AxisFrame, Blade

#: step of the central difference for the polars' slopes, rad (linear polars: the slope of the interval)
SLOPE_STEP = 1e-6


@dataclass(frozen=True)
class AeroOperatingPoint:
    """Section aerodynamics at one operating point, per AeroDyn node (SI, rad).

    span : node positions from the blade root (BlSpn; on a curved axis its arc length there), m; chord : m;
    centre : the aerodynamic centres' arms from the sections' reference points (3, nodes), m
    X, Y : relative velocity normal to the rotor plane and in it with the frozen induction, m/s
    theta : aerodynamic twist plus pitch, plus what a pitched canted section adds (alpha = atan2(X, Y) - theta);
    alpha : angle of attack;
    cl, cd, cm and their slopes dcl, dcd, dcm (per rad); a, ap : induction factors
    air_density : kg/m^3; rotor_speed : rad/s; shaft_axis : a in the blade frame (3,), or in each section's
    frame on a curved axis (3, nodes); wind_speed : m/s; pitch : rad

    The section frame is the blade frame on a straight axis and the curved axis's local frame (the frame of its
    degrees of freedom) on a curved one: :func:`on_the_axis`.
    """

    span: NDArray
    chord: NDArray
    centre: NDArray
    X: NDArray
    Y: NDArray
    theta: NDArray
    alpha: NDArray
    cl: NDArray
    cd: NDArray
    cm: NDArray
    dcl: NDArray
    dcd: NDArray
    dcm: NDArray
    a: NDArray
    ap: NDArray
    air_density: float
    rotor_speed: float
    shaft_axis: NDArray
    wind_speed: float
    pitch: float


def operating_point(rotor: Rotor, wind_speed: float, rotor_speed: float, pitch: float, blade: Blade | None = None
                    ) -> AeroOperatingPoint:
    """The BEM solution of ``rotor`` in uniform wind ``wind_speed`` (m/s) along the shaft at ``rotor_speed``
    (rad/s) and blade pitch ``pitch`` (rad), and the polars' slopes there; the aerodynamic centres' arms from the
    reference axis of ``blade`` (:func:`aerodynamic_centres`; None: from the pitch axis)."""
    inflow = Inflow(wind_speed, rotor.hub_height if math.isfinite(rotor.hub_height) else 1.0)
    performance = performance_at(rotor, inflow, rotor_speed, pitch, 0.0, np.zeros(1))
    w, alpha = performance.w[0, 0], performance.alpha[0, 0]
    theta = rotor.twist + pitch + performance.section_twist[0, 0]     # with what a pitched canted section adds
    angle = alpha + theta                         # the inflow angle in the section's plane (phi, but for a section
    #                                               canted or toed in AeroDyn's polar projection, BEM_Mod 2)
    slopes = polar_slopes(rotor, alpha)
    cm = performance.cm[0, 0] if rotor.options.pitching_moment else np.zeros_like(alpha)
    return on_the_axis(AeroOperatingPoint(
        span=rotor.span, chord=rotor.chord, centre=aerodynamic_centres(rotor, pitch),
        X=w * np.sin(angle), Y=w * np.cos(angle), theta=theta, alpha=alpha, cl=performance.cl[0, 0],
        cd=performance.cd[0, 0], cm=cm,
        dcl=slopes[0], dcd=slopes[1], dcm=slopes[2], a=performance.a[0, 0], ap=performance.ap[0, 0],
        air_density=rotor.air_density, rotor_speed=rotor_speed,
        shaft_axis=shaft_axis(rotor), wind_speed=wind_speed, pitch=pitch), rotor, blade)


def on_the_axis(op: AeroOperatingPoint, rotor: Rotor, blade: Blade | None) -> AeroOperatingPoint:
    """``op`` (spans ``BlSpn``, arms from the pitch axis and the shaft axis in the blade frame) of ``rotor`` on
    ``blade``'s reference axis: on a curved axis each AeroDyn node at the arc length where the axis reaches its
    ``BlSpn`` along the pitch axis, its arm from that axis point (:func:`aerodynamic_centres`) and the shaft axis
    in the axis's local frame there, the frame of the curved beam's degrees of freedom, which the section canted
    by ``BlCrvAng`` (the axis's slope) shares; the section's loads and motion are taken in it (a cant that differs
    from the axis's slope is left out). A straight axis: ``op`` as it is."""
    if blade is None or not blade.curved:
        return op
    arc = blade.axis.arc_length(op.span)
    frame = blade.axis_frame(arc)                      # pitched with the structure: the frame of its DOFs
    centre = aerodynamic_centres(rotor, op.pitch, blade, frame)
    return replace(op, span=arc, centre=frame.to_local(centre), shaft_axis=frame.to_local(op.shaft_axis))


def polar_slopes(rotor: Rotor, alpha: NDArray) -> NDArray:
    """(3, nodes): d(cl, cd, cm)/d(alpha) per rad at each node's angle of attack ``alpha`` (rad), by central
    differences of the polars as interpolated (:data:`SLOPE_STEP`); the cm slope is zero when the BEM leaves out
    the pitching moment."""
    slopes = np.zeros((3, len(alpha)))
    for node, (angle, airfoil) in enumerate(zip(alpha, rotor.airfoil)):
        up = rotor.polars[airfoil].coefficients(angle + SLOPE_STEP)
        down = rotor.polars[airfoil].coefficients(angle - SLOPE_STEP)
        slopes[:, node] = [(u[0] - d[0]) / (2 * SLOPE_STEP) for u, d in zip(up, down)]
    if not rotor.options.pitching_moment:
        slopes[2] = 0.0
    return slopes


def aerodynamic_centres(rotor: Rotor, pitch: float = 0.0, blade: Blade | None = None,
                        axis: AxisFrame | None = None) -> NDArray:
    """(3, nodes): the aerodynamic centres' offsets from the sections' reference points in the blade frame, m:
    AeroDyn's ``(0, -BlSwpAC, BlCrvAC)`` turned with the blade by ``pitch`` (rad), less the offset of ``blade``'s
    curved reference axis there (pitched alike), whose points' motion the structure's degrees of freedom are (the
    prebend BeamDyn's key points and AeroDyn's ``BlCrvAC`` both carry is no arm), at the axis point as far along
    the pitch axis as the node (``BlSpn``); ``axis``: that axis at the nodes, where the caller has it."""
    centre = pitched_offsets(rotor.curve, rotor.sweep, pitch).T
    if blade is not None and blade.curved:
        axis = axis if axis is not None else blade.axis.frame(blade.axis.arc_length(rotor.span), pitch)
        centre[1:] -= axis.position[1:]
    return centre


def shaft_axis(rotor: Rotor) -> NDArray:
    """The shaft axis in the coned blade frame, ``(sin precone, 0, cos precone)``."""
    return np.array([math.sin(rotor.precone), 0.0, math.cos(rotor.precone)])


def load_derivatives(op: AeroOperatingPoint) -> NDArray:
    """(4, 3, nodes): derivatives of (0, ft, fn, m) per length with respect to (X, Y, twist), from the section load
    formulas with cl, cd, cm linear about the operating angle of attack."""
    X, Y, c = op.X, op.Y, op.chord
    W = np.hypot(X, Y)
    inverse = np.divide(1.0, W, out=np.zeros_like(W), where=W > 0)
    half = 0.5 * op.air_density * c
    alpha_X, alpha_Y = Y * inverse**2, -X * inverse**2
    # fn = half W (cl Y + cd X), ft = half W (cl X - cd Y), m = half c W^2 cm
    normal, tangential = op.cl * Y + op.cd * X, op.cl * X - op.cd * Y
    normal_slope, tangential_slope = op.dcl * Y + op.dcd * X, op.dcl * X - op.dcd * Y
    J = np.zeros((4, 3, len(X)))
    J[2, 0] = half * (X * inverse * normal + W * (normal_slope * alpha_X + op.cd))
    J[2, 1] = half * (Y * inverse * normal + W * (normal_slope * alpha_Y + op.cl))
    J[2, 2] = half * W * normal_slope
    J[1, 0] = half * (X * inverse * tangential + W * (tangential_slope * alpha_X + op.cl))
    J[1, 1] = half * (Y * inverse * tangential + W * (tangential_slope * alpha_Y - op.cd))
    J[1, 2] = half * W * tangential_slope
    J[3, 0] = half * c * (2 * X * op.cm + W**2 * op.dcm * alpha_X)
    J[3, 1] = half * c * (2 * Y * op.cm + W**2 * op.dcm * alpha_Y)
    J[3, 2] = half * c * W**2 * op.dcm
    return J


def section_matrices(op: AeroOperatingPoint) -> tuple[NDArray, NDArray]:
    """Damping D and stiffness K_a per length on the kinematic vector d = (u, v, w, phi, -w', v'), (6, 6, nodes)."""
    J = load_derivatives(op)
    nodes = len(op.span)
    N = np.zeros((3, 6, nodes))
    N[:, :3] = np.eye(3)[..., None]
    N[:, 3:] = -skew(op.centre)
    out = np.concatenate([N, np.zeros((1, 6, nodes))])          # [N_ac; e_phi]
    out[3, 3] = 1.0
    E = np.array([[0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])           # (X, Y) from the relative air velocity
    velocity = np.einsum("ij,jkn->ikn", E, N)                    # d(X, Y) = -velocity dd/dt - ...
    shaft = np.broadcast_to(np.asarray(op.shaft_axis, dtype=float).reshape(3, -1), (3, nodes))   # per section
    rotation = op.rotor_speed * np.einsum("ij,jkn,kln->iln", E, skew(shaft), N)
    generalized = np.einsum("gpn,gcn->pcn", out, J)              # (6, 3, nodes): [N_ac; e_phi]^T J
    D = np.einsum("pcn,cqn->pqn", generalized[:, :2], velocity)
    K = np.einsum("pcn,cqn->pqn", generalized[:, :2], rotation)
    K[:, 3] -= generalized[:, 2]
    return D, K


def aero_matrices(matrices: BladeMatrices, op: AeroOperatingPoint) -> tuple[sp.csc_matrix, sp.csc_matrix]:
    """Damping and stiffness matrices on the free DOFs: the section matrices, linear between the AeroDyn nodes (zero
    outside their span), integrated on the blade's own mesh."""
    basis = Basis(span_mesh(matrices.dofs.nodes), beam_element(matrices.dofs.fields), intorder=QUADRATURE_ORDER)
    x = np.asarray(basis.global_coordinates())[0]         # the quadrature points of the matrices' own mesh
    D, K = section_matrices(op)

    def along(A: NDArray) -> NDArray:
        inside = (x >= op.span[0]) & (x <= op.span[-1])
        values = np.stack([[np.interp(x, op.span, A[i, j]) for j in range(6)] for i in range(6)])
        return values * inside

    parameters = AeroParameters(damping=along(D), stiffness=along(K))
    free = matrices.free
    damping = assemble_terms(matrices.quadrature, parameters, (aerodynamic_damping,))
    stiffness = assemble_terms(matrices.quadrature, parameters, (aerodynamic_stiffness,))
    return damping[free][:, free].tocsc(), stiffness[free][:, free].tocsc()
