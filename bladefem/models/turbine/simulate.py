"""Time integration of the turbine's structural equations and ElastoDyn-like outputs (table and plot)."""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from ...files import atomic_path, write_atomic
from .kane import TurbineModel
from .system import FreeSystem

RAD_S_TO_RPM = 30.0 / np.pi

#: output channel -> (unit, description); names after ElastoDyn's, signs in bladefem's frames
CHANNELS = {
    "OoPDefl1": ("m", "blade 1 tip out-of-plane deflection, positive downwind"),
    "IPDefl1": ("m", "blade 1 tip in-plane deflection, positive toward the leading edge (blade frame y)"),
    "TTDspFA": ("m", "tower-top fore-aft displacement, positive downwind"),
    "TTDspSS": ("m", "tower-top side-to-side displacement, positive to the left looking downwind"),
    "YawPzn": ("deg", "nacelle yaw angle"),
    "Azimuth": ("deg", "rotor azimuth (blade 1 up at 0)"),
    "RotSpeed": ("rpm", "rotor speed (low-speed shaft at the hub)"),
    "LSSGagVxa": ("rpm", "low-speed-shaft speed at the gearbox"),
    "GenSpeed": ("rpm", "generator (high-speed shaft) speed"),
    "RootMOoP1": ("kN m", "blade 1 root out-of-plane bending moment"),
    "RootMIP1": ("kN m", "blade 1 root in-plane bending moment"),
}


@dataclass(frozen=True)
class SimulationResult:
    """Time histories: time (T,) s, coordinates q and rates u (T, n), output channels (T,) each."""

    time: NDArray
    q: NDArray
    u: NDArray
    dofs: tuple[str, ...]
    free: NDArray
    outputs: dict[str, NDArray]
    evaluations: int


def root_moments(model: TurbineModel, q: NDArray, u: NDArray, du: NDArray, blade: int = 0) -> tuple[float, float]:
    """Out-of-plane and in-plane bending moments at a blade root (N m), from gravity and d'Alembert loads on the
    blade's span nodes and tip mass: ``M = sum (r_p - r_root) x m_p (g - a_p)`` in the blade frame; out-of-plane
    positive for downwind loads, in-plane positive for loads toward the leading edge."""
    motion = model.motion(q, u)
    p = model.params
    R = motion.blade_frames.R[blade]
    root = motion.apex.r + R[:, 0] * p.hub_radius
    masses = np.append(p.blade.point_mass, p.blade_tip_mass)
    nodes = motion.blades
    a = (nodes.G[blade] @ (nodes.Z[blade] @ du)) + nodes.a[blade]
    loads = masses[:, None] * (model.gravity - a)
    moment = np.sum(np.cross(nodes.r[blade] - root, loads), axis=0)
    local = R.T @ moment
    return float(-local[1]), float(local[2])


def outputs_at(system: FreeSystem, q: NDArray, u: NDArray) -> dict[str, float]:
    """ElastoDyn-like output channels at one state (SI values converted to the units of :data:`CHANNELS`)."""
    model = system.model
    p = model.params
    b1 = q[model.blade_columns[0]]
    tip = p.blade.tip_value.T @ b1
    top = p.tower.tip_value.T @ q[model.tower_columns]
    du = system.accelerations(q, u)
    flap, edge = root_moments(model, q, u, du)
    azimuth_rate = u[5] + u[6]
    return {
        "OoPDefl1": tip[1], "IPDefl1": tip[0], "TTDspFA": top[0], "TTDspSS": top[1],
        "YawPzn": np.degrees(q[4]), "Azimuth": np.degrees(q[5] + q[6]) % 360.0,
        "RotSpeed": azimuth_rate * RAD_S_TO_RPM, "LSSGagVxa": u[5] * RAD_S_TO_RPM,
        "GenSpeed": p.gearbox_ratio * u[5] * RAD_S_TO_RPM, "RootMOoP1": flap / 1e3, "RootMIP1": edge / 1e3,
    }


def runge_kutta4(rhs, x0: NDArray, times: NDArray, step: float) -> NDArray:
    """Classical fixed-step 4th-order Runge-Kutta (ElastoDyn's Method = 1) with ``step`` (s) no larger than
    requested, landing on every output time; returns the states at ``times`` (len(times), size)."""
    states = [x0]
    x, t = x0, times[0]
    for target in times[1:]:
        count = max(1, int(np.ceil((target - t) / step - 1e-9)))
        h = (target - t) / count
        for _ in range(count):
            k1 = rhs(t, x)
            k2 = rhs(t + h / 2, x + h / 2 * k1)
            k3 = rhs(t + h / 2, x + h / 2 * k2)
            k4 = rhs(t + h, x + h * k3)
            x = x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            t += h
        t = target
        states.append(x)
    return np.array(states)


def simulate(system: FreeSystem, duration: float, dt_output: float = 0.05, rtol: float = 1e-6,
             atol: float = 1e-8, method: str = "auto", step: float = 0.01) -> SimulationResult:
    """Integrate from t = 0 to ``duration`` (s), outputs every ``dt_output`` s.

    method : 'auto' (the compiled 8th-order Dormand-Prince 'DP853' when numba is installed, else scipy's
        'DOP853', the same scheme), 'DP853' or 'DP54' (compiled Dormand-Prince 8(5,3) or 5(4), numba only), a
        scipy ``solve_ivp`` method ('RK45', 'DOP853', ...; tolerances ``rtol``, ``atol``), or 'RK4' with the fixed
        ``step`` (s)
    """
    count = [0]

    def rhs(t: float, x: NDArray) -> NDArray:
        count[0] += 1
        return system(t, x)

    times = np.linspace(0.0, duration, int(round(duration / dt_output)) + 1)
    compiled = system.model.fast_equations()
    if method == "auto":
        method = "DP853" if hasattr(compiled, "integrate") else "DOP853"
    if method in ("DP54", "DP853"):
        if not hasattr(compiled, "integrate"):
            raise RuntimeError(f"method '{method}' needs numba (pip install numba)")
        states, evaluations = compiled.integrate(times, system.initial_state(), rtol, atol, system.q0, system.u0,
                                                 system.index, order=8 if method == "DP853" else 5)
        count[0] = int(evaluations)
    elif method == "RK4":
        states = runge_kutta4(rhs, system.initial_state(), times, step)
    else:
        solution = solve_ivp(rhs, (0.0, duration), system.initial_state(), method=method, t_eval=times,
                             rtol=rtol, atol=atol)
        if not solution.success:
            raise RuntimeError(f"time integration failed: {solution.message}")
        times, states = solution.t, solution.y.T
    qs, us = zip(*(system.full(t, x) for t, x in zip(times, states)))
    q, u = np.array(qs), np.array(us)
    rows = [outputs_at(system, qi, ui) for qi, ui in zip(q, u)]
    outputs = {name: np.array([row[name] for row in rows]) for name in CHANNELS}
    return SimulationResult(time=times, q=q, u=u, dofs=system.model.dofs, free=system.free, outputs=outputs,
                            evaluations=count[0])


def table_text(result: SimulationResult) -> str:
    """CSV text: time and every output channel, with units in the header."""
    names = list(CHANNELS)
    header = "Time_s," + ",".join(f"{name}_{CHANNELS[name][0].replace(' ', '')}" for name in names)
    data = np.column_stack([result.time] + [result.outputs[name] for name in names])
    lines = [header] + [",".join(f"{value:.9g}" for value in row) for row in data]
    return "\n".join(lines) + "\n"


def write_table(result: SimulationResult, path: str | os.PathLike) -> None:
    """Write the output table as CSV, atomically."""
    write_atomic(path, table_text(result))


def plot_outputs(result: SimulationResult, path: str | os.PathLike,
                 channels: tuple[str, ...] = ("OoPDefl1", "IPDefl1", "TTDspFA", "TTDspSS", "YawPzn", "RotSpeed",
                                               "GenSpeed", "RootMOoP1", "RootMIP1")) -> None:
    """Plot the chosen channels against time into an image file (written atomically)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(len(channels), 1, figsize=(8, 1.6 * len(channels)), sharex=True)
    for axis, name in zip(np.atleast_1d(axes), channels):
        axis.plot(result.time, result.outputs[name], lw=1)
        axis.set_ylabel(f"{name}\n[{CHANNELS[name][0]}]", fontsize=8)
        axis.grid(alpha=0.3)
    np.atleast_1d(axes)[-1].set_xlabel("time [s]")
    figure.tight_layout()
    try:
        with atomic_path(path) as temporary:
            figure.savefig(temporary, dpi=120)
    finally:
        plt.close(figure)
