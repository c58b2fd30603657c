"""numba kernels of the Kane equations: small linear algebra, the chain of frames, span-node sums, and the
right-hand side ``derivative`` for time integration (see :mod:`bladefem.models.turbine.compiled`)."""

from __future__ import annotations

import numpy as np

try:
    from numba import njit
except ImportError:                                    # pragma: no cover - numba is optional
    njit = None


if njit is not None:                                   # module-level kernels: numba caches them on disk

    @njit(cache=True)
    def cross(a, b):
        return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])

    @njit(cache=True)
    def mm(A, B):
        """A @ B by loops (small matrices: no BLAS call)."""
        out = np.zeros((A.shape[0], B.shape[1]))
        for i in range(A.shape[0]):
            for k in range(A.shape[1]):
                a = A[i, k]
                if a != 0.0:
                    for j in range(B.shape[1]):
                        out[i, j] += a * B[k, j]
        return out

    @njit(cache=True)
    def mv(A, x):
        """A @ x by loops."""
        out = np.zeros(A.shape[0])
        for i in range(A.shape[0]):
            for k in range(A.shape[1]):
                out[i] += A[i, k] * x[k]
        return out

    @njit(cache=True)
    def tmv(A, x):
        """A^T @ x by loops."""
        out = np.zeros(A.shape[1])
        for k in range(A.shape[0]):
            xk = x[k]
            if xk != 0.0:
                for i in range(A.shape[1]):
                    out[i] += A[k, i] * xk
        return out

    @njit(cache=True)
    def add_gram(M, J, m):
        """M += m J^T J by loops."""
        for i in range(J.shape[1]):
            for j in range(J.shape[1]):
                value = 0.0
                for r in range(J.shape[0]):
                    value += J[r, i] * J[r, j]
                M[i, j] += m * value

    @njit(cache=True)
    def axis_rotation(axis, angle):
        c, s = np.cos(angle), np.sin(angle)
        R = np.eye(3)
        i, j = (1, 2) if axis == 0 else ((2, 0) if axis == 1 else (0, 1))
        R[i, i] = c
        R[j, j] = c
        R[j, i] = s
        R[i, j] = -s
        return R

    @njit(cache=True)
    def rotate(R, w, W, al, axis, coefficients, q, u):
        """Frame turned about its own axis by coefficients . q (see kinematics.rotate)."""
        angle = 0.0
        rate = 0.0
        for i in range(q.shape[0]):
            angle += coefficients[i] * q[i]
            rate += coefficients[i] * u[i]
        k = R[:, axis].copy()
        al = al + cross(w, k) * rate
        w = w + k * rate
        W = W.copy()
        for i in range(coefficients.shape[0]):
            if coefficients[i] != 0.0:
                for r in range(3):
                    W[r, i] += k[r] * coefficients[i]
        return mm(R, axis_rotation(axis, angle)), w, W, al

    @njit(cache=True)
    def add_group(M, f, A, F, Z):
        """M += Z^T A Z, f += Z^T F."""
        AZ = mm(A, Z)
        for i in range(Z.shape[1]):
            for j in range(Z.shape[1]):
                value = 0.0
                for r in range(Z.shape[0]):
                    value += Z[r, i] * AZ[r, j]
                M[i, j] += value
        f += tmv(Z, F)

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
        d[order] = axial[p] - 0.5 * s2
        for r in range(3):
            for i in range(k):
                rate[r] += D[r, i] * u[i]
        bias[order] = bias_axial

    @njit(cache=True)
    def equations(q, u, n, t_across, t_short, t_axial, t_mass, b_across, b_short, b_axial, b_mass, b_columns,
                  b_rotations, fore_aft, side_side, yaw, azimuth, generator, tilt, rigid_offsets, rigid_mass,
                  inertias, gravity, K, C):
        M = np.zeros((n, n))
        f = np.zeros(n)
        # tower nodes: earth frame, fixed origin; J_p = D_p over the tower columns
        qt, ut = q[:4], u[:4]
        Pt = t_axial.shape[0]
        top_J = np.zeros((3, n))
        top_a = np.zeros(3)
        A = np.zeros((4, 4))
        F = np.zeros(4)
        D = np.zeros((3, 4))
        d, rate, bias, load = np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3)
        for p in range(Pt):
            beam_node(t_across, t_short, t_axial, p, qt, ut, 2, D, d, rate, bias)
            m = t_mass[p]
            for r in range(3):
                load[r] = m * (gravity[r] - bias[r])
            accumulate_node(A, F, D, m, load)
        top_J[:, :4] = D
        top_a = bias.copy()
        M[:4, :4] += A
        f[:4] += F
        # frames: tower top (fore-aft then side-side tilt), nacelle (yaw), shaft (tilt), rotor, generator
        R, w, W, al = np.eye(3), np.zeros(3), np.zeros((3, n)), np.zeros(3)
        R, w, W, al = rotate(R, w, W, al, 1, fore_aft, q, u)
        R, w, W, al = rotate(R, w, W, al, 0, side_side, q, u)
        RN, wN, WN, alN = rotate(R, w, W, al, 2, yaw, q, u)
        RS = mm(RN, tilt)
        RL, wL, WL, alL = rotate(RS, wN, WN, alN, 0, azimuth, q, u)
        RG, wG, WG, alG = rotate(RS, wN, WN, alN, 0, generator, q, u)
        # rigid points in the nacelle frame: nacelle centre of mass, apex, hub centre of mass
        apex_J = np.zeros((3, n))
        apex_a = np.zeros(3)
        for i in range(3):
            rho = mv(RN, rigid_offsets[i])
            J = top_J.copy()
            for c in range(n):
                J[:, c] += cross(WN[:, c], rho)
            a = top_a + cross(alN, rho) + cross(wN, cross(wN, rho))
            m = rigid_mass[i]
            add_gram(M, J, m)
            f += tmv(J, m * (gravity - a))
            if i == 1:
                apex_J, apex_a = J, a
        # blade nodes: G_p = [I, -[rho]x, R D] with Z = [J_apex; W_rotor; E_blade]
        kb = b_across.shape[0]
        Pb = b_axial.shape[0]
        D = np.zeros((3, kb))
        rho, moving, load = np.zeros(3), np.zeros(3), np.zeros(3)
        for b in range(b_rotations.shape[0]):
            Rb = mm(RL, b_rotations[b])
            cols = b_columns[b]
            qb, ub = q[cols], u[cols]
            A = np.zeros((6 + kb, 6 + kb))
            F = np.zeros(6 + kb)
            G = np.zeros((3, 6 + kb))
            G[0, 0] = 1.0
            G[1, 1] = 1.0
            G[2, 2] = 1.0
            for p in range(Pb):
                beam_node(b_across, b_short, b_axial, p, qb, ub, 0, D, d, rate, bias)
                for r in range(3):
                    rho[r] = Rb[r, 0] * d[0] + Rb[r, 1] * d[1] + Rb[r, 2] * d[2]
                    moving[r] = Rb[r, 0] * rate[0] + Rb[r, 1] * rate[1] + Rb[r, 2] * rate[2]
                    for i in range(kb):
                        G[r, 6 + i] = Rb[r, 0] * D[0, i] + Rb[r, 1] * D[1, i] + Rb[r, 2] * D[2, i]
                # a = a_apex + alpha x rho + omega x (omega x rho) + 2 omega x R d' + R d'' (d'' is axial only)
                w0, w1, w2 = wL[0], wL[1], wL[2]
                wr0 = w1 * rho[2] - w2 * rho[1]
                wr1 = w2 * rho[0] - w0 * rho[2]
                wr2 = w0 * rho[1] - w1 * rho[0]
                m = b_mass[p]
                load[0] = m * (gravity[0] - (apex_a[0] + alL[1] * rho[2] - alL[2] * rho[1] + w1 * wr2 - w2 * wr1
                                             + 2.0 * (w1 * moving[2] - w2 * moving[1]) + Rb[0, 0] * bias[0]))
                load[1] = m * (gravity[1] - (apex_a[1] + alL[2] * rho[0] - alL[0] * rho[2] + w2 * wr0 - w0 * wr2
                                             + 2.0 * (w2 * moving[0] - w0 * moving[2]) + Rb[1, 0] * bias[0]))
                load[2] = m * (gravity[2] - (apex_a[2] + alL[0] * rho[1] - alL[1] * rho[0] + w0 * wr1 - w1 * wr0
                                             + 2.0 * (w0 * moving[1] - w1 * moving[0]) + Rb[2, 0] * bias[0]))
                G[0, 4], G[0, 5] = rho[2], -rho[1]
                G[1, 3], G[1, 5] = -rho[2], rho[0]
                G[2, 3], G[2, 4] = rho[1], -rho[0]
                accumulate_node(A, F, G, m, load)
            Z = np.zeros((6 + kb, n))
            Z[:3] = apex_J
            Z[3:6] = WL
            for i in range(kb):
                Z[6 + i, cols[i]] = 1.0
            add_group(M, f, A, F, Z)
        # rigid bodies with one principal inertia: nacelle about yaw, hub and generator about the shaft
        for axis_frame, W_b, w_b, al_b, inertia in ((RN[:, 2].copy(), WN, wN, alN, inertias[0]),
                                                     (RL[:, 0].copy(), WL, wL, alL, inertias[1]),
                                                     (RG[:, 0].copy(), WG, wG, alG, inertias[2])):
            partial = tmv(W_b, axis_frame)
            M += inertia * np.outer(partial, partial)
            f -= inertia * ((axis_frame @ al_b) * partial + (axis_frame @ w_b) * tmv(W_b, cross(w_b, axis_frame)))
        f -= mv(K, q) + mv(C, u)
        return M, f

    @njit(cache=True)
    def derivative(t, x, q0, u0, index, *data):
        """dx/dt of the free coordinates x = (q_f, u_f); locked ones move on at their initial rate."""
        size = index.shape[0]
        q = q0 + u0 * t
        u = u0.copy()
        for i in range(size):
            q[index[i]] = x[i]
            u[index[i]] = x[size + i]
        M, f = equations(q, u, *data)
        Mf = np.empty((size, size))
        ff = np.empty(size)
        for i in range(size):
            ff[i] = f[index[i]]
            for j in range(size):
                Mf[i, j] = M[index[i], index[j]]
        out = np.empty(2 * size)
        out[:size] = x[size:]
        out[size:] = np.linalg.solve(Mf, ff)
        return out
