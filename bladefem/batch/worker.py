"""Run one case, in-process or as a Dask task: the result rows (one per mode, family and speed, or requirement).

Base models are read once per worker process, and the matrices of cases that share a structure (same inputs
apart from the rotor speed of a fixed mesh, or the analysis) are assembled once per worker.
"""

from __future__ import annotations

import hashlib
import json
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np

from .bundle import Bundle, materialize
from .cases import Case, apply_inputs, file_digest
from .turbine import TURBINE_ANALYSES, check_turbine_case

#: matrices kept per worker process (each a few MB for a converged blade)
MATRIX_CACHE_SIZE = 8
_matrices: dict[tuple, Any] = {}


@lru_cache(maxsize=16)
def _base(model: str, main: str | None, digest: str) -> Any:
    from ..check.models import read_structure
    return read_structure(Path(model), None if main is None else Path(main))


def structure_of(case: Case) -> Any:
    """The case's blade or tower: the base model (read once per worker) with the case's inputs applied."""
    model = Path(case.inputs.get("file", case.model))
    main = None if case.elastodyn_main is None else str(case.elastodyn_main)
    base = _base(str(model), main, file_digest(model))
    return apply_inputs(base, {k: v for k, v in case.inputs.items() if k != "file"})


def _structure_key(case: Case) -> str:
    inputs = {k: (np.asarray(v).tolist() if isinstance(v, np.ndarray) else v) for k, v in case.inputs.items()
              if k != "rpm"}
    model = Path(case.inputs.get("file", case.model))
    return hashlib.sha256(json.dumps([file_digest(model), str(case.elastodyn_main), inputs],
                                     sort_keys=True).encode()).hexdigest()


def blade_matrices_cached(case: Case, blade: Any, mesh_rpm: float) -> Any:
    """The blade's matrices as :func:`bladefem.modal.blade_matrices` builds them (same mesh, same numbers),
    assembled once per worker for cases that share the structure and mesh."""
    from ..modal import blade_matrices
    analysis = case.analysis
    key = (_structure_key(case), analysis.elements, analysis.n_modes,
           None if analysis.elements is not None else mesh_rpm)
    if key not in _matrices:
        if len(_matrices) >= MATRIX_CACHE_SIZE:
            _matrices.pop(next(iter(_matrices)))
        _matrices[key] = blade_matrices(blade, analysis.elements, analysis.n_modes, mesh_rpm)
    return _matrices[key]


def _names(kinds: list[str]) -> list[str]:
    from ..check.models import ordinal_names
    return ordinal_names(kinds)


def _modes_rows(case: Case, structure: Any) -> list[dict[str, Any]]:
    analysis = case.analysis
    rpm = float(case.inputs.get("rpm", analysis.rpm))
    if hasattr(structure, "precone"):
        from ..modal import solve_modes
        matrices = blade_matrices_cached(case, structure, rpm)
        result = solve_modes(matrices, rpm, analysis.n_modes, structure.notes + matrices.notes)
    else:
        from ..models.tower import tower_modes
        result, rpm = tower_modes(structure, analysis.n_modes, analysis.elements), 0.0
    return [{"rpm": rpm, "mode": i + 1, "name": name, "kind": mode.kind, "frequency_hz": mode.frequency_hz,
             "residual": mode.residual}
            for i, (name, mode) in enumerate(zip(_names(result.kinds), result.modes))]


def _campbell_rows(case: Case, structure: Any) -> list[dict[str, Any]]:
    from ..modal import campbell_sweep
    start, stop, count = case.analysis.sweep
    speeds = np.linspace(start, stop, count)
    if not hasattr(structure, "precone"):
        raise ValueError("a campbell analysis needs a blade")
    matrices = blade_matrices_cached(case, structure, float(np.max(speeds)))
    sweep = campbell_sweep(matrices, speeds, case.analysis.n_modes, structure.notes + matrices.notes)
    names = _names([family.kind for family in sweep.families])
    return [{"rpm": float(speed), "mode": f + 1, "name": name, "kind": family.kind,
             "frequency_hz": float(frequency)}
            for f, (name, family) in enumerate(zip(names, sweep.families))
            for speed, frequency in zip(speeds, family.frequencies_hz)]


def _check_rows(case: Case, structure: Any) -> list[dict[str, Any]]:
    from ..check import read_spec
    from ..check.evaluate import evaluate_requirement
    from ..check.models import ModelRun
    spec = read_spec(case.analysis.spec)
    model = spec.models[case.analysis.spec_model]
    run = ModelRun(model)
    run.__dict__["structure"] = structure                  # the case's model in place of the spec's input
    rows = []
    for req in spec.requirements:
        if req.model == model.name and req.kind != "baseline":
            rows += [{"requirement": o.requirement, "check": o.check, "passed": o.passed, "measured": o.measured,
                      "margin": o.margin, "unit": o.unit} for o in evaluate_requirement(run, req)]
    return rows


def _standstill_rows(case: Case, structure: Any) -> list[dict[str, Any]]:
    from .standstill import standstill_rows
    return standstill_rows(case, structure)


def _flutter_rows(case: Case, structure: Any) -> list[dict[str, Any]]:
    from .flutter import flutter_rows
    return flutter_rows(case, structure)


ANALYSES = {"modes": _modes_rows, "campbell": _campbell_rows, "check": _check_rows, "standstill": _standstill_rows,
            "flutter": _flutter_rows}


def input_columns(case: Case) -> dict[str, Any]:
    """The varied inputs as result columns (a per-station factor as its spanwise mean and the station list)."""
    columns: dict[str, Any] = {}
    for key, value in case.inputs.items():
        if isinstance(value, np.ndarray | list) and key != "file":
            columns[key] = float(np.mean(value))
            columns[f"{key}_stations"] = [float(v) for v in value]
        else:
            columns[key] = value
    return columns


def localized(case: Case, root: Path) -> Case:
    """The case with its input paths moved to the worker's copy of its bundle under ``root``."""
    from dataclasses import replace

    from .bundle import mirrored
    inputs = {**case.inputs, "file": str(mirrored(root, case.inputs["file"]))} if "file" in case.inputs \
        else case.inputs
    analysis = case.analysis if case.analysis.spec is None else \
        replace(case.analysis, spec=mirrored(root, case.analysis.spec))
    if analysis.aerodyn is not None:
        analysis = replace(analysis, aerodyn=mirrored(root, analysis.aerodyn))
    return replace(case, model=mirrored(root, case.model), inputs=inputs, analysis=analysis,
                   elastodyn_main=None if case.elastodyn_main is None else mirrored(root, case.elastodyn_main))


def run_case(case: Case, bundle: Bundle | None = None) -> list[dict[str, Any]]:
    """The result rows of one case; a failure gives one row with status 'error' and its message. With its
    ``bundle`` the case runs on the worker's copy of its input files (messages name the client's paths)."""
    head = {"case_index": case.index, "case_hash": case.hash, **input_columns(case)}
    root = None
    try:
        if bundle is not None:
            if bundle.digest != case.bundle:
                raise ValueError(f"case {case.index} was given the input files of another case")
            root = materialize(bundle)
            case = localized(case, root)
        if case.analysis.type in TURBINE_ANALYSES:
            check_turbine_case(case)
            rows = TURBINE_ANALYSES[case.analysis.type](case)
        else:
            rows = ANALYSES[case.analysis.type](case, structure_of(case))
    except Exception as error:                               # recorded, and the batch goes on
        message = f"{type(error).__name__}: {error}"
        if root is not None:
            message = message.replace(str(root), "")
        if bundle is not None and bundle.error is not None:     # the client's reader failed: its message is the cause
            message = bundle.error
        return [{**head, "status": "error", "error": message}]
    return [{**head, "status": "ok", "error": None, **row} for row in rows]
