"""Symbolic cross-check of the numeric Kane model: a 5-DOF turbine (tower fore-aft 1, nacelle yaw, generator
azimuth, drivetrain torsion, one blade's flap 1) derived independently with sympy.physics.mechanics.KanesMethod
(frames, points, particles and rigid bodies; springs and dampers as torque pairs) gives the same mass matrix and
forcing as the numeric assembly at random states.

The shapes are simple polynomials, ``phi = (x/L)^2`` (the blade's with an in-plane share), whose axial-shortening
integrals ``S(x) = (phi_y'^2 + phi_z'^2) 4 x^3 / (3 L^4)`` are written in closed form on the sympy side; both sides
use the same few span nodes and lumped masses. Only the modal elastic forces ``-K q`` (a given potential, not a
force on a body) are added to sympy's forcing by hand.
"""

from __future__ import annotations

import numpy as np
import pytest

from bladefem.models.turbine import (
    FreeSystem,
    ModalBeam,
    TurbineModel,
    TurbineParameters,
)

sympy = pytest.importorskip("sympy")
me = pytest.importorskip("sympy.physics.mechanics")

H, L = 30.0, 12.0                              # tower length and blade length, m
TOWER_X = np.array([6.0, 17.0, 26.0])          # tower span nodes, m
TOWER_W = np.array([9.0, 10.0, 11.0])          # their quadrature weights, m
BLADE_X = np.array([2.0, 7.0, 10.5])
BLADE_W = np.array([4.0, 4.0, 4.0])
FLAP_DIRECTION = np.array([0.3, 1.0])          # (in-plane, out-of-plane) share of the blade's flap 1 shape
GEOMETRY = dict(tower_base_height=0.0, twr2shft=1.7, overhang=-3.1, shaft_tilt=np.radians(-6.0),
                precone=np.radians(-4.0), hub_radius=1.4, hub_cm=0.4, hub_mass=900.0, hub_inertia=2100.0,
                generator_inertia=3.0, gearbox_ratio=50.0, nacelle_mass=4000.0, nacelle_yaw_inertia=9000.0,
                nacelle_cm=np.array([1.2, 0.3, 0.9]), yaw_bearing_mass=700.0, drivetrain_stiffness=3.0e6,
                drivetrain_damping=2.0e4, yaw_stiffness=8.0e6, yaw_damping=3.0e4, blade_tip_mass=35.0, gravity=9.81)
FREE = ("tower_fa1", "yaw", "generator_azimuth", "drivetrain", "blade1_flap1")


def quadratic_beam(x, w, mass, length, directions, stiffness):
    """A beam whose shapes are phi_i = d_i (x/L)^2, given directly as arrays at its nodes."""
    k = len(directions)
    d = np.asarray(directions, dtype=float)
    value = (x / length) ** 2
    slope = 2 * x / length**2
    dots = d @ d.T
    return ModalBeam(
        x=x, weight=w, mass=np.asarray(mass, dtype=float), value=value[None, :, None] * d[:, None, :],
        slope=slope[None, :, None] * d[:, None, :],
        curvature=np.full((k, len(x), 2), 2 / length**2) * d[:, None, :],
        stiffness=np.tile(np.eye(2) * stiffness, (len(x), 1, 1)),
        shortening=dots[:, :, None] * (4 * x**3 / (3 * length**4))[None, None, :],
        tip_value=d.copy(), tip_slope=2 / length * d, tip_shortening=dots * 4 / (3 * length),
        length=length, damping_ratio=np.zeros(k), names=tuple(f"mode {i}" for i in range(k)))


def numeric_model() -> TurbineModel:
    tower = quadratic_beam(TOWER_X, TOWER_W, [900.0, 700.0, 500.0], H,
                           [[1.0, 0.0], [0.7, 0.0], [0.0, 1.0], [0.0, 0.6]], 4.0e9)
    blade = quadratic_beam(BLADE_X, BLADE_W, [120.0, 80.0, 40.0], L,
                           [FLAP_DIRECTION, [1.0, -0.2], [0.1, 0.8]], 2.0e7)
    return TurbineModel(TurbineParameters(tower=tower, blade=blade, n_blades=1, **GEOMETRY))


def symbolic_equations(model: TurbineModel):
    """Mass matrix and forcing of the 5-DOF model from KanesMethod, as functions of (q, u)."""
    g = GEOMETRY
    q = me.dynamicsymbols("q0:5")
    u = me.dynamicsymbols("u0:5")
    qt, qy, qg, qd, qf = q
    N = me.ReferenceFrame("N")
    origin = me.Point("O")
    origin.set_vel(N, 0)
    bodies, loads = [], []
    gravity = -g["gravity"] * N.z

    def particle(name, position, mass):
        point = origin.locatenew(name, position)
        point.set_vel(N, position.dt(N))
        bodies.append(me.Particle(name + "p", point, mass))
        loads.append((point, mass * gravity))
        return point

    def shortening(x, length, direction):
        return (float(direction @ direction) * 4 * x**3 / (3 * length**4)) / 2

    for i, (x, w, m) in enumerate(zip(TOWER_X, TOWER_W, model.params.tower.mass)):
        particle(f"T{i}", (x / H) ** 2 * qt * N.x + (x - shortening(x, H, np.array([1.0, 0])) * qt**2) * N.z,
                 m * w)
    top_position = qt * N.x + (H - shortening(H, H, np.array([1.0, 0])) * qt**2) * N.z
    particle("top", top_position, g["yaw_bearing_mass"])
    B = N.orientnew("B", "Axis", [2 / H * qt, N.y])
    B.set_ang_vel(N, (2 / H) * u[0] * N.y)
    nacelle_frame = B.orientnew("Nc", "Axis", [qy, B.z])
    nacelle_frame.set_ang_vel(B, u[1] * B.z)
    cm = g["nacelle_cm"]
    nacelle_position = top_position + cm[0] * nacelle_frame.x + cm[1] * nacelle_frame.y + cm[2] * nacelle_frame.z
    nacelle_point = origin.locatenew("NcCM", nacelle_position)
    nacelle_point.set_vel(N, nacelle_position.dt(N))
    own = g["nacelle_yaw_inertia"] - g["nacelle_mass"] * (cm[0] ** 2 + cm[1] ** 2)
    bodies.append(me.RigidBody("nacelle", nacelle_point, nacelle_frame, g["nacelle_mass"],
                               (me.inertia(nacelle_frame, 0, 0, own), nacelle_point)))
    loads.append((nacelle_point, g["nacelle_mass"] * gravity))
    S = nacelle_frame.orientnew("S", "Axis", [-g["shaft_tilt"], nacelle_frame.y])
    S.set_ang_vel(nacelle_frame, 0)
    apex_position = top_position + g["twr2shft"] * nacelle_frame.z + g["overhang"] * S.x
    hub_position = apex_position + g["hub_cm"] * S.x
    hub_point = origin.locatenew("hub", hub_position)
    hub_point.set_vel(N, hub_position.dt(N))
    rotor = S.orientnew("L", "Axis", [qg + qd, S.x])
    rotor.set_ang_vel(S, (u[2] + u[3]) * S.x)
    generator = S.orientnew("G", "Axis", [g["gearbox_ratio"] * qg, S.x])
    generator.set_ang_vel(S, g["gearbox_ratio"] * u[2] * S.x)
    bodies.append(me.RigidBody("hub", hub_point, rotor, g["hub_mass"],
                               (me.inertia(rotor, g["hub_inertia"], 0, 0), hub_point)))
    loads.append((hub_point, g["hub_mass"] * gravity))
    bodies.append(me.RigidBody("generator", hub_point, generator, 0,
                               (me.inertia(generator, g["generator_inertia"], 0, 0), hub_point)))
    beta = g["precone"]
    e_x = np.sin(beta) * rotor.x + np.cos(beta) * rotor.z
    e_y = -rotor.y
    e_z = np.cos(beta) * rotor.x - np.sin(beta) * rotor.z
    blade_x = np.append(BLADE_X, L)
    blade_m = np.append(model.params.blade.point_mass, g["blade_tip_mass"])
    for i, (x, m) in enumerate(zip(blade_x, blade_m)):
        phi = (x / L) ** 2
        position = apex_position + (g["hub_radius"] + x - shortening(x, L, FLAP_DIRECTION) * qf**2) * e_x \
            + FLAP_DIRECTION[0] * phi * qf * e_y + FLAP_DIRECTION[1] * phi * qf * e_z
        particle(f"b{i}", position, m)
    torque = g["drivetrain_stiffness"] * qd + g["drivetrain_damping"] * u[3]
    ratio = g["gearbox_ratio"]
    loads += [(rotor, -torque * S.x), (generator, torque / ratio * S.x), (nacelle_frame, torque * (1 - 1 / ratio) * S.x)]
    yaw_torque = g["yaw_stiffness"] * qy + g["yaw_damping"] * u[1]
    loads += [(nacelle_frame, -yaw_torque * B.z), (B, yaw_torque * B.z)]
    kane = me.KanesMethod(N, q_ind=list(q), u_ind=list(u), kd_eqs=[qi.diff() - ui for qi, ui in zip(q, u)])
    kane.kanes_equations(bodies, loads)
    arguments = list(q) + list(u)
    return (sympy.lambdify(arguments, kane.mass_matrix, "numpy"), sympy.lambdify(arguments, kane.forcing, "numpy"))


@pytest.mark.slow
def test_numeric_kane_matches_sympy_kanes_method():
    model = numeric_model()
    mass, forcing = symbolic_equations(model)
    free = np.array([dof in FREE for dof in model.dofs])
    index = np.flatnonzero(free)
    stiffness = model.K[np.ix_(index, index)]
    elastic_only = stiffness.copy()
    elastic_only[np.ix_([1, 3], [1, 3])] = 0.0      # yaw and drivetrain springs are torques on the sympy side
    rng = np.random.default_rng(7)
    for _ in range(4):
        q, u = np.zeros(model.n), np.zeros(model.n)
        q[index] = rng.normal(scale=[0.4, 0.3, 3.0, 0.05, 0.8])
        u[index] = rng.normal(scale=[0.3, 0.2, 1.5, 0.1, 0.9])
        M, f = model.equations(q, u)
        args = list(q[index]) + list(u[index])
        M_sym = np.array(mass(*args), dtype=float)
        f_sym = np.array(forcing(*args), dtype=float).ravel() - elastic_only @ q[index]
        # both are double-precision evaluations of the same exact expressions: agreement to rounding, 1e-10
        np.testing.assert_allclose(M[np.ix_(index, index)], M_sym, rtol=0, atol=1e-10 * np.abs(M_sym).max())
        np.testing.assert_allclose(f[index], f_sym, rtol=0, atol=1e-10 * np.abs(f_sym).max())
    assert FreeSystem(model, free, q, u).size == 5
