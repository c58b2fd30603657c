"""Tower modal analysis: natural modes of a tower with its top mass, gravity and supports.

Results reuse :class:`~bladefem.modal.results.ModalResult`; for a tower the mode shape's ``flap`` is the fore-aft
deflection ``w`` and ``edge`` the side-side deflection ``v``, and the kinds are ``fore-aft``, ``side-side``,
``torsion``, ``axial`` and, on a floating platform, ``surge``, ``sway``, ``heave``, ``roll``, ``pitch``, ``yaw``
(the coordinate or field with the largest share of kinetic energy; platform shares are those of the rigid-body
motion of the whole system, beam shares those of the elastic motion relative to the platform; a mode that mostly
strains the tower is named after the tower's motion, :func:`mode_kind`). A mode's
``residual`` is the normwise backward error of the eigenpair (:func:`backward_errors`).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ..assembly.dofs import DofMap
from ..assembly.supports import BASE_FIELDS, PLATFORM_KINDS
from ..assembly.tower import TowerMatrices, assemble_tower
from ..modal.refinement import refine_until_converged
from ..modal.results import ModalResult, Mode
from ..modal.solve import DENSE_LIMIT, eigen_pairs, jacobi_scaling, mode_shape
from ..sections.tower import (
    Tower,
    as_tower,
)

#: tower kind of each beam field
TOWER_FIELD_KINDS: dict[str, str] = {"w": "fore-aft", "v": "side-side", "phi": "torsion", "u": "axial"}
#: a mode whose tower strain energy is more than this share of its potential energy is a tower mode (measured on
#: the floating reference decks: rigid-platform modes below 0.08, the coupled first bending modes 0.99-1.02)
TOWER_STRAIN_SHARE = 0.5
TOWER_KINDS: tuple[str, ...] = ("fore-aft", "side-side", "torsion", "axial", "surge", "sway", "heave", "roll",
                                "pitch", "yaw")
#: modes whose frequencies differ by less than this (relative) form a degenerate cluster, rotated into clean
#: fore-aft / side-side directions (a symmetric tower's pair is split only by rounding, ~1e-10)
DEGENERATE_RTOL = 1e-5
#: warn when the gravity load exceeds this fraction of the critical (buckling) load: the first frequency has then
#: dropped by about 1 - sqrt(1 - 0.5) = 29 % (omega^2 falls about linearly with the load)
BUCKLING_WARNING_FRACTION = 0.5
#: mesh of the buckling check (the critical load factor converges like h^4: 40 elements give ~1e-7)
BUCKLING_ELEMENTS = 40
#: tenfold increases of the shift tried when K is not positive definite
SHIFT_ATTEMPTS = 8
#: extra modes solved so that a degenerate pair straddling the last requested mode is rotated as a whole
CLUSTER_MARGIN = 2
MESH_RTOL = 1e-6


@dataclass(frozen=True)
class _BeamView:
    """The beam part of a full vector, in the form :func:`bladefem.modal.solve.mode_shape` reads."""

    dofs: DofMap
    free: NDArray[np.int64]


def _frequencies(values: NDArray) -> NDArray:
    return np.sign(values) * np.sqrt(np.abs(values)) / (2 * np.pi)


def inverse_pairs(K: sp.spmatrix, M: sp.spmatrix, n_modes: int) -> tuple[NDArray, NDArray]:
    """Lowest eigenpairs of ``K x = omega^2 M x`` from the inverse problem ``M x = mu K x``, ``mu = 1/omega^2``
    (K positive definite). The lowest omega^2 are then the largest mu, found to relative accuracy even when the
    stiffest element modes are 1e12 times stiffer (a platform's surge under a stiff tower); the direct dense
    problem through a Cholesky factor of M loses them to round-off. Raises LinAlgError if K is not definite."""
    n = K.shape[0]
    k = min(n_modes, n)
    if n <= DENSE_LIMIT or k >= n - 1:
        mu, vectors = la.eigh(M.toarray(), K.toarray(), subset_by_index=[n - k, n - 1], check_finite=False)
    else:
        with warnings.catch_warnings():
            warnings.simplefilter("error", spla.MatrixRankWarning)
            try:
                start = np.random.default_rng(0).standard_normal(n)     # ARPACK's own start moves with every call
                mu, vectors = spla.eigsh(K, k=k, M=M, sigma=0.0, which="LM", v0=start)
            except (RuntimeError, spla.MatrixRankWarning, spla.ArpackError) as error:   # incl. no convergence
                raise la.LinAlgError(str(error)) from None
        mu = 1.0 / mu
    if np.any(mu <= 0):
        raise la.LinAlgError("K is not positive definite")
    order = np.argsort(1.0 / mu)
    values, vectors = (1.0 / mu)[order], vectors[:, order]
    vectors = vectors / np.sqrt(np.einsum("ij,ij->j", vectors, M @ vectors))
    return values, vectors


def shifted_pairs(K: sp.spmatrix, M: sp.spmatrix, n_modes: int, shift: float) -> tuple[NDArray, NDArray, float]:
    """The inverse problem of ``K + s M`` from ``s = shift`` up (tenfold until definite); returns the shift used."""
    for _ in range(SHIFT_ATTEMPTS):
        try:
            values, vectors = inverse_pairs(K + shift * M, M, n_modes)
            return values - shift, vectors, shift
        except la.LinAlgError:
            shift *= 10
    raise la.LinAlgError("no shift makes K + s M positive definite")


def solve_tower(matrices: TowerMatrices, n_modes: int) -> tuple[NDArray, NDArray]:
    """Lowest eigenvalues (omega^2) and M-normalised eigenvectors on the independent coordinates, from the inverse
    problem. When K is not positive definite (a free rigid-body motion, a buckled tower) the inverse problem of
    ``K + s M`` is solved twice: first with ``s`` twice the largest |omega^2| the direct problem estimates, which
    gives every omega^2 to ~1e-16 s; then with ``s`` twice the larger of the lowest clearly nonzero omega^2 and the
    most negative one's magnitude, so that free motions come out at ~1e-8 of the lowest frequency."""
    K, M = matrices.reduced()
    try:
        return inverse_pairs(K, M, n_modes)
    except la.LinAlgError:
        estimate, _ = eigen_pairs(K, M, n_modes)
    try:
        values, vectors, shift = shifted_pairs(K, M, n_modes, 2 * float(np.max(np.abs(estimate))) or 1.0)
        nonzero = values[np.abs(values) > 1e-9 * shift]
        if nonzero.size:
            refined = 2 * max(float(np.abs(nonzero).min()), -float(values.min()))
            values, vectors, _ = shifted_pairs(K, M, n_modes, refined)
        return values, vectors
    except la.LinAlgError:
        return eigen_pairs(K, M, n_modes)


def converged_matrices(tower: Tower, n_modes: int = 10, rtol: float = MESH_RTOL,
                       max_elements: int = 800) -> TowerMatrices:
    """Matrices on the coarsest mesh (from ``max(24, stations - 1)`` elements doubled) whose lowest ``n_modes``
    frequencies are within ``rtol`` of the converged ones (:func:`bladefem.modal.refinement.refine_until_converged`,
    the blade's rule too); the finer mesh of the accepted pair is kept, for closed-form checks to 1e-7."""
    matrices, _ = refine_until_converged(lambda elements: assemble_tower(tower, elements),
                                         lambda matrices: _frequencies(solve_tower(matrices, n_modes)[0]),
                                         max(24, tower.sections.stations - 1), rtol, max_elements,
                                         finer=True)
    return matrices


def fore_aft_selection(matrices: TowerMatrices) -> NDArray[np.int64]:
    """Full-vector indices of motion in the fore-aft plane: the w field and the base's t_z and theta_y."""
    n = matrices.dofs.size
    return np.concatenate([matrices.dofs.field_dofs["w"], [n + 2, n + 4]])


def rotate_degenerate(matrices: TowerMatrices, values: NDArray, vectors: NDArray) -> tuple[NDArray, NDArray]:
    """Within each cluster of (nearly) equal frequencies, rotate the eigenvectors so that each has extremal
    fore-aft kinetic energy: eigenvectors of the cluster's fore-aft energy matrix ``X^T M_fa X``. The rotation is
    orthogonal, so the vectors stay M-orthonormal; the eigenvalues become the Rayleigh quotients
    ``sum_k U_ki^2 lambda_k``."""
    values, vectors = values.copy(), vectors.copy()
    omega = np.sqrt(np.abs(values))
    selection = fore_aft_selection(matrices)
    M_fa = matrices.M[selection][:, selection]
    i = 0
    while i < len(values):
        j = i + 1
        while j < len(values) and abs(omega[j] - omega[i]) <= DEGENERATE_RTOL * max(omega[i], 1e-300):
            j += 1
        if j - i > 1:
            full = matrices.expand(vectors[:, i:j])[selection]
            _, U = la.eigh(full.T @ (M_fa @ full))
            U = U[:, ::-1]                                       # the most fore-aft first
            vectors[:, i:j] = vectors[:, i:j] @ U
            values[i:j] = (U**2).T @ values[i:j]                 # Rayleigh quotients, without K x round-off
        i = j
    return values, vectors


def energy_shares(matrices: TowerMatrices, vectors: NDArray) -> list[dict[str, float]]:
    """Kinetic-energy share of each tower kind in each mode (diagonal blocks; see the module docstring)."""
    n = matrices.dofs.size
    full = matrices.expand(vectors)
    supports = matrices.tower.supports
    shares = {kind: np.zeros(vectors.shape[1]) for kind in TOWER_KINDS}
    if supports.platform is not None:
        q = vectors[matrices.n_elastic:]
        full = matrices.Z[:, :matrices.n_elastic] @ vectors[:matrices.n_elastic]
        _, M_r = matrices.reduced()
        diagonal = M_r.diagonal()[matrices.n_elastic:]
        for k, index in enumerate(supports.free_base):
            shares[PLATFORM_KINDS[index]] += diagonal[k] * q[k] ** 2
    elif supports.foundation is not None:
        diagonal = matrices.M.diagonal()[n:]
        for k, name in enumerate(BASE_FIELDS):
            shares[TOWER_FIELD_KINDS[name]] += diagonal[k] * full[n + k] ** 2
    for name, dofs in matrices.dofs.field_dofs.items():
        part = full[dofs]
        shares[TOWER_FIELD_KINDS[name]] += np.einsum("ij,ij->j", part, matrices.M[dofs][:, dofs] @ part)
    total = sum(shares.values())
    total = np.where(total > 0, total, 1.0)
    return [{kind: float(shares[kind][j] / total[j]) for kind in TOWER_KINDS} for j in range(vectors.shape[1])]


def critical_load_factor(matrices: TowerMatrices) -> float:
    """Smallest ``lambda > 0`` with ``K + lambda K_g`` singular: the gravity load at buckling over the actual one
    (inf without gravity or when gravity cannot destabilise the tower).

    It is ``1 / mu`` for the largest ``mu`` of ``G x = mu K x``, ``G = -K_g``: one Lanczos eigenvalue with K
    factored once (sparse), where the largest ``mu`` stands well apart from the rest, which crowd towards zero."""
    K, _ = matrices.reduced(0.0)
    K_g = matrices.Z.T @ matrices.K_gravity @ matrices.Z
    if K_g.nnz == 0 or not np.any(K_g.data):
        return float("inf")
    G = (-0.5 * (K_g + K_g.T)).tocsc()
    try:
        largest = _largest_load_ratio(K.tocsc(), G)
    except (RuntimeError, spla.ArpackError, spla.ArpackNoConvergence):     # K singular (a free rigid motion)
        K, G = K.toarray(), G.toarray()
        lam = la.eigvals(K, G)
        lam = lam[np.isfinite(lam) & (np.abs(lam.imag) <= 1e-9 * np.abs(lam)) & (lam.real > 0)].real
        return float(lam.min()) if lam.size else float("inf")
    return 1.0 / largest if largest > 0 else float("inf")


def _largest_load_ratio(K: sp.csc_matrix, G: sp.csc_matrix) -> float:
    """Largest ``mu`` of ``G x = mu K x`` (K positive definite), by Lanczos in K's inner product, Jacobi-scaled
    (values and slopes, axial and bending DOFs of very different stiffness)."""
    K, G, _ = jacobi_scaling(K, G)
    factor = spla.splu(K)
    n = K.shape[0]
    inverse = spla.LinearOperator((n, n), matvec=factor.solve, dtype=float)
    start = np.random.default_rng(0).standard_normal(n)      # fixed start: identical results run to run
    mu = spla.eigsh(G, k=1, M=K, Minv=inverse, which="LA", v0=start, tol=1e-12, return_eigenvectors=False)
    return float(mu[0])


def gravity_notes(tower: Tower) -> tuple[str, ...]:
    """Statement of the gravity load and its distance from buckling (warns when it is close)."""
    if tower.gravity == 0:
        return ("gravity off: no axial load, no top-mass pendulum effect",)
    factor = critical_load_factor(assemble_tower(tower, BUCKLING_ELEMENTS))
    note = (f"gravity {tower.gravity:g} m/s^2: self-weight and top-mass compression and the top mass's pendulum "
            f"effect included; buckling at {factor:.4g} times this load")
    if factor < 1:
        message = (f"the tower buckles under its own weight and top mass (critical load factor {factor:.4g}); "
                   "the lowest frequencies are imaginary (reported negative)")
    elif 1 / factor > BUCKLING_WARNING_FRACTION:
        message = (f"the gravity load is {100 / factor:.0f}% of the critical buckling load: the lowest "
                   "frequencies are strongly reduced by the axial compression")
    else:
        return (note,)
    warnings.warn(message, stacklevel=3)
    return (note, "warning: " + message)


def backward_errors(K: sp.spmatrix, M: sp.spmatrix, values: NDArray, vectors: NDArray) -> NDArray:
    """Normwise backward error ``||K x - lambda M x|| / ((||K|| + |lambda| ||M||) ||x||)`` (1-norms of the
    matrices) of each eigenpair: the relative change of K and M that makes the pair exact. Unlike
    ``||r|| / ||K x||`` it is not swamped by the round-off of ``K x`` when the mesh's stiffest modes are many
    orders above a soft rigid-body mode."""
    r = K @ vectors - (M @ vectors) * values
    scale = (spla.norm(K, 1) + np.abs(values) * spla.norm(M, 1)) * np.linalg.norm(vectors, axis=0)
    return np.linalg.norm(r, axis=0) / scale


def strain_shares(matrices: TowerMatrices, K: sp.spmatrix, vectors: NDArray) -> NDArray:
    """Share of each mode's potential energy (``x^T K x``, reduced K) that is the tower's elastic strain energy;
    0 for a rigid-body mode."""
    elastic = matrices.Z[:, :matrices.n_elastic]
    part = vectors[:matrices.n_elastic]
    strain = np.einsum("ij,ij->j", part, (elastic.T @ matrices.K_elastic @ elastic) @ part)
    total = np.abs(np.einsum("ij,ij->j", vectors, K @ vectors))
    return np.divide(strain, total, out=np.zeros_like(strain), where=total > 0)


def mode_kind(fractions: dict[str, float], strain_share: float) -> str:
    """The kind with the largest kinetic share; a mode that mostly strains the tower (:data:`TOWER_STRAIN_SHARE`)
    is named after the tower's own motion even where a massive platform holds most of its kinetic energy (the
    first bending modes of a floating tower, platform pitch and roll coupled in)."""
    kinds = TOWER_FIELD_KINDS.values() if strain_share > TOWER_STRAIN_SHARE else fractions
    return max(kinds, key=fractions.get)


def modal_result(matrices: TowerMatrices, values: NDArray, vectors: NDArray,
                 notes: tuple[str, ...] = ()) -> ModalResult:
    """A :class:`ModalResult` with tower kinds, relative residuals and mode shapes (shapes include base motion)."""
    K, M = matrices.reduced()
    residuals = backward_errors(K, M, values, vectors)
    fractions = energy_shares(matrices, vectors)
    strain = strain_shares(matrices, K, vectors)
    view = _BeamView(matrices.dofs, np.arange(matrices.dofs.size))
    full = matrices.expand(vectors)
    modes = []
    for j, value in enumerate(values):
        kind = mode_kind(fractions[j], strain[j])
        modes.append(Mode(frequency_hz=float(_frequencies(np.array([value]))[0]), kind=kind,
                          energy_fractions=fractions[j], residual=float(residuals[j]),
                          shape=mode_shape(view, full[:matrices.dofs.size, j], kind)))
    return ModalResult(rotor_speed_rpm=0.0, modes=modes, stations=matrices.tower.sections.span.copy(),
                       vectors=vectors, n_dofs=matrices.n_free, notes=notes)


def tower_matrices(tower: Tower, elements: int | None = None, n_modes: int = 10) -> TowerMatrices:
    """Matrices on a mesh of about ``elements`` elements, or on a mesh refined until converged (None)."""
    tower = as_tower(tower)
    return converged_matrices(tower, n_modes) if elements is None else assemble_tower(tower, elements)


def tower_modes(tower: Tower, n_modes: int = 10, elements: int | None = None) -> ModalResult:
    """Natural modes of ``tower`` (a :class:`~bladefem.sections.tower.Tower`, or reader output with sections and a
    top mass: clamped, standard gravity). ``elements``: target number of elements, or None to refine the mesh
    until the frequencies converge to 1e-6."""
    if n_modes < 1:
        raise ValueError("n_modes must be at least 1")
    tower = as_tower(tower)
    matrices = tower_matrices(tower, elements, n_modes)
    values, vectors = rotate_degenerate(matrices, *solve_tower(matrices, n_modes + CLUSTER_MARGIN))
    values, vectors = values[:n_modes], vectors[:, :n_modes]
    notes = tower.notes + gravity_notes(tower) + (
        "tower mode shapes: 'flap' is fore-aft (w, downwind), 'edge' is side-side (v)",)
    return modal_result(matrices, values, vectors, notes)


def with_blade_kinds(result: ModalResult) -> ModalResult:
    """The same result with fore-aft named 'flap' and side-side 'edge' (kinds and energy shares), for tools
    written for blades such as :mod:`bladefem.modal.elastodyn_fit`."""
    rename = {"fore-aft": "flap", "side-side": "edge"}
    modes = [Mode(frequency_hz=m.frequency_hz, kind=rename.get(m.kind, m.kind),
                  energy_fractions={rename.get(k, k): v for k, v in m.energy_fractions.items()},
                  residual=m.residual, shape=m.shape) for m in result.modes]
    return ModalResult(rotor_speed_rpm=result.rotor_speed_rpm, modes=modes, stations=result.stations,
                       vectors=result.vectors, n_dofs=result.n_dofs, notes=result.notes)
