"""Aerodynamic loads on the Kane turbine model: quasi-steady BEM at the AeroDyn blade nodes (numpy reference).

Each AeroDyn node (``BlSpn``) is a point of the flexible blade: its modal shapes, slopes and shortening integrals
are linear interpolations of the structural beam's (root, span nodes, tip), as OpenFAST maps ElastoDyn's blade
motion onto AeroDyn's nodes; the aerodynamic centre offsets (``BlCrvAC`` downwind, ``BlSwpAC`` against the
rotation) ride on rigid arms turned with the bent section to second order in its slopes (along the axis:
:attr:`TurbineAero.along`; across it: :func:`.kinematics.turned_arms`), each section canted by ``BlCrvAng``. At every
state the node's absolute velocity (tower, nacelle, rotor and blade motion) is subtracted from the wind, so
aerodynamic damping and stiffness come out of the loads. The inputs of the node solver
(:func:`bladefem.aero.bem.node_loads`) follow the section turned by the blade's in-plane and out-of-plane slopes
v', w' (:func:`bladefem.aero.polar.bent_axes`), with BEM_Mod 1 in AeroDyn's legacy projection (``NoSweepPitchTwist``):

    n = cos(cant) i1 - sin(cant) i3       the coned blade's downwind normal turned by the bent section's cant
    vx = (V_wind - v) . n,   vy = -(V_wind - v) . e_t      e_t the direction of rotation (toward the leading edge)
    r_local = distance from the shaft axis,  theta = BlTwist + pitch + the bent section's twist

and with BEM_Mod 2 its polar projection (:mod:`bladefem.aero.polar`: vx along the shaft, vy in the rotor plane, the
section's cant, toe, twist and the annulus dr/dz handed to the solver, whose loads act along the section's axes).

with the disk-averaged relative wind giving the skew angle ``chi0``, the skewed-wake azimuth and the tip-speed ratio
(AeroDyn's ``DiskAvgValues``). The loads per unit length, ``fn`` and ``ft`` along the projection's normal and
tangent and the pitching moment along its span axis, vary linearly between nodes along the undeflected arc length;
they are lumped at the nodes by virtual work (force: ``L/3, L/6`` per element, whose moment about any point is the
exact one of the line load; moment: ``L/2``), and enter Kane's equations as ``sum_p J_p^T F_p + W^T sum_p M_p`` (W the rotor's
partial angular velocities). See docs/turbine.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from ...aero.bem import NODE_OUTPUTS, solve_nodes
from ...aero.dynamic_wake import BLEND, disk_weights, solve_wake_nodes, time_constant, wake_derivative
from ...aero.performance import COLUMNS, induction_weight
from ...aero.polars import pack_polars
from ...aero.rotor import Inflow, Rotor
from ...errors import InputError
from ...aero.polar import Projection, pitched_offsets, projection
from .kinematics import BeamNodes, NodeGroup, carry_nodes, turned_arms
from .shapes import ModalBeam


@dataclass(frozen=True)
class TurbineAero:
    """The rotor's aerodynamics on one turbine model (SI, rad); every blade alike.

    rotor : planform, polars, air and BEM options (:class:`bladefem.aero.Rotor`)
    inflow : steady wind (speed at the reference height, shear, direction, upflow)
    pitch : collective blade pitch, rad (the structural model's blade shapes must be pitched alike)
    axial : (Na,) node distance from the rotor apex along the pitch axis (HubRad + BlSpn), m
    offset : (Na, 3) aerodynamic-centre offset in the blade frame (span, toward the leading edge, downwind), m: the
        planform's ``BlCrvAC`` downwind and ``BlSwpAC`` against the rotation, turned with the blade by ``pitch``
    value, slope : (k, Na, 2) the blade's modal shapes and slopes (in-plane, out-of-plane) at the nodes
    shortening : (k, k, Na) the shortening integrals S_ij at the nodes, 1/m
    arc : (Na,) AeroDyn's zLocal: hub radius plus the polyline length through the undeflected nodes, m
    tip_constant, hub_constant : (Na,) Prandtl's B (z_tip - z) / (2 z), B (z - z_hub) / (2 z_hub)
    """

    rotor: Rotor
    inflow: Inflow
    pitch: float
    axial: NDArray
    offset: NDArray
    value: NDArray
    slope: NDArray
    shortening: NDArray
    arc: NDArray
    tip_constant: NDArray
    hub_constant: NDArray

    @property
    def n_nodes(self) -> int:
        return len(self.axial)

    @property
    def theta(self) -> NDArray:
        """Twist plus pitch at the nodes, rad (alpha = phi - theta)."""
        return self.rotor.twist + self.pitch

    @cached_property
    def polar_arrays(self) -> tuple[NDArray, ...]:
        """The packed polars (:func:`bladefem.aero.polars.pack_polars`) the kernels read."""
        return pack_polars(self.rotor.polars).arrays

    @property
    def along(self) -> NDArray:
        """(k, Na) each node's motion along the blade axis per modal amplitude: its aerodynamic-centre offset o
        (``offset``, across the axis) turned by the section's rotation, -(o . slope) to first order in the slopes
        (as OpenFAST carries AeroDyn's node on the rigid arm from ElastoDyn's, turned with it: a prebent blade's
        node, upwind of the axis, moves outward as the blade bends downwind)."""
        return -np.einsum("kpa,pa->kp", self.slope, self.offset[:, 1:])

    @cached_property
    def undeflected_radius(self) -> NDArray:
        """(Na,) the nodes' distance from the shaft axis with the blade undeflected (coned by PreCone, the
        aerodynamic-centre offsets included), m: the r / R of the dynamic wake with DBEMT_Mod 1 and 3 and the
        weights of its disk-averaged induction (AeroDyn takes both from its initial radii)."""
        cone = self.rotor.precone
        return np.hypot(self.axial * math.cos(cone) - self.offset[:, 2] * math.sin(cone), self.offset[:, 1])

    @property
    def wake_states(self) -> int:
        """Number of dynamic-wake states per blade (4 per node), 0 when the induction is quasi-steady."""
        return 4 * self.n_nodes if self.rotor.dynamic_wake is not None and self.rotor.options.induction else 0

    @cached_property
    def options(self) -> NDArray:
        """The BEM switches as the kernels' option vector."""
        return self.rotor.options.vector()

    def force_lumping(self) -> NDArray:
        """(Na, Na) nodal forces of nodal loads per unit length varying linearly along the arc: ``L/3`` on the
        element's own node, ``L/6`` on the other."""
        length = np.diff(self.arc)
        L = np.zeros((self.n_nodes, self.n_nodes))
        for e, h in enumerate(length):
            L[e:e + 2, e:e + 2] += h / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]])
        return L

    def moment_weights(self) -> NDArray:
        """(Na,) trapezoidal weights of a distributed moment along the arc, m."""
        length = np.diff(self.arc)
        return np.concatenate([[0.0], length / 2]) + np.concatenate([length / 2, [0.0]])

    def with_wind(self, speed: float | None = None, shear_exponent: float | None = None) -> TurbineAero:
        """A copy with another wind speed at the reference height (m/s) or shear exponent."""
        inflow = replace(self.inflow, speed=self.inflow.speed if speed is None else speed,
                         shear_exponent=self.inflow.shear_exponent if shear_exponent is None else shear_exponent)
        return replace(self, inflow=inflow)

    @classmethod
    def from_deck(cls, deck, params, wind_speed: float | None = None, shear_exponent: float | None = None,
                  pitch: float | None = None) -> TurbineAero:
        """The aerodynamics of an OpenFAST deck (:class:`bladefem.builders.openfast_fst.OpenFASTDeck`, or anything with
        ``rotor()`` and ``inflow``) on the turbine ``params`` (:class:`TurbineParameters`); ``wind_speed`` (m/s)
        and ``shear_exponent`` override InflowWind's, ``pitch`` (rad) the structural model's."""
        inflow = deck.inflow
        inflow = replace(inflow, speed=inflow.speed if wind_speed is None else wind_speed,
                         shear_exponent=inflow.shear_exponent if shear_exponent is None else shear_exponent)
        return turbine_aero(deck.rotor(), inflow, params, params.pitch if pitch is None else pitch)


def turbine_aero(rotor: Rotor, inflow: Inflow, params, pitch: float) -> TurbineAero:
    """:class:`TurbineAero` of a rigid-rotor description on the turbine ``params``: the beam's shapes interpolated
    at the nodes, the loss constants from the undeflected arc length (AeroDyn computes them once)."""
    blade: ModalBeam = params.blade
    if rotor.n_blades != params.n_blades:
        raise InputError(f"the aerodynamic rotor has {rotor.n_blades} blades, the structure {params.n_blades}",
                         field="NumBl")
    if abs(rotor.hub_radius - params.hub_radius) > 1e-9 * max(1.0, params.hub_radius):
        raise InputError(f"the aerodynamic hub radius {rotor.hub_radius:g} m differs from the structure's "
                         f"{params.hub_radius:g} m", field="HubRad")
    if rotor.span[-1] > blade.length * (1 + 1e-6):
        raise InputError(f"the AeroDyn blade reaches {rotor.span[-1]:g} m from the root but the structural blade is "
                         f"{blade.length:g} m long", field="BlSpn")
    value, slope, shortening = interpolated_shapes(blade, rotor.span)
    offset = pitched_offsets(rotor.curve, rotor.sweep, pitch)
    points = np.column_stack([params.hub_radius + rotor.span, offset[:, 1:]])
    steps = np.linalg.norm(np.diff(np.vstack([[params.hub_radius, 0.0, 0.0], points]), axis=0), axis=1)
    arc = params.hub_radius + np.cumsum(steps)
    B, z_hub = params.n_blades, params.hub_radius
    tip_constant = B * (arc[-1] - arc) / (2 * arc)
    hub_constant = B * (arc - z_hub) / (2 * z_hub) if z_hub > 0 else np.full(arc.shape, np.inf)
    return TurbineAero(rotor=rotor, inflow=inflow, pitch=float(pitch), axial=params.hub_radius + rotor.span,
                       offset=offset, value=value, slope=slope, shortening=shortening, arc=arc,
                       tip_constant=tip_constant, hub_constant=hub_constant)


def interpolated_shapes(beam: ModalBeam, x: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """The beam's shapes (k, len(x), 2), slopes and shortening integrals (k, k, len(x)) at ``x`` (m from the root),
    interpolated linearly between the root (all zero), the beam's span nodes and its tip: the point is then the same
    linear combination of the structural nodes, as OpenFAST's mesh mapping makes it."""
    k = beam.n_modes
    nodes = np.concatenate([[0.0], beam.x, [beam.length]])
    value = np.concatenate([np.zeros((k, 1, 2)), beam.value, beam.tip_value[:, None]], axis=1)
    slope = np.concatenate([np.zeros((k, 1, 2)), beam.slope, beam.tip_slope[:, None]], axis=1)
    shortening = np.concatenate([np.zeros((k, k, 1)), beam.shortening, beam.tip_shortening[:, :, None]], axis=2)
    x = np.clip(np.asarray(x, dtype=float), 0.0, beam.length)
    weights = interpolation_matrix(nodes, x)                                  # (len(x), nodes)
    return (np.einsum("xj,ija->ixa", weights, value), np.einsum("xj,ija->ixa", weights, slope),
            np.einsum("xj,ikj->ikx", weights, shortening))


def interpolation_matrix(nodes: NDArray, x: NDArray) -> NDArray:
    """(len(x), len(nodes)) weights of linear interpolation between sorted ``nodes``."""
    i = np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, len(nodes) - 2)
    t = (x - nodes[i]) / (nodes[i + 1] - nodes[i])
    W = np.zeros((len(x), len(nodes)))
    W[np.arange(len(x)), i] = 1.0 - t
    W[np.arange(len(x)), i + 1] = t
    return W


@dataclass(frozen=True)
class AeroLoads:
    """Aerodynamic loads at one state (earth components, SI).

    generalized : (n,) generalized forces on the model's coordinates, N or N m
    forces, moments : (B, Na, 3) lumped nodal forces (N) and moments (N m)
    positions, velocities : (B, Na, 3) the nodes (aerodynamic centres) and their absolute velocities
    solution : (B, Na, 13) the node solver's outputs (:data:`bladefem.aero.performance.COLUMNS`; column 0 is the
        next call's guess)
    thrust, torque : RtAeroFxh (N) and RtAeroMxh (N m), along and about the shaft axis through the apex
    power : RtAeroPwr = rotor speed about the shaft x torque, W
    tsr, cp, ct : RtTSR, RtAeroCp, RtAeroCt; disk_velocity : disk-averaged relative wind along the shaft, m/s
    skew : chi0, rad
    quasi_steady : (B, Na, 2) with the dynamic wake: the quasi-steady induced velocities (a vx, a' vy) before the
        skew redistribution (the filters' input), m/s
    wake_rate : (B, Na, 4) d/dt of the dynamic-wake states (None without them); tau1 : its time constant, s
    """

    generalized: NDArray
    forces: NDArray
    moments: NDArray
    positions: NDArray
    velocities: NDArray
    solution: NDArray
    thrust: float
    torque: float
    power: float
    tsr: float
    cp: float
    ct: float
    disk_velocity: float
    skew: float
    quasi_steady: NDArray | None = None
    wake_rate: NDArray | None = None
    tau1: float = math.nan

    def column(self, name: str) -> NDArray:
        """One node quantity (B, Na) by its name in :data:`bladefem.aero.performance.COLUMNS`."""
        return self.solution[..., COLUMNS.index(name)]


def aero_nodes(model, aero: TurbineAero, q: NDArray, u: NDArray, motion=None) -> NodeGroup:
    """Positions, partial velocities (factored) and bias accelerations of every blade's aerodynamic nodes."""
    motion = model.motion(q, u) if motion is None else motion
    nodes = BeamNodes(aero.axial, aero.value, aero.shortening, (0, 1, 2), np.eye(model.n)[model.blade_columns],
                      aero.along)
    qb, ub = q[model.blade_columns], u[model.blade_columns]
    span = nodes.deflect(qb, ub)
    offset, partials, velocity, bias = turned_arms(aero.slope, aero.offset, qb, ub)
    return carry_nodes(motion.apex, motion.blade_frames, span.offset + aero.offset + offset,
                       span.partials + partials, nodes.selection, span.velocity + velocity, span.bias + bias)


def aero_loads(model, aero: TurbineAero, q: NDArray, u: NDArray, t: float = 0.0,
               guess: NDArray | None = None, wake: NDArray | None = None) -> AeroLoads:
    """BEM loads on the turbine ``model`` at state (q, u) in the wind at time t (s): quasi-steady, or with the
    induced velocities of the dynamic wake's states ``wake`` (B, Na, 4; :mod:`bladefem.aero.dynamic_wake`), whose
    rates then come with the loads.

    guess : (B, Na) previous inflow angles ``phi_solved`` (a warm start; None solves from scratch)
    """
    if not aero.wake_states:                 # no dynamic wake: states, if any, are ignored (as the kernels do)
        wake = None
    motion = model.motion(q, u)
    group = aero_nodes(model, aero, q, u, motion)
    r, v = group.r, group.velocity(u)
    R = motion.blade_frames.R
    i3, e_t, i1 = R[:, None, :, 0], R[:, None, :, 1], R[:, None, :, 2]
    v_slope, w_slope = np.einsum("bk,kpa->abp", q[model.blade_columns], aero.slope)
    relative = aero.inflow.velocity_at(r, t) - v
    apex, shaft = motion.apex.r, motion.rotor.R[:, 0]
    arm = r - apex
    frame = projection(aero.rotor.options.formulation == 2, arm, shaft, i1, e_t, i3, v_slope, w_slope,
                       aero.rotor.curve_angle, aero.pitch)
    vx, vy = frame.components(relative)
    r_local = np.linalg.norm(arm - (arm @ shaft)[..., None] * shaft, axis=-1)
    disk = disk_values(relative, shaft, R[:, :, 0], motion.rotor.omega @ shaft, r_local)
    solution, quasi = solve_all(aero, vx, vy, r_local, disk, guess, frame, wake)
    fn, ft, m = (solution[..., COLUMNS.index(name)][..., None] for name in ("fn", "ft", "m"))
    forces = np.einsum("ij,bjk->bik", aero.force_lumping(), fn * frame.normal + ft * frame.tangent)
    moments = aero.moment_weights()[None, :, None] * m * frame.span
    _, generalized = group.generalized(np.zeros(forces.shape[:2]), forces)
    generalized = generalized + motion.rotor.W.T @ moments.sum(axis=(0, 1))
    total_force = forces.sum(axis=(0, 1))
    total_moment = np.cross(arm, forces).sum(axis=(0, 1)) + moments.sum(axis=(0, 1))
    thrust, torque = float(total_force @ shaft), float(total_moment @ shaft)
    power = disk.speed * torque
    area = math.pi * disk.max_radius**2
    dynamic = 0.5 * aero.rotor.air_density * area * disk.velocity**2
    rate, tau1 = None, math.nan
    if wake is not None:
        wind_along = float(aero.inflow.velocity_at(r, t).reshape(-1, 3).mean(axis=0) @ shaft)
        rate, tau1 = wake_rates_of(aero, wake, quasi, vx, r_local, disk.velocity, wind_along)
    return AeroLoads(generalized=generalized, forces=forces, moments=moments, positions=r, velocities=v,
                     solution=solution, thrust=thrust, torque=torque, power=power, tsr=disk.tsr,
                     cp=power / (dynamic * disk.velocity) if disk.velocity else 0.0,
                     ct=thrust / dynamic if disk.velocity else 0.0, disk_velocity=disk.velocity, skew=disk.chi0,
                     quasi_steady=quasi, wake_rate=rate, tau1=tau1)


def wake_rates_of(aero: TurbineAero, wake: NDArray, quasi: NDArray, vx: NDArray, r_local: NDArray,
                  relative_along: float, wind_along: float) -> tuple[NDArray, float]:
    """The rates (B, Na, 4) of the dynamic-wake states and tau1 (s): the disk-averaged quasi-steady induction with
    AeroDyn's weights, the disk wind along the shaft (the relative wind ``relative_along`` with BEM_Mod 1, the
    undisturbed ``wind_along`` with BEM_Mod 2), R the largest node radius; r / R now (DBEMT_Mod 2) or undeflected."""
    settings = aero.rotor.dynamic_wake
    parameters = settings.vector()
    a_quasi = np.divide(quasi[..., 0], vx, out=np.zeros_like(vx), where=vx != 0.0)
    weights = disk_weights(np.broadcast_to(aero.undeflected_radius, r_local.shape))
    disk_wind = wind_along if aero.rotor.options.formulation == 2 else relative_along
    radius = float(r_local.max())
    tau1 = time_constant(parameters, float((weights * a_quasi).sum()), disk_wind, radius)
    ratio = r_local / radius if settings.model == 2 else np.broadcast_to(
        aero.undeflected_radius / aero.undeflected_radius.max(), r_local.shape)
    rate = np.empty(wake.shape)
    wake_derivative(wake.reshape(-1, 4), quasi.reshape(-1, 2), tau1, np.ascontiguousarray(ratio).ravel(),
                    parameters[BLEND], rate.reshape(-1, 4))
    return rate, float(tau1)


@dataclass(frozen=True)
class DiskValues:
    """AeroDyn's disk averages (``DiskAvgValues``): velocity = mean relative wind along the shaft (m/s), chi0 the
    skew angle (rad), skew_cos (B,) the cosine of each blade's angle from the most downwind direction of the rotor
    plane, speed the rotor's angular speed about the shaft (rad/s), max_radius the largest r_local (m), tsr and the
    induction weight of AeroDyn's low tip-speed-ratio blend."""

    velocity: float
    chi0: float
    skew_cos: NDArray
    speed: float
    max_radius: float
    tsr: float
    weight: float


def disk_values(relative: NDArray, shaft: NDArray, pitch_axes: NDArray, speed: float, r_local: NDArray
                ) -> DiskValues:
    """Disk averages of the relative wind (B, Na, 3) for the shaft axis, the blades' pitch axes (B, 3), the rotor
    speed (rad/s) and the nodes' distances from the shaft (B, Na)."""
    mean = relative.reshape(-1, 3).mean(axis=0)
    along = float(mean @ shaft)
    size = float(np.linalg.norm(mean))
    chi0 = math.acos(min(max(along / size, -1.0), 1.0)) if size > 0 else 0.0
    in_plane = mean - along * shaft
    norm = float(np.linalg.norm(in_plane))
    in_plane = in_plane / norm if norm > 1e-12 * max(size, 1.0) else np.zeros(3)
    radial = pitch_axes - (pitch_axes @ shaft)[:, None] * shaft
    radial /= np.linalg.norm(radial, axis=1, keepdims=True)
    max_radius = float(r_local.max())
    tsr = speed * max_radius / along if along else 0.0
    return DiskValues(velocity=along, chi0=chi0, skew_cos=radial @ in_plane, speed=float(speed),
                      max_radius=max_radius, tsr=tsr, weight=induction_weight(tsr))


def solve_all(aero: TurbineAero, vx: NDArray, vy: NDArray, r_local: NDArray, disk: DiskValues,
              guess: NDArray | None, frame: Projection, wake: NDArray | None = None) -> tuple[NDArray, NDArray]:
    """The node solver at every node of every blade: (B, Na, NODE_OUTPUTS), the sections oriented by ``frame``,
    and, with the dynamic wake's states ``wake`` (B, Na, 4: the loads then see its induced velocities), the
    quasi-steady induced velocities (B, Na, 2) (None without)."""
    rotor = aero.rotor
    shape = vx.shape
    tip_ratio = r_local / r_local.max(axis=1, keepdims=True)
    per_node = [np.ascontiguousarray(np.broadcast_to(x, shape).ravel()) for x in (
        vx, vy, r_local, rotor.chord, aero.theta + frame.twist, aero.tip_constant, aero.hub_constant, tip_ratio,
        np.full(shape, disk.chi0), disk.skew_cos[:, None], rotor.airfoil,
        np.full(shape, np.nan) if guess is None else guess, frame.cant, frame.toe, frame.drdz)]
    vx_, vy_, r_, chord, theta, tip_c, hub_c, ratio, chi0, skew_cos, airfoil, start, cant, toe, drdz = per_node
    out, quasi = np.empty((vx.size, NODE_OUTPUTS)), np.empty((vx.size, 2))
    args = (vx_, vy_, r_, chord, theta, tip_c, hub_c, float(rotor.n_blades), ratio, chi0, skew_cos, disk.weight,
            airfoil.astype(np.int64), *aero.polar_arrays, aero.options, float(rotor.air_density), start, cant, toe,
            drdz)
    if wake is None:
        solve_nodes(*args, out)
        return out.reshape(shape + (NODE_OUTPUTS,)), None
    solve_wake_nodes(*args, np.ascontiguousarray(wake, dtype=float).reshape(-1, 4), out, quasi)
    return out.reshape(shape + (NODE_OUTPUTS,)), quasi.reshape(shape + (2,))


def aero_forcing(model, aero: TurbineAero):
    """``forcing(q, u)``: the model's Kane forcing plus the aerodynamic generalized forces (the BEM re-solved at
    every call: quasi-steady induction), for :func:`bladefem.models.turbine.linearize.linearize`; ``model`` without
    aerodynamics of its own (a model built with ``aero`` has them in its equations already)."""
    if model.aero is not None:
        raise ValueError("the model carries aerodynamic loads already: use model.equations")

    def forcing(q: NDArray, u: NDArray) -> NDArray:
        return model.equations(q, u)[1] + aero_loads(model, aero, q, u).generalized
    return forcing
