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

from .kinematics import (FrameMotion, PointMotion, at_rest, axis_rotation, beam_deflection, carry, earth, rotate,
                         scatter, skew, turn)
from .parameters import TurbineParameters


@dataclass(frozen=True)
class TurbineMotion:
    """Motion of every body at one state (earth components)."""

    tower: PointMotion          # (P_t,) tower span nodes
    tower_top: PointMotion      # (), yaw bearing
    tower_top_frame: FrameMotion
    nacelle: FrameMotion
    shaft: FrameMotion          # non-rotating, x along the shaft (downwind)
    rotor: FrameMotion          # rotates with the rotor azimuth
    generator: FrameMotion
    nacelle_cm: PointMotion
    apex: PointMotion
    hub_cm: PointMotion
    blade_frames: FrameMotion   # R (B, 3, 3)
    blades: PointMotion         # (B, P_b) span nodes
    blade_tips: PointMotion     # (B,)


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
    """The turbine's equations of motion ``M(q) du/dt = f(q, u)`` over all generalized coordinates ``q``."""

    def __init__(self, params: TurbineParameters) -> None:
        p = self.params = params
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
        self.tower_axial = p.tower.x + 0.0
        self.blade_axial = p.hub_radius + p.blade.x
        self.masses = np.concatenate([
            p.tower.point_mass, [p.yaw_bearing_mass, p.nacelle_mass, p.hub_mass],
            np.tile(p.blade.point_mass, p.n_blades), np.full(p.n_blades, p.blade_tip_mass)])
        self.sqrt_masses = np.sqrt(self.masses)
        self.gravity = np.array([0.0, 0.0, -p.gravity])
        nacelle_own = p.nacelle_yaw_inertia - p.nacelle_mass * (p.nacelle_cm[0] ** 2 + p.nacelle_cm[1] ** 2)
        self.nacelle_inertia = np.diag([0.0, 0.0, nacelle_own])
        self.hub_inertia = np.diag([p.hub_inertia, 0.0, 0.0])
        self.generator_inertia = np.diag([p.generator_inertia, 0.0, 0.0])
        tower_top_mass = p.rotor_nacelle_mass
        springs = [(np.array([index["drivetrain"]]), np.array([[p.drivetrain_stiffness]])),
                   (np.array([index["yaw"]]), np.array([[p.yaw_stiffness]]))]
        dampers = [(np.array([index["drivetrain"]]), np.array([[p.drivetrain_damping]])),
                   (np.array([index["yaw"]]), np.array([[p.yaw_damping]]))]
        blade_K, blade_C = p.blade.generalized_stiffness(), p.blade.damping_matrix(p.blade_tip_mass)
        self.K = block_diagonal(n, [(self.tower_columns, p.tower.generalized_stiffness()), *springs,
                                    *[(cols, blade_K) for cols in self.blade_columns]])
        self.C = block_diagonal(n, [(self.tower_columns, p.tower.damping_matrix(tower_top_mass)), *dampers,
                                    *[(cols, blade_C) for cols in self.blade_columns]])

    # -- kinematics ---------------------------------------------------------------------------------------------

    def motion(self, q: NDArray, u: NDArray) -> TurbineMotion:
        """Positions, velocities, partial velocities and bias accelerations of every body at state (q, u)."""
        p, n = self.params, self.n
        base = at_rest(np.array([0.0, 0.0, p.tower_base_height]), n)
        ground = earth(n)
        qt, ut = q[:4], u[:4]
        span = beam_deflection(self.tower_axial, p.tower.value, p.tower.shortening, qt, ut, (2, 0, 1))
        tower = carry(base, ground, span.offset, scatter(span.partials, self.tower_columns, n), span.velocity,
                      span.bias)
        top = beam_deflection(np.array([p.tower.length]), p.tower.tip_value[:, None, :],
                              p.tower.tip_shortening[:, :, None], qt, ut, (2, 0, 1))
        tower_top = carry(base, ground, top.offset[0], scatter(top.partials[0], self.tower_columns, n),
                          top.velocity[0], top.bias[0])
        bent = rotate(rotate(ground, 1, self.fore_aft_tilt, q, u), 0, self.side_side_tilt, q, u)
        nacelle = rotate(bent, 2, self.yaw, q, u)
        nacelle_cm = carry(tower_top, nacelle, p.nacelle_cm)
        shaft = turn(nacelle, self.tilt)
        shaft_point = carry(tower_top, nacelle, np.array([0.0, 0.0, p.twr2shft]))
        apex = carry(shaft_point, shaft, np.array([p.overhang, 0.0, 0.0]))
        hub_cm = carry(apex, shaft, np.array([p.hub_cm, 0.0, 0.0]))
        rotor = rotate(shaft, 0, self.azimuth, q, u)
        generator = rotate(shaft, 0, self.generator_angle, q, u)
        blade_frames = turn(rotor, self.blade_rotations)
        qb, ub = q[self.blade_columns], u[self.blade_columns]
        span = beam_deflection(self.blade_axial, p.blade.value, p.blade.shortening, qb, ub, (0, 1, 2))
        blades = carry(apex, blade_frames, span.offset, scatter(span.partials, self.blade_columns, n),
                       span.velocity, span.bias)
        tip = beam_deflection(np.array([p.hub_radius + p.blade.length]), p.blade.tip_value[:, None, :],
                              p.blade.tip_shortening[:, :, None], qb, ub, (0, 1, 2))
        blade_tips = carry(apex, blade_frames, tip.offset[:, 0], scatter(tip.partials[:, 0], self.blade_columns, n),
                           tip.velocity[:, 0], tip.bias[:, 0])
        return TurbineMotion(tower=tower, tower_top=tower_top, tower_top_frame=bent, nacelle=nacelle, shaft=shaft,
                             rotor=rotor, generator=generator, nacelle_cm=nacelle_cm, apex=apex, hub_cm=hub_cm,
                             blade_frames=blade_frames, blades=blades, blade_tips=blade_tips)

    def mass_points(self, motion: TurbineMotion) -> PointMotion:
        """All point masses stacked in the order of ``self.masses``."""
        parts = [motion.tower, motion.tower_top, motion.nacelle_cm, motion.hub_cm, motion.blades,
                 motion.blade_tips]
        return PointMotion(
            r=np.concatenate([part.r.reshape(-1, 3) for part in parts]),
            v=np.concatenate([part.v.reshape(-1, 3) for part in parts]),
            J=np.concatenate([part.J.reshape(-1, 3, self.n) for part in parts]),
            a=np.concatenate([part.a.reshape(-1, 3) for part in parts]))

    def rigid_bodies(self, motion: TurbineMotion) -> list[tuple[FrameMotion, NDArray]]:
        """(frame, inertia tensor about the centre of mass in frame components) of the bodies with rotary inertia."""
        return [(motion.nacelle, self.nacelle_inertia), (motion.rotor, self.hub_inertia),
                (motion.generator, self.generator_inertia)]

    # -- Kane's equations ---------------------------------------------------------------------------------------

    def equations(self, q: NDArray, u: NDArray) -> tuple[NDArray, NDArray]:
        """Mass matrix M(q) (n, n) and forcing f(q, u) (n,) with ``M du/dt = f``."""
        motion = self.motion(q, u)
        points = self.mass_points(motion)
        weighted = (points.J * self.sqrt_masses[:, None, None]).reshape(-1, self.n)
        M = weighted.T @ weighted
        loads = self.masses[:, None] * (self.gravity - points.a)
        f = points.J.reshape(-1, self.n).T @ loads.ravel()
        for frame, local in self.rigid_bodies(motion):
            inertia = frame.R @ local @ frame.R.T
            M += frame.W.T @ inertia @ frame.W
            f -= frame.W.T @ (inertia @ frame.alpha + skew(frame.omega) @ inertia @ frame.omega)
        f -= self.K @ q + self.C @ u
        return M, f

    def energy(self, q: NDArray, u: NDArray) -> tuple[float, float]:
        """Kinetic energy ``1/2 u^T M u`` and potential energy (gravity above the ground, strain, springs), J."""
        motion = self.motion(q, u)
        points = self.mass_points(motion)
        kinetic = 0.5 * np.sum(self.masses * np.sum(points.v**2, axis=1))
        for frame, local in self.rigid_bodies(motion):
            kinetic += 0.5 * frame.omega @ frame.R @ local @ frame.R.T @ frame.omega
        potential = -np.sum(self.masses * (points.r @ self.gravity)) + 0.5 * q @ self.K @ q
        return float(kinetic), float(potential)
