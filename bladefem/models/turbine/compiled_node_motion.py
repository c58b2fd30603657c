"""numba kernels of the aerodynamic nodes' motion (the compiled twin of :func:`.aero.aero_nodes` and
:func:`bladefem.aero.polar.projection`): their positions, velocities and partials from the structural kernel's
blade frames and shared partials, the bent sections' axes and the relative wind (:func:`node_kinematics`), and
each node's inflow projected as its BEM takes it (:func:`projected_inflow`). Like every kernel that runs per node
they allocate nothing and count no references: their vectors are scratch rows of the aero state
(:func:`.compiled_aero_arrays.aero_state`). :func:`.compiled_loads.add_aero` calls them.
"""

from __future__ import annotations

import math

from ...numba_cache import cached_njit

njit = cached_njit()

if njit is not None:                                   # module-level kernels: numba caches them on disk
    from ...aero.polar import curved_axes, euler_frame
    from ...aero.wind import point_wind
    from .compiled_aero_arrays import APEX_VELOCITY, BIAS, BLADE_Q, BLADE_U, MOVING, OFFSET, OMEGA, RATE, SPUN, WIND
    from .compiled_kernels import beam_node

    @njit(cache=True, _nrt=False)
    def cross(a, b, out):
        out[0] = a[1] * b[2] - a[2] * b[1]
        out[1] = a[2] * b[0] - a[0] * b[2]
        out[2] = a[0] * b[1] - a[1] * b[0]

    @njit(cache=True, _nrt=False)
    def node_kinematics(q, u, data, aero, work, state, t):
        """Positions, velocities, R D, deflected normals and span axes, relative wind (at time t) of every
        aerodynamic node; the rotor's angular velocity in the scratch's row ``OMEGA``. Like every kernel here
        that runs per node, it allocates nothing and counts no references (its arrays: the state's scratch)."""
        b_columns = data[9]
        across, short, axial, offset, slope = aero[0], aero[1], aero[2], aero[3], aero[4]
        params, table, grid, curve = aero[19], aero[20], aero[21], aero[25]
        cos_pitch, sin_pitch = math.cos(aero[26][0]), math.sin(aero[26][0])
        Z_w, frame_w, apex_w = work[0], work[1], work[2]
        rho_w, vel_w, RD_w, normal_w, span_w, rel_w = state[0], state[1], state[2], state[3], state[4], state[5]
        tangent_w = state[14]
        n, k = q.shape[0], across.shape[0]
        vectors, D, modal = state[15], state[16], state[17]
        wind, apex_v, omega, d, rate = vectors[WIND], vectors[APEX_VELOCITY], vectors[OMEGA], vectors[OFFSET], \
            vectors[RATE]
        bias, moving, wr, qb, ub = vectors[BIAS], vectors[MOVING], vectors[SPUN], modal[BLADE_Q], modal[BLADE_U]
        for r in range(3):
            apex_v[r], omega[r] = 0.0, 0.0
            for c in range(n):
                apex_v[r] += Z_w[0, r, c] * u[c]
                omega[r] += Z_w[0, 3 + r, c] * u[c]
        for b in range(frame_w.shape[0]):
            R = frame_w[b]
            for i in range(k):
                qb[i] = q[b_columns[b, i]]
                ub[i] = u[b_columns[b, i]]
            for p in range(axial.shape[0]):
                beam_node(across, short, axial, p, qb, ub, 0, D, d, rate, bias)
                v, w, v_rate, w_rate = 0.0, 0.0, 0.0, 0.0
                for i in range(k):
                    v += slope[i, p, 0] * qb[i]
                    w += slope[i, p, 1] * qb[i]
                    v_rate += slope[i, p, 0] * ub[i]
                    w_rate += slope[i, p, 1] * ub[i]
                # the arms turned by the bent section, to second order across the axis (kinematics.turned_arms)
                a = offset[p, 1] * v + offset[p, 2] * w
                a_rate = offset[p, 1] * v_rate + offset[p, 2] * w_rate
                d[1] -= 0.5 * a * v
                d[2] -= 0.5 * a * w
                rate[1] -= 0.5 * (a_rate * v + a * v_rate)
                rate[2] -= 0.5 * (a_rate * w + a * w_rate)
                for i in range(k):
                    a_i = offset[p, 1] * slope[i, p, 0] + offset[p, 2] * slope[i, p, 1]
                    D[1, i] -= 0.5 * (a_i * v + a * slope[i, p, 0])
                    D[2, i] -= 0.5 * (a_i * w + a * slope[i, p, 1])
                # the section canted in the pitched blade (kinematics.pitched_slopes, polar.projection)
                n3, nt, n1, t3, tt, t1, s3, st, s1 = curved_axes(cos_pitch * v - sin_pitch * w,
                                                                 sin_pitch * v + cos_pitch * w, curve[p, 0],
                                                                 curve[p, 1])
                nt, n1 = cos_pitch * nt + sin_pitch * n1, cos_pitch * n1 - sin_pitch * nt
                tt, t1 = cos_pitch * tt + sin_pitch * t1, cos_pitch * t1 - sin_pitch * tt
                st, s1 = cos_pitch * st + sin_pitch * s1, cos_pitch * s1 - sin_pitch * st
                for r in range(3):
                    rho_w[b, p, r] = (R[r, 0] * (d[0] + offset[p, 0]) + R[r, 1] * (d[1] + offset[p, 1])
                                      + R[r, 2] * (d[2] + offset[p, 2]))
                    moving[r] = R[r, 0] * rate[0] + R[r, 1] * rate[1] + R[r, 2] * rate[2]
                    for i in range(k):
                        RD_w[b, p, r, i] = R[r, 0] * D[0, i] + R[r, 1] * D[1, i] + R[r, 2] * D[2, i]
                    normal_w[b, p, r] = n3 * R[r, 0] + nt * R[r, 1] + n1 * R[r, 2]
                    tangent_w[b, p, r] = t3 * R[r, 0] + tt * R[r, 1] + t1 * R[r, 2]
                    span_w[b, p, r] = s3 * R[r, 0] + st * R[r, 1] + s1 * R[r, 2]
                cross(omega, rho_w[b, p], wr)
                point_wind(apex_w[0] + rho_w[b, p, 0], apex_w[1] + rho_w[b, p, 1], apex_w[2] + rho_w[b, p, 2], t,
                           params, table, grid, wind)
                for r in range(3):
                    vel_w[b, p, r] = apex_v[r] + wr[r] + moving[r]
                    rel_w[b, p, r] = wind[r] - vel_w[b, p, r]

    @njit(cache=True, _nrt=False)
    def projected_inflow(rho_w, b, p, rel, normal, tangent, span, R, shaft, polar, pitch):
        """(vx, vy, cos cant, sin cant, cos toe, sin toe, twist, dr/dz) of node p of blade b (the twin of
        :func:`bladefem.aero.polar.projection`; the cant and toe as :func:`bladefem.aero.bem.angle_geometry` gives
        them) for its bent section's axes ``normal``, ``tangent``, ``span`` (pitched by ``pitch``, rad), which
        are turned in place into the axes its loads act along: the legacy projection against the unturned, unpitched
        blade (frame ``R``), or (``polar``) AeroDyn's local polar frame; ``twist`` is what the orientation adds to
        the pitch."""
        if not polar:
            m11, m12, m13, m21, m22, m23, m31 = 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
            for r in range(3):
                m11 += normal[r] * R[r, 2]
                m12 -= normal[r] * R[r, 1]
                m13 += normal[r] * R[r, 0]
                m21 -= tangent[r] * R[r, 2]
                m22 += tangent[r] * R[r, 1]
                m23 -= tangent[r] * R[r, 0]
                m31 += span[r] * R[r, 2]
            twist, _, _, c, s, _, _ = euler_frame(m11, m12, m13, m21, m22, m23, m31)
            vx, vy = 0.0, 0.0
            for r in range(3):
                normal[r] = c * R[r, 2] - s * R[r, 0]
                span[r] = s * R[r, 2] + c * R[r, 0]
                tangent[r] = R[r, 1]
                vx += rel[r] * normal[r]
                vy -= rel[r] * tangent[r]
            return vx, vy, 1.0, 0.0, 1.0, 0.0, twist - pitch, 1.0
        j = max(p, 1)
        rho, prev = rho_w[b, j], rho_w[b, j - 1]
        along, step_along = 0.0, 0.0
        for r in range(3):
            along += rho_w[b, p, r] * shaft[r]
            step_along += (rho[r] - prev[r]) * shaft[r]
        step, step_projected = 0.0, 0.0
        for r in range(3):
            step += (rho[r] - prev[r]) ** 2
            step_projected += (rho[r] - prev[r] - step_along * shaft[r]) ** 2
        # z_l: the node's radial direction (rotor plane), y_l = z_l x shaft; scalars, no arrays per node
        z0, z1, z2 = (rho_w[b, p, 0] - along * shaft[0], rho_w[b, p, 1] - along * shaft[1],
                      rho_w[b, p, 2] - along * shaft[2])
        size = z0 * z0 + z1 * z1 + z2 * z2
        if size == 0.0:                   # a node on the shaft (hub radius 0): the section's span axis points out
            span_along = span[0] * shaft[0] + span[1] * shaft[1] + span[2] * shaft[2]
            z0, z1, z2 = span[0] - span_along * shaft[0], span[1] - span_along * shaft[1], \
                span[2] - span_along * shaft[2]
            size = z0 * z0 + z1 * z1 + z2 * z2
        size = math.sqrt(size)
        z0, z1, z2 = z0 / size, z1 / size, z2 / size
        y0, y1, y2 = z1 * shaft[2] - z2 * shaft[1], z2 * shaft[0] - z0 * shaft[2], z0 * shaft[1] - z1 * shaft[0]
        vx = rel[0] * shaft[0] + rel[1] * shaft[1] + rel[2] * shaft[2]
        vy = rel[0] * y0 + rel[1] * y1 + rel[2] * y2
        m11 = normal[0] * shaft[0] + normal[1] * shaft[1] + normal[2] * shaft[2]
        m12 = normal[0] * y0 + normal[1] * y1 + normal[2] * y2
        m13 = normal[0] * z0 + normal[1] * z1 + normal[2] * z2
        m21 = -(tangent[0] * shaft[0] + tangent[1] * shaft[1] + tangent[2] * shaft[2])
        m22 = -(tangent[0] * y0 + tangent[1] * y1 + tangent[2] * y2)
        m23 = -(tangent[0] * z0 + tangent[1] * z1 + tangent[2] * z2)
        m31 = span[0] * shaft[0] + span[1] * shaft[1] + span[2] * shaft[2]
        twist, c, s, cb, sb, ct, st = euler_frame(m11, m12, m13, m21, m22, m23, m31)
        for r in range(3):
            n, t = normal[r], tangent[r]
            normal[r] = c * n - s * t
            tangent[r] = s * n + c * t
        drdz = math.sqrt(step_projected) / math.sqrt(step) if step > 0.0 else 0.0
        return vx, vy, cb, sb, ct, st, twist - pitch, drdz
