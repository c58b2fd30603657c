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
    def scratch_size(k):
        """Length of :func:`blade_inertia`'s scratch for k shapes (its sums, in the order it takes them)."""
        nz, nx = 1 + k + k * (k + 1) // 2, 1 + k
        return nz + nx + k * k + 3 + 6 + 9 + 3 * k + 9 * k + 3 * k * (3 * k + 1) // 2 + 9 * k * k + 3 + k + 9 \
            + 3 * k + 3 + 9

    @njit(cache=True, _nrt=False)
    def contract(table, vector, out):
        """out = table (r, c) @ vector (c,) by loops."""
        for r in range(table.shape[0]):
            value = 0.0
            for c in range(table.shape[1]):
                value += table[r, c] * vector[c]
            out[r] = value

    @njit(cache=True, _nrt=False)
    def contract_outer(table, a, b, out):
        """out = table (r, len(a) len(b)) @ (a (x) b), the outer product flattened in C order, without forming it."""
        nb = b.shape[0]
        for r in range(table.shape[0]):
            value = 0.0
            for i in range(a.shape[0]):
                partial = 0.0
                for j in range(nb):
                    partial += table[r, i * nb + j] * b[j]
                value += a[i] * partial
            out[r] = value

    @njit(cache=True, _nrt=False)
    def unfold(values, out):
        """The symmetric matrix ``out`` (n, n) of its upper triangle's rows ``values`` (:func:`upper`)."""
        row = 0
        for a in range(out.shape[0]):
            for b in range(a, out.shape[0]):
                out[a, b] = out[b, a] = values[row]
                row += 1

    @njit(cache=True, _nrt=False)
    def monomials(q, zeta, xi):
        """(zeta, xi) of :mod:`this module <.compiled_invariants>` at q, into ``zeta`` and ``xi``."""
        k = q.shape[0]
        zeta[0] = xi[0] = 1.0
        column = 1 + k
        for i in range(k):
            zeta[1 + i] = xi[1 + i] = q[i]
            for j in range(i, k):
                zeta[column] = q[i] * q[j]
                column += 1

    @njit(cache=True, _nrt=False)
    def blade_inertia(invariants, q, u, g, w, al, A, F, scratch):
        """One blade's ``A = sum_p m G_p^T G_p`` and ``F = sum_p G_p^T m (g - a_p)`` in its own frame, from its
        :func:`blade_invariants`, for ``G_p = [I, -[d_p]x, D_p]`` over (translation, rotation, shape coordinates):
        ``g`` gravity less the apex's bias acceleration, ``w`` and ``al`` the blade frame's angular velocity and
        bias angular acceleration, all in the blade's components; the nodes' bias acceleration
        ``a_p = al x d + w x (w x d) + 2 w x D u - (u^T S_p u) e_x`` (the axial shortening's). A (6 + k, 6 + k)
        and F (6 + k,) are overwritten; its sums go to ``scratch`` (:func:`scratch_size`): it allocates nothing."""
        mass, I1, I2, I3, I4, I5, I6, I7, I8, _ = invariants
        k = q.shape[0]
        nz, nx = 1 + k + k * (k + 1) // 2, 1 + k
        pairs = 3 * k * (3 * k + 1) // 2
        at = 0
        zeta = scratch[at:at + nz]
        at += nz
        xi = scratch[at:at + nx]
        at += nx
        uu = scratch[at:at + k * k]
        at += k * k
        s1 = scratch[at:at + 3]                               # sum m d
        at += 3
        dd_upper = scratch[at:at + 6]
        at += 6
        dd = scratch[at:at + 9].reshape((3, 3))               # sum m d d^T
        at += 9
        SD = scratch[at:at + 3 * k]                           # sum m D (3, k), flat (r, i)
        at += 3 * k
        T = scratch[at:at + 9 * k]                            # sum m D[r, i] d[s], flat (r, i, s)
        at += 9 * k
        U_upper = scratch[at:at + pairs]
        at += pairs
        U = scratch[at:at + 9 * k * k].reshape((3 * k, 3 * k))   # sum m D[r, i] D[s, j] at (r k + i, s k + j)
        at += 9 * k * k
        sigma_d = scratch[at:at + 3]                          # sum m (u^T S u) d
        at += 3
        sigma_D = scratch[at:at + k]                          # sum m (u^T S u) D[0, :]
        at += k
        J = scratch[at:at + 9].reshape((3, 3))                # sum m (|d|^2 I - d d^T)
        at += 9
        cross_d = scratch[at:at + 3 * k].reshape((3, k))      # sum m d x D[:, i]
        at += 3 * k
        rate_sum = scratch[at:at + 3]                         # sum m D u
        at += 3
        H = scratch[at:at + 9].reshape((3, 3))                # sum m (D u) d^T
        monomials(q, zeta, xi)
        for i in range(k):
            for j in range(k):
                uu[i * k + j] = u[i] * u[j]
        contract(I1, zeta, s1)
        contract_outer(I2, zeta, zeta, dd_upper)
        unfold(dd_upper, dd)
        contract(I3, xi, SD)
        contract_outer(I4, xi, zeta, T)
        contract_outer(I5, xi, xi, U_upper)
        unfold(U_upper, U)
        contract_outer(I6, uu, zeta, sigma_d)
        contract_outer(I7, uu, xi, sigma_D)
        sigma = 0.0
        for i in range(k):
            for j in range(k):
                sigma += I8[i, j] * u[i] * u[j]
        trace = dd[0, 0] + dd[1, 1] + dd[2, 2]
        for r in range(3):
            rate_sum[r] = 0.0
            for s in range(3):
                J[r, s] = (trace if r == s else 0.0) - dd[r, s]
                H[r, s] = 0.0
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
        # forcing: sum G^T m (g - a_p), the parts of a_p in turn (the cross products written out: no arrays)
        ws0, ws1_, ws2 = w[1] * s1[2] - w[2] * s1[1], w[2] * s1[0] - w[0] * s1[2], w[0] * s1[1] - w[1] * s1[0]
        Jw0 = J[0, 0] * w[0] + J[0, 1] * w[1] + J[0, 2] * w[2]
        Jw1 = J[1, 0] * w[0] + J[1, 1] * w[1] + J[1, 2] * w[2]
        Jw2 = J[2, 0] * w[0] + J[2, 1] * w[1] + J[2, 2] * w[2]
        translation0 = (al[1] * s1[2] - al[2] * s1[1]) + (w[1] * ws2 - w[2] * ws1_) \
            + 2.0 * (w[1] * rate_sum[2] - w[2] * rate_sum[1])
        translation1 = (al[2] * s1[0] - al[0] * s1[2]) + (w[2] * ws0 - w[0] * ws2) \
            + 2.0 * (w[2] * rate_sum[0] - w[0] * rate_sum[2])
        translation2 = (al[0] * s1[1] - al[1] * s1[0]) + (w[0] * ws1_ - w[1] * ws0) \
            + 2.0 * (w[0] * rate_sum[1] - w[1] * rate_sum[0])
        rotation0 = (s1[1] * g[2] - s1[2] * g[1]) - (w[1] * Jw2 - w[2] * Jw1)
        rotation1 = (s1[2] * g[0] - s1[0] * g[2]) - (w[2] * Jw0 - w[0] * Jw2)
        rotation2 = (s1[0] * g[1] - s1[1] * g[0]) - (w[0] * Jw1 - w[1] * Jw0)
        trace_H = H[0, 0] + H[1, 1] + H[2, 2]
        for r in range(3):
            rotation = rotation0 if r == 0 else (rotation1 if r == 1 else rotation2)
            F[r] = mass * g[r] - (translation0 if r == 0 else (translation1 if r == 1 else translation2))
            rotation -= 2.0 * trace_H * w[r]
            for s in range(3):
                rotation += -J[r, s] * al[s] + 2.0 * H[r, s] * w[s]
            F[3 + r] = rotation
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
                    skew = 0.0 if r == s else ((w[3 - r - s] if (s - r) % 3 == 2 else -w[3 - r - s]))
                    if skew != 0.0:
                        coriolis = 0.0
                        for j in range(k):
                            coriolis += U[r * k + i, s * k + j] * u[j]
                        value -= 2.0 * skew * coriolis
            F[6 + i] = value

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
