"""Design checks for CI: a spec of models and modal requirements (frequency windows, resonance margins against
rotor harmonics, the tower's soft-stiff band, regression against a baseline, ElastoDyn coefficients still
representing the FE modes), evaluated to PASS/FAIL outcomes with JUnit XML and JSON outputs.

    from bladefem.check import run_check
    outcomes = run_check("cases/nrel5mw_check.yaml")
    assert all(o.passed for o in outcomes)
"""

from __future__ import annotations

from pathlib import Path

from .evaluate import Outcome, evaluate
from .spec import ModelSpec, Requirement, Spec, read_spec


def run_check(spec_path: str | Path, update_baseline: bool = False) -> list[Outcome]:
    """Read the spec at ``spec_path`` and evaluate every requirement (see :func:`evaluate`)."""
    return evaluate(read_spec(spec_path), update_baseline)


__all__ = ["ModelSpec", "Outcome", "Requirement", "Spec", "evaluate", "read_spec", "run_check"]
