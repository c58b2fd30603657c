"""Evaluate the requirements of a spec: one :class:`Outcome` per checked quantity (a requirement on several modes
or harmonics gives one outcome for each)."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

from . import baseline
from .margins import harmonic_margin, window_distance
from .models import ModelRun
from .spec import Requirement, Spec

DEFAULT_MIN_MAC = 0.95
DEFAULT_BASELINE_MODES = 4
DEFAULT_TOWER_MODES = ("fore-aft 1", "side-side 1")


@dataclass(frozen=True)
class Outcome:
    """The result of checking one quantity.

    requirement : the requirement's name
    check : what was checked, e.g. 'flap 1 vs 3P'
    passed : whether the requirement holds
    measured : the measured value (in ``unit``)
    limit : the limit it is held to, as text with its unit
    margin : how far the measured value is inside the limit (negative: outside), in ``unit``
    unit : unit of ``measured`` and ``margin``
    detail : where and how (speed of the worst point, values there)
    """

    requirement: str
    check: str
    passed: bool
    measured: float
    limit: str
    margin: float
    unit: str
    detail: str = ""


def _found(req: Requirement, field: str, lookup: Callable[..., Any], *args: Any) -> Any:
    """``lookup(*args)``, a missing mode reported at the requirement's line in the spec."""
    try:
        return lookup(*args)
    except LookupError as error:
        raise req.error(str(error.args[0]), field) from None


def _window(run: ModelRun, req: Requirement) -> Iterator[Outcome]:
    p = req.parameters
    low, high = p["hz"]
    if p.get("rpm") == "operating":
        curve = _found(req, "mode", run.curve, p["mode"])
        distance, k = window_distance(curve.frequency_hz, low, high)
        frequency, speed = curve.frequency_hz[k], curve.rpm[k]
        span = f"over {curve.rpm[0]:g}-{curve.rpm[-1]:g} rpm"
    else:
        speed = float(p.get("rpm", 0.0))
        frequency = _found(req, "mode", run.mode, p["mode"], speed).frequency_hz
        distance, _ = window_distance(np.array([frequency]), low, high)
        span = f"at {speed:g} rpm"
    yield Outcome(req.name, f"{p['mode']} {span}", distance >= 0, float(frequency), f"[{low:g}, {high:g}] Hz",
                  distance, "Hz", f"{p['mode']} = {frequency:.5g} Hz at {speed:.4g} rpm")


def _resonance(run: ModelRun, req: Requirement) -> Iterator[Outcome]:
    p = req.parameters
    limit = p["margin_percent"]
    for name in p["modes"]:
        curve = _found(req, "modes", run.curve, name)
        for n in p["harmonics"]:
            worst = harmonic_margin(curve.rpm, curve.frequency_hz, n)
            percent = 100 * worst.margin
            what = "crosses" if worst.crossing else "closest to"
            detail = (f"{what} {n}P at {worst.rpm:.4g} rpm ({name} {worst.frequency_hz:.5g} Hz, {n}P "
                      f"{worst.excitation_hz:.5g} Hz)")
            yield Outcome(req.name, f"{name} vs {n}P", percent >= limit, percent, f">= {limit:g} %",
                          percent - limit, "%", detail)


def _soft_stiff(run: ModelRun, req: Requirement) -> Iterator[Outcome]:
    if run.is_blade:
        raise req.error(f"applies to a tower model; '{run.spec.name}' is a blade")
    low_rpm, high_rpm = run.spec.operating_rpm  # type: ignore[misc]
    one_p_max, b_p_min = high_rpm / 60.0, run.spec.blades * low_rpm / 60.0
    limit = req.parameters["margin_percent"]
    for name in req.parameters.get("modes", DEFAULT_TOWER_MODES):
        frequency = _found(req, "modes", run.mode, name, 0.0).frequency_hz
        above = 100 * (frequency / one_p_max - 1)
        below = 100 * (1 - frequency / b_p_min)
        percent = min(above, below)
        side = f"1P max {one_p_max:.4g} Hz" if above <= below else f"{run.spec.blades}P min {b_p_min:.4g} Hz"
        yield Outcome(req.name, f"{name} in [1P max, {run.spec.blades}P min]", percent >= limit, percent,
                      f">= {limit:g} %", percent - limit, "%",
                      f"{name} {frequency:.5g} Hz; band {one_p_max:.4g}-{b_p_min:.4g} Hz; nearest {side}")


def _baseline(run: ModelRun, req: Requirement, update: bool) -> Iterator[Outcome]:
    p = req.parameters
    rpm = float(p.get("rpm", 0.0))
    count = int(p.get("modes", DEFAULT_BASELINE_MODES))
    current = dict(list(run.named_modes(rpm, count).items())[:count])
    if update:
        baseline.store_entry(p["file"], run.spec.name, rpm, current)
    stored = {m["name"]: m for m in baseline.find_entry(p["file"], run.spec.name, rpm)["modes"]}
    tolerance, min_mac = p["tolerance_percent"], p.get("min_mac", DEFAULT_MIN_MAC)
    for name, mode in current.items():
        if name not in stored:
            yield Outcome(req.name, f"{name} at {rpm:g} rpm vs baseline", False, mode.frequency_hz,
                          "present in the baseline", -math.inf, "Hz", f"{name} is new: not in {p['file']}")
            continue
        before = stored[name]["frequency_hz"]
        change = 100 * abs(mode.frequency_hz / before - 1)
        similarity = baseline.mac(baseline.shape_vector(stored[name]["shape"]),
                                  baseline.shape_vector(baseline.shape_samples(mode)))
        passed = change <= tolerance and similarity >= min_mac
        yield Outcome(req.name, f"{name} at {rpm:g} rpm vs baseline", passed, change,
                      f"<= {tolerance:g} %, MAC >= {min_mac:g}", tolerance - change, "%",
                      f"{before:.6g} Hz -> {mode.frequency_hz:.6g} Hz, MAC {similarity:.4f}")


def _elastodyn(run: ModelRun, req: Requirement) -> Iterator[Outcome]:
    from .elastodyn import elastodyn_verdicts
    yield from elastodyn_verdicts(run, req)


def _standstill(run: ModelRun, req: Requirement) -> Iterator[Outcome]:
    from .aeroelastic import standstill_verdicts
    yield from standstill_verdicts(run, req)


def _flutter(run: ModelRun, req: Requirement) -> Iterator[Outcome]:
    from .flutter import flutter_verdict
    yield flutter_verdict(run, req)


EVALUATORS: dict[str, Callable[..., Iterator[Outcome]]] = {
    "window": _window, "resonance": _resonance, "soft_stiff": _soft_stiff, "elastodyn": _elastodyn,
    "standstill_damping": _standstill, "flutter": _flutter}


def evaluate_requirement(run: ModelRun, req: Requirement, update_baseline: bool = False) -> list[Outcome]:
    """The outcomes of one requirement on its model's run (solutions are kept on ``run`` for the next one)."""
    if req.kind == "baseline":
        return list(_baseline(run, req, update_baseline))
    return list(EVALUATORS[req.kind](run, req))


def model_runs(spec: Spec) -> dict[str, ModelRun]:
    """One (lazily solved) run per model of ``spec``."""
    return {name: ModelRun(model) for name, model in spec.models.items()}


def evaluate(spec: Spec, update_baseline: bool = False) -> list[Outcome]:
    """Every outcome of every requirement of ``spec``, in spec order; with ``update_baseline`` the baseline files
    are rewritten from the present results first (and their checks then pass)."""
    runs = model_runs(spec)
    return [outcome for req in spec.requirements
            for outcome in evaluate_requirement(runs[req.model], req, update_baseline)]
