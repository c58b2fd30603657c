"""Baseline files of a regression requirement: stored frequencies and mode shapes, compared by relative frequency
change and MAC.

A baseline file is JSON: ``{"format": "bladefem-baseline-1", "entries": [{"model", "rpm", "modes": [{"name",
"frequency_hz", "shape": {"x_m", "flap", "edge", "twist_rad"}}]}]}``; several models (or speeds) share a file, one
entry each. Shapes are sampled at :data:`SHAPE_POINTS` evenly spaced span (or height) positions.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError
from ..files import write_atomic
from ..formats.yamlnodes import load_yaml
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
    """The entries of a baseline file ([] when it does not exist), each checked: an :class:`InputError` names the
    file, line and field of the first value that is missing, of the wrong kind, not finite or out of range. (JSON
    is read by the line-keeping YAML reader, of which it is a subset.)"""
    if not os.path.lexists(path):
        return []
    data, lines = load_yaml(path)

    def error(message: str, *key: Any) -> InputError:
        field = "".join(f"[{k}]" if isinstance(k, int) else f".{k}" for k in key).lstrip(".")
        return InputError(message, file=str(path), line=lines.get(key, lines.get(key[:-1])), field=field or None)

    if not isinstance(data, dict) or data.get("format") != FORMAT or not isinstance(data.get("entries"), list):
        raise error(f"not a bladefem baseline file (expected \"format\": \"{FORMAT}\" and a list \"entries\")")
    for i, entry in enumerate(data["entries"]):
        _check_entry(entry, ("entries", i), error)
    return data["entries"]


def _check_entry(entry: Any, key: tuple, error) -> None:
    if not isinstance(entry, dict):
        raise error("expected a mapping with model, rpm and modes", *key)
    if not isinstance(entry.get("model"), str):
        raise error("expected the model's name (text)", *key, "model")
    _number(entry.get("rpm"), (*key, "rpm"), error, low=0.0)
    modes = entry.get("modes")
    if not isinstance(modes, list):
        raise error("expected a list of modes", *key, "modes")
    for m, mode in enumerate(modes):
        where = (*key, "modes", m)
        if not isinstance(mode, dict) or not isinstance(mode.get("name"), str):
            raise error("expected a mode with a name, frequency_hz and shape", *where)
        _number(mode.get("frequency_hz"), (*where, "frequency_hz"), error, low=0.0, strict=True)
        shape = mode.get("shape")
        if not isinstance(shape, dict):
            raise error("expected the shape: x_m, flap, edge, twist_rad", *where, "shape")
        for name in ("x_m", "flap", "edge", "twist_rad"):
            values = shape.get(name)
            if not isinstance(values, list) or len(values) != SHAPE_POINTS:
                got = f"{len(values)} values" if isinstance(values, list) else shown_kind(values)
                raise error(f"expected a list of {SHAPE_POINTS} numbers, got {got}", *where, "shape", name)
            for v, value in enumerate(values):
                _number(value, (*where, "shape", name, v), error)
        if not any(value != 0 for name in ("flap", "edge", "twist_rad") for value in shape[name]):
            raise error("the shape is zero everywhere (no MAC can be computed)", *where, "shape")


def shown_kind(value: Any) -> str:
    return "nothing" if value is None else f"{type(value).__name__} {json.dumps(value)[:20]}"


def _number(value: Any, key: tuple, error, low: float | None = None, strict: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise error(f"expected a number, got {shown_kind(value)}", *key)
    number = float(value)
    if not math.isfinite(number) or abs(number) > 1e30:
        raise error(f"expected a finite number of magnitude below 1e30, got {value}", *key)
    if low is not None and (number < low or strict and number == low):
        raise error(f"must be {'greater than' if strict else 'at least'} {low:g}, got {value}", *key)
    return number


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
    write_atomic(path, json.dumps({"format": FORMAT, "entries": entries}, indent=1) + "\n", replaces_input=True)
