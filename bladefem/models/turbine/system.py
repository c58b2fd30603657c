"""The turbine's equations restricted to the free degrees of freedom; locked ones follow a prescribed motion.

A locked coordinate keeps its initial rate: ``q_l(t) = q_l(0) + u_l(0) t`` (constant rotor speed when the
generator azimuth is locked while spinning; rigid body when a flexible mode is locked at rest). The free ones obey
``M_ff du_f/dt = f_f`` (the locked ones have zero acceleration).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ...errors import InputError
from .kane import TurbineModel
from .parameters import BLADE_DOFS, PLATFORM_DOFS

#: groups of degrees of freedom accepted by ``--dof`` (besides single coordinate names)
GROUPS = {
    "tower": ("tower_fa1", "tower_fa2", "tower_ss1", "tower_ss2"),
    "tower1": ("tower_fa1", "tower_ss1"),
    "yaw": ("yaw",),
    "generator": ("generator_azimuth",),
    "drivetrain": ("drivetrain",),
    "flap1": ("flap1",), "edge1": ("edge1",), "flap2": ("flap2",),
    "blades": BLADE_DOFS,
}


def select_dofs(dofs: tuple[str, ...], names: Iterable[str]) -> NDArray[np.bool_]:
    """Mask of the free coordinates from names: 'all', a coordinate ('blade2_edge1'), a group ('tower', 'tower1',
    'blades', 'flap1', ...; blade groups apply to every blade)."""
    free = np.zeros(len(dofs), dtype=bool)
    for name in names:
        if name == "all":
            free[:] = True
        elif name in dofs:
            free[dofs.index(name)] = True
        elif name in GROUPS:
            for member in GROUPS[name]:
                for i, dof in enumerate(dofs):
                    if dof == member or (member in BLADE_DOFS and dof.endswith("_" + member)):
                        free[i] = True
        else:
            known = ", ".join(("all",) + tuple(GROUPS) + PLATFORM_DOFS)
            raise InputError(f"unknown degree of freedom '{name}' (use {known}, or bladeK_flap1 etc.)", field="dof")
    return free


@dataclass
class FreeSystem:
    """First-order equations ``dx/dt = F(t, x)`` of the free coordinates, ``x = (q_f, u_f)``.

    model : the full turbine model; free : (n,) mask; q0, u0 : (n,) initial coordinates and rates (locked ones
    move on at their initial rate)
    """

    model: TurbineModel
    free: NDArray[np.bool_]
    q0: NDArray
    u0: NDArray

    def __post_init__(self) -> None:
        self.free = np.asarray(self.free, dtype=bool)
        self.q0 = np.asarray(self.q0, dtype=float).copy()
        self.u0 = np.asarray(self.u0, dtype=float).copy()
        self.index = np.flatnonzero(self.free)
        self.block = np.ix_(self.index, self.index)

    @property
    def size(self) -> int:
        return len(self.index)

    def initial_state(self) -> NDArray:
        return np.concatenate([self.q0[self.index], self.u0[self.index]])

    def full(self, t: float, x: NDArray) -> tuple[NDArray, NDArray]:
        """All coordinates and rates at time t for the free state x."""
        q = self.q0 + self.u0 * t
        u = self.u0.copy()
        q[self.index] = x[:self.size]
        u[self.index] = x[self.size:]
        return q, u

    def accelerations(self, q: NDArray, u: NDArray) -> NDArray:
        """du/dt of all coordinates (zero for the locked ones)."""
        M, f = self.model.fast_equations()(q, u)
        du = np.zeros(self.model.n)
        ix = self.index
        du[ix] = np.linalg.solve(M[self.block], f[ix])
        return du

    def __call__(self, t: float, x: NDArray) -> NDArray:
        equations = self.model.fast_equations()
        if hasattr(equations, "derivative"):
            return equations.derivative(t, x, self.q0, self.u0, self.index)
        q, u = self.full(t, x)
        M, f = equations(q, u)
        return np.concatenate([x[self.size:], np.linalg.solve(M[self.block], f[self.index])])
