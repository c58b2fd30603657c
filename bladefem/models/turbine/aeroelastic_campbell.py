"""Aeroelastic Campbell diagram over wind speeds: an operating point and its linear model at each wind speed, the
modes gathered by name with their frequencies and damping ratios."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ...aero.rotor import Inflow, Rotor
from .aero import TurbineAero, turbine_aero
from .aeroelastic import AeroelasticModel, linearize_at
from .control import Generator
from .kane import TurbineModel
from .operating_point import steady_state


@dataclass(frozen=True)
class OperatingRequest:
    """A point to linearize at: wind speed (m/s), rotor speed (rad/s; None: trimmed by the torque law), pitch
    (rad), and the azimuth (rad) a parked rotor stands at."""

    wind_speed: float
    rotor_speed: float | None
    pitch: float
    azimuth: float = 0.0


@dataclass
class AeroelasticTurbine:
    """The turbine of an aeroelastic analysis.

    structure : the structural model at a blade pitch (rad) (the pitch turns the blade shapes), without loads of
        its own; called once per pitch
    rotor, inflow : the aerodynamics (the inflow's speed is replaced per operating point)
    free : (n,) the free coordinates; generator : the torque law (used when the rotor speed is trimmed)
    """

    structure: Callable[[float], TurbineModel]
    rotor: Rotor
    inflow: Inflow
    free: NDArray
    generator: Generator | None = None
    _models: dict[float, TurbineModel] = field(default_factory=dict)

    def model(self, pitch: float) -> TurbineModel:
        """The structure at ``pitch`` (rad), built once."""
        if pitch not in self._models:
            self._models[pitch] = self.structure(pitch)
        return self._models[pitch]

    def aero(self, model: TurbineModel, wind_speed: float, pitch: float) -> TurbineAero:
        inflow = Inflow(wind_speed, self.inflow.reference_height, self.inflow.shear_exponent, self.inflow.direction,
                        self.inflow.upflow)
        return turbine_aero(self.rotor, inflow, model.params, pitch)


def rotor_speed(rpm: float | None, generator_free: bool, generator: Generator | None,
                deck_speed: float) -> tuple[float | None, str | None]:
    """The rotor speed (rad/s) to linearize at, and a note: ``rpm`` (rpm) imposed; else, the generator free, None
    (trimmed by the torque law); else the deck's ``deck_speed`` (rad/s, generator locked). ValueError when the
    generator is free and the deck has no torque law."""
    if rpm is not None:
        return rpm * math.pi / 30, None
    if generator_free and generator is not None and generator.torque_law:
        return None, "rotor speed from the generator torque law (ServoDyn VSContrl 1) at fixed pitch"
    if generator_free:
        raise ValueError("the generator is free but the deck has no torque law (ServoDyn VSContrl 1)")
    return deck_speed, f"rotor speed {deck_speed * 30 / math.pi:g} rpm (RotSpeed, generator locked)"


def linearize_point(turbine: AeroelasticTurbine, request: OperatingRequest, induction: str = "frozen",
                    per_passage: int = 4, q0: NDArray | None = None) -> AeroelasticModel:
    """The operating point of ``request`` and the aeroelastic linear model there."""
    model = turbine.model(request.pitch)
    aero = turbine.aero(model, request.wind_speed, request.pitch)
    point = steady_state(model, aero, turbine.free, request.rotor_speed, turbine.generator, per_passage, q0,
                         request.azimuth)
    return linearize_at(model, aero, point, turbine.free, turbine.generator if point.trimmed else None, induction)


@dataclass(frozen=True)
class AeroelasticCampbell:
    """Modes over wind speed.

    wind_speeds : (S,) m/s; rpm : (S,) rotor speeds; pitch_deg : (S,) blade pitch
    names : mode names in order of first appearance; frequencies_hz, damping_ratios : (len(names), S), NaN where a
    name does not occur; linearizations : the linear model at each wind speed
    """

    wind_speeds: NDArray
    rpm: NDArray
    pitch_deg: NDArray
    names: list[str]
    frequencies_hz: NDArray
    damping_ratios: NDArray
    linearizations: list[AeroelasticModel]


def aeroelastic_campbell(turbine: AeroelasticTurbine, requests: Sequence[OperatingRequest], induction: str = "frozen",
                         per_passage: int = 4,
                         progress: Callable[[Iterable[OperatingRequest]], Iterable[OperatingRequest]] | None = None
                         ) -> AeroelasticCampbell:
    """Linearize at each request (each operating point starts from the previous one's deflections) and gather the
    modes by name."""
    results: list[AeroelasticModel] = []
    q0 = None
    for request in (progress or iter)(list(requests)):
        result = linearize_point(turbine, request, induction, per_passage, q0)
        results.append(result)
        q0 = result.point.q if result.point.symmetric else None
    names: list[str] = []
    for result in results:
        names += [mode.name for mode in result.modes if mode.name not in names]
    frequencies = np.full((len(names), len(results)), np.nan)
    damping = np.full_like(frequencies, np.nan)
    for j, result in enumerate(results):
        for mode in result.modes:
            i = names.index(mode.name)
            frequencies[i, j], damping[i, j] = mode.frequency_hz, mode.damping_ratio
    return AeroelasticCampbell(
        wind_speeds=np.array([r.point.wind_speed for r in results]), rpm=np.array([r.point.rpm for r in results]),
        pitch_deg=np.array([math.degrees(r.point.pitch) for r in results]), names=names, frequencies_hz=frequencies,
        damping_ratios=damping, linearizations=results)


def campbell_text(result: AeroelasticCampbell) -> str:
    """CSV: one row per wind speed (rotor speed, pitch), a frequency (Hz) and a damping-ratio column per mode."""
    header = ["wind_speed [m/s]", "rotor_speed [rpm]", "pitch [deg]"]
    header += [f"{name} [Hz]" for name in result.names] + [f"{name} damping [-]" for name in result.names]
    rows = [",".join(header)]
    for j in range(len(result.wind_speeds)):
        values = [result.wind_speeds[j], result.rpm[j], result.pitch_deg[j],
                  *result.frequencies_hz[:, j], *result.damping_ratios[:, j]]
        rows.append(",".join("" if np.isnan(v) else f"{v:.6g}" for v in values))
    return "\n".join(rows) + "\n"
