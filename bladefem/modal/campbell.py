"""Campbell sweep: modes over rotor speed, families followed by MAC between neighbouring speeds."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from scipy.optimize import linear_sum_assignment

from ..assembly import BladeMatrices
from .results import CampbellResult, ModalResult, ModeFamily
from .solve import solve_modes

#: extra modes computed at every speed so that a family that drifts upward past the window is still matched
TRACKING_MARGIN = 4


def mac_matrix(previous: NDArray, current: NDArray, M: sp.spmatrix) -> NDArray:
    """Modal assurance criterion (x_i^T M y_j)^2 / ((x_i^T M x_i)(y_j^T M y_j)) between two sets of vectors."""
    cross = previous.T @ (M @ current)
    norms = np.einsum("ij,ij->j", previous, M @ previous)[:, None] * np.einsum("ij,ij->j", current, M @ current)
    return cross**2 / norms


def track_families(results: Sequence[ModalResult], M: sp.spmatrix, n_families: int) -> list[ModeFamily]:
    """Follow the lowest ``n_families`` modes of the first speed through all speeds by maximum total MAC
    (Hungarian assignment between neighbouring speeds), so crossings and veerings keep families continuous."""
    indices = np.zeros((len(results), n_families), dtype=np.int64)
    macs = np.ones((len(results), n_families))
    indices[0] = np.arange(n_families)
    for k in range(1, len(results)):
        mac = mac_matrix(results[k - 1].vectors[:, indices[k - 1]], results[k].vectors, M)
        rows, cols = linear_sum_assignment(-mac)
        indices[k, rows] = cols
        macs[k, rows] = mac[rows, cols]
    families = []
    for f in range(n_families):
        frequencies = np.array([results[k].modes[indices[k, f]].frequency_hz for k in range(len(results))])
        kind = results[0].modes[f].kind
        families.append(ModeFamily(kind=kind, frequencies_hz=frequencies, indices=indices[:, f], mac=macs[:, f]))
    return families


def campbell_sweep(matrices: BladeMatrices, rpm: Sequence[float], n_modes: int = 6, notes: tuple[str, ...] = (),
                   progress: Callable[[Iterable[float]], Iterable[float]] | None = None) -> CampbellResult:
    """Modes at each rotor speed in ``rpm`` (rpm), from one assembly (K = K0 + Omega^2 K2).

    ``progress`` optionally wraps the loop over speeds (e.g. a progress bar)."""
    rpm = np.asarray(rpm, dtype=float)
    results = [solve_modes(matrices, speed, n_modes + TRACKING_MARGIN, notes) for speed in (progress or iter)(rpm)]
    M = matrices.M[matrices.free][:, matrices.free]
    n_families = min(n_modes, len(results[0].modes))
    return CampbellResult(rpm=rpm, families=track_families(results, M, n_families), results=results, notes=notes)
