"""Kane's equations of the turbine, assembled numerically at one state.

Generalized inertia forces ``F*_k = -sum_p m_p v_k^p . a^p - sum_b omega_k^b . (I_b alpha_b + omega_b x I_b
omega_b)`` and active forces ``F_k = sum_p v_k^p . m_p g - (K q + C u)_k`` (gravity on every mass; modal elastic and
damping forces; drivetrain and yaw springs and dampers) are summed over the span nodes and rigid bodies. With
``a = J du/dt + a_b`` this gives ``M(q) du/dt = f(q, u)`` with ``M = sum m J^T J + sum W^T I W`` and
``f = F + F*(du/dt = 0)``. The centrifugal and gravitational stiffening of blades and tower come from the axial
shortening inside ``J`` and ``a_b``; nothing is linearised.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .kinematics import (
    BeamNodes,
    FrameMotion,
    NodeGroup,
    PointMotion,
    at_rest,
    axis_rotation,
    carry,
    carry_nodes,
    earth,
    rotate,
    skew,
    turn,
)
from .parameters import TurbineParameters


def pick(points: PointMotion, index: object) -> PointMotion:
    """A subset of points, ``index`` applied to the leading axes."""
    return PointMotion(r=points.r[index], v=points.v[index], J=points.J[index], a=points.a[index])


@dataclass(frozen=True)
class TurbineMotion:
    """Motion of every body at one state (earth components).

    tower : (P_t + 1,) tower span nodes, the last one the tower top (yaw bearing)
    rigid : (3,) nacelle centre of mass, rotor apex, hub centre of mass
    blades : (B, P_b + 1) blade span nodes, the last one each blade's tip
    """

    tower: NodeGroup
    tower_top: PointMotion
    rigid: PointMotion
    blades: NodeGroup
    tower_top_frame: FrameMotion
    nacelle: FrameMotion
    shaft: FrameMotion          # non-rotating, x along the shaft (downwind)
    rotor: FrameMotion          # rotates with the rotor azimuth
    generator: FrameMotion
    blade_frames: FrameMotion   # R (B, 3, 3)

    @property
    def apex(self) -> PointMotion:
        return pick(self.rigid, 1)


def cone_rotation(precone: float) -> NDArray:
    """Blade axes (x span, y leading edge, z downwind) in the rotor frame (x shaft, blade 1 along z)."""
    s, c = np.sin(precone), np.cos(precone)
    return np.array([[s, 0.0, c], [0.0, -1.0, 0.0], [c, 0.0, -s]]).T


def block_diagonal(n: int, blocks: list[tuple[NDArray, NDArray]]) -> NDArray:
    """An n x n matrix with each (columns, block) placed on the diagonal."""
    A = np.zeros((n, n))
    for cols, block in blocks:
        A[np.ix_(cols, cols)] += block
    return A


class TurbineModel:
    """The turbine's equations of motion ``M(q) du/dt = f(q, u)`` over all generalized coordinates ``q``.

    params : the structure; aero : aerodynamic loads (:class:`~bladefem.models.turbine.aero.TurbineAero`, quasi-steady
    BEM at the AeroDyn nodes) or None; generator : the generator torque law
    (:class:`~bladefem.models.turbine.control.Generator`) or None. Both enter the forcing ``f``.
    """

    def __init__(self, params: TurbineParameters, aero=None, generator=None) -> None:
        p = self.params = params
        self.aero, self.generator = aero, generator
        self.dofs = p.dofs
        n = self.n = len(self.dofs)
        index = {name: i for i, name in enumerate(self.dofs)}
        self.tower_columns = np.arange(4)
        self.blade_columns = 7 + 3 * np.arange(p.n_blades)[:, None] + np.arange(3)[None, :]
        unit = np.eye(n)
        self.fore_aft_tilt = np.zeros(n)
        self.fore_aft_tilt[:4] = p.tower.tip_slope[:, 0]
        self.side_side_tilt = np.zeros(n)
        self.side_side_tilt[:4] = -p.tower.tip_slope[:, 1]
        self.yaw = unit[index["yaw"]]
        self.azimuth = unit[index["generator_azimuth"]] + unit[index["drivetrain"]]
        self.generator_angle = p.gearbox_ratio * unit[index["generator_azimuth"]]
        self.tilt = axis_rotation(1, -p.shaft_tilt)
        self.blade_rotations = np.stack([axis_rotation(0, 2 * np.pi * k / p.n_blades) @ cone_rotation(p.precone)
                                         for k in range(p.n_blades)])
        self._nodes()
        self._fast = None
        self.base = at_rest(np.array([0.0, 0.0, p.tower_base_height]), n)
        blade = np.append(p.blade.point_mass, p.blade_tip_mass)
        self.tower_masses = np.append(p.tower.point_mass, p.yaw_bearing_mass)
        self.rigid_masses = np.array([p.nacelle_mass, 0.0, p.hub_mass])
        self.blade_masses = np.tile(blade, (p.n_blades, 1))
        self.masses = np.concatenate([self.tower_masses, self.rigid_masses, self.blade_masses.ravel()])
        self.gravity = np.array([0.0, 0.0, -p.gravity])
        nacelle_own = p.nacelle_yaw_inertia - p.nacelle_mass * (p.nacelle_cm[0] ** 2 + p.nacelle_cm[1] ** 2)
        self.inertias = (nacelle_own, p.hub_inertia, p.generator_inertia)
        springs = [(np.array([index["drivetrain"]]), np.array([[p.drivetrain_stiffness]])),
                   (np.array([index["yaw"]]), np.array([[p.yaw_stiffness]]))]
        dampers = [(np.array([index["drivetrain"]]), np.array([[p.drivetrain_damping]])),
                   (np.array([index["yaw"]]), np.array([[p.yaw_damping]]))]
        blade_K = p.blade.generalized_stiffness()
        blade_C, tower_C = p.damping_matrices()
        self.K = block_diagonal(n, [(self.tower_columns, p.tower.generalized_stiffness()), *springs,
                                    *[(cols, blade_K) for cols in self.blade_columns]])
        self.C = block_diagonal(n, [(self.tower_columns, tower_C), *dampers,
                                    *[(cols, blade_C) for cols in self.blade_columns]])

    def fast_equations(self):
        """The fastest available ``(q, u) -> (M, f)``: the numba-compiled kernel (:mod:`.compiled`) if numba is
        installed, else :meth:`equations`."""
        if self._fast is None:
            from .compiled import compiled_equations
            self._fast = compiled_equations(self) or self.equations
        return self._fast

    # -- kinematics ---------------------------------------------------------------------------------------------

    def _nodes(self) -> None:
        """Span nodes of the tower and blades with the free end appended, and the offsets of the nacelle centre of
        mass, rotor apex and hub centre of mass in the nacelle frame."""
        p, unit = self.params, np.eye(self.n)

        def nodes(beam, start, order, selection):
            return BeamNodes(start + np.append(beam.x, beam.length),
                             np.concatenate([beam.value, beam.tip_value[:, None]], axis=1),
                             np.concatenate([beam.shortening, beam.tip_shortening[:, :, None]], axis=2),
                             order, selection)

        self.tower_nodes = nodes(p.tower, 0.0, (2, 0, 1), unit[self.tower_columns])
        self.blade_nodes = nodes(p.blade, p.hub_radius, (0, 1, 2), unit[self.blade_columns])
        shaft_axis = self.tilt[:, 0]
        shaft = np.array([0.0, 0.0, p.twr2shft])
        self.rigid_offsets = np.array([p.nacelle_cm, shaft + p.overhang * shaft_axis,
                                       shaft + (p.overhang + p.hub_cm) * shaft_axis])

    def motion(self, q: NDArray, u: NDArray) -> TurbineMotion:
        """Positions, velocities, partial velocities and bias accelerations of every body at state (q, u)."""
        n = self.n
        ground = earth(n)
        span = self.tower_nodes.deflect(q[:4], u[:4])
        tower = carry_nodes(self.base, ground, span.offset, span.partials, self.tower_nodes.selection,
                            span.velocity, span.bias)
        bent = rotate(rotate(ground, 1, self.fore_aft_tilt, q, u), 0, self.side_side_tilt, q, u)
        nacelle = rotate(bent, 2, self.yaw, q, u)
        top = tower.point(-1, u)
        rigid = carry(top, nacelle, self.rigid_offsets)
        shaft = turn(nacelle, self.tilt)
        rotor = rotate(shaft, 0, self.azimuth, q, u)
        generator = rotate(shaft, 0, self.generator_angle, q, u)
        blade_frames = turn(rotor, self.blade_rotations)
        span = self.blade_nodes.deflect(q[self.blade_columns], u[self.blade_columns])
        blades = carry_nodes(pick(rigid, 1), blade_frames, span.offset, span.partials, self.blade_nodes.selection,
                             span.velocity, span.bias)
        return TurbineMotion(tower=tower, tower_top=top, rigid=rigid, blades=blades, tower_top_frame=bent,
                             nacelle=nacelle,
                             shaft=shaft, rotor=rotor, generator=generator, blade_frames=blade_frames)

    def positions(self, motion: TurbineMotion) -> NDArray:
        """Positions of all point masses (in the order of ``self.masses``), (N, 3)."""
        return np.concatenate([motion.tower.r, motion.rigid.r, motion.blades.r.reshape(-1, 3)])

    def rigid_bodies(self, motion: TurbineMotion) -> list[tuple[FrameMotion, NDArray, float]]:
        """(frame, unit axis in earth components, moment of inertia about it through the centre of mass) of the
        bodies with rotary inertia, each about one body axis as in ElastoDyn: the nacelle about the yaw axis (its
        NacYIner less the share of its centre of mass), the hub and the generator about the shaft."""
        frames = (motion.nacelle, motion.rotor, motion.generator)
        return [(frame, frame.R[:, axis], inertia) for frame, axis, inertia in zip(frames, (2, 0, 0), self.inertias)]

    # -- Kane's equations ---------------------------------------------------------------------------------------

    def equations(self, q: NDArray, u: NDArray, blade_forces: NDArray | None = None, t: float = 0.0,
                  wake: NDArray | None = None) -> tuple[NDArray, NDArray]:
        """Mass matrix M(q) (n, n) and forcing f(q, u) (n,) with ``M du/dt = f``; ``blade_forces`` (B, P + 1, 3),
        N in earth components, are external forces on the blade nodes (tip last), added to the forcing as
        ``sum_p J_p^T F_p``; the model's aerodynamic loads (in the wind at time t, s; with the dynamic wake's
        states ``wake``, else quasi-steady) and generator torque, if any, are included."""
        motion = self.motion(q, u)
        M, f = np.zeros((self.n, self.n)), np.zeros(self.n)
        for group, masses, external in ((motion.tower, self.tower_masses, None),
                                        (motion.blades, self.blade_masses, blade_forces)):
            loads = masses[..., None] * (self.gravity - group.a)
            dM, df = group.generalized(masses, loads if external is None else loads + external)
            M += dM
            f += df
        rigid = motion.rigid
        weighted = rigid.J * np.sqrt(self.rigid_masses)[:, None, None]
        M += np.einsum("pik,pil->kl", weighted, weighted)
        f += np.einsum("pik,pi->k", rigid.J, self.rigid_masses[:, None] * (self.gravity - rigid.a))
        for frame, axis, inertia in self.rigid_bodies(motion):
            # H = I k (k . omega): dH/dt = I [k (k . alpha) + (k . omega) omega x k] at zero accelerations
            partial = frame.W.T @ axis
            M += inertia * np.outer(partial, partial)
            f -= inertia * ((axis @ frame.alpha) * partial
                            + (axis @ frame.omega) * (frame.W.T @ (skew(frame.omega) @ axis)))
        f -= self.K @ q + self.C @ u
        return M, f + self.applied_forces(q, u, t, wake)

    def applied_forces(self, q: NDArray, u: NDArray, t: float = 0.0, wake: NDArray | None = None) -> NDArray:
        """Generalized forces (n,) of the aerodynamic loads (wind at time t; the dynamic wake's states ``wake``)
        and the generator torque at (q, u)."""
        f = np.zeros(self.n)
        if self.aero is not None:
            from .aero import aero_loads
            f += aero_loads(self, self.aero, q, u, t, wake=wake).generalized
        if self.generator is not None:
            g = self.dofs.index("generator_azimuth")
            ratio = self.params.gearbox_ratio
            f[g] -= ratio * self.generator.torque(ratio * u[g])
        return f

    def energy(self, q: NDArray, u: NDArray) -> tuple[float, float]:
        """Kinetic energy and potential energy (gravity above the ground, strain, springs), J."""
        motion = self.motion(q, u)
        kinetic = 0.5 * (np.sum(self.tower_masses * np.sum(motion.tower.velocity(u) ** 2, axis=-1))
                         + np.sum(self.rigid_masses * np.sum(motion.rigid.v**2, axis=-1))
                         + np.sum(self.blade_masses * np.sum(motion.blades.velocity(u) ** 2, axis=-1)))
        for frame, axis, inertia in self.rigid_bodies(motion):
            kinetic += 0.5 * inertia * (axis @ frame.omega) ** 2
        potential = -np.sum(self.masses * (self.positions(motion) @ self.gravity)) + 0.5 * q @ self.K @ q
        return float(kinetic), float(potential)
