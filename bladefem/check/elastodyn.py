"""The ``elastodyn`` requirement: the mode-shape polynomials in an ElastoDyn blade or tower file still represent the
finite-element modes, judged by the frequency ElastoDyn derives from each polynomial against the FE frequency."""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from ..builders.detect import detect_format
from ..builders.elastodyn_blade import read_elastodyn_blade
from ..formats.elastodyn_main import read_elastodyn_main
from ..builders.elastodyn_tower import read_elastodyn_tower
from .models import ModelRun
from .spec import Requirement

if TYPE_CHECKING:
    from .evaluate import Outcome


def _file_coefficients(run: ModelRun, req: Requirement):
    """(main file or None, coefficient file, its coefficients) for the model's input."""
    kind = detect_format(run.spec.input)
    main_path = run.spec.input if kind == "elastodyn-main" else run.spec.elastodyn_main
    main = read_elastodyn_main(main_path) if main_path else None
    if kind == "elastodyn-main":
        source = main.blade_files[0]
    elif kind in ("elastodyn-blade", "elastodyn-tower"):
        source = run.spec.input
    else:
        raise req.error(f"needs an ElastoDyn main, blade or tower file; '{run.spec.name}' is a {kind} input")
    read = read_elastodyn_tower if kind == "elastodyn-tower" else read_elastodyn_blade
    return main, source, read(source).modes


def elastodyn_verdicts(run: ModelRun, req: Requirement) -> Iterator[Outcome]:
    """One outcome per polynomial of the file (blade flap 1, flap 2, edge 1; tower fore-aft and side-side 1, 2)."""
    from ..modal.elastodyn_fit import blade_coefficients
    from ..models.tower_fit import tower_coefficients
    from .evaluate import Outcome

    main, source, shipped = _file_coefficients(run, req)
    tolerance = req.parameters["tolerance_percent"]
    if run.is_blade:
        rpm = req.parameters.get("rpm", main.rotor_speed_rpm if main else 0.0)
        nodes = main.blade_nodes if main else 17
        result = blade_coefficients(run.structure, rpm, nodes=nodes, elements=run.spec.elements, shipped=shipped)
        speed = f" at {rpm:g} rpm"
    else:
        nodes = main.tower_nodes if main else 20
        result = tower_coefficients(run.structure, nodes=nodes, elements=run.spec.elements, shipped=shipped)
        speed = ""
    for name, fit in (result.shipped or {}).items():
        difference = 100 * (fit.elastodyn_frequency_hz / fit.fe_frequency_hz - 1)
        yield Outcome(req.name, f"{fit.label} polynomial in {source.name}{speed}", abs(difference) <= tolerance,
                      difference, f"|diff| <= {tolerance:g} %", tolerance - abs(difference), "%",
                      f"ElastoDyn {fit.elastodyn_frequency_hz:.5g} Hz vs FE {fit.fe_frequency_hz:.5g} Hz "
                      f"(fit rms error {fit.fit.rms_error:.2e})")
