"""Results as plain data (the CLI's ``--json``) and atomic file writing."""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from ..files import write_atomic
from ..modal import CampbellResult, ModalResult

__all__ = ["campbell_to_dict", "dumps", "modal_to_dict", "tower_campbell_to_dict", "write_atomic"]


def _floats(values: np.ndarray) -> list[float]:
    return [float(v) for v in np.asarray(values).ravel()]


def modal_to_dict(result: ModalResult, method: str = "fe") -> dict[str, Any]:
    """``{"frequencies_hz": [...], "modes": [{"frequency_hz", "kind", ...}], ...}``; shapes at the stations."""
    modes = []
    for mode in result.modes:
        shape = mode.shape.at(result.stations)
        modes.append({
            "frequency_hz": mode.frequency_hz,
            "kind": mode.kind,
            "energy_fractions": mode.energy_fractions,
            "residual": mode.residual,
            "shape": {"x_m": _floats(result.stations), "flap": _floats(shape["flap"]),
                      "flap_slope": _floats(shape["flap_slope"]), "edge": _floats(shape["edge"]),
                      "edge_slope": _floats(shape["edge_slope"]), "twist_rad": _floats(shape["twist"]),
                      "axial": _floats(shape["axial"])},
        })
        if mode.damping_ratio is not None:
            modes[-1].update(damping_ratio=mode.damping_ratio, damped_frequency_hz=mode.damped_frequency_hz)
    return {"method": method, "rotor_speed_rpm": result.rotor_speed_rpm,
            "frequencies_hz": _floats(result.frequencies_hz), "modes": modes, "n_dofs": result.n_dofs,
            "notes": list(result.notes)}


def campbell_to_dict(result: CampbellResult) -> dict[str, Any]:
    """``{"rpm": [...], "families": [{"kind", "frequencies_hz": [...], "min_mac"}], "notes": [...]}``."""
    families = []
    for family in result.families:
        families.append({"kind": family.kind, "frequencies_hz": _floats(family.frequencies_hz),
                         "min_mac": float(family.mac.min())})
        if family.damping_ratios is not None:
            families[-1]["damping_ratios"] = _floats(family.damping_ratios)
    return {"rpm": _floats(result.rpm), "families": families, "notes": list(result.notes)}


def tower_campbell_to_dict(chart: Any) -> dict[str, Any]:
    """A tower's rotor-speed chart (:class:`bladefem.models.tower_campbell.TowerCampbell`): the modes, the 1P and
    blade-passing bands (Hz) over the operating range (rpm), the bands each mode hits and the classification."""
    return {"rpm": _floats(chart.rpm), "operating_rpm": list(chart.operating_rpm), "blades": chart.blades,
            "margin": chart.margin,
            "bands": [{"harmonic": band.harmonic, "low_hz": band.low_hz, "high_hz": band.high_hz}
                      for band in chart.bands],
            "modes": [{"frequency_hz": mode.frequency_hz, "kind": mode.kind, "bands_hit": chart.bands_hit(mode)}
                      for mode in chart.modes.modes],
            "first_bending_hz": chart.first_bending.frequency_hz, "verdict": chart.verdict,
            "statement": chart.statement(), "notes": list(chart.modes.notes)}


def dumps(data: dict[str, Any]) -> str:
    return json.dumps(data, indent=2)
