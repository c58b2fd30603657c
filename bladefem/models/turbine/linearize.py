"""Linearization about an operating point: state matrix, multi-blade coordinates, modes with names.

The operating point is the undeflected turbine at rotor speed ``Omega`` and azimuth ``psi`` (as bladefem's modal
solvers: static deflections are not included). With ``M`` frozen at the operating point (exact at an equilibrium),
``A = [[0, I], [M^-1 df/dq, M^-1 df/du]]``; the Jacobians of the Kane forcing are central finite differences.
For a spinning rotor the blade coordinates are moved to multi-blade (Coleman) coordinates — collective,
cosine, sine — and the state matrix is averaged over the azimuth, which removes the periodicity for 3 blades.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .kane import TurbineModel
from .parameters import BLADE_DOFS, DOF_LABELS
from .system import FreeSystem

ORDINALS = {"1": "1st", "2": "2nd"}


def forcing_jacobians(system: FreeSystem, q: NDArray, u: NDArray, step: float = 1e-6) -> tuple[NDArray, NDArray,
                                                                                                  NDArray]:
    """M_ff, df_f/dq_f and df_f/du_f at (q, u) by central differences (relative step ``step``)."""
    model, ix = system.model, system.index
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
            target[:, column] = (model.equations(*args_plus)[1][ix] - model.equations(*args_minus)[1][ix]) / (2 * h)
    return M[np.ix_(ix, ix)], dq, du


def state_matrix(system: FreeSystem, q: NDArray, u: NDArray) -> NDArray:
    """A of the free coordinates at (q, u), states (q_f, u_f)."""
    M, dq, du = forcing_jacobians(system, q, u)
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
    the participation of each coordinate (largest 1)."""

    name: str
    frequency_hz: float
    damping_ratio: float
    damped_frequency_hz: float
    participation: dict[str, float]


@dataclass(frozen=True)
class LinearModel:
    """State matrix at an operating point (averaged over azimuth in multi-blade coordinates when the rotor
    spins), the names of its coordinates, and its modes sorted by frequency."""

    A: NDArray
    coordinates: list[str]
    rpm: float
    modes: list[LinearMode]


def mode_name(coordinate: str, used: set[str]) -> str:
    """Readable mode name from its dominant coordinate, e.g. 'tower_fa1' -> '1st tower fore-aft',
    'collective_flap1' -> '1st blade collective flap', 'cosine_flap1' -> '1st blade asymmetric flap'; a mode led
    by the generator azimuth is the drivetrain torsion, one led by the drivetrain twist the collective edge
    coupled to it. A repeated name gets a count, '(2)'."""
    kind, _, mode = coordinate.partition("_")
    if kind in ("collective", "cosine", "sine"):
        family = "flap" if mode.startswith("flap") else "edge"
        group = "collective" if kind == "collective" else "asymmetric"
        name = f"{ORDINALS[mode[-1]]} blade {group} {family}"
    elif kind.startswith("blade"):
        name = f"{ORDINALS[mode[-1]]} {'flap' if mode.startswith('flap') else 'edge'} of blade {kind[5:]}"
    elif kind == "tower":
        name = f"{ORDINALS[mode[-1]]} tower {'fore-aft' if mode.startswith('fa') else 'side-side'}"
    elif coordinate == "generator_azimuth":
        name = "1st drivetrain torsion"
    elif coordinate == "drivetrain":
        name = "1st blade collective edge / drivetrain"
    else:
        name = DOF_LABELS.get(coordinate, coordinate)
    base, count = name, 2
    while name in used:
        name = f"{base} ({count})"
        count += 1
    used.add(name)
    return name


#: below this natural frequency a mode is the rigid rotor rotation (a zero pair, split by the state's loads)
RIGID_HZ = 0.02


def modes_of(A: NDArray, coordinates: list[str], scale: NDArray, rpm: float) -> list[LinearMode]:
    """Eigen-analysis: one mode per complex-conjugate pair (and per real eigenvalue), named by the coordinate
    with the largest ``|z_i| scale_i`` (``scale`` = sqrt of the modal mass diagonal, so blades and tower compare
    by kinetic energy); the rigid rotor rotation (below :data:`RIGID_HZ`) is left out."""
    values, vectors = np.linalg.eig(A)
    m = len(coordinates)
    rows = []
    for i, lam in enumerate(values):
        frequency = abs(lam) / (2 * np.pi)
        if lam.imag < -1e-9 or frequency < RIGID_HZ:
            continue
        weights = np.abs(vectors[:m, i]) * scale
        rows.append((frequency, -lam.real / abs(lam), abs(lam.imag) / (2 * np.pi), weights / weights.max(), i))
    rows.sort(key=lambda row: row[0])
    used: set[str] = set()
    names = [mode_name(coordinates[int(np.argmax(row[3]))], used) for row in rows]
    names = whirl_names(names)
    return [LinearMode(name=name, frequency_hz=float(frequency), damping_ratio=float(damping),
                       damped_frequency_hz=float(damped),
                       participation={c: float(p) for c, p in zip(coordinates, participation)})
            for name, (frequency, damping, damped, participation, _) in zip(names, rows)]


def whirl_names(names: list[str]) -> list[str]:
    """An asymmetric pair ('... asymmetric flap' and '... asymmetric flap (2)', in frequency order) becomes its
    backward and forward whirl: in the fixed frame the backward whirl is the lower, at w - Omega, the forward at
    w + Omega (at rest the two coincide and the names are a convention)."""
    renamed = list(names)
    for i, name in enumerate(names):
        if " asymmetric " in name and not name.endswith(")") and f"{name} (2)" in names:
            renamed[i] = f"{name} (backward whirl)"
            renamed[names.index(f"{name} (2)")] = f"{name} (forward whirl)"
    return renamed


def operating_point(model: TurbineModel, rpm: float, azimuth: float = 0.0) -> tuple[NDArray, NDArray]:
    """Undeflected turbine at rotor speed ``rpm`` (rpm) and rotor azimuth (rad)."""
    q, u = np.zeros(model.n), np.zeros(model.n)
    q[5] = azimuth
    u[5] = rpm * np.pi / 30.0
    return q, u


def linearize(model: TurbineModel, free: NDArray, rpm: float = 0.0, azimuths: int = 8,
              mbc: bool = True) -> LinearModel:
    """Linear model of the free coordinates at rotor speed ``rpm``; with a spinning 3-blade rotor and ``mbc``, in
    multi-blade coordinates averaged over ``azimuths`` equally spaced azimuths (else at azimuth 0)."""
    q, u = operating_point(model, rpm)
    system = FreeSystem(model, free, q, u)
    speed = u[5]
    transform = mbc_transform(system, 0.0) if mbc else None
    names = [model.dofs[i] for i in system.index]
    mass_diagonal = np.diag(model.equations(q, u)[0])[system.index]
    if transform is None:
        A = state_matrix(system, q, u)
        scale = np.sqrt(mass_diagonal)
    else:
        A = np.zeros((2 * system.size, 2 * system.size))
        for psi in np.arange(azimuths) * 2 * np.pi / azimuths:
            q, u = operating_point(model, rpm, psi)
            T, dT, ddT, names = mbc_transform(FreeSystem(model, free, q, u), psi)
            A += mbc_state_matrix(state_matrix(FreeSystem(model, free, q, u), q, u), T, dT, ddT, speed) / azimuths
        scale = np.sqrt(np.abs(transform[0]).T @ mass_diagonal / np.maximum(np.abs(transform[0]).sum(axis=0), 1))
    return LinearModel(A=A, coordinates=names, rpm=rpm, modes=modes_of(A, names, scale, rpm))
