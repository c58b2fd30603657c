"""Random samples of a batch plan: each property's multiplicative factors at the blade stations, from a normal,
lognormal or uniform distribution, fully correlated along the span or a Gaussian field with an exponential
correlation length."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError


def correlated_normals(rng: np.random.Generator, stations: np.ndarray, length: float | None) -> np.ndarray:
    """Standard normal values at the station positions (fractions of the span): one shared value when
    ``length`` is None (fully correlated), else a Gaussian field with correlation exp(-|dx| / length)."""
    if length is None:
        return np.full(len(stations), rng.standard_normal())
    covariance = np.exp(-np.abs(stations[:, None] - stations[None, :]) / length)
    return np.linalg.cholesky(covariance + 1e-12 * np.eye(len(stations))) @ rng.standard_normal(len(stations))


def factors(spec: dict[str, Any], z: np.ndarray) -> np.ndarray:
    """Multiplicative factors from standard normal values ``z`` for one property's distribution."""
    kind = spec["distribution"]
    if kind == "normal":
        return 1.0 + spec.get("std_percent", 5.0) / 100.0 * z
    if kind == "lognormal":
        return np.exp(spec.get("sigma", 0.05) * z)
    from scipy.special import ndtr               # uniform: the normal's probability, mapped to the interval
    return 1.0 + spec.get("half_width_percent", 5.0) / 100.0 * (2.0 * ndtr(z) - 1.0)


def sample_cases(samples: dict[str, Any], base: Path, stations: np.ndarray) -> list[dict[str, Any]]:
    """The scale factors of each sampled case (``samples`` of a plan, ``base`` the plan file for errors)."""
    rng = np.random.default_rng(int(samples["seed"]))
    cases = []
    for _ in range(samples["count"]):
        inputs: dict[str, Any] = {}
        for name, spec in samples["properties"].items():
            field_ = factors(spec, correlated_normals(rng, stations, spec.get("correlation_length")))
            if np.any(field_ <= 0):
                raise InputError(f"a sampled factor of '{name}' is not positive: narrow the distribution",
                                 file=str(base), field=f"samples.properties.{name}")
            inputs[f"{name}_scale"] = field_ if spec.get("correlation_length") else float(field_[0])
        cases.append(inputs)
    return cases
