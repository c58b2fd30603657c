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
from .initial import ELASTODYN_DOFS
from .kane import TurbineModel
from .parameters import BLADE_DOFS, PLATFORM_DOFS

#: groups of degrees of freedom accepted by ``--dof`` (besides single coordinate names and ElastoDyn's switches)
GROUPS = {
    "tower": ("tower_fa1", "tower_fa2", "tower_ss1", "tower_ss2"),
    "tower1": ("tower_fa1", "tower_ss1"),
    "yaw": ("yaw",),
    "generator": ("generator_azimuth",),
    "drivetrain": ("drivetrain",),
    "flap1": ("flap1",), "edge1": ("edge1",), "flap2": ("flap2",),
    "blades": BLADE_DOFS,
}
SWITCH_VALUES = {"true": True, "on": True, "1": True, "false": False, "off": False, "0": False}


def dof_members(dofs: tuple[str, ...], name: str) -> list[int]:
    """Indices of the coordinates a name stands for: 'all', a coordinate ('blade2_edge1'), a group ('tower',
    'tower1', 'blades', 'flap1', ...; blade groups apply to every blade) or an ElastoDyn switch ('GenDOF',
    'FlapDOF1', ...)."""
    if name == "all":
        return list(range(len(dofs)))
    if name in dofs:
        return [dofs.index(name)]
    members = GROUPS.get(name) or ((ELASTODYN_DOFS[name],) if name in ELASTODYN_DOFS else None)
    if members is None:
        known = ", ".join(("all",) + tuple(GROUPS) + PLATFORM_DOFS + tuple(ELASTODYN_DOFS))
        raise InputError(f"unknown degree of freedom '{name}' (use {known}, or bladeK_flap1 etc.)", field="dof")
    return [i for i, dof in enumerate(dofs) for member in members
            if dof == member or (member in BLADE_DOFS and dof.endswith("_" + member))]


def select_dofs(dofs: tuple[str, ...], names: Iterable[str], base: NDArray[np.bool_] | None = None
                ) -> NDArray[np.bool_]:
    """Mask of the free coordinates. Plain names (see :func:`dof_members`) are the free set; ``NAME=on|off``
    (also ``True``/``False``, e.g. ``GenDOF=False``) frees or locks coordinates of ``base`` (default all free) or
    of the named set."""
    names = list(names)
    plain = [name for name in names if "=" not in name]
    free = np.zeros(len(dofs), dtype=bool) if plain else (
        np.ones(len(dofs), dtype=bool) if base is None else np.asarray(base, dtype=bool).copy())
    for name in plain:
        free[dof_members(dofs, name)] = True
    for entry in names:
        if "=" in entry:
            name, _, value = entry.partition("=")
            if value.strip().lower() not in SWITCH_VALUES:
                raise InputError(f"expected NAME=on or NAME=off, got '{entry}'", field="dof")
            free[dof_members(dofs, name.strip())] = SWITCH_VALUES[value.strip().lower()]
    return free


@dataclass
class FreeSystem:
    """First-order equations ``dx/dt = F(t, x)`` of the free coordinates and the dynamic wake,
    ``x = (q_f, u_f, w)``: ``w`` the dynamic wake's states (B, Na, 4) flattened (:mod:`bladefem.aero.dynamic_wake`;
    empty with quasi-steady induction).

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

    @property
    def wake_size(self) -> int:
        """Number of dynamic-wake states (0 with quasi-steady induction)."""
        aero = self.model.aero
        return 0 if aero is None else self.model.params.n_blades * aero.wake_states

    def initial_state(self) -> NDArray:
        """x at t = 0: the initial coordinates and rates, the dynamic wake at rest on the quasi-steady induction
        there (AeroDyn's ``DBEMT_InitStates``)."""
        x = np.concatenate([self.q0[self.index], self.u0[self.index]])
        if not self.wake_size:
            return x
        from ...aero.dynamic_wake import initial_wake
        from .aero import aero_loads
        aero = self.model.aero
        rest = np.zeros((self.model.params.n_blades, aero.n_nodes, 4))
        quasi = aero_loads(self.model, aero, self.q0, self.u0, 0.0, wake=rest).quasi_steady
        return np.concatenate([x, initial_wake(quasi).ravel()])

    def full(self, t: float, x: NDArray) -> tuple[NDArray, NDArray]:
        """All coordinates and rates at time t for the free state x."""
        q = self.q0 + self.u0 * t
        u = self.u0.copy()
        q[self.index] = x[:self.size]
        u[self.index] = x[self.size:2 * self.size]
        return q, u

    def wake(self, x: NDArray) -> NDArray | None:
        """The dynamic wake's states (B, Na, 4) of the free state x (None with quasi-steady induction)."""
        if not self.wake_size:
            return None
        return np.asarray(x[2 * self.size:], dtype=float).reshape(self.model.params.n_blades, -1, 4)

    def accelerations(self, q: NDArray, u: NDArray, t: float = 0.0, wake: NDArray | None = None) -> NDArray:
        """du/dt of all coordinates (zero for the locked ones) at time t (with the dynamic wake's states
        ``wake``)."""
        M, f = self.model.fast_equations()(q, u, t=t, wake=wake)
        du = np.zeros(self.model.n)
        ix = self.index
        du[ix] = np.linalg.solve(M[self.block], f[ix])
        return du

    def __call__(self, t: float, x: NDArray) -> NDArray:
        equations = self.model.fast_equations()
        if hasattr(equations, "rate"):
            return equations.rate(t, x, self.q0, self.u0, self.index)
        q, u = self.full(t, x)
        wake = self.wake(x)
        M, f = equations(q, u, t=t, wake=wake)
        rates = [x[self.size:2 * self.size], np.linalg.solve(M[self.block], f[self.index])]
        if wake is not None:                 # the reference path solves the nodes once more for the wake's rates
            from .aero import aero_loads
            rates.append(aero_loads(self.model, self.model.aero, q, u, t, wake=wake).wake_rate.ravel())
        return np.concatenate(rates)
