"""Aerodynamic loads of the turbine with the induction held at an operating point (frozen wake), and their
Jacobians over the generalized coordinates and speeds.

OpenFAST linearizes AeroDyn's BEM with a frozen wake (``DBEMT_Mod`` -1): the induced velocities of every node,
``vx a`` along the normal and ``vy a'`` in the plane of rotation, are held at their operating-point values while
the structure moves (``BEMT.f90``, ``computeFrozenWake``), so a node's inflow is

    x = vx - (vx a)_op,   y = vy + (vy a')_op,   phi = atan2(x, y),   alpha = phi - theta,

with ``vx``, ``vy`` the node's relative wind projected as in :mod:`bladefem.models.turbine.aero` (the same
kinematics and projection, :func:`node_inflow`; with BEM_Mod 2 x is further scaled by cos(cant) and the section
sees its own angle, ``ComputePhiWithInduction``), and the section loads of :func:`bladefem.aero.section.section_loads`
at (x, y). The
quasi-steady alternative re-solves the BEM for every perturbation (:func:`bladefem.models.turbine.aero.aero_loads`).

The Jacobians (:func:`aero_jacobians`) are central differences: over the speeds ``u`` the nodes' velocities change
by ``h J_i`` at fixed positions and frames (exact: ``v = J(q) u``), so the kinematics are evaluated once; over the
coordinates ``q`` the kinematics are re-evaluated (positions, frames, partial velocities and the sections' slopes,
hence their cant, toe and twist, all move).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from ...aero.bem import NODE_OUTPUTS, solve_nodes
from ...aero.performance import COLUMNS
from .aero import TurbineAero, aero_loads, aero_nodes
from ...aero.polar import Projection, projection
from .kinematics import NodeGroup

#: relative step of the central differences (the loads are smooth between polar knots; 1e-6 balances truncation
#: and rounding for the O(1) to O(100) coordinates and speeds of a turbine)
STEP = 1e-6
FN, FT, PM = (COLUMNS.index(name) for name in ("fn", "ft", "m"))


@dataclass(frozen=True)
class NodeInflow:
    """The aerodynamic nodes of every blade at one state (earth components).

    group : positions and factored partial velocities (:class:`~bladefem.models.turbine.kinematics.NodeGroup`)
    velocity : (B, Na, 3) node velocities, m/s; wind : (B, Na, 3) the undisturbed wind there, m/s
    normal, tangent, span : (B, Na, 3) unit vectors the section loads act along (``frame``'s: the bent section's
        normal and direction of rotation, less the twist its orientation carries, and its span axis)
    rotor_W : (3, n) partial angular velocities of the rotor (the pitching moments act on it)
    frame : the projection of the relative wind and the sections' orientation (:mod:`bladefem.aero.polar`)
    """

    group: NodeGroup
    velocity: NDArray
    wind: NDArray
    normal: NDArray
    tangent: NDArray
    span: NDArray
    rotor_W: NDArray
    frame: Projection

    def components(self, velocity: NDArray) -> tuple[NDArray, NDArray]:
        """(vx, vy) of the relative wind for node velocities ``velocity`` (..., B, Na, 3), projected as the
        BEM takes them."""
        return self.frame.components(self.wind - velocity)


def node_inflow(model, aero: TurbineAero, q: NDArray, u: NDArray) -> NodeInflow:
    """The nodes' kinematics at (q, u), projected as :func:`bladefem.models.turbine.aero.aero_loads` does."""
    motion = model.motion(q, u)
    group = aero_nodes(model, aero, q, u, motion)
    R = motion.blade_frames.R
    i3, e_t, i1 = R[:, None, :, 0], R[:, None, :, 1], R[:, None, :, 2]
    v_slope, w_slope = np.einsum("bk,kpa->abp", q[model.blade_columns], aero.slope)
    frame = projection(aero.rotor.options.formulation == 2, group.r - motion.apex.r, motion.rotor.R[:, 0], i1, e_t,
                       i3, v_slope, w_slope, aero.rotor.curve_angle, aero.pitch)
    return NodeInflow(group=group, velocity=group.velocity(u), wind=aero.inflow.velocity(group.r[..., 2]),
                      normal=frame.normal, tangent=frame.tangent, span=frame.span, rotor_W=motion.rotor.W,
                      frame=frame)


@dataclass(frozen=True)
class HeldInduction:
    """Induced velocities held at an operating point, (B, Na) each, m/s: ``axial`` = vx a (subtracted from vx),
    ``tangential`` = vy a' (added to vy)."""

    axial: NDArray
    tangential: NDArray


def held_induction(model, aero: TurbineAero, q: NDArray, u: NDArray) -> HeldInduction:
    """The quasi-steady BEM's induced velocities at the state (q, u)."""
    loads = aero_loads(model, aero, q, u)
    vx, vy = node_inflow(model, aero, q, u).components(loads.velocities)
    return HeldInduction(axial=vx * loads.column("a"), tangential=vy * loads.column("ap"))


@dataclass(frozen=True)
class SectionAero:
    """What the frozen-wake loads need of a :class:`TurbineAero`, prepared once: the rotor, the same rotor with the
    BEM's induction off (its node solver then returns the section loads at the velocities it is handed,
    :func:`bladefem.aero.bem.node_loads`), the force lumping matrix and the moment weights."""

    aero: TurbineAero
    bare: TurbineAero
    lumping: NDArray
    weights: NDArray

    @classmethod
    def of(cls, aero: TurbineAero) -> SectionAero:
        rotor = aero.rotor
        bare = replace(aero, rotor=replace(rotor, options=replace(rotor.options, induction=False)))
        return cls(aero=aero, bare=bare, lumping=aero.force_lumping(), weights=aero.moment_weights())

    def section_loads(self, x: NDArray, y: NDArray, frame: Projection) -> NDArray:
        """(fn, ft, m) per unit length (..., B, Na, 3) at the inflow velocities (x, y) (..., B, Na), m/s, of the
        sections oriented by ``frame``."""
        bare, rotor = self.bare, self.bare.rotor
        shape = x.shape
        x_, y_, chord, theta, cant, toe = (np.ascontiguousarray(np.broadcast_to(value, shape), dtype=float).ravel()
                                           for value in (x, y, rotor.chord, bare.theta + frame.twist, frame.cant,
                                                         frame.toe))
        ones = np.ones(x.size)
        airfoil = np.ascontiguousarray(np.broadcast_to(rotor.airfoil, shape)).ravel().astype(np.int64)
        out = np.empty((x.size, NODE_OUTPUTS))
        solve_nodes(x_, y_, ones, chord, theta, ones, ones, float(rotor.n_blades), ones, 0 * ones, 0 * ones, 1.0,
                    airfoil, *bare.polar_arrays, bare.options, float(rotor.air_density), np.full(x.size, np.nan),
                    cant, toe, ones, out)
        return out[:, [FN, FT, PM]].reshape(shape + (3,))

    def nodal_loads(self, inflow: NodeInflow, loads: NDArray) -> tuple[NDArray, NDArray]:
        """Lumped nodal forces and moments (..., B, Na, 3) of the section loads (..., B, Na, 3), as
        :func:`~bladefem.models.turbine.aero.aero_loads` lumps them."""
        per_length = loads[..., 0:1] * inflow.normal + loads[..., 1:2] * inflow.tangent
        forces = np.einsum("ij,...bjk->...bik", self.lumping, per_length)
        return forces, self.weights[:, None] * loads[..., 2:3] * inflow.span

    def generalized(self, model, held: HeldInduction, q: NDArray, u: NDArray) -> NDArray:
        """Generalized aerodynamic forces (B, n) of each blade's loads at (q, u) with the induced velocities
        ``held``."""
        inflow = node_inflow(model, self.aero, q, u)
        vx, vy = inflow.components(inflow.velocity)
        loads = self.section_loads(vx - held.axial, vy + held.tangential, inflow.frame)
        return per_blade_forces(inflow, *self.nodal_loads(inflow, loads))


def per_blade_forces(inflow: NodeInflow, forces: NDArray, moments: NDArray) -> NDArray:
    """``J_p^T F_p`` summed over each blade's nodes plus ``W_rotor^T`` times its moments, (..., B, n), for nodal
    forces and moments (..., B, Na, 3)."""
    return (np.einsum("bpkn,...bpk->...bn", inflow.group.J, forces)
            + np.einsum("kn,...bk->...bn", inflow.rotor_W, moments.sum(axis=-2)))


def perturbation_groups(model, columns: NDArray, separable: bool) -> list[NDArray]:
    """The coordinates perturbed together: one at a time, or (``separable``: each blade's loads depend on its own
    coordinates only, as with a frozen wake) the same mode of every blade at once."""
    if not separable:
        return [np.array([i]) for i in columns]
    blade_of = {int(i): b for b, row in enumerate(model.blade_columns) for i in row}
    groups: dict[object, list[int]] = {}
    for i in columns:
        key = int(i) if int(i) not in blade_of else ("mode", list(model.blade_columns[blade_of[int(i)]]).index(i))
        groups.setdefault(key, []).append(int(i))
    return [np.array(group) for group in groups.values()]


def aero_jacobians(model, aero: TurbineAero, q: NDArray, u: NDArray, columns: NDArray,
                   held: HeldInduction | None, sections: SectionAero | None = None) -> tuple[NDArray, NDArray]:
    """dQ/dq and dQ/du (n, len(columns)) of the aerodynamic generalized forces Q at (q, u) over the coordinates
    ``columns``: the frozen wake with the induced velocities ``held`` (``sections`` prepared from ``aero``, or
    prepared here), or (``held`` None) the quasi-steady BEM re-solved for every perturbation."""
    position = {int(i): j for j, i in enumerate(columns)}
    dq, du = np.zeros((model.n, len(columns))), np.zeros((model.n, len(columns)))
    if held is None:
        def forces(qq: NDArray, uu: NDArray) -> NDArray:
            return aero_loads(model, aero, qq, uu).generalized[None]
    else:
        sections = sections or SectionAero.of(aero)

        def forces(qq: NDArray, uu: NDArray) -> NDArray:
            return sections.generalized(model, held, qq, uu)
    blade_of = {int(i): b for b, row in enumerate(model.blade_columns) for i in row}
    for group in perturbation_groups(model, columns, held is not None):
        h = STEP * max(1.0, float(np.abs(q[group]).max()))
        plus, minus = q.copy(), q.copy()
        plus[group] += h
        minus[group] -= h
        change = (forces(plus, u) - forces(minus, u)) / (2 * h)
        for i in group:
            dq[:, position[int(i)]] = change[blade_of[int(i)]] if len(group) > 1 else change.sum(axis=0)
    if held is None:
        for j, i in enumerate(columns):
            h = STEP * max(1.0, abs(u[i]))
            plus, minus = u.copy(), u.copy()
            plus[i] += h
            minus[i] -= h
            du[:, j] = (forces(q, plus) - forces(q, minus)).sum(axis=0) / (2 * h)
        return dq, du
    # frozen wake: the velocities move by h J_i at fixed kinematics, all perturbations in one call
    inflow = node_inflow(model, aero, q, u)
    steps = STEP * np.maximum(1.0, np.abs(u[columns]))
    change = np.moveaxis(inflow.group.J[..., columns] * steps, -1, 0)       # (k, B, Na, 3)
    vx, vy = inflow.components(np.concatenate([inflow.velocity + change, inflow.velocity - change]))
    loads = sections.section_loads(vx - held.axial, vy + held.tangential, inflow.frame)
    Q = per_blade_forces(inflow, *sections.nodal_loads(inflow, loads)).sum(axis=-2)    # (2k, n)
    k = len(columns)
    du = ((Q[:k] - Q[k:]) / (2 * steps[:, None])).T
    return dq, du
