"""The same Kane equations as :meth:`TurbineModel.equations`, compiled with numba (optional) for time integration.

The kinematics are the two rules of ``kinematics.py`` written as loops over frames, span nodes and blades; the
generalized inertia and active forces are summed in the factored form ``Z^T (sum_p m_p G_p^T G_p) Z`` per node
group. :func:`compiled_equations` returns None when numba is not installed; tests check that both paths give the
same mass matrix and forcing to rounding.
"""

from __future__ import annotations

import os

import numpy as np
from numpy.typing import NDArray

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

    # Dormand-Prince 5(4) tableau
    _C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
    _A = np.array([[0, 0, 0, 0, 0, 0],
                   [1 / 5, 0, 0, 0, 0, 0],
                   [3 / 40, 9 / 40, 0, 0, 0, 0],
                   [44 / 45, -56 / 15, 32 / 9, 0, 0, 0],
                   [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0, 0],
                   [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0],
                   [35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84]])
    _B = np.array([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0])
    _E = np.array([71 / 57600, 0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])

    @njit(cache=True)
    def dormand_prince(times, x0, rtol, atol, q0, u0, index, *data):
        """Adaptive Dormand-Prince 5(4) with local extrapolation (scipy's RK45 scheme), steps landing on the
        output times; returns the states at ``times`` and the number of right-hand sides."""
        size = x0.shape[0]
        out = np.empty((times.shape[0], size))
        out[0] = x0
        x = x0.copy()
        t = times[0]
        k = np.empty((7, size))
        k[0] = derivative(t, x, q0, u0, index, *data)
        count = 1
        h = min(1e-3, times[-1] - t) if times.shape[0] > 1 else 0.0
        for n in range(1, times.shape[0]):
            target = times[n]
            while t < target - 1e-12 * max(1.0, abs(target)):
                h = min(h, target - t)
                for i in range(1, 7):
                    stage = x.copy()
                    for j in range(i):
                        if _A[i, j] != 0.0:
                            stage += h * _A[i, j] * k[j]
                    k[i] = derivative(t + _C[i] * h, stage, q0, u0, index, *data)
                    count += 1
                new = x + h * (_B @ k)
                error = h * (_E @ k)
                scale = atol + rtol * np.maximum(np.abs(x), np.abs(new))
                norm = np.sqrt(np.mean((error / scale) ** 2))
                if norm <= 1.0:
                    t += h
                    x = new
                    k[0] = k[6]                          # first same as last
                    factor = 5.0 if norm == 0.0 else min(5.0, 0.9 * norm ** -0.2)
                else:
                    factor = max(0.2, 0.9 * norm ** -0.2)
                h *= factor
            out[n] = x
        return out, count

    @njit(cache=True)
    def dormand_prince_853(times, x0, rtol, atol, A, B, C, E3, E5, q0, u0, index, *data):
        """Adaptive 8th-order Dormand-Prince with the 5th/3rd-order error estimate (Hairer's DOP853, scipy's
        scheme and tableau), steps landing on the output times; states at ``times`` and right-hand sides."""
        size = x0.shape[0]
        stages = B.shape[0]
        out = np.empty((times.shape[0], size))
        out[0] = x0
        x = x0.copy()
        t = times[0]
        k = np.zeros((stages + 1, size))
        k[0] = derivative(t, x, q0, u0, index, *data)
        count = 1
        h = min(1e-3, times[-1] - t) if times.shape[0] > 1 else 0.0
        for n in range(1, times.shape[0]):
            target = times[n]
            while t < target - 1e-12 * max(1.0, abs(target)):
                h = min(h, target - t)
                for i in range(1, stages):
                    stage = x.copy()
                    for j in range(i):
                        if A[i, j] != 0.0:
                            stage += h * A[i, j] * k[j]
                    k[i] = derivative(t + C[i] * h, stage, q0, u0, index, *data)
                    count += 1
                new = x.copy()
                for j in range(stages):
                    new += h * B[j] * k[j]
                k[stages] = derivative(t + h, new, q0, u0, index, *data)
                count += 1
                scale = atol + rtol * np.maximum(np.abs(x), np.abs(new))
                err5 = (E5 @ k) / scale
                err3 = (E3 @ k) / scale
                e5, e3 = np.sum(err5**2), np.sum(err3**2)
                norm = 0.0 if e5 == 0.0 and e3 == 0.0 else h * e5 / np.sqrt((e5 + 0.01 * e3) * size)
                if norm <= 1.0:
                    t += h
                    x = new
                    k[0] = k[stages]
                    factor = 10.0 if norm == 0.0 else min(10.0, 0.9 * norm ** -0.125)
                else:
                    factor = max(0.2, 0.9 * norm ** -0.125)
                h *= factor
            out[n] = x
        return out, count


def _kernels():
    """The compiled (equations, derivative, Dormand-Prince 5(4), DOP853) kernels."""
    return equations, derivative, dormand_prince, dormand_prince_853


def _dop853_tableau() -> tuple[NDArray, ...]:
    """Hairer's DOP853 coefficients as scipy ships them (A, B, C for the 12 stages; E3, E5 error weights)."""
    from scipy.integrate._ivp import dop853_coefficients as d
    stages = d.N_STAGES
    return (np.ascontiguousarray(d.A[:stages, :stages]), np.ascontiguousarray(d.B),
            np.ascontiguousarray(d.C[:stages]), np.ascontiguousarray(d.E3), np.ascontiguousarray(d.E5))


_KERNELS = None


class CompiledEquations:
    """The compiled kernels bound to one model's data: ``equations(q, u) -> (M, f)`` and
    ``derivative(t, x, q0, u0, index)`` for :class:`FreeSystem`."""

    def __init__(self, kernels, data) -> None:
        self.kernels, self.data = kernels, data

    def __call__(self, q: NDArray, u: NDArray) -> tuple[NDArray, NDArray]:
        return self.kernels[0](np.ascontiguousarray(q, dtype=float), np.ascontiguousarray(u, dtype=float),
                               *self.data)

    def derivative(self, t: float, x: NDArray, q0: NDArray, u0: NDArray, index: NDArray) -> NDArray:
        return self.kernels[1](float(t), np.ascontiguousarray(x, dtype=float), q0, u0, index, *self.data)

    def integrate(self, times: NDArray, x0: NDArray, rtol: float, atol: float, q0: NDArray, u0: NDArray,
                  index: NDArray, order: int = 5) -> tuple[NDArray, int]:
        """Compiled adaptive Dormand-Prince from times[0], 5(4) (``order=5``) or 8(5,3) (``order=8``); states at
        ``times`` and the number of right-hand sides."""
        times = np.ascontiguousarray(times, dtype=float)
        x0 = np.ascontiguousarray(x0, dtype=float)
        if order == 8:
            return self.kernels[3](times, x0, float(rtol), float(atol), *_dop853_tableau(), q0, u0, index,
                                   *self.data)
        return self.kernels[2](times, x0, float(rtol), float(atol), q0, u0, index, *self.data)


def compiled_equations(model) -> CompiledEquations | None:
    """The compiled kernels on ``model``'s data; None without numba or with the environment variable
    BLADEFEM_NO_NUMBA set."""
    global _KERNELS
    if njit is None or os.environ.get("BLADEFEM_NO_NUMBA"):
        return None
    if _KERNELS is None:
        _KERNELS = _kernels()
    tower, blade = model.tower_nodes, model.blade_nodes
    data = (model.n,
            tower.across_flat.reshape(tower.k, tower.P, 3).copy(), tower.shortening_flat.reshape(4, 4, -1).copy(),
            _axial_array(tower), model.tower_masses.copy(),
            blade.across_flat.reshape(blade.k, blade.P, 3).copy(),
            blade.shortening_flat.reshape(blade.k, blade.k, -1).copy(), _axial_array(blade),
            model.blade_masses[0].copy(), model.blade_columns.astype(np.int64), model.blade_rotations.copy(),
            model.fore_aft_tilt.copy(), model.side_side_tilt.copy(), model.yaw.copy(), model.azimuth.copy(),
            model.generator_angle.copy(), model.tilt.copy(), model.rigid_offsets.copy(), model.rigid_masses.copy(),
            np.array(model.inertias, dtype=float), model.gravity.copy(), model.K.copy(),
            model.C.copy())
    return CompiledEquations(_KERNELS, data)


def _axial_array(nodes) -> NDArray:
    """Undeflected axial positions of a node group (the offsets' axial component at zero deflection)."""
    return np.broadcast_to(np.asarray(nodes.axial, dtype=float), (nodes.P,)).copy()
