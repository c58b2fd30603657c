"""Self-check: finite elements, the Galerkin model and closed-form or published references side by side.

Each row compares one frequency (nondimensional ``omega sqrt(m L^4 / EI)`` for the uniform cases, Hz for the
NREL 5MW blade) from up to three independent sources: a closed form or published table, the finite-element solver
and the Galerkin model. ``difference`` is the largest relative difference between any two of them; a row is ``ok``
when it stays within ``bound``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import InputError
from .modal.results import ModalResult
from .models.galerkin import galerkin_modes, galerkin_system, solve
from .sections import Blade, SectionTable, TipMass

__all__ = ["NREL5MW_MAIN", "VerifyRow", "format_table", "nrel5mw_rows", "uniform_rows", "verification_rows"]

Solver = Callable[..., ModalResult]

#: Default NREL 5MW input (ElastoDyn main file of the land-based turbine, with AdjBlMs, HubRad and PreCone),
#: installed with the package (bladefem/data), so that the self-check runs from any installation.
NREL5MW_MAIN = Path(__file__).resolve().parent / "data" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
#: Uniform cases: FE (mesh converged to 1e-6) and a 14-term Galerkin agree to ~1e-7; the references are given to
#: 6-7 digits (rounding up to 1.4e-6). The issue's acceptance: Galerkin-FE 1e-5, Galerkin-table 1e-4.
UNIFORM_BOUND = 1e-5
#: NREL 5MW: the acceptance bound between FE and the converged (40-term) Galerkin model.
NREL5MW_BOUND = 1e-3
UNIFORM_TERMS = (14, 14, 6)
NREL5MW_TERMS = (40, 40, 0)

CANTILEVER_ROOTS = (1.87510407, 4.69409113, 7.85475744)
ROTATING_FLAP = {6.0: (7.36037, 26.80908, 66.68391), 12.0: (13.17015, 37.60311, 79.61448)}
TIP_MASS_MU1 = (1.557298, 16.25009, 50.89584)
SOUTHWELL_K1 = 1.193336


@dataclass(frozen=True)
class VerifyRow:
    """One check: a frequency from a reference, the FE and the Galerkin model (any may be None)."""

    case: str
    quantity: str
    reference: float | None
    fe: float | None
    galerkin: float | None
    bound: float

    @property
    def difference(self) -> float:
        """Largest relative difference between any two of the available values."""
        values = np.array([v for v in (self.reference, self.fe, self.galerkin) if v is not None])
        return float((values.max() - values.min()) / np.abs(values).min()) if values.size > 1 else float("nan")

    @property
    def ok(self) -> bool:
        return bool(self.difference <= self.bound)


def uniform_blade(edge_stiffness: float = 4.0, **options) -> Blade:
    """m = EI = L = 1 (so Omega is lambda and omega is w), GJ = 0.01, i_flap = 1e-4, i_edge = 1e-3."""
    sections = SectionTable(span=np.array([0.0, 1.0]), mass=1.0, flap_stiffness=1.0, edge_stiffness=edge_stiffness,
                            torsion_stiffness=0.01, flap_inertia=1e-4, edge_inertia=1e-3)
    return Blade(sections, name="uniform", **options)


def rigid_section_uniform_blade(edge_stiffness: float = 4.0, **options) -> Blade:
    """The uniform blade without section inertias (the beam of the published tables), rigid torsion."""
    sections = SectionTable(span=np.array([0.0, 1.0]), mass=1.0, flap_stiffness=1.0, edge_stiffness=edge_stiffness)
    return Blade(sections, name="uniform", **options)


def rpm_of(omega: float) -> float:
    return omega * 30.0 / np.pi


def omegas(result: ModalResult, kind: str, count: int) -> list[float]:
    """The first ``count`` circular frequencies (rad/s) of one kind."""
    return [2 * np.pi * mode.frequency_hz for mode in result.modes if mode.kind == kind][:count]


def both(fe: Solver, blade: Blade, rpm: float, n_modes: int, terms: tuple[int, int, int]):
    return fe(blade, rpm, n_modes), galerkin_modes(blade, rpm, n_modes, terms)


def bending_rows(case: str, kind: str, reference, fe_result, g_result) -> list[VerifyRow]:
    fe_values, g_values = omegas(fe_result, kind, len(reference)), omegas(g_result, kind, len(reference))
    return [VerifyRow(case, f"w{n + 1} {kind}", ref, f, g, UNIFORM_BOUND)
            for n, (ref, f, g) in enumerate(zip(reference, fe_values, g_values))]


def uniform_rows(fe: Solver) -> list[VerifyRow]:
    """Closed forms and published tables on the uniform blade (R = 0, no precone)."""
    terms = UNIFORM_TERMS
    rows = bending_rows("cantilever at rest", "flap", [b**2 for b in CANTILEVER_ROOTS],
                        *both(fe, rigid_section_uniform_blade(), 0.0, 6, terms))
    for lam, table in ROTATING_FLAP.items():
        rows += bending_rows(f"rotating, lambda={lam:g}", "flap", table,
                             *both(fe, rigid_section_uniform_blade(), rpm_of(lam), 6, terms))
    lam = 12.0
    lag = [np.sqrt(w**2 - lam**2) for w in ROTATING_FLAP[lam]]   # omega_lag^2 = omega_flap^2(EI_lag) - Omega^2
    rows += bending_rows(f"lag, lambda={lam:g}", "edge", lag,
                         *both(fe, rigid_section_uniform_blade(edge_stiffness=1.0), rpm_of(lam), 6, terms))
    rows += bending_rows("tip mass mu=1", "flap", TIP_MASS_MU1,
                         *both(fe, rigid_section_uniform_blade(tip_mass=TipMass(1.0)), 0.0, 6, terms))
    return rows + [torsion_row(fe), southwell_row(fe)]


def torsion_row(fe: Solver, lam: float = 6.0) -> VerifyRow:
    """First torsion frequency with the propeller moment: omega^2 = omega_0^2 + Omega^2 (i_e - i_f) / (i_e + i_f)."""
    i_flap, i_edge, GJ = 1e-4, 1e-3, 0.01
    polar = i_flap + i_edge
    reference = np.sqrt((np.pi / 2) ** 2 * GJ / polar + lam**2 * (i_edge - i_flap) / polar)
    fe_result, g_result = both(fe, uniform_blade(edge_stiffness=40.0), rpm_of(lam), 10, UNIFORM_TERMS)
    return VerifyRow(f"torsion, lambda={lam:g}", "w1 torsion", float(reference), omegas(fe_result, "torsion", 1)[0],
                     omegas(g_result, "torsion", 1)[0], UNIFORM_BOUND)


def southwell_row(fe: Solver, lam: float = 0.25) -> VerifyRow:
    """First flap Southwell coefficient, the limit of (omega^2 - omega_0^2) / Omega^2 for Omega -> 0.

    The quotient is K1 + c lambda^2 + O(lambda^4); Richardson extrapolation from lambda and 2 lambda removes the
    lambda^2 term while keeping omega^2 - omega_0^2 large against the solvers' round-off.
    """
    blade = rigid_section_uniform_blade()

    def coefficient(solver: Solver, **options) -> float:
        rest = omegas(solver(blade, 0.0, 2, **options), "flap", 1)[0]
        quotient = [(omegas(solver(blade, rpm_of(speed), 2, **options), "flap", 1)[0] ** 2 - rest**2) / speed**2
                    for speed in (lam, 2 * lam)]
        return (4 * quotient[0] - quotient[1]) / 3

    return VerifyRow("Southwell, lambda->0", "K1 flap", SOUTHWELL_K1, coefficient(fe),
                     coefficient(galerkin_modes, terms=UNIFORM_TERMS), UNIFORM_BOUND)


def nrel5mw_blade(path: str | Path = NREL5MW_MAIN) -> Blade:
    """The NREL 5MW blade from an ElastoDyn main file."""
    from .builders.elastodyn_blade import blade_from_elastodyn_main
    if not Path(path).is_file():
        raise InputError("NREL 5MW ElastoDyn main file not found", file=str(path), field="--nrel5mw")
    return blade_from_elastodyn_main(path)


def nrel5mw_rows(fe: Solver, path: str | Path = NREL5MW_MAIN, rpm_values=(0.0, 12.1)) -> list[VerifyRow]:
    """FE against the converged Galerkin model on the NREL 5MW blade: first four (bending) modes, Hz."""
    blade = nrel5mw_blade(path)
    matrices, notes = galerkin_system(blade, NREL5MW_TERMS)
    rows = []
    for rpm in rpm_values:
        fe_result, g_result = fe(blade, rpm, 4), solve(blade, matrices, rpm, 4, notes)
        for n, (f, g) in enumerate(zip(fe_result.modes, g_result.modes)):
            quantity = f"mode {n + 1} {f.kind}" + ("" if f.kind == g.kind else f" / {g.kind}")
            rows.append(VerifyRow(f"NREL 5MW, {rpm:g} rpm", f"{quantity} (Hz)", None, f.frequency_hz,
                                  g.frequency_hz if f.kind == g.kind else float("nan"), NREL5MW_BOUND))
    return rows


def verification_rows(fe: Solver | None = None, nrel5mw: str | Path = NREL5MW_MAIN) -> list[VerifyRow]:
    """All checks. ``fe``: the finite-element solver ``modes(blade, rpm, n_modes)`` (default bladefem.modal)."""
    if fe is None:
        from .modal import modes as fe
    return uniform_rows(fe) + nrel5mw_rows(fe, nrel5mw)


def _number(value: float | None, width: int) -> str:
    return f"{'-':>{width}}" if value is None else f"{value:>{width}.7g}"


def format_table(rows: list[VerifyRow]) -> str:
    """The rows as a plain-text table, with a closing summary line."""
    header = (f"{'case':<24} {'quantity':<20} {'reference':>12} {'FE':>12} {'Galerkin':>12} {'difference':>10} "
              f"{'bound':>7}  ok")
    lines = [header, "-" * len(header)]
    for row in rows:
        lines.append(f"{row.case:<24} {row.quantity:<20} {_number(row.reference, 12)} {_number(row.fe, 12)} "
                     f"{_number(row.galerkin, 12)} {row.difference:>10.2e} {row.bound:>7.0e}  "
                     f"{'yes' if row.ok else 'NO'}")
    failed = sum(not row.ok for row in rows)
    lines.append("-" * len(header))
    lines.append(f"{failed} of {len(rows)} checks outside their bounds" if failed
                 else f"all {len(rows)} checks within their bounds")
    return "\n".join(lines)
