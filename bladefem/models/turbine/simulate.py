"""Time integration of the turbine's structural equations and ElastoDyn's output channels (table and plot).

Outputs are written every ``dt_output`` seconds exactly (``k dt_output <= duration``), taken from the integrator's
continuous extension: the adaptive steps are not forced onto the output times. The run stops with a
:class:`DivergenceError` as soon as the state is not finite or a beam deflects more than its length.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from ...files import atomic_path, write_atomic
from .kane import TurbineModel
from .parameters import coordinate_label
from .system import FreeSystem

RAD_S_TO_RPM = 30.0 / np.pi
#: largest |lambda| h for which classical RK4 stays stable on an undamped mode (2 sqrt(2) on the imaginary axis)
RK4_STABILITY = 2.8
#: integrators: the compiled ones (numba), scipy's, and fixed-step RK4
METHODS = ("auto", "DP853", "DP54", "RK45", "DOP853", "RK4")

#: output channel -> (unit, description): OpenFAST ElastoDyn's names, definitions and signs
CHANNELS = {
    "OoPDefl1": ("m", "blade 1 tip out-of-plane deflection, positive downwind (xc1)"),
    "IPDefl1": ("m", "blade 1 tip in-plane deflection, positive toward the trailing edge (yc1)"),
    "TTDspFA": ("m", "tower-top fore-aft displacement, positive downwind"),
    "TTDspSS": ("m", "tower-top side-to-side displacement, positive to the left looking downwind"),
    "YawPzn": ("deg", "nacelle yaw angle"),
    "Azimuth": ("deg", "rotor azimuth (blade 1 up at 0)"),
    "RotSpeed": ("rpm", "rotor speed (low-speed shaft at the hub)"),
    "LSSGagVxa": ("rpm", "low-speed-shaft speed at the gearbox"),
    "GenSpeed": ("rpm", "generator (high-speed shaft) speed"),
    "RootMOoP1": ("kN m", "blade 1 root out-of-plane bending moment (from downwind loads positive)"),
    "RootMIP1": ("kN m", "blade 1 root in-plane bending moment (from loads toward the leading edge positive)"),
}


class UnstableStep(ValueError):
    """A fixed step beyond the stability limit of the fastest mode."""


class DivergenceError(RuntimeError):
    """The time integration blew up: ``time`` (s), the coordinate and why."""

    def __init__(self, message: str, time: float, coordinate: str) -> None:
        super().__init__(message)
        self.time, self.coordinate = time, coordinate


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


def output_times(duration: float, dt_output: float) -> NDArray:
    """``0, dt, 2 dt, ...`` up to ``duration`` (s; a last multiple within 1e-9 dt of it counts)."""
    if not (math.isfinite(duration) and duration > 0 and math.isfinite(dt_output) and dt_output > 0):
        raise ValueError(f"need a positive duration and output step, got {duration} and {dt_output}")
    if dt_output > duration * (1 + 1e-12):
        raise ValueError(f"the output step {dt_output:g} s exceeds the simulated time {duration:g} s")
    return np.arange(int(math.floor(duration / dt_output + 1e-9)) + 1) * dt_output


def root_moments(model: TurbineModel, q: NDArray, u: NDArray, du: NDArray, blade: int = 0) -> tuple[float, float]:
    """Out-of-plane and in-plane bending moments at a blade root (N m), from gravity and d'Alembert loads on the
    blade's span nodes and tip mass: ``M = sum (r_p - r_root) x m_p (g - a_p)`` in the blade frame; out-of-plane
    positive for downwind loads, in-plane positive for loads toward the leading edge (OpenFAST's RootMOoP1 and
    RootMIP1)."""
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


def channels(system: FreeSystem, time: NDArray, q: NDArray, u: NDArray, moments: NDArray) -> dict[str, NDArray]:
    """The output channels (units of :data:`CHANNELS`) for coordinates and rates (T, n) and the blade-1 root
    moments (T, 2) in N m."""
    model = system.model
    p = model.params
    tip = q[:, model.blade_columns[0]] @ p.blade.tip_value          # (T, 2): in-plane toward the LE, out-of-plane
    top = q[:, model.tower_columns] @ p.tower.tip_value             # (T, 2): fore-aft, side-side
    return {
        "OoPDefl1": tip[:, 1], "IPDefl1": -tip[:, 0], "TTDspFA": top[:, 0], "TTDspSS": top[:, 1],
        "YawPzn": np.degrees(q[:, 4]), "Azimuth": np.degrees(q[:, 5] + q[:, 6]) % 360.0,
        "RotSpeed": (u[:, 5] + u[:, 6]) * RAD_S_TO_RPM, "LSSGagVxa": u[:, 5] * RAD_S_TO_RPM,
        "GenSpeed": p.gearbox_ratio * u[:, 5] * RAD_S_TO_RPM, "RootMOoP1": moments[:, 0] / 1e3,
        "RootMIP1": moments[:, 1] / 1e3,
    }


def divergence_limits(system: FreeSystem) -> NDArray:
    """Largest credible magnitude of each free state: a beam's modal amplitude whose tip deflection would exceed
    the beam's length, a drivetrain twist of 1 rad; rates and rigid rotations unbounded."""
    model = system.model
    p = model.params
    limit = np.full(model.n, np.inf)
    tower = np.linalg.norm(p.tower.tip_value, axis=1)
    limit[model.tower_columns] = p.tower.length / np.maximum(tower, 1e-12)
    blade = np.linalg.norm(p.blade.tip_value, axis=1)
    limit[model.blade_columns] = p.blade.length / np.maximum(blade, 1e-12)
    limit[model.dofs.index("drivetrain")] = 1.0
    return np.concatenate([limit[system.index], np.full(system.size, np.inf)])


def diverged(system: FreeSystem, state: int, time: float, status: int, method: str) -> DivergenceError:
    """The error for a blown-up state (index into the free state) at ``time``."""
    position = state % system.size
    dof = system.model.dofs[system.index[position]]
    what = "is not finite" if status == 1 else "exceeds its physical limit (a deflection larger than the beam)"
    hint = " (reduce --step)" if method == "RK4" else " (tighten --rtol)"
    kind = "rate" if state >= system.size else "coordinate"
    return DivergenceError(f"the solution diverged at t = {time:.4g} s: the {kind} of {coordinate_label(dof)} "
                           f"({dof}) {what}{hint}", time, dof)


def rk4_stable_step(system: FreeSystem) -> tuple[float, str]:
    """Largest stable RK4 step (s) for the free system linearized at its initial state, and the coordinate that
    dominates (by energy share) the mode with the largest |eigenvalue|, which sets it."""
    from .linearize import state_matrix
    from .mode_names import participation
    model, ix = system.model, system.index
    q, u = system.full(0.0, system.initial_state())
    values, vectors = np.linalg.eig(state_matrix(system, q, u))
    fastest = int(np.argmax(np.abs(values)))
    share = participation(vectors[:system.size, fastest], np.diag(model.K)[ix],
                          np.diag(model.equations(q, u)[0])[ix], abs(values[fastest]))
    dof = model.dofs[ix[int(np.argmax(share))]]
    return RK4_STABILITY / abs(values[fastest]), f"{coordinate_label(dof)}, {abs(values[fastest]) / 2 / np.pi:.3g} Hz"


def runge_kutta4(rhs, x0: NDArray, times: NDArray, step: float, check: Callable[[float, NDArray], None]) -> NDArray:
    """Classical fixed-step 4th-order Runge-Kutta (ElastoDyn's Method = 1) with steps no larger than ``step`` (s)
    landing on every output time; ``check(t, x)`` after each output step."""
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
        check(t, x)
        states.append(x)
    return np.array(states)


def simulate(system: FreeSystem, duration: float, dt_output: float = 0.05, rtol: float = 1e-6,
             atol: float = 1e-8, method: str = "auto", step: float = 0.01,
             progress: Callable[[float], None] | None = None) -> SimulationResult:
    """Integrate from t = 0 to ``duration`` (s), outputs every ``dt_output`` s.

    method : 'auto' (the compiled 8th-order Dormand-Prince 'DP853' when numba is installed, else scipy's
        'DOP853', the same scheme), 'DP853' or 'DP54' (compiled Dormand-Prince 8(5,3) or 5(4), numba only), a
        scipy ``solve_ivp`` method ('RK45', 'DOP853', ...; tolerances ``rtol``, ``atol``), or 'RK4' with the fixed
        ``step`` (s; refused with :class:`UnstableStep` beyond the stability limit of the fastest mode)
    progress : called with the simulated time as the run advances (compiled integrators and RK4)
    """
    times = output_times(duration, dt_output)
    compiled = system.model.fast_equations()
    if method == "auto":
        method = "DP853" if hasattr(compiled, "integrate") else "DOP853"
    limit = divergence_limits(system)
    count = [0]

    def rhs(t: float, x: NDArray) -> NDArray:
        count[0] += 1
        return system(t, x)

    def check(t: float, x: NDArray) -> None:
        bad = np.flatnonzero(~np.isfinite(x) | (np.abs(x) > limit))
        if bad.size:
            raise diverged(system, int(bad[0]), t, 1 if not np.isfinite(x[bad[0]]) else 2, method)
        if progress is not None:
            progress(t)

    if method in ("DP54", "DP853"):
        if not hasattr(compiled, "integrate"):
            raise RuntimeError(f"method '{method}' needs numba (pip install numba)")
        run = compiled.integrate(times, system.initial_state(), rtol, atol, system.q0, system.u0, system.index,
                                 order=8 if method == "DP853" else 5, limit=limit, progress=progress)
        if run.status:
            raise diverged(system, run.offending, run.time, run.status, method)
        states, count[0] = run.states, run.evaluations
    elif method == "RK4":
        stable, dof = rk4_stable_step(system)
        if step > stable:
            raise UnstableStep(f"RK4 with a step of {step:g} s is unstable for the fastest mode ({dof}): the step must "
                             f"be below {stable:.3g} s")
        states = runge_kutta4(rhs, system.initial_state(), times, step, check)
    else:
        solution = solve_ivp(rhs, (0.0, times[-1]), system.initial_state(), method=method, t_eval=times,
                             rtol=rtol, atol=atol)
        if not solution.success:
            raise RuntimeError(f"time integration failed: {solution.message}")
        states = solution.y.T
        for t, x in zip(times, states):
            check(t, x)
    full = [system.full(t, x) for t, x in zip(times, states)]
    q, u = np.array([a for a, _ in full]), np.array([b for _, b in full])
    if hasattr(compiled, "root_moments"):
        moments = compiled.root_moments(times, states, system.q0, system.u0, system.index)
    else:
        moments = np.array([root_moments(system.model, qi, ui, system.accelerations(qi, ui)) for qi, ui in zip(q, u)])
    return SimulationResult(time=times, q=q, u=u, dofs=system.model.dofs, free=system.free,
                            outputs=channels(system, times, q, u, moments), evaluations=count[0])


def table_text(result: SimulationResult) -> str:
    """CSV text: time and every output channel, with units in the header."""
    names = list(CHANNELS)
    header = "Time_s," + ",".join(f"{name}_{CHANNELS[name][0].replace(' ', '')}" for name in names)
    data = np.column_stack([result.time] + [result.outputs[name] for name in names])
    body = "\n".join(",".join(row) for row in np.char.mod("%.9g", data))
    return header + "\n" + body + "\n"


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
