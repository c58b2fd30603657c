"""Dynamic wake: Oye's model of the lag of the induced velocities behind the loads, as AeroDyn's DBEMT.

At every blade node the quasi-steady induced velocities of the BEM, ``v_qs`` = (a vx, a' vy) (AeroDyn's
``vind_s`` = (-a Vx, a' Vy), ``BEMT.f90``, ``SetInputs_For_DBEMT``; bladefem takes the axial one positive when it
slows the flow), pass through two first-order filters (S. Oye, "Tjaereborg udvidet kontrol", DTU, 1990; Snel and
Schepers, ECN-C--94-107, 1995; OpenFAST's ``modules/aerodyn/src/DBEMT.f90``):

    tau1 dv_int/dt + v_int = v_qs + k tau1 dv_qs/dt,   k = 0.6
    tau2 dv/dt + v = v_int

and the loads see the filtered ``v``: a = v_axial / vx, a' = v_tangential / vy (limited as AeroDyn's, then the
skewed-wake redistribution and the low tip-speed-ratio blend, as for the quasi-steady induction). The time
constants (``DBEMT.f90``, ``ComputeTau1`` and ``ComputeTau2``):

    tau1 = 1.1 R / ((1 - 1.3 min(a_disk, 0.5)) max(U_disk, 0.1)), at most 100 s      DBEMT_Mod 2
    tau1 = tau1_const                                                               DBEMT_Mod 1 and 3
    tau2 = (0.39 - 0.26 (r / R)^2) tau1

with R the largest distance of a node from the shaft, U_disk the disk-averaged wind along the shaft (the relative
wind with BEM_Mod 1, the undisturbed wind with BEM_Mod 2, AeroDyn's ``Un_disk``), a_disk the quasi-steady axial
induction averaged with AeroDyn's weights (:func:`disk_weights`), and r / R the node's current radius ratio
(DBEMT_Mod 2) or the undeflected one (1 and 3).

The derivative of the input is removed by the state z = v_int - k v_qs (AeroDyn's own state with DBEMT_Mod 3,
"Reduced velocity", ``DBEMT_CalcContStateDeriv``):

    dz/dt = ((1 - k) v_qs - z) / tau1,    dv/dt = (z + k v_qs - v) / tau2

which holds with tau1 varying in time as well. bladefem integrates these with the structure (one state vector, the
adaptive integrator's error control on both); DBEMT_Mod 1 and 3 differ only in how OpenFAST discretizes them
(1: the exact solution over a time step for an input varying linearly; 3: Adams-Bashforth-Moulton on the same
equations), so in bladefem they are one model. At the start the filters sit at the quasi-steady solution (z =
(1 - k) v_qs, v = v_qs: AeroDyn's ``DBEMT_InitStates``). Nodes whose induction is fixed by a zero loss factor
(tip or hub with TipLoss/HubLoss) keep it, as AeroDyn's ``FixedInductions``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ._jit import kernel
from .bem import angle_geometry, filtered_induction, induced_loads, node_induction
from .options import INDUCTION

#: Oye's blending constant k (AeroDyn's ``k_0ye``)
OYE_K = 0.6
#: AeroDyn's bounds in the time-varying tau1: the largest disk induction, the smallest disk wind (m/s), the
#: longest tau1 (s)
MAX_DISK_INDUCTION, MIN_DISK_WIND, MAX_TAU1 = 0.5, 0.1, 100.0
#: states per node: z and v of the axial and the tangential induced velocity
STATES = 4
#: indices of :data:`WAKE_PARAMETERS`-style vectors the kernels read: model (1, 2, 3), tau1_const (s), k
MODEL, TAU1_CONST, BLEND = range(3)


@dataclass(frozen=True)
class DynamicWake:
    """AeroDyn's dynamic wake switches: ``model`` = DBEMT_Mod (1 constant tau1, 2 tau1 varying with the rotor's
    induction and wind, 3 constant tau1 in OpenFAST's continuous formulation: the same equations here),
    ``tau1_const`` (s, DBEMT_Mod 1 and 3; not used with 2)."""

    model: int
    tau1_const: float = float("nan")

    def __post_init__(self) -> None:
        if self.model not in (1, 2, 3):
            raise ValueError(f"DBEMT_Mod must be 1, 2 or 3, got {self.model}")
        if self.model != 2 and not self.tau1_const > 0:
            raise ValueError(f"tau1_const must be positive, got {self.tau1_const}")

    def vector(self) -> NDArray[np.float64]:
        """(model, tau1_const, k) for the kernels."""
        return np.array([float(self.model), float(self.tau1_const), OYE_K])


def disk_weights(r_local: NDArray) -> NDArray:
    """AeroDyn's weights of the disk-averaged axial induction (``BEMT.f90``, ``BEMT_SetParameters``): for the
    undeflected radii ``r_local`` (B, Na), w = 35/32 (1 - u^2)^3 with u = (r / R_max - 0.7) / 0.1 clipped to
    [-1, 1], normalised to one per blade, then divided by the number of blades (the nodes between 0.6 and 0.8 R
    count)."""
    r_local = np.asarray(r_local, dtype=float)
    u = np.clip((r_local / r_local.max() - 0.7) / 0.1, -1.0, 1.0)
    w = 35.0 / 32.0 * (1.0 - np.abs(u) ** 2) ** 3
    total = w.sum(axis=-1, keepdims=True)
    w = np.where(total > 0, w / np.where(total > 0, total, 1.0), w)
    return w / r_local.shape[0]


@kernel
def time_constant(parameters, disk_induction, disk_wind, disk_radius):
    """tau1, s: ``tau1_const`` (DBEMT_Mod 1, 3) or Oye's 1.1 R / ((1 - 1.3 a) U) (DBEMT_Mod 2, a at most 0.5, U at
    least 0.1 m/s, tau1 at most 100 s: ``DBEMT.f90``, ``ComputeTau1``)."""
    if parameters[MODEL] != 2.0:
        return parameters[TAU1_CONST]
    a = min(disk_induction, MAX_DISK_INDUCTION)
    wind = max(disk_wind, MIN_DISK_WIND)
    return min(1.1 * disk_radius / ((1.0 - 1.3 * a) * wind), MAX_TAU1)


@kernel
def wake_rates(z, v, quasi_steady, tau1, span_ratio, blend):
    """(dz/dt, dv/dt) of one induced velocity: the reduced intermediate z, the filtered v, the quasi-steady input
    (m/s), tau1 (s), the node's r / R and k; tau2 = (0.39 - 0.26 (r / R)^2) tau1 (``ComputeTau2``)."""
    tau2 = (0.39 - 0.26 * span_ratio * span_ratio) * tau1
    return ((1.0 - blend) * quasi_steady - z) / tau1, (z + blend * quasi_steady - v) / tau2


@kernel
def wake_derivative(wake, quasi_steady, tau1, span_ratio, blend, out):
    """``out`` (n, 4) = the rates of the states ``wake`` (n, 4: z_axial, z_tangential, v_axial, v_tangential) for
    the quasi-steady induced velocities (n, 2), tau1 (s) and the nodes' r / R (n,)."""
    for i in range(wake.shape[0]):
        for c in range(2):
            out[i, c], out[i, 2 + c] = wake_rates(wake[i, c], wake[i, 2 + c], quasi_steady[i, c], tau1,
                                                  span_ratio[i], blend)


@kernel
def wake_node_loads(vx, vy, r_local, chord, theta, tip_constant, hub_constant, n_blades, tip_ratio, chi0, skew_cos,
                    induction_weight, airfoil, knots, values, coefs, start, count, options, air_density, guess, cant,
                    toe, drdz, axial, tangential):
    """:func:`bladefem.aero.bem.node_loads` with the dynamic wake's induced velocities ``axial``, ``tangential``
    (m/s) in place of the quasi-steady ones: the same 13 outputs, then the quasi-steady induced velocities (a vx,
    a' vy) of the node (the filters' input)."""
    return framed_wake_node_loads(vx, vy, r_local, chord, theta, tip_constant, hub_constant, n_blades, tip_ratio,
                                  chi0, skew_cos, induction_weight, airfoil, knots, values, coefs, start, count,
                                  options, air_density, guess, angle_geometry(cant, toe, drdz), axial, tangential)


@kernel
def framed_wake_node_loads(vx, vy, r_local, chord, theta, tip_constant, hub_constant, n_blades, tip_ratio, chi0,
                           skew_cos, induction_weight, airfoil, knots, values, coefs, start, count, options,
                           air_density, guess, geometry, axial, tangential):
    """:func:`wake_node_loads` for the node's :func:`bladefem.aero.bem.angle_geometry`."""
    phi_solved, valid, fixed, a_qs, ap_qs = node_induction(vx, vy, r_local, chord, theta, tip_constant,
                                                           hub_constant, n_blades, chi0, airfoil, knots, values,
                                                           coefs, start, count, options, guess, geometry)
    a, ap = a_qs, ap_qs
    if options[INDUCTION] != 0.0 and not fixed:
        a, ap = filtered_induction(vx, vy, axial, tangential)
    a, ap, phi, alpha, w, cl, cd, cm, fn, ft, m = induced_loads(
        vx, vy, a, ap, phi_solved, valid, fixed, chord, theta, tip_constant, hub_constant, tip_ratio, chi0,
        skew_cos, induction_weight, airfoil, knots, values, coefs, start, count, options, air_density, geometry)
    return phi_solved, a, ap, phi, alpha, w, cl, cd, cm, fn, ft, m, valid, a_qs * vx, ap_qs * vy


@kernel
def solve_wake_nodes(vx, vy, r_local, chord, theta, tip_constant, hub_constant, n_blades, tip_ratio, chi0,
                     skew_cos, induction_weight, airfoil, knots, values, coefs, start, count, options, air_density,
                     guess, cant, toe, drdz, wake, out, quasi_steady):
    """:func:`wake_node_loads` at every node of flat arrays (as :func:`bladefem.aero.bem.solve_nodes`), the
    filtered velocities from ``wake`` (n, 4); the quasi-steady induced velocities into ``quasi_steady`` (n, 2)."""
    for i in range(vx.shape[0]):
        phi_solved, a, ap, phi, alpha, w, cl, cd, cm, fn, ft, m, valid, v_axial, v_tangential = wake_node_loads(
            vx[i], vy[i], r_local[i], chord[i], theta[i], tip_constant[i], hub_constant[i], n_blades, tip_ratio[i],
            chi0[i], skew_cos[i], induction_weight, airfoil[i], knots, values, coefs, start, count, options,
            air_density, guess[i], cant[i], toe[i], drdz[i], wake[i, 2], wake[i, 3])
        out[i, 0], out[i, 1], out[i, 2], out[i, 3], out[i, 4] = phi_solved, a, ap, phi, alpha
        out[i, 5], out[i, 6], out[i, 7], out[i, 8] = w, cl, cd, cm
        out[i, 9], out[i, 10], out[i, 11], out[i, 12] = fn, ft, m, 1.0 if valid else 0.0
        quasi_steady[i, 0], quasi_steady[i, 1] = v_axial, v_tangential


def initial_wake(quasi_steady: NDArray, blend: float = OYE_K) -> NDArray:
    """The filters at rest on the quasi-steady induced velocities (..., 2) (axial, tangential): (..., 4) = (z_axial,
    z_tangential, v_axial, v_tangential) with z = (1 - k) v_qs, v = v_qs."""
    quasi_steady = np.asarray(quasi_steady, dtype=float)
    return np.concatenate([(1.0 - blend) * quasi_steady, quasi_steady], axis=-1)


def step_response(t: NDArray, tau1: float, tau2: float, blend: float = OYE_K) -> NDArray:
    """The filtered v(t) for a unit step of v_qs at t = 0 from rest at zero (closed form, t >= 0): z jumps by
    nothing, the k tau1 dv_qs/dt term makes v_int = 1 - (1 - k) exp(-t / tau1), and
    v = 1 - (1 - k) tau1 / (tau1 - tau2) exp(-t / tau1) - (1 - (1 - k) tau1 / (tau1 - tau2)) exp(-t / tau2)."""
    t = np.asarray(t, dtype=float)
    c = (1.0 - blend) * tau1 / (tau1 - tau2)
    return 1.0 - c * np.exp(-t / tau1) - (1.0 - c) * np.exp(-t / tau2)
