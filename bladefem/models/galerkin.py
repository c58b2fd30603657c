"""Analytical (assumed-modes Galerkin) model of a rotating, pretwisted cantilever blade.

The second, independent solution path next to the finite elements (seed paper 002, eqs. 25-34, with the physics
of docs/THEORY.md): flap ``w``, lead-lag ``v`` and torsion ``phi`` expanded in shape functions that satisfy the
clamped-root conditions, mass and stiffness from Galerkin integrals over the span, natural frequencies from
``det(K0 + Omega^2 K2 - omega^2 M) = 0``. The blade is inextensible (no axial DOF); without GJ the torsion is rigid.
It shares only the raw section table and blade geometry (:class:`bladefem.sections.SectionTable`, :class:`Blade`)
with the finite-element code; section stiffness and mass moments are its own (:mod:`.galerkin_sections`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import scipy.linalg as la
from numpy.typing import NDArray
from scipy.optimize import linear_sum_assignment

from ..errors import InputError
from ..modal.results import (
    KINDS,
    CampbellResult,
    ModalResult,
    Mode,
    ModeFamily,
    ModeShape,
    dominant_kind,
    signed_frequency_hz,
)
from ..sections import Blade
from .galerkin_basis import BASES, Basis, bending_shapes, torsion_shapes
from .galerkin_matrices import GalerkinMatrices, Terms, galerkin_matrices

#: The seed paper's truncation N_w, N_v, N_phi.
PAPER_TERMS = (5, 5, 3)


def rpm_to_rad_s(rpm: float) -> float:
    """Rotor speed in rad/s from rpm."""
    return float(rpm) * np.pi / 30.0


def parse_terms(text: str) -> tuple[int, int, int]:
    """``"NW,NV,NPHI"`` (the CLI's ``--terms``) as three integers; raises :class:`InputError`."""
    parts = [part.strip() for part in str(text).split(",")]
    try:
        values = tuple(int(part) for part in parts)
    except ValueError:
        values = ()
    if len(values) != 3:
        raise InputError(f"expected three integers NW,NV,NPHI, got '{text}'", field="--terms")
    return check_terms(values, field="--terms")


def check_terms(terms: Sequence[int], field: str = "terms") -> tuple[int, int, int]:
    """Validate the numbers of assumed modes: flap and edge at least 1, torsion at least 0."""
    flap, edge, torsion = (int(value) for value in terms)
    if flap < 1 or edge < 1 or torsion < 0:
        raise InputError(f"need N_w >= 1, N_v >= 1 and N_phi >= 0, got {flap},{edge},{torsion}", field=field)
    return flap, edge, torsion


def model_terms(blade: Blade, terms: Sequence[int]) -> tuple[Terms, tuple[str, ...]]:
    """The terms used for ``blade`` (no torsion terms without GJ) and notes stating the modelling choices."""
    if blade.root != "cantilever":
        raise InputError(f"the Galerkin model is for cantilever roots only, got root '{blade.root}'", field="root")
    flap, edge, torsion = check_terms(terms)
    notes = [f"Galerkin model: N_w, N_v, N_phi = {flap}, {edge}, {torsion}; inextensible (no axial DOF)"]
    if blade.sections.torsion_stiffness is None and torsion:
        torsion = 0
        notes.append("no torsion stiffness (GJ) in the input: torsion is rigid, its terms are dropped")
    if blade.sections.full is not None and blade.sections.full.shear_flexible:
        notes.append("Euler-Bernoulli: the transverse shear is condensed (the finite elements keep it unless "
                     "--sections condensed)")
    return Terms(flap, edge, torsion), tuple(notes)


def fields_at(x: NDArray, length: float, terms: Terms, basis: Basis, q: NDArray) -> dict[str, NDArray]:
    """Flap and edge deflection (m) and slope (rad) and twist (rad) of coefficient vector ``q`` at ``x``."""
    sl = terms.slices()
    w, dw, _ = bending_shapes(x, length, terms.flap, basis)
    v, dv, _ = bending_shapes(x, length, terms.edge, basis)
    phi = torsion_shapes(x, length, terms.torsion)[0]
    return {"flap": w @ q[sl["flap"]], "flap_slope": dw @ q[sl["flap"]], "edge": v @ q[sl["edge"]],
            "edge_slope": dv @ q[sl["edge"]], "twist": phi @ q[sl["torsion"]], "axial": np.zeros(len(x))}


def mode_shape(blade: Blade, matrices: GalerkinMatrices, q: NDArray, kind: str) -> ModeShape:
    """The mode at the section stations, scaled so that its largest deflection (or twist, for a torsion mode) is
    +1."""
    x = blade.sections.span
    shape = fields_at(x, blade.length, matrices.terms, matrices.basis, q)
    if kind == "torsion":
        reference = shape["twist"]
    else:
        reference = np.concatenate([shape["flap"], shape["edge"]])
    scale = reference[np.argmax(np.abs(reference))]
    scale = scale if abs(scale) > 0 else 1.0
    return ModeShape(x=x.copy(), **{key: value / scale for key, value in shape.items()})


def energy_fractions(matrices: GalerkinMatrices, vectors: NDArray) -> list[dict[str, float]]:
    """Kinetic-energy share of flap, edge and torsion coefficients in each mode (diagonal field blocks of M)."""
    shares = {}
    for kind, sl in matrices.terms.slices().items():
        part = vectors[sl]
        shares[kind] = np.einsum("ij,ij->j", part, matrices.M[sl, sl] @ part)
    total = sum(shares.values())
    return [{kind: float(shares[kind][j] / total[j]) if kind in shares else 0.0 for kind in KINDS}
            for j in range(vectors.shape[1])]


def solve(blade: Blade, matrices: GalerkinMatrices, rpm: float, n_modes: int,
          notes: tuple[str, ...] = ()) -> ModalResult:
    """Lowest ``n_modes`` modes of ``K0 + Omega^2 K2 - omega^2 M`` at rotor speed ``rpm`` (rpm)."""
    if n_modes < 1:
        raise InputError(f"need at least one mode, got {n_modes}", field="n_modes")
    K = matrices.K0 + rpm_to_rad_s(rpm) ** 2 * matrices.K2
    n_modes = min(n_modes, matrices.terms.size)
    try:
        values, vectors = la.eigh(K, matrices.M, subset_by_index=[0, n_modes - 1])
    except la.LinAlgError as error:
        raise InputError(f"the Galerkin mass matrix is numerically singular with {matrices.terms.size} "
                         f"'{matrices.basis}' terms ({error}); use the 'jacobi' basis or fewer terms",
                         field="terms") from error
    Kx = K @ vectors
    residuals = np.linalg.norm(Kx - matrices.M @ vectors * values, axis=0) / np.linalg.norm(Kx, axis=0)
    fractions = energy_fractions(matrices, vectors)
    modes = []
    for j, value in enumerate(values):
        kind = dominant_kind(fractions[j])
        modes.append(Mode(frequency_hz=signed_frequency_hz(value), kind=kind, energy_fractions=fractions[j],
                          residual=float(residuals[j]), shape=mode_shape(blade, matrices, vectors[:, j], kind)))
    return ModalResult(rotor_speed_rpm=float(rpm), modes=modes, stations=blade.sections.span.copy(),
                       vectors=vectors, n_dofs=matrices.terms.size, notes=blade.notes + notes)


def galerkin_system(blade: Blade, terms: Sequence[int] = PAPER_TERMS,
                    basis: Basis = "jacobi") -> tuple[GalerkinMatrices, tuple[str, ...]]:
    """Matrices ``M, K0, K2`` of ``blade`` with ``terms = (N_w, N_v, N_phi)`` and the modelling notes."""
    if basis not in BASES:
        raise InputError(f"unknown Galerkin basis '{basis}' (choose from {', '.join(BASES)})", field="basis")
    if blade.curved:
        raise InputError("the Galerkin model is a straight beam: a curved reference axis (prebend, sweep) is not "
                         "modelled (--straight-axis straightens it; the finite elements take the curve)",
                         field="--method")
    chosen, notes = model_terms(blade, terms)
    return galerkin_matrices(blade, chosen, basis), notes


def galerkin_modes(blade: Blade, rpm: float = 0.0, n_modes: int = 10, terms: tuple[int, int, int] = PAPER_TERMS,
                   basis: Basis = "jacobi") -> ModalResult:
    """Natural modes of a cantilever ``blade`` at rotor speed ``rpm`` (rpm) by the Galerkin method.

    ``terms = (N_w, N_v, N_phi)``: numbers of flap, lead-lag and torsion shape functions (the seed paper uses
    5, 5, 3). ``vectors`` of the result are the M-normalised coefficient vectors ``(a, b, c)``.
    """
    matrices, notes = galerkin_system(blade, terms, basis)
    return solve(blade, matrices, rpm, n_modes, notes)


def mac(previous: NDArray, current: NDArray, M: NDArray) -> NDArray:
    """Modal assurance criterion between two sets of coefficient vectors, with the mass matrix as metric."""
    cross = previous.T @ M @ current
    norms = np.einsum("ij,ij->j", previous, M @ previous)[:, None] * np.einsum("ij,ij->j", current, M @ current)
    return cross**2 / norms


def galerkin_campbell(blade: Blade, rpm_values: Sequence[float], n_modes: int = 6,
                      terms: tuple[int, int, int] = PAPER_TERMS, basis: Basis = "jacobi") -> CampbellResult:
    """Modes over rotor speeds ``rpm_values`` (rpm), the lowest ``n_modes`` of the first speed followed by MAC."""
    matrices, notes = galerkin_system(blade, terms, basis)
    rpm = np.asarray(rpm_values, dtype=float)
    results = [solve(blade, matrices, speed, matrices.terms.size, notes) for speed in rpm]
    count = min(n_modes, matrices.terms.size)
    indices = np.zeros((len(rpm), count), dtype=np.int64)
    macs = np.ones((len(rpm), count))
    indices[0] = np.arange(count)
    for k in range(1, len(rpm)):
        similarity = mac(results[k - 1].vectors[:, indices[k - 1]], results[k].vectors, matrices.M)
        rows, cols = linear_sum_assignment(-similarity)
        indices[k, rows], macs[k, rows] = cols, similarity[rows, cols]
    families = [ModeFamily(kind=results[0].modes[f].kind,
                           frequencies_hz=np.array([results[k].modes[indices[k, f]].frequency_hz
                                                    for k in range(len(rpm))]),
                           indices=indices[:, f], mac=macs[:, f]) for f in range(count)]
    return CampbellResult(rpm=rpm, families=families, results=results, notes=blade.notes + notes)
