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
(``BEMOptions.formulation``), of a section turned by both slopes of the bent blade (:func:`bent_axes`: the least
rotation of the span axis onto the deflected one, a section without torsion, ElastoDyn's orientation of its blade
nodes) and AeroDyn's Euler angles of that orientation (:func:`euler_angles`, ``EulerExtract``).

Legacy (BEM_Mod 1, ``NoSweepPitchTwist``, AeroDyn.f90 ``Calculate_MeshOrientation_NoSweepPitchTwist``): the angles
against the unturned blade (x i1, y -e_t, z i3); vx along the blade's normal turned by the cant alone
(cos(cant) i1 - sin(cant) i3), vy against the rotation e_t; the section is plane in that frame (cant 0, toe 0,
dr/dz 1) and its twist (the bent section's, added to the aerodynamic twist and pitch) is the angles' third.

Polar (BEM_Mod 2, ``APM_BEM_Polar``; AeroDyn.f90 ``SetInputsForBEMT``, ``Calculate_MeshOrientation_Rel2Hub``,
``TwistToeCant_FromLocalPolar``): the node's local polar frame x_l = the shaft axis, z_l = the node's position
from the apex projected onto the rotor plane and normalised, y_l = z_l x x_l; vx = V . x_l, vy = V . y_l. The
bent section's untwisted axes (n, -e_t, s) in that frame give AeroDyn's Euler angles R = R_z(-twist) R_y(cant)
R_x(toe) (above, with the twist 0): the cant (precone and the out-of-plane slope), the toe (the in-plane slope and
the node's position off the blade's radial line: in-plane deflection and the aerodynamic-centre sweep) and the
twist the bent section carries (of the order of the product of its two slopes), which adds to ``theta``; the
section's loads act along its untwisted axes turned back by that twist. The annulus factor dr/dz = |dr_proj| /
|dr| of the segment from the previous node (the first node takes the second's).
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
    return section_inflow(phi, math.sin(phi), math.cos(phi), math.cos(cant), math.sin(cant), math.cos(toe),
                          math.sin(toe))[0]


@kernel
def section_inflow(phi, x, y, cb, sb, ct, st):
    """(angle, sine, cosine) of :func:`section_angle` of phi = atan2(x, y) for the inflow of components (x, y) at a
    section of cant b and toe t (their cosines and sines), the sine and cosine from the components (the atan2's
    arguments scaled to unit length: no trigonometric call); (phi, 0, 1) where both are zero."""
    plane = sb == 0.0 and st == 0.0 and cb > 0.0 and ct > 0.0      # cant and toe 0
    if not plane:                        # (sin phi_N, cos phi_N) times a positive factor, turned by the toe
        x, y = cb * x + sb * st * y * cb, ct * y * cb
    size = math.sqrt(x * x + y * y)
    if size == 0.0:
        return phi, 0.0, 1.0
    return phi if plane else math.atan2(x, y), x / size, y / size


@kernel
def polar_coefficients(alpha, theta, cant, toe, cl, cd, options):
    """(Cx, Cy): the section's force coefficients along x_l (normal to the rotor plane) and along -y_l (in the
    plane, towards the leading edge) for cl, cd at the angle of attack alpha, the chord turned by theta, drag only
    with AIDrag (normal to the chord) / TIDrag (along it), as AeroDyn's momentum balance takes them."""
    return framed_coefficients(math.cos(alpha), math.sin(alpha), cl, cd, options, math.cos(theta), math.sin(theta),
                               math.cos(cant), math.sin(cant), math.cos(toe), math.sin(toe))


@kernel
def framed_coefficients(cos_alpha, sin_alpha, cl, cd, options, cw, sw, cb, sb, ct, st):
    """:func:`polar_coefficients` with cos and sin of alpha, theta (w), the cant (b) and the toe (t) given."""
    cn = cl * cos_alpha + (cd * sin_alpha if options[AI_DRAG] != 0.0 else 0.0)
    ca = -cl * sin_alpha + (cd * cos_alpha if options[TI_DRAG] != 0.0 else 0.0)
    # chord normal x_s = cos(theta) x' - sin(theta) y', chord y_s = sin(theta) x' + cos(theta) y'
    cx = cb * (cn * cw + ca * sw)
    cy = -(cn * (cw * sb * st - sw * ct) + ca * (sw * sb * st + cw * ct))
    return cx, cy


@kernel
def bent_axes(v_slope, w_slope):
    """The axes of a section turned by its in-plane and out-of-plane slopes v', w' (toward the leading edge and
    downwind): the least rotation taking the span axis i3 onto the deflected axis (i3 + v' e_t + w' i1) / L,
    L = sqrt(1 + v'^2 + w'^2) (Rodrigues, the rotation axis normal to i3: a section without torsion, as ElastoDyn's
    ``SmllRotTrans`` of its two slopes). Returns the components of the turned normal n, tangent e_t (direction of
    rotation) and span axis s along the unturned (i3, e_t, i1): (n3, nt, n1, t3, tt, t1, s3, st, s1). With v' = 0
    the normal is (i1 - w' i3) / L and e_t is unturned."""
    size = math.sqrt(1.0 + v_slope * v_slope + w_slope * w_slope)
    h = 1.0 / (size * (size + 1.0))
    vw = v_slope * w_slope * h
    return (-w_slope / size, -vw, 1.0 / size + v_slope * v_slope * h,
            -v_slope / size, 1.0 / size + w_slope * w_slope * h, -vw,
            1.0 / size, v_slope / size, w_slope / size)


@kernel
def curved_axes(v_slope, w_slope, cos_curve, sin_curve):
    """:func:`bent_axes` of a section whose undeflected axes are already canted by the blade's curvature angle c
    (AeroDyn's ``BlCrvAng``, positive downwind: the reference orientation R_y(c) of its blade nodes): the normal
    cos(c) i1 - sin(c) i3 and span axis sin(c) i1 + cos(c) i3, turned by the deflection's rotation (as OpenFAST maps
    the structural node's rotation onto the AeroDyn node, keeping the node's reference orientation)."""
    n3, nt, n1, t3, tt, t1, s3, st, s1 = bent_axes(v_slope, w_slope)
    return (cos_curve * n3 - sin_curve * s3, cos_curve * nt - sin_curve * st, cos_curve * n1 - sin_curve * s1,
            t3, tt, t1,
            sin_curve * n3 + cos_curve * s3, sin_curve * nt + cos_curve * st, sin_curve * n1 + cos_curve * s1)


@kernel
def euler_angles(m11, m12, m13, m21, m22, m23, m31):
    """(toe, cant, twist), rad: AeroDyn's Euler angles of a section (``TwistToeCant_FromLocalPolar``: NWTC
    ``EulerExtract`` of M = R(theta_z) R(theta_y) R(theta_x), toe = theta_x, cant = theta_y, twist = -theta_z) from
    the entries M_ij = (section axis i) . (reference axis j), the section axes (chord normal x', towards the trailing
    edge y', span z') untwisted by the aerodynamic twist."""
    cy = math.sqrt(m11 * m11 + m21 * m21)
    if cy < 1e-14:                                       # gimbal lock: the span along the reference x axis
        return math.atan2(m23, m22), math.atan2(m31, cy), 0.0
    cz, sz = m11 / cy, -m21 / cy
    return math.atan2(sz * m13 + cz * m23, sz * m12 + cz * m22), math.atan2(m31, cy), -math.atan2(-m21, m11)


@kernel
def euler_frame(m11, m12, m13, m21, m22, m23, m31):
    """(twist, cos twist, sin twist, cos cant, sin cant, cos toe, sin toe) of :func:`euler_angles`, each cosine
    and sine from the entries (the arguments of the angle's atan2 scaled to unit length; theta_z = atan2(-m21,
    m11): cos = m11 / c_y, sin = -m21 / c_y, c_y = |(m11, m21)|): the cant and the toe enter the BEM only through
    their cosines and sines (:func:`bladefem.aero.bem.angle_geometry`), so no arctangent is taken for them."""
    cy = math.sqrt(m11 * m11 + m21 * m21)
    cant_size = math.sqrt(m31 * m31 + cy * cy)
    if cy < 1e-14:                                       # gimbal lock: the span along the reference x axis
        toe_size = math.sqrt(m23 * m23 + m22 * m22)
        return 0.0, 1.0, 0.0, cy / cant_size, m31 / cant_size, m22 / toe_size, m23 / toe_size
    cz, sz = m11 / cy, -m21 / cy
    x, y = sz * m12 + cz * m22, sz * m13 + cz * m23
    toe_size = math.sqrt(x * x + y * y)
    return -math.atan2(-m21, m11), cz, -sz, cy / cant_size, m31 / cant_size, x / toe_size, y / toe_size


@dataclass(frozen=True)
class Projection:
    """x_axis, y_axis : (B, Na, 3) the unit vectors vx and vy are taken along; cant, toe : (B, Na) rad; twist :
    (B, Na) the section's twist from its orientation, rad (added to the aerodynamic twist and pitch); drdz :
    (B, Na) the annulus factor; normal, tangent, span : (B, Na, 3) the axes the node loads fn, ft and the pitching
    moment act along."""

    x_axis: NDArray
    y_axis: NDArray
    cant: NDArray
    toe: NDArray
    twist: NDArray
    drdz: NDArray
    normal: NDArray
    tangent: NDArray
    span: NDArray

    def components(self, relative: NDArray) -> tuple[NDArray, NDArray]:
        """(vx, vy) of relative winds (..., B, Na, 3)."""
        return (np.einsum("...k,...k->...", relative, self.x_axis),
                np.einsum("...k,...k->...", relative, self.y_axis))


def pitched_axes(normal: NDArray, tangent: NDArray, pitch: NDArray | float) -> tuple[NDArray, NDArray]:
    """The blade's normal i1 and tangent e_t (..., 3) turned about its pitch axis by ``pitch`` (rad, positive to
    feather, broadcast over the leading axes): ``cos p i1 + sin p e_t`` and ``cos p e_t - sin p i1``, the frame
    a pitched blade's geometry (aerodynamic-centre offsets, cant) is given in."""
    p = np.asarray(pitch, dtype=float)[..., None]
    c, s = np.cos(p), np.sin(p)
    return c * normal + s * tangent, c * tangent - s * normal


def turned(y: NDArray, z: NDArray, angle: NDArray | float) -> tuple[NDArray, NDArray]:
    """Across components (y along e_t, toward the leading edge; z along i1, downwind) of a vector turned with the
    blade about its pitch axis by ``angle`` (rad, positive to feather): ``(y cos + z sin, -y sin + z cos)``. With
    ``-angle``: the unpitched components resolved along the axes pitched by ``angle`` (:func:`pitched_axes`)."""
    c, s = np.cos(angle), np.sin(angle)
    return y * c + z * s, -y * s + z * c


def pitched_offsets(curve: NDArray, sweep: NDArray, pitch: float) -> NDArray:
    """(Na, 3) aerodynamic-centre offsets in the blade frame (span, toward the leading edge, downwind), m, of
    ``curve`` downwind and ``sweep`` against the rotation (m) turned with the blade by ``pitch`` (rad, to feather),
    as AeroDyn places ``BlCrvAC`` and ``BlSwpAC`` in the pitched blade frame (:func:`pitched_axes`)."""
    curve, sweep = np.asarray(curve, dtype=float), np.asarray(sweep, dtype=float)
    return np.column_stack([np.zeros_like(curve), *turned(-sweep, curve, pitch)])


def projection(polar: bool, arm: NDArray, shaft: NDArray, normal: NDArray, tangent: NDArray, span: NDArray,
               in_plane_slope: NDArray | float = 0.0, out_of_plane_slope: NDArray | float = 0.0,
               curve_angle: NDArray | float = 0.0, pitch: NDArray | float = 0.0) -> Projection:
    """The projection of every node: ``arm`` (B, Na, 3) the nodes from the apex, ``shaft`` (3,) the shaft axis,
    ``normal``, ``tangent`` (direction of rotation), ``span`` (B, Na, 3) the undeflected, unpitched blade's axes
    i1, e_t, i3, the sections pitched by ``pitch`` (rad, broadcast to (B, Na)), canted in the pitched blade by its
    curvature angle ``curve_angle`` (Na,) rad (``BlCrvAng``) and turned by the slopes (B, Na) of the deflected blade
    (:func:`curved_axes`), given along the unpitched e_t and i1 (in-plane, out-of-plane). AeroDyn composes a
    node's orientation so, twist last: R_z(-twist) R_y(cant) R_z(-pitch) (the pitch about the root's axis first); its Euler angles mix the pitch into the cant and the twist of a canted
    section. ``twist`` of the result is what the section's orientation adds to the aerodynamic twist and the pitch
    (the extracted angle less the pitch)."""
    shape = arm.shape[:-1]
    normal, tangent, span = (np.broadcast_to(axis, arm.shape) for axis in (normal, tangent, span))
    pitch = np.broadcast_to(np.asarray(pitch, dtype=float), shape)
    normal_p, tangent_p = pitched_axes(normal, tangent, pitch)
    basis = np.stack([span, tangent_p, normal_p], axis=-2)                       # (B, Na, 3 axes, 3)
    slopes = turned(*(np.broadcast_to(np.asarray(slope, dtype=float), shape)
                      for slope in (in_plane_slope, out_of_plane_slope)), -pitch)   # along the pitched axes
    curve = np.broadcast_to(np.asarray(curve_angle, dtype=float), shape)
    c = np.stack(np.vectorize(curved_axes, otypes=[float] * 9)(*slopes, np.cos(curve), np.sin(curve)), axis=-1)
    n_b, t_b, s_b = (np.einsum("...i,...ik->...k", c[..., 3 * j:3 * j + 3], basis) for j in range(3))
    dot = lambda a, b: np.einsum("...k,...k", a, b)                           # noqa: E731
    if not polar:
        # AeroDyn's NoSweepPitchTwist: the Euler angles against the unturned, unpitched blade (x i1, y -e_t, z i3);
        # vx along the blade's normal turned by the cant alone, vy against the rotation, the loads along those axes
        m = [dot(n_b, normal), -dot(n_b, tangent), dot(n_b, span), -dot(t_b, normal), dot(t_b, tangent),
             -dot(t_b, span), dot(s_b, normal)]
        _, cant, twist = (np.asarray(a) for a in np.vectorize(euler_angles, otypes=[float] * 3)(*m))
        x_a = np.cos(cant)[..., None] * normal - np.sin(cant)[..., None] * span
        z_a = np.sin(cant)[..., None] * normal + np.cos(cant)[..., None] * span
        return Projection(x_axis=x_a, y_axis=-tangent, cant=np.zeros(shape), toe=np.zeros(shape),
                          twist=twist - pitch, drdz=np.ones(shape), normal=x_a, tangent=tangent, span=z_a)
    radial = arm - (arm @ shaft)[..., None] * shaft
    on_axis = np.linalg.norm(radial, axis=-1, keepdims=True) == 0.0   # a node on the shaft (hub radius 0): the
    outward = np.where(on_axis, s_b - (s_b @ shaft)[..., None] * shaft, radial)   # section's span axis points out
    z_l = outward / np.linalg.norm(outward, axis=-1, keepdims=True)
    x_l = np.broadcast_to(shaft, arm.shape)
    y_l = np.cross(z_l, x_l)
    m = [dot(n_b, x_l), dot(n_b, y_l), dot(n_b, z_l), -dot(t_b, x_l), -dot(t_b, y_l), -dot(t_b, z_l), dot(s_b, x_l)]
    toe, cant, twist = (np.asarray(a) for a in np.vectorize(euler_angles, otypes=[float] * 3)(*m))
    # the loads' axes: the section's untwisted axes (x', -y') turned back by the twist its orientation carries
    cz, sz = np.cos(twist)[..., None], np.sin(twist)[..., None]
    load_normal, load_tangent = cz * n_b - sz * t_b, sz * n_b + cz * t_b
    step = np.linalg.norm(np.diff(arm, axis=-2), axis=-1)
    step_projected = np.linalg.norm(np.diff(radial, axis=-2), axis=-1)
    drdz = np.divide(step_projected, step, out=np.zeros_like(step), where=step > 0)
    drdz = np.concatenate([drdz[..., :1], drdz], axis=-1)
    return Projection(x_axis=x_l, y_axis=y_l, cant=cant, toe=toe, twist=twist - pitch, drdz=drdz,
                      normal=load_normal, tangent=load_tangent, span=s_b)
