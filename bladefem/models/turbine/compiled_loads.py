"""numba kernels of the applied loads, aerodynamic and generator torque (the compiled twin of :mod:`.aero` and
:mod:`.control`), and the loaded equations the integrators and outputs call.

:func:`add_aero` runs after the structural kernel (:func:`.compiled_kernels.equations`), which leaves each blade's
frame, shared partials ``Z = [J_apex; W_rotor; E_blade]`` and the apex position in ``work``: the aerodynamic nodes'
kinematics follow from those (``omega = W u``, ``v_apex = J_apex u``; :mod:`.compiled_node_motion`), the node
solver runs node by node (from each node's previous root, :func:`previous_root`; the numpy twin solves from
scratch, and the two agree to the BEM's tolerance), and the lumped loads add
``Z^T sum_p [F; rho x F + M; (R D)^T F]`` to the forcing. ``aero`` is the tuple of
:func:`.compiled_aero_arrays.aero_data`; ``state`` the arrays of :func:`.compiled_aero_arrays.aero_state`. The
kernels :func:`equations` and :func:`loaded_equations` take ``data = (structure, aero, generator law)`` and ``work
= (structural work, aero state)``.

The dynamic wake's states (:mod:`bladefem.aero.dynamic_wake`) ride at the end of the integrator's state vector,
after the free coordinates and rates: :func:`load_wake` copies them into the aero state before the equations (which
then use their induced velocities and leave the states' rates there), :func:`store_wake_rate` copies the rates into
dx/dt; a state vector without them (or a call of the equations alone) gives the quasi-steady loads. Without them
each node solve leaves its induced velocities (vx a, vy a') in the state, and with the hold flag set (the third of
``state[13]``) the nodes take those instead of solving (a frozen wake, as
:meth:`.frozen_wake.SectionAero.generalized`: the section loads of :func:`bladefem.aero.section.section_loads` at
the new inflow), for the stages of a step between two solves.
"""

from __future__ import annotations

import math

from ...numba_cache import cached_njit

njit = cached_njit()

if njit is not None:                                   # module-level kernels: numba caches them on disk
    from ...aero.bem import framed_node_loads
    from ...aero.section import framed_section_loads
    from ...aero.dynamic_wake import BLEND, MODEL, framed_wake_node_loads, time_constant, wake_rates
    from ...aero.options import FORMULATION
    from ...aero.performance import induction_weight
    from .compiled_aero_arrays import ARM, IN_PLANE, LOAD, MEAN, OMEGA, RADIAL, SHARED
    from .compiled_node_motion import cross, node_kinematics, projected_inflow
    from . import control
    from .compiled_kernels import equations as structural_equations

    @njit(cache=True, _nrt=False)
    def previous_root(row):
        """Where a node's solve starts (:func:`bladefem.aero.bem.solve_inflow_angle`): its root at the solve before
        (``row``: that solve's outputs); nan (from scratch) where that solve found no valid root: its fallback angle
        lies in the momentum region, and a root bracketed next to it would be kept though Ning's search from scratch
        finds none (the momentum region's ends of one sign, an even number of roots there)."""
        return row[0] if row[12] != 0.0 else math.nan

    @njit(cache=True, _nrt=False)
    def add_aero(f, q, u, data, aero, work, state, t):
        """f += the generalized aerodynamic forces at (q, u) and time t; fills ``state`` (loads, solutions, rotor
        summary)."""
        nodes = aero[2].shape[0]
        if nodes == 0:
            return
        lumping, weights, chord, theta, tip_c, hub_c, airfoil = aero[5], aero[6], aero[7], aero[8], aero[9], \
            aero[10], aero[11]
        knots, values, coefs, start, count, options, scalars = aero[12], aero[13], aero[14], aero[15], aero[16], \
            aero[17], aero[18]
        Z_w, frame_w, shaft = work[0], work[1], work[4][3]
        rho_w, RD_w, normal_w, span_w, rel_w, out_w, force_w, moment_w, hub = state[0], state[2], state[3], \
            state[4], state[5], state[6], state[7], state[8], state[9]
        tangent_w = state[14]
        node_kinematics(q, u, data, aero, work, state, t)
        vectors, shared, r_local, tip = state[15], state[17][SHARED], state[18], state[19]
        omega, mean, in_plane, arm, load, radial = vectors[OMEGA], vectors[MEAN], vectors[IN_PLANE], vectors[ARM], \
            vectors[LOAD], vectors[RADIAL]
        B, k = frame_w.shape[0], RD_w.shape[3]
        wake_parameters, disk_weight, ratio0 = aero[22], aero[23], aero[24]
        wake, wake_rate, quasi, wake_flag = state[10], state[11], state[12], state[13]
        lagging = wake_flag[0] != 0.0 and wake_parameters[MODEL] != 0.0
        held = wake_flag[2] != 0.0 and not lagging
        disk_induction = 0.0
        # disk averages (AeroDyn's DiskAvgValues): relative wind, skew angle and direction, tip-speed ratio
        mean[0], mean[1], mean[2] = 0.0, 0.0, 0.0
        for b in range(B):
            for p in range(nodes):
                for r in range(3):
                    mean[r] += rel_w[b, p, r] / (B * nodes)
        along = mean[0] * shaft[0] + mean[1] * shaft[1] + mean[2] * shaft[2]
        size = math.sqrt(mean[0] ** 2 + mean[1] ** 2 + mean[2] ** 2)
        chi0 = math.acos(min(max(along / size, -1.0), 1.0)) if size > 0.0 else 0.0
        norm = 0.0
        for r in range(3):
            in_plane[r] = mean[r] - along * shaft[r]
            norm += in_plane[r] ** 2
        norm = math.sqrt(norm)
        for r in range(3):
            in_plane[r] = in_plane[r] / norm if norm > 1e-12 * max(size, 1.0) else 0.0
        for b in range(B):
            tip[b] = 0.0
            for p in range(nodes):
                rho = rho_w[b, p]
                axial = rho[0] * shaft[0] + rho[1] * shaft[1] + rho[2] * shaft[2]
                r_local[b, p] = math.sqrt(max((rho[0] - axial * shaft[0]) ** 2 + (rho[1] - axial * shaft[1]) ** 2
                                              + (rho[2] - axial * shaft[2]) ** 2, 0.0))
                tip[b] = max(tip[b], r_local[b, p])
        speed = omega[0] * shaft[0] + omega[1] * shaft[1] + omega[2] * shaft[2]
        max_radius = 0.0
        for b in range(B):
            max_radius = max(max_radius, tip[b])
        tsr = speed * max_radius / along if along != 0.0 else 0.0
        weight = induction_weight(tsr)
        thrust, torque = 0.0, 0.0
        for b in range(B):
            R = frame_w[b]
            axial = R[0, 0] * shaft[0] + R[1, 0] * shaft[1] + R[2, 0] * shaft[2]
            length = 0.0
            for r in range(3):
                radial[r] = R[r, 0] - axial * shaft[r]
                length += radial[r] ** 2
            skew_cos = (radial[0] * in_plane[0] + radial[1] * in_plane[1] + radial[2] * in_plane[2]) / math.sqrt(
                length)
            for p in range(nodes):
                vx, vy, cb, sb, ct, st, twist, drdz = projected_inflow(
                    rho_w, b, p, rel_w[b, p], normal_w[b, p], tangent_w[b, p], span_w[b, p], R, shaft,
                    options[FORMULATION] == 2.0, aero[26][0])
                if lagging:
                    phi_solved, a, ap, phi, alpha, w, cl, cd, cm, fn, ft, m, valid, q_axial, q_tangential = \
                        framed_wake_node_loads(vx, vy, r_local[b, p], chord[p], theta[p] + twist, tip_c[p],
                                               hub_c[p], scalars[1], r_local[b, p] / tip[b], chi0, skew_cos, weight,
                                               airfoil[p], knots, values, coefs, start, count, options, scalars[0],
                                               previous_root(out_w[b, p]), (cb, sb, ct, st, drdz), wake[b, p, 2],
                                               wake[b, p, 3])
                    quasi[b, p, 0], quasi[b, p, 1] = q_axial, q_tangential
                    if vx != 0.0:
                        disk_induction += disk_weight[p] * q_axial / vx
                elif held:                             # the induced velocities of the last solve (frozen wake)
                    a = quasi[b, p, 0] / vx if vx != 0.0 else 0.0
                    ap = quasi[b, p, 1] / vy if vy != 0.0 else 0.0
                    phi, alpha, w, cl, cd, cm, fn, ft, m = framed_section_loads(
                        vx, vy, a, ap, chord[p], theta[p] + twist, airfoil[p], knots, values, coefs, start, count,
                        options, scalars[0], cb, sb, ct, st)
                    phi_solved, valid = out_w[b, p, 0], out_w[b, p, 12] != 0.0
                else:
                    phi_solved, a, ap, phi, alpha, w, cl, cd, cm, fn, ft, m, valid = framed_node_loads(
                        vx, vy, r_local[b, p], chord[p], theta[p] + twist, tip_c[p], hub_c[p], scalars[1],
                        r_local[b, p] / tip[b], chi0, skew_cos, weight, airfoil[p], knots, values, coefs, start,
                        count, options, scalars[0], previous_root(out_w[b, p]), (cb, sb, ct, st, drdz))
                    quasi[b, p, 0], quasi[b, p, 1] = a * vx, ap * vy
                row = out_w[b, p]
                row[0], row[1], row[2], row[3], row[4], row[5], row[6] = phi_solved, a, ap, phi, alpha, w, cl
                row[7], row[8], row[9], row[10], row[11] = cd, cm, fn, ft, m
                row[12] = 1.0 if valid else 0.0
            # lumped loads: forces by virtual work of linear loads (tridiagonal), moments by the trapezoidal rule
            for i in range(6 + k):
                shared[i] = 0.0
            for p in range(nodes):
                for r in range(3):
                    value = 0.0
                    for j in range(max(p - 1, 0), min(p + 2, nodes)):
                        value += lumping[p, j] * (out_w[b, j, 9] * normal_w[b, j, r]
                                                  + out_w[b, j, 10] * tangent_w[b, j, r])
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
        if lagging:
            wake_flag[1] = wake_derivatives(wake, quasi, wake_rate, wake_parameters, ratio0, r_local, max_radius,
                                            disk_induction, along, state[1], rel_w, shaft, options[FORMULATION])

    @njit(cache=True, _nrt=False)
    def wake_derivatives(wake, quasi, rate, parameters, ratio0, r_local, max_radius, disk_induction, along, velocity,
                         relative, shaft, formulation):
        """The rates of the dynamic wake's states into ``rate``; returns tau1 (s). The disk wind: the relative
        wind along the shaft ``along`` (BEM_Mod 1), the undisturbed wind's mean along it (BEM_Mod 2)."""
        disk_wind = along
        if formulation == 2.0:
            disk_wind = 0.0
            count = relative.shape[0] * relative.shape[1]
            for b in range(relative.shape[0]):
                for p in range(relative.shape[1]):
                    for r in range(3):
                        disk_wind += (relative[b, p, r] + velocity[b, p, r]) * shaft[r] / count
        tau1 = time_constant(parameters, disk_induction, disk_wind, max_radius)
        for b in range(wake.shape[0]):
            for p in range(wake.shape[1]):
                ratio = r_local[b, p] / max_radius if parameters[MODEL] == 2.0 else ratio0[p]
                for c in range(2):
                    rate[b, p, c], rate[b, p, 2 + c] = wake_rates(wake[b, p, c], wake[b, p, 2 + c], quasi[b, p, c],
                                                                  tau1, ratio, parameters[BLEND])
        return tau1

    @njit(cache=True)
    def load_wake(x, size, state):
        """The dynamic wake's states x[2 size:] into the aero state (and the flag that they are given)."""
        wake, flag = state[10], state[13]
        flag[0] = 1.0 if x.shape[0] > 2 * size else 0.0
        if flag[0] == 0.0:
            return
        i = 2 * size
        for b in range(wake.shape[0]):
            for p in range(wake.shape[1]):
                for c in range(4):
                    wake[b, p, c] = x[i]
                    i += 1

    @njit(cache=True)
    def store_wake_rate(out, size, state):
        """dx/dt of the dynamic wake's states (left in the aero state by the equations) into out[2 size:]."""
        if out.shape[0] == 2 * size:
            return
        rate = state[11]
        i = 2 * size
        for b in range(rate.shape[0]):
            for p in range(rate.shape[1]):
                for c in range(4):
                    out[i] = rate[b, p, c]
                    i += 1

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

    @njit(cache=True, inline="always")
    def loaded_equations(q, u, data, work, t, structural, aerodynamic):
        """Mass matrix and forcing with the aerodynamic loads (wind at time t) and the generator torque, from the
        kernels ``structural`` (:func:`.compiled_kernels.equations`) and ``aerodynamic`` (:func:`add_aero`), called
        directly or as first-class functions (:mod:`.compiled_calls`). Inlined by numba into its callers."""
        structure, aero, law = data
        M, f = structural(q, u, structure, work[0])
        aerodynamic(f, q, u, structure, aero, work[0], work[1], t)
        add_generator(f, u, structure[15], law)
        return M, f

    @njit(cache=True, inline="always")
    def equations(q, u, data, work, t):
        """:func:`loaded_equations` calling the kernels directly."""
        return loaded_equations(q, u, data, work, t, structural_equations, add_aero)
