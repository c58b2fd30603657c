"""Blade-node kinematics of a rigid rotor turning at constant speed, vectorised over azimuths, blades and nodes.

What AeroDyn's BEM hands its BEM solver, computed here for a rigid rotor: the relative velocity components vx and vy
in the projection of the rotor's BEM_Mod (:func:`bladefem.aero.polar.projection`; legacy "no sweep, pitch, twist"
frame: vx along i1, the coned blade's downwind normal, and vy along -e_t, opposite to the rotation; polar: along the
shaft and in the rotor plane, with the section's cant, toe and the annulus dr/dz), the distance r_local from the
shaft axis, the tip- and hub-loss constants from the
distance z along the blade from the rotor centre, and the skewed-wake inputs: chi0 the angle between the shaft axis
and the disk-averaged wind, and the cosine of the angle between a blade and the in-plane direction of that wind
(the most downwind azimuth).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .polar import pitched_axes, projection
from .rotor import Inflow, Rotor


@dataclass(frozen=True)
class NodeKinematics:
    """Inputs of :func:`bladefem.aero.bem.node_loads` at (azimuth, blade, node), and the frames to sum loads.

    position : node relative to the rotor centre (..., 3), m; shaft : x_s (3,)
    normal, rotation, axis : (..., 3) the axes the node loads fn, ft and the pitching moment act along (the
        projection's: i1, e_t (direction of the blade motion) and i3, the pitch axis, turned by the section's
        cant ``BlCrvAng`` in the legacy projection)
    vx, vy : relative velocity components, m/s; r_local : m; z : distance along the blade from the centre, m
    tip_constant, hub_constant : Prandtl constants; tip_ratio : r_local / max r_local of the blade
    chi0 : skew angle per azimuth (n_az,), rad; skew_cos : (..,)
    disk_velocity : disk-averaged wind along x_s per azimuth (n_az,), m/s; max_radius : largest r_local, m
    cant, toe : (..,) the section's angles in its local polar frame (zero in the legacy projection), rad;
    drdz : (..,) the annulus factor (1 in the legacy projection); twist : (..,) what the pitched, canted section's
    orientation adds to the aerodynamic twist and the pitch (AeroDyn's Euler angle), rad
    """

    position: NDArray
    shaft: NDArray
    normal: NDArray
    rotation: NDArray
    axis: NDArray
    vx: NDArray
    vy: NDArray
    r_local: NDArray
    z: NDArray
    tip_constant: NDArray
    hub_constant: NDArray
    tip_ratio: NDArray
    chi0: NDArray
    skew_cos: NDArray
    disk_velocity: NDArray
    max_radius: float
    cant: NDArray
    toe: NDArray
    drdz: NDArray
    twist: NDArray


def shaft_frame(tilt: float, yaw: float) -> tuple[NDArray, NDArray, NDArray]:
    """(x_s, y_s, z_s): shaft axis downwind, lateral, and 'up' in the plane of rotation."""
    ct, st, cy, sy = math.cos(tilt), math.sin(tilt), math.cos(yaw), math.sin(yaw)
    x = np.array([ct * cy, ct * sy, st])
    z = np.array([-st * cy, -st * sy, ct])
    return x, np.cross(z, x), z


def rigid_rotor(rotor: Rotor, inflow: Inflow, rotor_speed: float, azimuths: NDArray,
                yaw: float = 0.0, pitch: float = 0.0) -> NodeKinematics:
    """Kinematics of every node at the rotor azimuths ``azimuths`` (rad, blade 1) for rotor speed ``rotor_speed``
    (rad/s), nacelle yaw ``yaw`` and blade pitch ``pitch`` (rad): the pitch turns the whole blade about its pitch
    axis, its aerodynamic-centre offsets and the sections' cant with it (AeroDyn places them in the pitched blade
    frame)."""
    xs, ys, zs = shaft_frame(rotor.shaft_tilt, yaw)
    psi = np.asarray(azimuths, dtype=float)[:, None] + 2 * np.pi * np.arange(rotor.n_blades) / rotor.n_blades
    radial = np.cos(psi)[..., None] * zs - np.sin(psi)[..., None] * ys               # (n_az, B, 3)
    tangent = np.cross(xs, radial)
    cone_c, cone_s = math.cos(rotor.precone), math.sin(rotor.precone)
    axis = cone_s * xs + cone_c * radial                                              # i3
    normal = cone_c * xs - cone_s * radial                                            # i1
    along = rotor.hub_radius + rotor.span
    normal_p, tangent_p = pitched_axes(normal, tangent, pitch)
    position = (along[:, None] * axis[..., None, :] + rotor.curve[:, None] * normal_p[..., None, :]
                - rotor.sweep[:, None] * tangent_p[..., None, :])                     # (n_az, B, n, 3)
    height = rotor.hub_height + position[..., 2]
    wind = inflow.velocity(height)
    velocity = wind - rotor_speed * np.cross(xs, position)
    normal_n = np.broadcast_to(normal[..., None, :], position.shape)
    tangent_n = np.broadcast_to(tangent[..., None, :], position.shape)
    axis_n = np.broadcast_to(axis[..., None, :], position.shape)
    frame = projection(rotor.options.formulation == 2, position, xs, normal_n, tangent_n, axis_n,
                       curve_angle=rotor.curve_angle, pitch=pitch)
    vx, vy = frame.components(velocity)
    axial = position @ xs
    r_local = np.linalg.norm(position - axial[..., None] * xs, axis=-1)
    z = _distance_along_blade(rotor, position, axis)
    z_hub, z_tip = rotor.hub_radius, z[..., -1:]
    tip_constant = rotor.n_blades * (z_tip - z) / (2 * z)
    hub_constant = (rotor.n_blades * (z - z_hub) / (2 * z_hub)) if z_hub > 0 else np.full(z.shape, np.inf)
    tip_ratio = r_local / r_local.max(axis=-1, keepdims=True)
    disk_wind = wind.mean(axis=(1, 2))                                               # (n_az, 3)
    disk_velocity = disk_wind @ xs
    speed = np.linalg.norm(disk_wind, axis=-1)
    chi0 = np.arccos(np.clip(np.divide(disk_velocity, speed, out=np.ones_like(speed), where=speed > 0), -1, 1))
    in_plane = disk_wind - disk_velocity[:, None] * xs
    size = np.linalg.norm(in_plane, axis=-1, keepdims=True)
    in_plane = np.divide(in_plane, size, out=np.zeros_like(in_plane), where=size > 1e-12 * np.maximum(speed, 1)[:,
                                                                                                         None])
    skew_cos = np.broadcast_to(np.einsum("abk,ak->ab", radial, in_plane)[..., None], vx.shape)
    return NodeKinematics(position, xs, frame.normal, frame.tangent, frame.span, vx, vy, r_local, z, tip_constant,
                          hub_constant, tip_ratio, chi0, skew_cos, disk_velocity, float(r_local.max()), frame.cant,
                          frame.toe, frame.drdz, frame.twist)


def _distance_along_blade(rotor: Rotor, position: NDArray, axis: NDArray) -> NDArray:
    """AeroDyn's zLocal: hub radius plus the polyline length from the blade root through the nodes, m."""
    root = rotor.hub_radius * axis[..., None, :]
    steps = np.linalg.norm(np.diff(np.concatenate([root, position], axis=-2), axis=-2), axis=-1)
    return rotor.hub_radius + np.cumsum(steps, axis=-1)
