"""numba kernels of the applied loads, aerodynamic and generator torque (the compiled twin of :mod:`.aero` and
:mod:`.control`), and the loaded equations the integrators and outputs call.

:func:`add_aero` runs after the structural kernel (:func:`.compiled_kernels.equations`), which leaves each blade's
frame, shared partials ``Z = [J_apex; W_rotor; E_blade]`` and the apex position in ``work``: the aerodynamic nodes'
kinematics follow from those (``omega = W u``, ``v_apex = J_apex u``), the node solver runs node by node (from
scratch, as the numpy twin: the loads are a function of the state alone), and the lumped loads add
``Z^T sum_p [F; rho x F + M; (R D)^T F]`` to the forcing. ``aero`` is the tuple of :func:`aero_data`; ``state``
the arrays of :func:`aero_state`. The kernels :func:`equations` and :func:`derivative` take ``data = (structure,
aero, generator law)`` and ``work = (structural work, aero state)``.
"""

from __future__ import annotations

import math

import numpy as np

from ...numba_cache import cached_njit

njit = cached_njit()

#: columns of the rotor summary a call leaves in the state (``state[-1]``)
HUB = ("thrust", "torque", "power", "tsr", "cp", "ct", "disk_velocity", "skew")


def aero_data(model) -> tuple:
    """The aerodynamic arrays of ``model`` in the order :func:`add_aero` unpacks them (empty arrays without
    aerodynamics, so that the kernels compile once for both)."""
    from ...aero.rotor import Inflow
    from .aero import TurbineAero
    aero: TurbineAero | None = model.aero
    k = model.params.blade.n_modes
    if aero is None:
        empty = np.zeros(0)
        return (np.zeros((k, 0, 3)), np.zeros((k, k, 0)), empty, np.zeros((0, 3)), np.zeros((k, 0)),
                np.zeros((0, 0)), empty, empty, empty, empty, empty, np.zeros(0, dtype=np.int64), np.zeros(1),
                np.zeros((1, 3)), np.zeros((1, 3, 4)), np.zeros(1, dtype=np.int64), np.ones(1, dtype=np.int64),
                np.zeros(13), np.zeros(2), *Inflow(0.0, 1.0).arrays())
    across = np.zeros((k, aero.n_nodes, 3))
    across[:, :, 1:] = aero.value
    inflow, rotor = aero.inflow, aero.rotor
    knots, values, coefs, start, count = aero.polar_arrays
    return (across, aero.shortening.copy(), aero.axial.copy(), aero.offset.copy(),
            np.ascontiguousarray(aero.slope[:, :, 1]), aero.force_lumping(), aero.moment_weights(),
            rotor.chord.copy(), np.ascontiguousarray(aero.theta, dtype=float), aero.tip_constant.copy(),
            aero.hub_constant.copy(), rotor.airfoil.astype(np.int64), knots, values, coefs, start, count,
            aero.options.copy(), np.array([rotor.air_density, float(rotor.n_blades)]), *inflow.arrays())


def aero_state(blades: int, nodes: int, modes: int) -> tuple:
    """Per node: offset from the apex rho, absolute velocity (B, Na, 3), R D (B, Na, 3, k), the deflected normal
    and span axis (B, Na, 3), the relative wind (B, Na, 3), the node solutions (B, Na, 13), lumped forces and
    moments (B, Na, 3); the rotor summary (:data:`HUB`)."""
    shape = (blades, nodes, 3)
    return (np.zeros(shape), np.zeros(shape), np.zeros((blades, nodes, 3, modes)), np.zeros(shape),
            np.zeros(shape), np.zeros(shape), np.zeros((blades, nodes, 13)), np.zeros(shape), np.zeros(shape),
            np.zeros(len(HUB)))


if njit is not None:                                   # module-level kernels: numba caches them on disk
    from ...aero.bem import node_loads
    from ...aero.options import FORMULATION
    from ...aero.performance import induction_weight
    from ...aero.wind import point_wind
    from .compiled_kernels import beam_node
    from .compiled_state import full_state, state_rate
    from . import control
    from .compiled_kernels import equations as structural_equations

    @njit(cache=True)
    def cross(a, b, out):
        out[0] = a[1] * b[2] - a[2] * b[1]
        out[1] = a[2] * b[0] - a[0] * b[2]
        out[2] = a[0] * b[1] - a[1] * b[0]

    @njit(cache=True)
    def node_kinematics(q, u, data, aero, work, state, t):
        """Positions, velocities, R D, deflected normals and span axes, relative wind (at time t) of every
        aerodynamic node."""
        b_columns = data[9]
        across, short, axial, offset, slope = aero[0], aero[1], aero[2], aero[3], aero[4]
        params, table, grid = aero[19], aero[20], aero[21]
        wind = np.zeros(3)
        Z_w, frame_w, apex_w = work[4], work[5], work[6]
        rho_w, vel_w, RD_w, normal_w, span_w, rel_w = state[0], state[1], state[2], state[3], state[4], state[5]
        n, k = q.shape[0], across.shape[0]
        apex_v, omega = np.zeros(3), np.zeros(3)
        for r in range(3):
            for c in range(n):
                apex_v[r] += Z_w[0, r, c] * u[c]
                omega[r] += Z_w[0, 3 + r, c] * u[c]
        D = np.zeros((3, k))
        d, rate, bias, moving, wr = np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3)
        qb, ub = np.empty(k), np.empty(k)
        for b in range(frame_w.shape[0]):
            R = frame_w[b]
            for i in range(k):
                qb[i] = q[b_columns[b, i]]
                ub[i] = u[b_columns[b, i]]
            for p in range(axial.shape[0]):
                beam_node(across, short, axial, p, qb, ub, 0, D, d, rate, bias)
                w = 0.0
                for i in range(k):
                    w += slope[i, p] * qb[i]
                stretch = math.sqrt(1.0 + w * w)
                for r in range(3):
                    rho_w[b, p, r] = (R[r, 0] * (d[0] + offset[p, 0]) + R[r, 1] * (d[1] + offset[p, 1])
                                      + R[r, 2] * (d[2] + offset[p, 2]))
                    moving[r] = R[r, 0] * rate[0] + R[r, 1] * rate[1] + R[r, 2] * rate[2]
                    for i in range(k):
                        RD_w[b, p, r, i] = R[r, 0] * D[0, i] + R[r, 1] * D[1, i] + R[r, 2] * D[2, i]
                    normal_w[b, p, r] = (R[r, 2] - w * R[r, 0]) / stretch
                    span_w[b, p, r] = (R[r, 0] + w * R[r, 2]) / stretch
                cross(omega, rho_w[b, p], wr)
                point_wind(apex_w[0] + rho_w[b, p, 0], apex_w[1] + rho_w[b, p, 1], apex_w[2] + rho_w[b, p, 2], t,
                           params, table, grid, wind)
                for r in range(3):
                    vel_w[b, p, r] = apex_v[r] + wr[r] + moving[r]
                    rel_w[b, p, r] = wind[r] - vel_w[b, p, r]
        return omega

    @njit(cache=True)
    def projected_inflow(rho_w, b, p, rel, normal, span, tangent, shaft, polar):
        """(vx, vy, cant, toe, dr/dz) of node p of blade b (the twin of :func:`bladefem.aero.polar.projection`):
        the legacy projection on the normal and against the rotation, or (``polar``) AeroDyn's local polar frame."""
        if not polar:
            vx = rel[0] * normal[0] + rel[1] * normal[1] + rel[2] * normal[2]
            vy = -(rel[0] * tangent[0] + rel[1] * tangent[1] + rel[2] * tangent[2])
            return vx, vy, 0.0, 0.0, 1.0
        z_l, y_l = np.zeros(3), np.zeros(3)
        j = max(p, 1)
        rho, prev = rho_w[b, j], rho_w[b, j - 1]
        along, step_along = 0.0, 0.0
        for r in range(3):
            along += rho_w[b, p, r] * shaft[r]
            step_along += (rho[r] - prev[r]) * shaft[r]
        size, step, step_projected = 0.0, 0.0, 0.0
        for r in range(3):
            z_l[r] = rho_w[b, p, r] - along * shaft[r]
            size += z_l[r] ** 2
            step += (rho[r] - prev[r]) ** 2
            step_projected += (rho[r] - prev[r] - step_along * shaft[r]) ** 2
        if size == 0.0:                   # a node on the shaft (hub radius 0): the section's span axis points out
            span_along = span[0] * shaft[0] + span[1] * shaft[1] + span[2] * shaft[2]
            for r in range(3):
                z_l[r] = span[r] - span_along * shaft[r]
                size += z_l[r] ** 2
        size = math.sqrt(size)
        for r in range(3):
            z_l[r] /= size
        cross(z_l, shaft, y_l)
        vx, vy, s_x, n_x, t_z, t_y = 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
        for r in range(3):
            vx += rel[r] * shaft[r]
            vy += rel[r] * y_l[r]
            s_x += span[r] * shaft[r]
            n_x += normal[r] * shaft[r]
            t_z += tangent[r] * z_l[r]
            t_y += tangent[r] * y_l[r]
        drdz = math.sqrt(step_projected) / math.sqrt(step) if step > 0.0 else 0.0
        return vx, vy, math.atan2(s_x, n_x), math.atan2(-t_z, -t_y), drdz

    @njit(cache=True)
    def add_aero(f, q, u, data, aero, work, state, t):
        """f += the generalized aerodynamic forces at (q, u) and time t; fills ``state`` (loads, solutions, rotor summary)."""
        nodes = aero[2].shape[0]
        if nodes == 0:
            return
        lumping, weights, chord, theta, tip_c, hub_c, airfoil = aero[5], aero[6], aero[7], aero[8], aero[9], \
            aero[10], aero[11]
        knots, values, coefs, start, count, options, scalars = aero[12], aero[13], aero[14], aero[15], aero[16], \
            aero[17], aero[18]
        Z_w, frame_w, shaft = work[4], work[5], work[8][3]
        rho_w, RD_w, normal_w, span_w, rel_w, out_w, force_w, moment_w, hub = state[0], state[2], state[3], \
            state[4], state[5], state[6], state[7], state[8], state[9]
        omega = node_kinematics(q, u, data, aero, work, state, t)
        B, k = frame_w.shape[0], RD_w.shape[3]
        # disk averages (AeroDyn's DiskAvgValues): relative wind, skew angle and direction, tip-speed ratio
        mean = np.zeros(3)
        for b in range(B):
            for p in range(nodes):
                for r in range(3):
                    mean[r] += rel_w[b, p, r] / (B * nodes)
        along = mean[0] * shaft[0] + mean[1] * shaft[1] + mean[2] * shaft[2]
        size = math.sqrt(mean[0] ** 2 + mean[1] ** 2 + mean[2] ** 2)
        chi0 = math.acos(min(max(along / size, -1.0), 1.0)) if size > 0.0 else 0.0
        in_plane = np.zeros(3)
        norm = 0.0
        for r in range(3):
            in_plane[r] = mean[r] - along * shaft[r]
            norm += in_plane[r] ** 2
        norm = math.sqrt(norm)
        for r in range(3):
            in_plane[r] = in_plane[r] / norm if norm > 1e-12 * max(size, 1.0) else 0.0
        r_local = np.zeros((B, nodes))
        tip = np.zeros(B)
        for b in range(B):
            for p in range(nodes):
                rho = rho_w[b, p]
                axial = rho[0] * shaft[0] + rho[1] * shaft[1] + rho[2] * shaft[2]
                r_local[b, p] = math.sqrt(max((rho[0] - axial * shaft[0]) ** 2 + (rho[1] - axial * shaft[1]) ** 2
                                              + (rho[2] - axial * shaft[2]) ** 2, 0.0))
                tip[b] = max(tip[b], r_local[b, p])
        speed = omega[0] * shaft[0] + omega[1] * shaft[1] + omega[2] * shaft[2]
        max_radius = tip.max()
        tsr = speed * max_radius / along if along != 0.0 else 0.0
        weight = induction_weight(tsr)
        thrust, torque = 0.0, 0.0
        arm, load = np.zeros(3), np.zeros(3)
        for b in range(B):
            R = frame_w[b]
            radial = np.zeros(3)
            axial = R[0, 0] * shaft[0] + R[1, 0] * shaft[1] + R[2, 0] * shaft[2]
            length = 0.0
            for r in range(3):
                radial[r] = R[r, 0] - axial * shaft[r]
                length += radial[r] ** 2
            skew_cos = (radial[0] * in_plane[0] + radial[1] * in_plane[1] + radial[2] * in_plane[2]) / math.sqrt(
                length)
            for p in range(nodes):
                vx, vy, cant, toe, drdz = projected_inflow(rho_w, b, p, rel_w[b, p], normal_w[b, p], span_w[b, p],
                                                           R[:, 1], shaft, options[FORMULATION] == 2.0)
                phi_solved, a, ap, phi, alpha, w, cl, cd, cm, fn, ft, m, valid = node_loads(
                    vx, vy, r_local[b, p], chord[p], theta[p], tip_c[p], hub_c[p], scalars[1], r_local[b, p] / tip[b],
                    chi0, skew_cos, weight, airfoil[p], knots, values, coefs, start, count, options, scalars[0],
                    math.nan, cant, toe, drdz)
                row = out_w[b, p]
                row[0], row[1], row[2], row[3], row[4], row[5], row[6] = phi_solved, a, ap, phi, alpha, w, cl
                row[7], row[8], row[9], row[10], row[11] = cd, cm, fn, ft, m
                row[12] = 1.0 if valid else 0.0
            # lumped loads: forces by virtual work of linear loads (tridiagonal), moments by the trapezoidal rule
            shared = np.zeros(6 + k)
            for p in range(nodes):
                for r in range(3):
                    value = 0.0
                    for j in range(max(p - 1, 0), min(p + 2, nodes)):
                        value += lumping[p, j] * (out_w[b, j, 9] * normal_w[b, j, r] + out_w[b, j, 10] * R[r, 1])
                    force_w[b, p, r] = value
                    moment_w[b, p, r] = weights[p] * out_w[b, p, 11] * span_w[b, p, r]
                F, M, rho = force_w[b, p], moment_w[b, p], rho_w[b, p]
                cross(rho, F, arm)
                for r in range(3):
                    shared[r] += F[r]
                    shared[3 + r] += arm[r] + M[r]
                    load[r] = arm[r] + M[r]
                for i in range(k):
                    shared[6 + i] += RD_w[b, p, 0, i] * F[0] + RD_w[b, p, 1, i] * F[1] + RD_w[b, p, 2, i] * F[2]
                thrust += F[0] * shaft[0] + F[1] * shaft[1] + F[2] * shaft[2]
                torque += load[0] * shaft[0] + load[1] * shaft[1] + load[2] * shaft[2]
            Z = Z_w[b]
            for i in range(Z.shape[1]):
                for r in range(6 + k):
                    f[i] += Z[r, i] * shared[r]
        area = math.pi * max_radius ** 2
        dynamic = 0.5 * scalars[0] * area * along * along
        power = speed * torque
        hub[0], hub[1], hub[2], hub[3] = thrust, torque, power, tsr
        hub[4] = power / (dynamic * along) if along != 0.0 else 0.0
        hub[5] = thrust / dynamic if along != 0.0 else 0.0
        hub[6], hub[7] = along, chi0

    law_torque = njit(cache=True)(control.law_torque)       # the torque law, compiled

    @njit(cache=True)
    def add_generator(f, u, generator_angle, law):
        """f -= T dtheta_g/du: the generator torque T (law at the generator speed) between generator and nacelle.
        Returns T."""
        speed = 0.0
        for i in range(u.shape[0]):
            speed += generator_angle[i] * u[i]
        torque = law_torque(law, speed)
        for i in range(u.shape[0]):
            f[i] -= torque * generator_angle[i]
        return torque

    @njit(cache=True)
    def equations(q, u, data, work, t):
        """Mass matrix and forcing with the aerodynamic loads (wind at time t) and the generator torque."""
        structure, aero, law = data
        M, f = structural_equations(q, u, structure, work[0])
        add_aero(f, q, u, structure, aero, work[0], work[1], t)
        add_generator(f, u, structure[15], law)
        return M, f

    @njit(cache=True)
    def derivative(t, x, q0, u0, index, data, work):
        """dx/dt of the free coordinates x = (q_f, u_f)."""
        q, u = full_state(t, x, q0, u0, index)
        M, f = equations(q, u, data, work, t)
        return state_rate(x, M, f, index)
