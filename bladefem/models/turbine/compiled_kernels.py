"""numba kernels of the Kane equations (see :mod:`bladefem.models.turbine.compiled`).

Everything is written as loops over 3-vectors and small matrices (no BLAS, no LAPACK: that keeps the compile time
down and the small products fast). The model's arrays travel as one tuple ``data`` (:func:`compiled.model_data`);
``work`` holds, per blade node, what external loads need (see :func:`equations`).
"""

from __future__ import annotations

import numpy as np

from ...numba_cache import cached_njit

njit = cached_njit()


if njit is not None:                                   # module-level kernels: numba caches them on disk
    from .compiled_invariants import blade_inertia, pitched_frame, scratch_size, to_blade


    @njit(cache=True)
    def solve_spd(A, b):
        """x with A x = b for a symmetric positive definite A (Cholesky by loops); A and b are left intact."""
        n = b.shape[0]
        L = np.zeros((n, n))
        for j in range(n):
            s = A[j, j]
            for k in range(j):
                s -= L[j, k] * L[j, k]
            if not s > 0.0:
                return np.full(n, np.nan)
            L[j, j] = np.sqrt(s)
            for i in range(j + 1, n):
                s = A[i, j]
                for k in range(j):
                    s -= L[i, k] * L[j, k]
                L[i, j] = s / L[j, j]
        x = b.copy()
        for i in range(n):
            for k in range(i):
                x[i] -= L[i, k] * x[k]
            x[i] /= L[i, i]
        for i in range(n - 1, -1, -1):
            for k in range(i + 1, n):
                x[i] -= L[k, i] * x[k]
            x[i] /= L[i, i]
        return x

    @njit(cache=True)
    def store_row(matrix, row, vector):
        """matrix[row] = vector by a loop (slice assignment makes numba type its error messages: slow to compile)."""
        for i in range(vector.shape[0]):
            matrix[row, i] = vector[i]

    @njit(cache=True)
    def store_block(matrix, row, column, block):
        """matrix[row:row + m, column:column + k] = block (m x k) by loops."""
        for i in range(block.shape[0]):
            for j in range(block.shape[1]):
                matrix[row + i, column + j] = block[i, j]

    @njit(cache=True)
    def rotation_step(R, axis, angle):
        """R @ (rotation by ``angle`` about the frame's own axis ``axis``)."""
        c, s = np.cos(angle), np.sin(angle)
        i, j = (1, 2) if axis == 0 else ((2, 0) if axis == 1 else (0, 1))
        out = R.copy()
        for r in range(3):
            out[r, i] = c * R[r, i] + s * R[r, j]
            out[r, j] = -s * R[r, i] + c * R[r, j]
        return out

    @njit(cache=True)
    def rotate(R, w, W, al, axis, coefficients, q, u):
        """Frame turned about its own axis by ``coefficients . q`` (see kinematics.rotate): R, omega, partial
        angular velocities W (3, n) and bias angular acceleration."""
        angle = 0.0
        rate = 0.0
        for i in range(q.shape[0]):
            angle += coefficients[i] * q[i]
            rate += coefficients[i] * u[i]
        k0, k1, k2 = R[0, axis], R[1, axis], R[2, axis]
        al2 = al.copy()
        al2[0] += (w[1] * k2 - w[2] * k1) * rate
        al2[1] += (w[2] * k0 - w[0] * k2) * rate
        al2[2] += (w[0] * k1 - w[1] * k0) * rate
        w2 = w.copy()
        w2[0] += k0 * rate
        w2[1] += k1 * rate
        w2[2] += k2 * rate
        W2 = W.copy()
        for i in range(coefficients.shape[0]):
            if coefficients[i] != 0.0:
                W2[0, i] += k0 * coefficients[i]
                W2[1, i] += k1 * coefficients[i]
                W2[2, i] += k2 * coefficients[i]
        return rotation_step(R, axis, angle), w2, W2, al2

    @njit(cache=True)
    def carried_point(J, base_a, W, w, al, rho):
        """A point at ``rho`` (m) from a base point of a rigid body (angular velocity ``w``, its partials ``W``
        (3, n), angular acceleration bias ``al``): its velocity partials ``J += W x rho`` (in place, J the base's)
        and its acceleration bias ``base_a + al x rho + w x (w x rho)`` (returned)."""
        for c in range(J.shape[1]):
            J[0, c] += W[1, c] * rho[2] - W[2, c] * rho[1]
            J[1, c] += W[2, c] * rho[0] - W[0, c] * rho[2]
            J[2, c] += W[0, c] * rho[1] - W[1, c] * rho[0]
        wr = np.array([w[1] * rho[2] - w[2] * rho[1], w[2] * rho[0] - w[0] * rho[2], w[0] * rho[1] - w[1] * rho[0]])
        return np.array([base_a[0] + al[1] * rho[2] - al[2] * rho[1] + w[1] * wr[2] - w[2] * wr[1],
                         base_a[1] + al[2] * rho[0] - al[0] * rho[2] + w[2] * wr[0] - w[0] * wr[2],
                         base_a[2] + al[0] * rho[1] - al[1] * rho[0] + w[0] * wr[1] - w[1] * wr[0]])

    @njit(cache=True)
    def accumulate_node(A, F, G, m, load):
        """A += m G^T G, F += G^T load for one node (G is 3 x c)."""
        c = G.shape[1]
        for i in range(c):
            F[i] += G[0, i] * load[0] + G[1, i] * load[1] + G[2, i] * load[2]
            gi0, gi1, gi2 = m * G[0, i], m * G[1, i], m * G[2, i]
            for j in range(i, c):
                value = gi0 * G[0, j] + gi1 * G[1, j] + gi2 * G[2, j]
                A[i, j] += value
                if j != i:
                    A[j, i] += value

    @njit(cache=True)
    def add_group(M, f, A, F, Z):
        """M += Z^T A Z, f += Z^T F (Z is c x n)."""
        c, n = Z.shape
        AZ = np.zeros((c, n))
        for i in range(c):
            for k in range(c):
                a = A[i, k]
                if a != 0.0:
                    for j in range(n):
                        AZ[i, j] += a * Z[k, j]
        for i in range(n):
            for r in range(c):
                z = Z[r, i]
                if z != 0.0:
                    f[i] += z * F[r]
                    for j in range(n):
                        M[i, j] += z * AZ[r, j]

    @njit(cache=True)
    def add_rigid_point(M, f, J, m, load):
        """M += m J^T J, f += J^T load for a point with partial velocities J (3 x n)."""
        n = J.shape[1]
        for i in range(n):
            f[i] += J[0, i] * load[0] + J[1, i] * load[1] + J[2, i] * load[2]
            for j in range(n):
                M[i, j] += m * (J[0, i] * J[0, j] + J[1, i] * J[1, j] + J[2, i] * J[2, j])

    @njit(cache=True)
    def add_rotor_body(M, f, R, w, W, al, axis, inertia):
        """A body with one principal inertia about its axis k: M += I (W^T k)(W^T k)^T,
        f -= I [(k . alpha) W^T k + (k . omega) W^T (omega x k)]."""
        k0, k1, k2 = R[0, axis], R[1, axis], R[2, axis]
        c0, c1, c2 = w[1] * k2 - w[2] * k1, w[2] * k0 - w[0] * k2, w[0] * k1 - w[1] * k0
        spin = k0 * w[0] + k1 * w[1] + k2 * w[2]
        acceleration = k0 * al[0] + k1 * al[1] + k2 * al[2]
        n = W.shape[1]
        partial = np.empty(n)
        for i in range(n):
            partial[i] = W[0, i] * k0 + W[1, i] * k1 + W[2, i] * k2
        for i in range(n):
            f[i] -= inertia * (acceleration * partial[i] + spin * (W[0, i] * c0 + W[1, i] * c1 + W[2, i] * c2))
            for j in range(n):
                M[i, j] += inertia * partial[i] * partial[j]

    @njit(cache=True)
    def beam_node(across, shortening, axial, p, q, u, order, D, d, rate, bias):
        """Fill the offset d, partials D (3, k), velocity and bias of node p in its frame (see
        kinematics.BeamNodes)."""
        k = across.shape[0]
        s2 = 0.0
        bias_axial = 0.0
        for r in range(3):
            d[r] = 0.0
            rate[r] = 0.0
            bias[r] = 0.0
        for i in range(k):
            Sq = 0.0
            Su = 0.0
            for j in range(k):
                Sq += shortening[i, j, p] * q[j]
                Su += shortening[i, j, p] * u[j]
            s2 += Sq * q[i]
            bias_axial -= Su * u[i]
            for r in range(3):
                D[r, i] = across[i, p, r]
                d[r] += across[i, p, r] * q[i]
            D[order, i] -= Sq
        d[order] += axial[p] - 0.5 * s2
        for r in range(3):
            for i in range(k):
                rate[r] += D[r, i] * u[i]
        bias[order] = bias_axial

    @njit(cache=True)
    def equations(q, u, data, work):
        """Mass matrix M (n, n) and forcing f (n,) of ``M du/dt = f`` at (q, u). Fills in ``work``
        (:class:`.compiled.CompiledEquations`) per blade the shared partials Z (B, 6 + k, n) and the blade frame
        (B, 3, 3); the apex position (3,); the hub centre of mass's partial velocities (3, n); rows of (4, 3): the
        hub's bias acceleration, its offset from the apex, the rotor's bias angular acceleration and the shaft axis,
        all earth components; per blade its ``A = sum m G^T G`` (B, 6 + k, 6 + k) and
        ``F = sum G^T m (g - a_bias)`` (B, 6 + k) over its nodes, from their modal integrals
        (:mod:`.compiled_invariants`), in the frame of the integrals (:func:`.compiled_invariants.pitched_frame`):
        the blade's gravity and inertial loads at accelerations ``Z du`` are then ``F - A T^T Z du`` there (the
        force, and the moment about the apex; T of :func:`.compiled_invariants.to_blade`)."""
        (n, t_across, t_short, t_axial, t_mass, b_across, b_short, b_axial, b_mass, b_columns, b_rotations,
         fore_aft, side_side, yaw, azimuth, generator, tilt, rigid_offsets, rigid_mass, inertias, gravity,
         K, C, base_height, b_invariants) = data
        Z_w, frame_w, apex_w, hub_J_w, hub_w, blade_A, blade_F = work
        M = np.zeros((n, n))
        f = np.zeros(n)
        # tower nodes: earth frame, fixed origin; J_p = D_p over the tower columns
        qt, ut = q[:4], u[:4]
        A = np.zeros((4, 4))
        F = np.zeros(4)
        D = np.zeros((3, 4))
        d, rate, bias, load = np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3)
        for p in range(t_axial.shape[0]):
            beam_node(t_across, t_short, t_axial, p, qt, ut, 2, D, d, rate, bias)
            m = t_mass[p]
            for r in range(3):
                load[r] = m * (gravity[r] - bias[r])
            accumulate_node(A, F, D, m, load)
        top_J = np.zeros((3, n))
        store_block(top_J, 0, 0, D)
        top_a = bias.copy()
        top_r = d.copy()                     # the last tower node is the tower top
        top_r[2] += base_height
        for i in range(4):
            f[i] += F[i]
            for j in range(4):
                M[i, j] += A[i, j]
        # frames: tower top (fore-aft then side-side tilt), nacelle (yaw), shaft (tilt), rotor, generator
        R, w, W, al = np.zeros((3, 3)), np.zeros(3), np.zeros((3, n)), np.zeros(3)
        R[0, 0] = R[1, 1] = R[2, 2] = 1.0
        R, w, W, al = rotate(R, w, W, al, 1, fore_aft, q, u)
        R, w, W, al = rotate(R, w, W, al, 0, side_side, q, u)
        RN, wN, WN, alN = rotate(R, w, W, al, 2, yaw, q, u)
        RS = np.zeros((3, 3))
        for r in range(3):
            for c in range(3):
                RS[r, c] = RN[r, 0] * tilt[0, c] + RN[r, 1] * tilt[1, c] + RN[r, 2] * tilt[2, c]
        RL, wL, WL, alL = rotate(RS, wN, WN, alN, 0, azimuth, q, u)
        for r in range(3):
            hub_w[2, r] = alL[r]
            hub_w[3, r] = RL[r, 0]
        RG, wG, WG, alG = rotate(RS, wN, WN, alN, 0, generator, q, u)
        # rigid points in the nacelle frame: nacelle centre of mass, apex, hub centre of mass
        apex_J = np.zeros((3, n))
        apex_a = np.zeros(3)
        rho = np.zeros(3)
        for i in range(3):
            for r in range(3):
                rho[r] = RN[r, 0] * rigid_offsets[i, 0] + RN[r, 1] * rigid_offsets[i, 1] \
                    + RN[r, 2] * rigid_offsets[i, 2]
            J = top_J.copy()
            a = carried_point(J, top_a, WN, wN, alN, rho)
            m = rigid_mass[i]
            for r in range(3):
                load[r] = m * (gravity[r] - a[r])
            add_rigid_point(M, f, J, m, load)
            if i == 1:
                store_block(apex_J, 0, 0, J)
                for r in range(3):
                    apex_a[r] = a[r]
                    apex_w[r] = top_r[r] + rho[r]
            elif i == 2:
                store_block(hub_J_w, 0, 0, J)
                for r in range(3):
                    hub_w[0, r] = a[r]
                    hub_w[1, r] = top_r[r] + rho[r] - apex_w[r]
        # blades: G_p = [I, -[rho]x, R D] with Z = [J_apex; W_rotor; E_blade], summed by the modal integrals
        kb = b_across.shape[0]
        g, w, al = np.zeros(3), np.zeros(3), np.zeros(3)
        scratch = np.empty(scratch_size(kb))
        for b in range(b_rotations.shape[0]):
            Rb = np.zeros((3, 3))
            for r in range(3):
                for c in range(3):
                    Rb[r, c] = RL[r, 0] * b_rotations[b, 0, c] + RL[r, 1] * b_rotations[b, 1, c] \
                        + RL[r, 2] * b_rotations[b, 2, c]
            store_block(frame_w[b], 0, 0, Rb)
            cols = b_columns[b]
            qb, ub = np.empty(kb), np.empty(kb)
            for i in range(kb):
                qb[i] = q[cols[i]]
                ub[i] = u[cols[i]]
            Ri = pitched_frame(Rb, b_invariants[9])
            for c in range(3):                           # the components in the frame of the integrals
                g[c] = w[c] = al[c] = 0.0
                for r in range(3):
                    g[c] += Ri[r, c] * (gravity[r] - apex_a[r])
                    w[c] += Ri[r, c] * wL[r]
                    al[c] += Ri[r, c] * alL[r]
            A, F = blade_A[b], blade_F[b]
            blade_inertia(b_invariants, qb, ub, g, w, al, A, F, scratch)
            Z = Z_w[b]
            store_block(Z, 0, 0, apex_J)
            store_block(Z, 3, 0, WL)
            for i in range(kb):
                for c in range(n):
                    Z[6 + i, c] = 0.0
                Z[6 + i, cols[i]] = 1.0
            add_group(M, f, A, F, to_blade(Z, Ri))
        # rigid bodies with one principal inertia: nacelle about yaw, hub and generator about the shaft
        add_rotor_body(M, f, RN, wN, WN, alN, 2, inertias[0])
        add_rotor_body(M, f, RL, wL, WL, alL, 0, inertias[1])
        add_rotor_body(M, f, RG, wG, WG, alG, 0, inertias[2])
        for i in range(n):
            for j in range(n):
                f[i] -= K[i, j] * q[j] + C[i, j] * u[j]
        return M, f
