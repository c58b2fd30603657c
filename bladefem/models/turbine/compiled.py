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

if njit is not None:
    from .compiled_integrators import dormand_prince, dormand_prince_853
    from .compiled_kernels import derivative, equations


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
