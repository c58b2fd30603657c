"""Compiled output channels that need the equations of motion (root moments, shaft loads, generator torque) and the
aerodynamic rotor summary, for all output rows in one call (:func:`bladefem.models.turbine.outputs.load_outputs`
is the numpy version)."""

from __future__ import annotations

import numpy as np

from ...numba_cache import cached_njit

njit = cached_njit()

#: columns of :func:`load_outputs` (SI): blade root moments (N m), low-speed-shaft thrust (N) and torque (N m),
#: generator torque (N m), the aerodynamic rotor summary (compiled_aero_arrays.HUB), aerodynamic and damping power (W),
#: tower-base moment about the base's x and y axes (N m)
COLUMNS = ("root_oop", "root_ip", "shaft_thrust", "shaft_torque", "generator_torque", "aero_thrust", "aero_torque",
           "aero_power", "tsr", "cp", "ct", "disk_velocity", "skew", "aero_work", "damping_power", "tower_base_x",
           "tower_base_y")
#: the leading columns a controller's call measures (:func:`.compiled_control.fill`: root moments, shaft torque):
#: a row of this length gets only these, without the power, damping and tower-base channels
MEASURED = 5

if njit is not None:
    from .compiled_state import free_accelerations, full_state
    from .compiled_loads import law_torque, load_wake, loaded_equations
    from .compiled_invariants import pitched_frame, to_blade
    from .compiled_tower_base import add_tower_and_nacelle

if njit is not None:                                   # module-level kernels: numba caches them on disk

    @njit(cache=True)
    def load_outputs(kernels, times, states, q0, u0, index, data, work, hub_radius, blade):
        """The :data:`COLUMNS` at each output row (:func:`output_row`), with ``kernels`` (structural equations,
        aerodynamic loads, output row) called directly or as first-class functions (:mod:`.compiled_calls`)."""
        structural, aerodynamic, outputs = kernels
        out = np.zeros((times.shape[0], len(COLUMNS)))
        for row in range(times.shape[0]):
            q, u = full_state(times[row], states[row], q0, u0, index)
            load_wake(states[row], index.shape[0], work[1])
            M, f = loaded_equations(q, u, data, work, times[row], structural, aerodynamic)
            outputs(q, u, M, f, index, data, work, hub_radius, blade, out[row])
        return out

    @njit(cache=True)
    def output_row(q, u, M, f, index, data, work, hub_radius, blade, out):
        """Fill ``out`` with the :data:`COLUMNS` at (q, u) (the first :data:`MEASURED` where it is that short),
        given the equations ``M du/dt = f`` there (whose kernel has just left that state's motion and loads in
        ``work``). Root moments of ``blade``: ``sum (r - r_root) x
        (m (g - a) + F_aero) + M_aero`` in the blade frame (out-of-plane positive for downwind loads, in-plane for
        loads toward the leading edge); shaft loads: the force and the moment about the apex of the rotor's (hub and
        blades) gravity, d'Alembert and aerodynamic loads, along the shaft; generator torque: the law's, plus whatever
        holds a locked generator at its speed; tower-base moment: the rotor's loads carried from the apex to the
        base, plus the tower, nacelle and rotary inertias (:func:`.compiled_tower_base.add_tower_and_nacelle`)."""
        structure, law = data[0], data[2]
        n, gravity, C = structure[0], structure[20], structure[22]
        generator, rigid_mass, inertias = structure[15], structure[18], structure[19]
        Z_w, frame_w, apex, hub_J, hub, blade_A, blade_F = work[0]
        state = work[1]
        a_rho, a_vel, a_force, a_moment, summary = state[0], state[1], state[7], state[8], state[9]
        k = blade_F.shape[1] - 6
        g_index = np.argmax(np.abs(generator))
        load, arm, force, moment = np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3)
        du = np.zeros(n)
        free = free_accelerations(M, f, index)
        for i in range(index.shape[0]):
            du[index[i]] = free[i]
        shaft = hub[3]
        for r in range(3):
            force[r] = 0.0
            moment[r] = 0.0
        omega = np.zeros(3)
        for b in range(frame_w.shape[0]):
            Z, R = Z_w[b], frame_w[b]
            shared = np.zeros(6 + k)
            for r in range(6 + k):
                for c in range(n):
                    shared[r] += Z[r, c] * du[c]
            if b == 0:
                for r in range(3):
                    for c in range(n):
                        omega[r] += Z[3 + r, c] * u[c]
            # the blade's gravity and inertial loads: sum_p G_p^T m (g - a_p) = F - A T^T Z du in the frame of its
            # modal integrals (force; moment about the apex), turned to earth and carried to its root at hub_radius
            # along its axis
            Ri = pitched_frame(R, structure[24][9])
            turned = to_blade(shared.reshape(6 + k, 1), Ri)
            local = blade_F[b].copy()
            for r in range(6 + k):
                for c in range(6 + k):
                    local[r] -= blade_A[b, r, c] * turned[c, 0]
            blade_moment, from_root = np.zeros(3), np.zeros(3)
            for r in range(3):
                load[r] = Ri[r, 0] * local[0] + Ri[r, 1] * local[1] + Ri[r, 2] * local[2]
                blade_moment[r] = Ri[r, 0] * local[3] + Ri[r, 1] * local[4] + Ri[r, 2] * local[5]
                moment[r] += blade_moment[r]
                force[r] += load[r]
                from_root[r] = -hub_radius * R[r, 0]               # the apex from the root
            accumulate_moment(blade_moment, from_root, load)
            for p in range(a_rho.shape[1]):
                for r in range(3):
                    arm[r] = a_rho[b, p, r] - hub_radius * R[r, 0]
                    force[r] += a_force[b, p, r]
                    blade_moment[r] += a_moment[b, p, r]
                    moment[r] += a_moment[b, p, r]
                accumulate_moment(blade_moment, arm, a_force[b, p])
                accumulate_moment(moment, a_rho[b, p], a_force[b, p])
            if b == blade:
                out[0] = -(R[0, 1] * blade_moment[0] + R[1, 1] * blade_moment[1] + R[2, 1] * blade_moment[2])
                out[1] = R[0, 2] * blade_moment[0] + R[1, 2] * blade_moment[1] + R[2, 2] * blade_moment[2]
        # hub: point mass at its centre of mass, inertia about the shaft
        spin = 0.0
        for r in range(3):
            value = hub[0, r]
            for c in range(n):
                value += hub_J[r, c] * du[c]
                spin += Z_w[0, 3 + r, c] * du[c] * shaft[r]
            load[r] = rigid_mass[2] * (gravity[r] - value)
            force[r] += load[r]
            spin += hub[2, r] * shaft[r]
        accumulate_moment(moment, hub[1], load)
        out[2] = force[0] * shaft[0] + force[1] * shaft[1] + force[2] * shaft[2]
        out[3] = moment[0] * shaft[0] + moment[1] * shaft[1] + moment[2] * shaft[2] - inertias[1] * spin
        # generator torque: the law's, less the generalized force that holds a locked generator
        speed = 0.0
        residual = -f[g_index]
        for c in range(n):
            speed += generator[c] * u[c]
            residual += M[g_index, c] * du[c]
        out[4] = law_torque(law, speed) - residual / generator[g_index]
        if out.shape[0] <= MEASURED:
            return
        for i in range(8):
            out[5 + i] = summary[i]
        power = 0.0
        for b in range(a_rho.shape[0]):
            for p in range(a_rho.shape[1]):
                for r in range(3):
                    power += a_force[b, p, r] * a_vel[b, p, r] + a_moment[b, p, r] * omega[r]
        out[13] = power
        damping = 0.0
        for i in range(n):
            for j in range(n):
                damping += u[i] * C[i, j] * u[j]
        out[14] = damping
        arm[0], arm[1], arm[2] = apex[0], apex[1], apex[2] - structure[23]
        base = moment.copy()
        accumulate_moment(base, arm, force)
        add_tower_and_nacelle(q, u, du, structure, base)
        out[15] = base[0]
        out[16] = base[1]

    @njit(cache=True)
    def accumulate_moment(total, arm, load):
        """total += arm x load."""
        total[0] += arm[1] * load[2] - arm[2] * load[1]
        total[1] += arm[2] * load[0] - arm[0] * load[2]
        total[2] += arm[0] * load[1] - arm[1] * load[0]
