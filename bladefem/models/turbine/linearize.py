"""Linearization about an operating point: state matrix, multi-blade coordinates, modes with names.

The operating point is the undeflected turbine at rotor speed ``Omega``, rotor azimuth ``psi`` and nacelle yaw (as
bladefem's modal solvers, and as OpenFAST linearizes at its initial state: static deflections are not included).
With ``M`` frozen at the operating point (exact at an equilibrium), ``A = [[0, I], [M^-1 df/dq, M^-1 df/du]]``;
the Jacobians of the Kane forcing are central finite differences.

Parked (``Omega = 0``) the turbine is linearized at the one azimuth given, as OpenFAST does; when the three blades
are alike the blade coordinates are then expressed in multi-blade (Coleman) coordinates — collective, cosine,
sine — at that azimuth, a constant change of basis that leaves the eigenvalues of the blade-coordinate
linearization unchanged and only serves the names. For a spinning rotor the state matrix is transformed to
multi-blade coordinates and averaged over the azimuth, which removes the periodicity for 3 blades.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ...errors import SolveError
from .kane import TurbineModel
from .mode_names import name_modes, participation
from .parameters import BLADE_DOFS
from .system import FreeSystem

#: below this natural frequency a mode is a rigid-body motion (a zero pair, split by the state's loads)
RIGID_HZ = 0.02
#: participations below this share are left out of :attr:`LinearMode.participation`
SHARE_SHOWN = 1e-3

Forcing = Callable[[NDArray, NDArray], NDArray]


def forcing_jacobians(system: FreeSystem, q: NDArray, u: NDArray, step: float = 1e-6,
                      forcing: Forcing | None = None) -> tuple[NDArray, NDArray, NDArray]:
    """M_ff, df_f/dq_f and df_f/du_f at (q, u) by central differences (relative step ``step``); ``forcing(q, u)``
    (default the model's Kane forcing) may add external loads, whose stiffness and damping then enter."""
    model, ix = system.model, system.index
    forcing = forcing or (lambda qq, uu: model.equations(qq, uu)[1])
    M, _ = model.equations(q, u)
    dq = np.zeros((len(ix), len(ix)))
    du = np.zeros((len(ix), len(ix)))
    for column, i in enumerate(ix):
        for target, vector in ((dq, q), (du, u)):
            h = step * max(1.0, abs(vector[i]))
            plus, minus = vector.copy(), vector.copy()
            plus[i] += h
            minus[i] -= h
            args_plus = (plus, u) if vector is q else (q, plus)
            args_minus = (minus, u) if vector is q else (q, minus)
            target[:, column] = (forcing(*args_plus)[ix] - forcing(*args_minus)[ix]) / (2 * h)
    return M[np.ix_(ix, ix)], dq, du


def state_matrix(system: FreeSystem, q: NDArray, u: NDArray, forcing: Forcing | None = None) -> NDArray:
    """A of the free coordinates at (q, u), states (q_f, u_f)."""
    M, dq, du = forcing_jacobians(system, q, u, forcing=forcing)
    m = system.size
    A = np.zeros((2 * m, 2 * m))
    A[:m, m:] = np.eye(m)
    A[m:, :m] = np.linalg.solve(M, dq)
    A[m:, m:] = np.linalg.solve(M, du)
    return A


def mbc_transform(system: FreeSystem, azimuth: float) -> tuple[NDArray, NDArray, NDArray, list[str]] | None:
    """Coleman transform of the free coordinates at rotor azimuth ``azimuth`` (rad): ``q = T z``, with ``dT/dpsi``
    and ``d2T/dpsi2``, and the names of ``z``; None unless there are 3 blades with the same free modes."""
    model = system.model
    if model.params.n_blades != 3:
        return None
    free_blade = system.free[model.blade_columns]
    if not (free_blade.any() and (free_blade == free_blade[0]).all()):
        return None
    ix = list(system.index)
    names: list[str] = []
    columns: list[tuple[str, int, int]] = []       # (kind, position in ix, mode j)
    for pos, i in enumerate(ix):
        dof = model.dofs[i]
        if dof.startswith("blade1_"):
            j = BLADE_DOFS.index(dof.split("_", 1)[1])
            for kind in ("collective", "cosine", "sine"):
                columns.append((kind, pos, j))
                names.append(f"{kind}_{BLADE_DOFS[j]}")
        elif not dof.startswith("blade"):
            columns.append(("fixed", pos, -1))
            names.append(dof)
    size = len(ix)
    T, dT, ddT = (np.zeros((size, size)) for _ in range(3))
    row_of = {i: pos for pos, i in enumerate(ix)}
    for col, (kind, pos, j) in enumerate(columns):
        if kind == "fixed":
            T[pos, col] = 1.0
            continue
        for k in range(3):
            row = row_of[model.blade_columns[k, j]]
            psi = azimuth + 2 * np.pi * k / 3
            value = {"collective": (1.0, 0.0, 0.0), "cosine": (np.cos(psi), -np.sin(psi), -np.cos(psi)),
                     "sine": (np.sin(psi), np.cos(psi), -np.sin(psi))}[kind]
            T[row, col], dT[row, col], ddT[row, col] = value
    return T, dT, ddT, names


def mbc_state_matrix(A: NDArray, T: NDArray, dT: NDArray, ddT: NDArray, speed: float) -> NDArray:
    """State matrix in multi-blade coordinates: x = Tx z with Tx = [[T, 0], [Omega T', T]]:
    ``A_z = Tx^-1 (A Tx - dTx/dt)``."""
    m = len(T)
    Tx = np.block([[T, np.zeros((m, m))], [speed * dT, T]])
    dTx = np.block([[speed * dT, np.zeros((m, m))], [speed**2 * ddT, speed * dT]])
    return np.linalg.solve(Tx, A @ Tx - dTx)


@dataclass(frozen=True)
class LinearMode:
    """A mode of the linearized turbine: name, natural frequency (Hz), damping ratio, damped frequency (Hz), and
    the participation of each coordinate (energy shares, summing to 1; shares below 0.1 % left out)."""

    name: str
    frequency_hz: float
    damping_ratio: float
    damped_frequency_hz: float
    participation: dict[str, float]
    oscillating: bool = True

    @property
    def time_constant(self) -> float:
        """1 / |lambda|, s: the decay time of a non-oscillating mode (a real root, |lambda| = 2 pi frequency_hz)."""
        return 1.0 / (2 * np.pi * self.frequency_hz) if self.frequency_hz > 0 else float("inf")

    def as_dict(self) -> dict:
        return {"name": self.name, "frequency_hz": self.frequency_hz, "damping_ratio": self.damping_ratio,
                "oscillating": self.oscillating, "participation": self.participation}


@dataclass(frozen=True)
class LinearModel:
    """State matrix at an operating point (averaged over azimuth in multi-blade coordinates when the rotor
    spins), the names of its coordinates, the rotor speed (rpm) and azimuth (deg; None when averaged over it),
    its modes sorted by frequency and the rigid-body motions left out of them."""

    A: NDArray
    coordinates: list[str]
    rpm: float
    azimuth_deg: float | None
    modes: list[LinearMode]
    rigid: list[str]

    def as_dict(self) -> dict:
        """``{"rpm", "azimuth_deg", "modes": [{"name", "frequency_hz", "damping_ratio", "participation"}]}``."""
        return {"rpm": self.rpm, "azimuth_deg": self.azimuth_deg, "modes": [m.as_dict() for m in self.modes]}


def operating_point(model: TurbineModel, rpm: float, azimuth: float = 0.0, yaw: float = 0.0) -> tuple[NDArray,
                                                                                                     NDArray]:
    """Undeflected turbine at rotor speed ``rpm`` (rpm), rotor azimuth and nacelle yaw (rad)."""
    q, u = np.zeros(model.n), np.zeros(model.n)
    q[model.dofs.index("generator_azimuth")] = azimuth
    q[model.dofs.index("yaw")] = yaw
    u[model.dofs.index("generator_azimuth")] = rpm * np.pi / 30.0
    return q, u


def modes_of(A: NDArray, coordinates: list[str], stiffness: NDArray, mass: NDArray, spinning: bool
             ) -> tuple[list[LinearMode], list[str]]:
    """Modes (one per complex-conjugate pair and per real eigenvalue) sorted by frequency, named by their
    participation (:mod:`.mode_names`), and the names of the rigid-body motions (below :data:`RIGID_HZ`)."""
    if not np.isfinite(A).all():
        raise SolveError("the linearized state matrix holds infinite or undefined values: a stiffness, damping or "
                         "inertia of the deck is too extreme for double precision")
    values, vectors = np.linalg.eig(A)
    m = len(coordinates)
    rows = []
    for i, lam in enumerate(values):
        if lam.imag < -1e-9:
            continue
        omega = abs(lam)
        z = vectors[:m, i]
        # a rigid-body motion has no strain: its coordinates compare by kinetic energy alone
        rigid_motion = omega < 2 * np.pi * RIGID_HZ
        share = participation(z, 0 * stiffness if rigid_motion else stiffness, mass, max(omega, 1.0) if
                              rigid_motion else omega)
        rows.append((omega / (2 * np.pi), -lam.real / omega if omega > 0 else 0.0, abs(lam.imag) / (2 * np.pi),
                     z, share, lam.imag > 1e-9 * max(omega, 1.0)))
    rows.sort(key=lambda row: row[0])
    rigid = [row[0] < RIGID_HZ for row in rows]
    names = name_modes([row[3] for row in rows], [row[4] for row in rows], coordinates, rigid, spinning,
                       [row[5] for row in rows])
    modes = [LinearMode(name=name, frequency_hz=float(f), damping_ratio=float(zeta), damped_frequency_hz=float(fd),
                        participation={c: round(float(s), 6) for c, s in zip(coordinates, share) if s >= SHARE_SHOWN},
                        oscillating=bool(swings))
             for name, (f, zeta, fd, _, share, swings), is_rigid in zip(names, rows, rigid) if not is_rigid]
    return modes, list(dict.fromkeys(name for name, is_rigid in zip(names, rigid) if is_rigid))


def linearize(model: TurbineModel, free: NDArray, rpm: float = 0.0, azimuth: float = 0.0, azimuths: int = 8,
              mbc: bool = True, yaw: float = 0.0, forcing: Forcing | None = None) -> LinearModel:
    """Linear model of the free coordinates at rotor speed ``rpm`` (rpm), nacelle yaw (rad).

    Parked (rpm 0): at rotor ``azimuth`` (rad), named in multi-blade coordinates when the blades allow it.
    Spinning with 3 alike free blades and ``mbc``: multi-blade coordinates averaged over ``azimuths`` equally
    spaced azimuths from ``azimuth``; otherwise in blade coordinates at ``azimuth``.
    """
    q, u = operating_point(model, rpm, azimuth, yaw)
    system = FreeSystem(model, free, q, u)
    speed = u[model.dofs.index("generator_azimuth")]
    transform = mbc_transform(system, azimuth) if mbc else None
    names = [model.dofs[i] for i in system.index]
    block = np.ix_(system.index, system.index)
    if transform is None:
        A = state_matrix(system, q, u, forcing)
        stiffness, mass = np.diag(model.K[block]), np.diag(model.equations(q, u)[0][block])
    elif rpm == 0.0:
        T, _, _, names = transform
        Tx = np.kron(np.eye(2), T)
        A = np.linalg.solve(Tx, state_matrix(system, q, u, forcing) @ Tx)
        stiffness = np.diag(T.T @ model.K[block] @ T)
        mass = np.diag(T.T @ model.equations(q, u)[0][block] @ T)
    else:
        A = np.zeros((2 * system.size, 2 * system.size))
        stiffness, mass = np.zeros(system.size), np.zeros(system.size)
        for psi in azimuth + np.arange(azimuths) * 2 * np.pi / azimuths:
            q, u = operating_point(model, rpm, psi, yaw)
            at = FreeSystem(model, free, q, u)
            T, dT, ddT, names = mbc_transform(at, psi)
            A += mbc_state_matrix(state_matrix(at, q, u, forcing), T, dT, ddT, speed) / azimuths
            stiffness += np.diag(T.T @ model.K[block] @ T) / azimuths
            mass += np.diag(T.T @ model.equations(q, u)[0][block] @ T) / azimuths
    averaged = transform is not None and rpm != 0.0
    modes, rigid = modes_of(A, names, stiffness, mass, spinning=rpm != 0.0)
    return LinearModel(A=A, coordinates=names, rpm=float(rpm),
                       azimuth_deg=None if averaged else float(np.degrees(azimuth)), modes=modes, rigid=rigid)
