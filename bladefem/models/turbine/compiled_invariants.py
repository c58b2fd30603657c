"""The blades' inertia as modal integrals: each right-hand side sums over the shapes, not over the span points.

A blade node p sits at ``d_p(q) = Phi_p zeta(q)`` in the blade frame and its offset's partials are
``D_p(q)[:, i] = Psi_p[:, i] xi(q)``, with the monomials ``zeta = (1, q, q_i q_j for i <= j)`` and ``xi = (1, q)``
(the axial shortening ``-1/2 q^T S_p q`` is the quadratic part, :func:`.compiled_kernels.beam_node`). Every sum over
the nodes that the Kane equations of a blade need is then a product of mass-weighted integrals of ``Phi`` and
``Psi``, computed once (:func:`blade_invariants`), with monomials of the state (:func:`blade_inertia`): the first
and second moments ``sum m d`` and ``sum m d d^T``, ``sum m D``, ``sum m D (x) d``, ``sum m D (x) D`` and the axial
bias terms of ``sum m (u^T S_p u) (d, D)``. These are the flexible-body invariants of multibody codes (Shabana,
"Dynamics of Multibody Systems", ch. 5; SIMPACK's SID files, MSC Adams' modal neutral files), here exact: the
same quadrature points and the same polynomial kinematics as the node sums of the numpy twin of
:func:`.compiled_kernels.equations` (:meth:`bladefem.models.turbine.kane.TurbineModel.equations`), which
``tests/test_turbine_compiled.py`` compares to rounding.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ...numba_cache import cached_njit

njit = cached_njit()


def blade_invariants(across: NDArray, shortening: NDArray, axial: NDArray, masses: NDArray) -> tuple:
    """The mass-weighted integrals of one blade (shared by all blades): ``across`` (k, P, 3), ``shortening``
    (k, k, P), ``axial`` (P,) node positions along the span (m), ``masses`` (P,) lumped node masses (kg).

    Returns (total mass, I1 (3, nz), I2 (6, nz nz), I3 (3 k, nx), I4 (3 k 3, nx nz), I5 (3 k (3 k + 1) / 2, nx nx),
    I6 (3, k k nz), I7 (k, k k nx), I8 (k, k), turn); the row order (r, i, s, j) of a flattened tensor is C order;
    I2 and I5, symmetric in (s, t) and in ((r, i), (s, j)), keep the rows of their upper triangles (:func:`upper`).
    ``turn`` (cos, sin) of the pitch the shapes were turned by since (:mod:`.pitching`, a turn about the span
    axis x: the shapes' across components (y, z) go to (y cos + z sin, -y sin + z cos), the axial ones stay), set
    in place: the integrals of the turned shapes are those of a frame turned alike (:func:`pitched_frame`)."""
    k, P = across.shape[:2]
    pairs = [(i, j) for i in range(k) for j in range(i, k)]
    nz, nx = 1 + k + len(pairs), 1 + k
    S = np.moveaxis(shortening, 2, 0)                                  # (P, k, k)
    Phi = np.zeros((P, 3, nz))
    Phi[:, 0, 0] = axial
    Phi[:, :, 1:1 + k] = np.moveaxis(across, 0, 2)
    for column, (i, j) in enumerate(pairs, start=1 + k):
        Phi[:, 0, column] = -0.5 * (S[:, i, j] + S[:, j, i]) if i != j else -0.5 * S[:, i, i]
    Psi = np.zeros((P, 3, k, nx))
    Psi[:, :, :, 0] = np.moveaxis(across, 0, 2)
    Psi[:, 0, :, 1:] = -S
    m = masses
    return (float(m.sum()),
            np.einsum("p,psa->sa", m, Phi),
            upper(np.einsum("p,psa,ptb->stab", m, Phi, Phi).reshape(3, 3, nz * nz)),
            np.einsum("p,pric->ric", m, Psi).reshape(3 * k, nx),
            np.einsum("p,pric,psa->risca", m, Psi, Phi).reshape(9 * k, nx * nz),
            upper(np.einsum("p,pric,psje->risjce", m, Psi, Psi).reshape(3 * k, 3 * k, nx * nx)),
            np.einsum("p,pij,psa->sija", m, S, Phi).reshape(3, k * k * nz),
            np.einsum("p,pjl,pic->ijlc", m, S, Psi[:, 0]).reshape(k, k * k * nx),
            np.einsum("p,pij->ij", m, S), np.array([1.0, 0.0]))


def upper(table: NDArray) -> NDArray:
    """The rows (a, b), a <= b, of a table (n, n, c) symmetric in (a, b), in C order: (n (n + 1) / 2, c)."""
    rows, columns = np.triu_indices(table.shape[0])
    return np.ascontiguousarray(table[rows, columns])


if njit is not None:                                   # module-level kernels: numba caches them on disk

    @njit(cache=True)
    def contract(table, vector):
        """table (r, c) @ vector (c,) by loops."""
        out = np.zeros(table.shape[0])
        for r in range(table.shape[0]):
            value = 0.0
            for c in range(table.shape[1]):
                value += table[r, c] * vector[c]
            out[r] = value
        return out

    @njit(cache=True)
    def outer(a, b):
        """The flattened outer product a (x) b."""
        out = np.empty(a.shape[0] * b.shape[0])
        for i in range(a.shape[0]):
            for j in range(b.shape[0]):
                out[i * b.shape[0] + j] = a[i] * b[j]
        return out

    @njit(cache=True)
    def unfold(values, n):
        """The symmetric (n, n) matrix of its upper triangle's rows ``values`` (:func:`upper`)."""
        out = np.empty((n, n))
        row = 0
        for a in range(n):
            for b in range(a, n):
                out[a, b] = out[b, a] = values[row]
                row += 1
        return out

    @njit(cache=True)
    def monomials(q):
        """(zeta, xi) of :mod:`this module <.compiled_invariants>` at q."""
        k = q.shape[0]
        zeta = np.empty(1 + k + k * (k + 1) // 2)
        xi = np.empty(1 + k)
        zeta[0] = xi[0] = 1.0
        column = 1 + k
        for i in range(k):
            zeta[1 + i] = xi[1 + i] = q[i]
            for j in range(i, k):
                zeta[column] = q[i] * q[j]
                column += 1
        return zeta, xi

    @njit(cache=True)
    def blade_inertia(invariants, q, u, g, w, al, A, F):
        """One blade's ``A = sum_p m G_p^T G_p`` and ``F = sum_p G_p^T m (g - a_p)`` in its own frame, from its
        :func:`blade_invariants`, for ``G_p = [I, -[d_p]x, D_p]`` over (translation, rotation, shape coordinates):
        ``g`` gravity less the apex's bias acceleration, ``w`` and ``al`` the blade frame's angular velocity and
        bias angular acceleration, all in the blade's components; the nodes' bias acceleration
        ``a_p = al x d + w x (w x d) + 2 w x D u - (u^T S_p u) e_x`` (the axial shortening's). A (6 + k, 6 + k)
        and F (6 + k,) are overwritten."""
        mass, I1, I2, I3, I4, I5, I6, I7, I8, _ = invariants
        k = q.shape[0]
        zeta, xi = monomials(q)
        s1 = contract(I1, zeta)                               # sum m d
        dd = unfold(contract(I2, outer(zeta, zeta)), 3)       # sum m d d^T
        SD = contract(I3, xi)                                 # sum m D (3, k), flat (r, i)
        T = contract(I4, outer(xi, zeta))                     # sum m D[r, i] d[s], flat (r, i, s)
        U = unfold(contract(I5, outer(xi, xi)), 3 * k)        # sum m D[r, i] D[s, j] at (r k + i, s k + j)
        uu = outer(u, u)
        sigma_d = contract(I6, outer(uu, zeta))               # sum m (u^T S u) d
        sigma_D = contract(I7, outer(uu, xi))                 # sum m (u^T S u) D[0, :]
        sigma = 0.0
        for i in range(k):
            for j in range(k):
                sigma += I8[i, j] * u[i] * u[j]
        trace = dd[0, 0] + dd[1, 1] + dd[2, 2]
        J = np.empty((3, 3))                                  # sum m (|d|^2 I - d d^T)
        for r in range(3):
            for s in range(3):
                J[r, s] = (trace if r == s else 0.0) - dd[r, s]
        X = np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])       # w x
        cross_d = np.empty((3, k))                            # sum m d x D[:, i]
        rate_sum = np.zeros(3)                                # sum m D u
        H = np.zeros((3, 3))                                  # sum m (D u) d^T
        for i in range(k):
            for r in range(3):
                rate_sum[r] += SD[r * k + i] * u[i]
                for s in range(3):
                    H[r, s] += T[(r * k + i) * 3 + s] * u[i]
            cross_d[0, i] = T[(2 * k + i) * 3 + 1] - T[(1 * k + i) * 3 + 2]
            cross_d[1, i] = T[(0 * k + i) * 3 + 2] - T[(2 * k + i) * 3 + 0]
            cross_d[2, i] = T[(1 * k + i) * 3 + 0] - T[(0 * k + i) * 3 + 1]
        for r in range(6 + k):
            F[r] = 0.0
            for s in range(6 + k):
                A[r, s] = 0.0
        # translation rows: sum m G_t^T G = [m I, -[s1]x, sum m D]
        for r in range(3):
            A[r, r] = mass
        A[0, 4], A[0, 5], A[1, 5] = s1[2], -s1[1], s1[0]
        A[1, 3], A[2, 3], A[2, 4] = -s1[2], s1[1], -s1[0]
        for r in range(3):
            for i in range(k):
                A[r, 6 + i] = SD[r * k + i]
            for s in range(3):
                A[3 + r, 3 + s] = J[r, s]
            for i in range(k):
                A[3 + r, 6 + i] = cross_d[r, i]
        for i in range(k):
            for j in range(k):
                value = 0.0
                for r in range(3):
                    value += U[r * k + i, r * k + j]
                A[6 + i, 6 + j] = value
        for r in range(6 + k):
            for s in range(r):
                A[r, s] = A[s, r]
        # forcing: sum G^T m (g - a_p), the parts of a_p in turn
        ws1 = cross3(w, s1)
        Jw = np.zeros(3)
        for r in range(3):
            for s in range(3):
                Jw[r] += J[r, s] * w[s]
        translation = cross3(al, s1) + cross3(w, ws1) + 2.0 * cross3(w, rate_sum)
        rotation = cross3(s1, g) - cross3(w, Jw)
        trace_H = H[0, 0] + H[1, 1] + H[2, 2]
        for r in range(3):
            F[r] = mass * g[r] - translation[r]
            rotation[r] -= 2.0 * trace_H * w[r]
            for s in range(3):
                rotation[r] += -J[r, s] * al[s] + 2.0 * H[r, s] * w[s]
            F[3 + r] = rotation[r]
        F[0] += sigma
        F[4] += sigma_d[2]
        F[5] -= sigma_d[1]
        spin = w[0] * w[0] + w[1] * w[1] + w[2] * w[2]
        for i in range(k):
            value = sigma_D[i]
            for r in range(3):
                value += SD[r * k + i] * g[r] - al[r] * cross_d[r, i]
                for s in range(3):
                    centripetal = w[r] * w[s] - (spin if r == s else 0.0)
                    value -= centripetal * T[(r * k + i) * 3 + s]
                    if X[r, s] != 0.0:
                        coriolis = 0.0
                        for j in range(k):
                            coriolis += U[r * k + i, s * k + j] * u[j]
                        value -= 2.0 * X[r, s] * coriolis
            F[6 + i] = value

    @njit(cache=True)
    def cross3(a, b):
        """a x b."""
        return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])

    @njit(cache=True)
    def to_blade(Z, R):
        """T^T Z for T = diag(R, R, I): a blade's partials Z (6 + k, n) (translation, rotation rows in earth
        components, shape rows) with the translation and rotation rows in the frame R's components, where
        :func:`blade_inertia` gives A and F (so that ``Z^T T A T^T Z = (T^T Z)^T A (T^T Z)``)."""
        out = Z.copy()
        for block in range(2):
            for c in range(Z.shape[1]):
                for s in range(3):
                    value = 0.0
                    for r in range(3):
                        value += R[r, s] * Z[3 * block + r, c]
                    out[3 * block + s, c] = value
        return out

    @njit(cache=True)
    def pitched_frame(R, turn):
        """R Q for the blade frame R (columns: earth components of its axes) and Q the pitch turn of the shapes
        since the integrals were taken (``turn`` = (cos, sin), :func:`blade_invariants`): d = Q d_0, D = Q D_0."""
        c, s = turn[0], turn[1]
        out = R.copy()
        for r in range(3):
            out[r, 1] = c * R[r, 1] - s * R[r, 2]
            out[r, 2] = s * R[r, 1] + c * R[r, 2]
        return out
