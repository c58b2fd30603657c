"""Baseline files of a regression requirement: stored frequencies and mode shapes, compared by relative frequency
change and MAC.

A baseline file is JSON: ``{"format": "bladefem-baseline-1", "entries": [{"model", "rpm", "modes": [{"name",
"frequency_hz", "shape": {"x_m", "flap", "edge", "twist_rad"}}]}]}``; several models (or speeds) share a file, one
entry each. Shapes are sampled at :data:`SHAPE_POINTS` evenly spaced span (or height) positions.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError
from ..files import write_atomic
from ..modal.results import Mode

FORMAT = "bladefem-baseline-1"
SHAPE_POINTS = 21
COMPONENTS = ("flap", "edge", "twist")


def shape_samples(mode: Mode) -> dict[str, list[float]]:
    """The mode's flap, edge and twist at evenly spaced positions along the beam (m)."""
    x = np.linspace(mode.shape.x[0], mode.shape.x[-1], SHAPE_POINTS)
    values = mode.shape.at(x)
    return {"x_m": x.tolist(), **{f"{c}_rad" if c == "twist" else c: values[c].tolist() for c in COMPONENTS}}


def shape_vector(samples: dict[str, list[float]]) -> np.ndarray:
    return np.concatenate([np.asarray(samples["twist_rad" if c == "twist" else c], dtype=float) for c in COMPONENTS])


def mac(a: np.ndarray, b: np.ndarray) -> float:
    """Modal assurance criterion of two sampled shapes: (a.b)^2 / ((a.a)(b.b))."""
    return float(np.dot(a, b) ** 2 / (np.dot(a, a) * np.dot(b, b)))


def read_entries(path: Path) -> list[dict[str, Any]]:
    """The entries of a baseline file ([] when it does not exist)."""
    if not path.exists():
        return []
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as error:
        raise InputError(f"cannot read baseline file ({error})", file=str(path)) from None
    if not isinstance(data, dict) or data.get("format") != FORMAT or not isinstance(data.get("entries"), list):
        raise InputError(f"not a bladefem baseline file (expected \"format\": \"{FORMAT}\")", file=str(path))
    return data["entries"]


def find_entry(path: Path, model: str, rpm: float) -> dict[str, Any]:
    for entry in read_entries(path):
        if entry.get("model") == model and float(entry.get("rpm", -1)) == float(rpm):
            return entry
    raise InputError(f"no baseline for model '{model}' at {rpm:g} rpm: create it with --update-baseline",
                     file=str(path))


def store_entry(path: Path, model: str, rpm: float, modes: dict[str, Mode]) -> None:
    """Write (or replace) the entry of ``model`` at ``rpm`` in the baseline file, atomically; others are kept."""
    entries = [e for e in read_entries(path) if not (e.get("model") == model and float(e.get("rpm", -1)) == rpm)]
    entries.append({"model": model, "rpm": rpm,
                    "modes": [{"name": name, "frequency_hz": mode.frequency_hz, "shape": shape_samples(mode)}
                              for name, mode in modes.items()]})
    entries.sort(key=lambda e: (e["model"], e["rpm"]))
    write_atomic(path, json.dumps({"format": FORMAT, "entries": entries}, indent=1) + "\n")
