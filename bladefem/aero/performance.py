"""Rotor-level BEM: thrust, torque, power, Cp, Ct and spanwise distributions of a rigid rotor in steady wind.

The nodes of every blade are solved at each rotor azimuth (one is enough for an axisymmetric case; with shaft tilt,
yaw, upflow or shear the loads are averaged over azimuths spread evenly over one blade passage). Loads per unit
length (force and pitching moment) vary linearly between nodes and are summed like AeroDyn's line meshes
(:func:`line_load_resultant`); thrust is the resultant along the shaft axis, torque the moment about it (the
pitching moments count through the cone angle). Cp, Ct and the tip-speed ratio use AeroDyn's definitions
(RtAeroCp, RtAeroCt, RtTSR): the swept area pi R^2 with R the largest distance of a node from the shaft axis, and
the disk-averaged wind component along the shaft.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ._jit import kernel
from .bem import NODE_OUTPUTS, solve_nodes
from .kinematics import NodeKinematics, rigid_rotor
from .polars import pack_polars
from .rotor import Inflow, Rotor

#: Azimuths averaged over when the inflow is not axisymmetric.
DEFAULT_AZIMUTHS = 16
#: Columns of the node-solution array (see bladefem.aero.bem.node_loads).
COLUMNS = ("phi_solved", "a", "ap", "phi", "alpha", "w", "cl", "cd", "cm", "fn", "ft", "m", "valid")


@dataclass(frozen=True)
class RotorPerformance:
    """Steady rotor loads (SI, rad); node arrays have shape (azimuth, blade, node).

    wind_speed : horizontal wind speed at the reference height, m/s; rotor_speed : rad/s; pitch, yaw : rad
    thrust : along the shaft, N; torque : about the shaft, N m; power : W
    cp, ct, tsr : AeroDyn's RtAeroCp, RtAeroCt, RtTSR; area : pi R^2, m^2; disk_velocity : m/s
    azimuths : rad; r_local, z : m; a, ap : induction factors; phi, alpha : rad; w : relative speed, m/s;
    cl, cd, cm; fn, ft : force per length normal to the plane (downwind) and along the rotation, N/m;
    m : pitching moment per length, N m/m; valid : the BEM equations had a solution
    section_twist : what the pitched, canted section's orientation adds to the aerodynamic twist and the pitch
    (AeroDyn's Euler angle, :func:`bladefem.aero.polar.projection`), rad
    """

    wind_speed: float
    rotor_speed: float
    pitch: float
    yaw: float
    thrust: float
    torque: float
    power: float
    cp: float
    ct: float
    tsr: float
    area: float
    disk_velocity: float
    azimuths: NDArray
    r_local: NDArray
    z: NDArray
    a: NDArray
    ap: NDArray
    phi: NDArray
    alpha: NDArray
    w: NDArray
    cl: NDArray
    cd: NDArray
    cm: NDArray
    fn: NDArray
    ft: NDArray
    m: NDArray
    valid: NDArray
    section_twist: NDArray

    @property
    def rpm(self) -> float:
        return self.rotor_speed * 30.0 / math.pi

    @property
    def pitch_deg(self) -> float:
        return math.degrees(self.pitch)

    def spanwise(self, name: str) -> NDArray:
        """A node quantity averaged over azimuths and blades, one value per node."""
        return np.mean(getattr(self, name), axis=(0, 1))


def rotor_performance(source, wind_speed: float | None = None, rpm: float = 0.0, pitch_deg: float = 0.0, *,
                      shear_exponent: float | None = None, yaw_deg: float = 0.0,
                      azimuths: int | None = None) -> RotorPerformance:
    """Steady loads of a rigid rotor.

    source : a :class:`Rotor`, or an object with ``rotor()`` (and optionally ``inflow``, an :class:`Inflow`), such
        as :class:`bladefem.builders.openfast_fst.OpenFASTDeck`
    wind_speed : horizontal wind speed at the reference height (the hub height unless the deck's InflowWind says
        otherwise), m/s; default the deck's
    rpm : rotor speed; pitch_deg : blade pitch (positive to feather); yaw_deg : nacelle yaw
    shear_exponent : power-law exponent; default the deck's, else 0
    azimuths : number of rotor positions averaged; default 1 for axisymmetric inflow, else 16
    """
    rotor = source.rotor() if hasattr(source, "rotor") else source
    inflow: Inflow | None = getattr(source, "inflow", None)
    if inflow is None:
        if wind_speed is None:
            raise ValueError("wind_speed is needed for a rotor without an inflow description")
        inflow = Inflow(wind_speed, rotor.hub_height, shear_exponent or 0.0)
    inflow = Inflow(inflow.speed if wind_speed is None else wind_speed, inflow.reference_height,
                    inflow.shear_exponent if shear_exponent is None else shear_exponent, inflow.direction,
                    inflow.upflow)
    if inflow.shear_exponent and not math.isfinite(rotor.hub_height):
        raise ValueError("wind shear needs the rotor's hub height")
    yaw = math.radians(yaw_deg)
    axisymmetric = not (rotor.shaft_tilt or yaw or inflow.shear_exponent or inflow.direction or inflow.upflow)
    count = azimuths or (1 if axisymmetric else DEFAULT_AZIMUTHS)
    psi = np.arange(count) * (2 * np.pi / rotor.n_blades) / count
    return performance_at(rotor, inflow, rpm * math.pi / 30.0, math.radians(pitch_deg), yaw, psi)


def performance_at(rotor: Rotor, inflow: Inflow, rotor_speed: float, pitch: float, yaw: float,
                   azimuths: NDArray) -> RotorPerformance:
    """:func:`rotor_performance` in SI units at the given rotor azimuths (rad)."""
    kin = rigid_rotor(rotor, inflow, rotor_speed, azimuths, yaw, pitch)
    solution = solve_kinematics(rotor, kin, rotor_speed, pitch)
    column = {name: solution[..., i] for i, name in enumerate(COLUMNS)}
    force = column["fn"][..., None] * kin.normal + column["ft"][..., None] * kin.rotation
    total_force, total_moment = line_load_resultant(kin.position, force, column["m"][..., None] * kin.axis, kin.z)
    thrust = float(np.mean(total_force.sum(axis=1) @ kin.shaft))
    torque = float(np.mean(total_moment.sum(axis=1) @ kin.shaft))
    disk = float(np.mean(kin.disk_velocity))
    area = math.pi * kin.max_radius ** 2
    power = torque * rotor_speed
    dynamic = 0.5 * rotor.air_density * area * disk ** 2
    return RotorPerformance(
        wind_speed=inflow.speed, rotor_speed=rotor_speed, pitch=pitch, yaw=yaw, thrust=thrust, torque=torque,
        power=power, cp=power / (dynamic * disk) if disk else 0.0, ct=thrust / dynamic if disk else 0.0,
        tsr=rotor_speed * kin.max_radius / disk if disk else 0.0, area=area, disk_velocity=disk,
        azimuths=np.asarray(azimuths, dtype=float), r_local=kin.r_local, z=kin.z, a=column["a"],
        ap=column["ap"], phi=column["phi"], alpha=column["alpha"], w=column["w"], cl=column["cl"],
        cd=column["cd"], cm=column["cm"], fn=column["fn"], ft=column["ft"], m=column["m"],
        valid=column["valid"] > 0.5, section_twist=kin.twist)


def line_load_resultant(position: NDArray, force: NDArray, moment: NDArray, z: NDArray) -> tuple[NDArray, NDArray]:
    """Resultant force and moment about the origin of loads per unit length (..., node, 3) varying linearly between
    nodes at ``position`` along a line of arc length ``z`` (AeroDyn's Line2 load meshes lumped to the hub point): the
    force by the trapezoidal rule, the moment of the force exactly for linear load and linear position
    (L/6 (2 p_a x f_a + p_a x f_b + p_b x f_a + 2 p_b x f_b) per element), the distributed moment by the trapezoidal
    rule."""
    length = np.diff(z, axis=-1)[..., None]
    pa, pb, fa, fb = position[..., :-1, :], position[..., 1:, :], force[..., :-1, :], force[..., 1:, :]
    total_force = np.sum(0.5 * length * (fa + fb), axis=-2)
    arm = 2 * np.cross(pa, fa) + np.cross(pa, fb) + np.cross(pb, fa) + 2 * np.cross(pb, fb)
    total_moment = np.sum(length / 6 * arm + 0.5 * length * (moment[..., :-1, :] + moment[..., 1:, :]), axis=-2)
    return total_force, total_moment


@kernel
def induction_weight(tsr):
    """AeroDyn's switch-off of the induction at low tip-speed ratio: 0 below 1, 1 above 2, a cosine blend
    between."""
    tsr = abs(tsr)
    if tsr >= 2.0:
        return 1.0
    if tsr <= 1.0:
        return 0.0
    return 0.5 * (1.0 - math.cos((tsr - 1.0) * math.pi))


def solve_kinematics(rotor: Rotor, kin: NodeKinematics, rotor_speed: float, pitch: float) -> NDArray:
    """Node solutions (..., NODE_OUTPUTS) for the kinematics ``kin`` (one induction weight per azimuth)."""
    table = pack_polars(rotor.polars)
    options = rotor.options.vector()
    shape = kin.vx.shape
    out = np.empty(shape + (NODE_OUTPUTS,))
    theta = rotor.twist + pitch + kin.twist
    for i in range(shape[0]):
        tsr = rotor_speed * kin.max_radius / kin.disk_velocity[i] if kin.disk_velocity[i] else 0.0
        flat = [np.ascontiguousarray(np.broadcast_to(x, shape[1:]).ravel()) for x in (
            kin.vx[i], kin.vy[i], kin.r_local[i], rotor.chord, theta[i], kin.tip_constant[i], kin.hub_constant[i],
            kin.tip_ratio[i], np.full(shape[1:], kin.chi0[i]), kin.skew_cos[i], rotor.airfoil, kin.cant[i],
            kin.toe[i], kin.drdz[i])]
        vx, vy, r_local, chord, twist, tip_c, hub_c, tip_ratio, chi0, skew_cos, airfoil, cant, toe, drdz = flat
        result = np.empty((vx.size, NODE_OUTPUTS))
        solve_nodes(vx, vy, r_local, chord, twist, tip_c, hub_c, float(rotor.n_blades), tip_ratio, chi0, skew_cos,
                    induction_weight(tsr), airfoil, *table.arrays, options, float(rotor.air_density),
                    np.full(vx.size, np.nan), cant, toe, drdz, result)
        out[i] = result.reshape(shape[1:] + (NODE_OUTPUTS,))
    return out
