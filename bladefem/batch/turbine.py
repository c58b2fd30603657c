"""Turbine analyses of a batch: the Kane turbine model of an OpenFAST deck per case, simulated in steady wind
(statistics of each output channel over a window) or linearized about its operating point (aeroelastic modes with
their damping, as ``bladefem turbine DECK.fst --linearize``).

A case's wind speed (m/s), rotor speed (rpm) and pitch (deg) are the plan's grid values where it varies them,
else the analysis's, else the deck's (InflowWind ``HWindSpeed``; the torque law or ``RotSpeed``; ``BlPitch``).
A given rotor speed locks the generator, as ``bladefem turbine --rpm`` does.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

import numpy as np

from ..errors import InputError


def operating_inputs(case: Any) -> tuple[float | None, float | None, float | None]:
    """(wind speed m/s, rotor speed rpm, pitch deg) of a case, None where the deck decides."""
    analysis = case.analysis

    def pick(key: str, default: float | None) -> float | None:
        return float(case.inputs[key]) if key in case.inputs else default

    return (pick("wind_speed_m_s", analysis.wind_speed), pick("rpm", analysis.turbine_rpm),
            pick("pitch_deg", analysis.pitch_deg))


@lru_cache(maxsize=8)
def _deck(path: str, digest: str, wind_speed: float | None, pitch_deg: float | None, rpm: float | None,
          leave_out: tuple[str, ...] = ()) -> Any:
    from ..builders.turbine_deck import read_turbine_deck
    ways = set(leave_out) | ({"--rpm"} if rpm is not None else set())     # a fixed rotor speed stands for DISCON
    return read_turbine_deck(path, wind_speed=wind_speed, pitch=None if pitch_deg is None else math.radians(pitch_deg),
                             blade_shapes="fe", rpm=rpm, gauss_points=2, leave_out=frozenset(ways),
                             dynamic_wake=True)                 # simulate_rows's deck: a time simulation


def turbine_deck(case: Any) -> Any:
    """The case's deck (:class:`~bladefem.builders.turbine_deck.TurbineDeck`), read once per worker and operating point."""
    from .cases import file_digest
    model = case.inputs.get("file", case.model)
    wind_speed, rpm, pitch_deg = operating_inputs(case)
    return _deck(str(model), file_digest(model), wind_speed, pitch_deg, rpm, tuple(case.analysis.leave_out))


def simulate_rows(case: Any) -> list[dict[str, Any]]:
    """Simulate ``analysis.seconds`` (s) from the deck's initial state, in the deck's wind or in the case's turbulent
    box (``analysis.turbulence``, the case's ``turbulence_seed``); one row per output channel with its mean,
    standard deviation, minimum, maximum and damage-equivalent load (:mod:`.loads`, 1 Hz equivalent cycles, with
    the channel's S-N slope ``wohler_m``) over ``[analysis.statistics_from, seconds]`` (s), in the channel's unit
    (OpenFAST's names and units)."""
    from .loads import damage_equivalent_load, wohler_slope
    from ..models.turbine import FreeSystem, TurbineModel, select_dofs
    from ..models.turbine.initial import free_from_switches, initial_state
    from ..models.turbine.outputs import CHANNELS
    from ..models.turbine.simulate import ABSOLUTE_TOLERANCE, simulate

    analysis = case.analysis
    deck = turbine_deck(case)
    wind_speed, rpm, pitch_deg = operating_inputs(case)
    aero = deck.aero if analysis.turbulence is None else turbulent_aero(deck.aero, analysis,
                                                                         int(case.inputs.get("turbulence_seed", 1)))
    model = TurbineModel(deck.params, aero=aero, generator=deck.generator)
    switches, conditions = deck.switches, deck.conditions
    if rpm is not None:
        switches = {**switches, "GenDOF": False}
        conditions = conditions.with_(rotor_speed=rpm * math.pi / 30)
    free = select_dofs(model.dofs, [], base=free_from_switches(model.dofs, switches))
    q0, u0, _ = initial_state(model, free, conditions)
    result = simulate(FreeSystem(model, free, q0, u0), analysis.seconds, dt_output=analysis.dt, rtol=analysis.rtol,
                      atol=analysis.rtol * ABSOLUTE_TOLERANCE)
    window = result.time >= analysis.statistics_from - 1e-9
    head = {"wind_speed_m_s": None if model.aero is None else float(model.aero.inflow.speed),
            "rpm": None if rpm is None else rpm, "pitch_deg": None if pitch_deg is None else pitch_deg}
    rows = []
    span = analysis.seconds - analysis.statistics_from
    for name in (n for n in CHANNELS if n in result.outputs):
        values = np.asarray(result.outputs[name])[window]
        m = wohler_slope(name)
        rows.append({**head, "channel": name, "unit": CHANNELS[name][0], "mean": float(np.mean(values)),
                     "std": float(np.std(values)), "min": float(np.min(values)), "max": float(np.max(values)),
                     "del": damage_equivalent_load(values, m, span), "wohler_m": m})
    return rows


def turbulent_aero(aero: Any, analysis: Any, key: int) -> Any:
    """The deck's aerodynamics in the case's turbulent box (about the deck's or the case's wind speed at the hub,
    with the deck's shear), refused if the box does not hold the rotor for the run."""
    from dataclasses import replace

    from ..aero.turbulence import TurbulenceSpec, rotor_width, turbulent_grid

    if aero is None:
        raise InputError("a turbulent box needs the deck's aerodynamics (CompAero 2)",
                         field="analysis.turbulence_class")
    inflow, rotor = aero.inflow, aero.rotor
    if inflow.kind != "steady":
        raise InputError(f"the deck gives {inflow.kind} wind: a turbulent box replaces steady wind only",
                         field="analysis.turbulence_class")
    radius, hub = float(rotor.hub_radius + rotor.span[-1]), float(rotor.hub_height)
    kind, percent, points, dt = analysis.turbulence
    spec = TurbulenceSpec(speed=inflow.speed * (hub / inflow.reference_height) ** inflow.shear_exponent,
                          hub_height=hub, shear_exponent=inflow.shear_exponent, duration=analysis.seconds,
                          width=rotor_width(radius), turbulence_class=kind,
                          intensity=None if percent is None else percent / 100, key=key, dt=dt, points=points)
    inflow = replace(inflow, grid=turbulent_grid(spec))
    inflow.check_covers(hub, radius, analysis.seconds)
    return replace(aero, inflow=inflow)


def linearize_rows(case: Any) -> list[dict[str, Any]]:
    """The aeroelastic modes at the case's operating point (``bladefem turbine DECK.fst --linearize --wind-speed U
    [--rpm R] [--pitch-deg P] [--induction I]`` with its defaults): one row per mode with its name, frequency (Hz)
    and damping ratio, and the operating point's rotor speed (rpm) and pitch (deg)."""
    from ..builders.openfast_fst import read_openfast_deck
    from ..builders.turbine_elastodyn import (
        NREL5MW_YAW_DAMPING,
        NREL5MW_YAW_STIFFNESS,
        deck_conditions,
        turbine_from_elastodyn,
    )
    from ..models.turbine import TurbineModel
    from ..models.turbine.aeroelastic_campbell import (
        AeroelasticTurbine,
        OperatingRequest,
        linearize_point,
        rotor_speed,
    )
    from ..models.turbine.control import Generator
    from ..models.turbine.initial import free_from_switches
    from ..models.turbine.parameters import dof_names

    path = str(case.inputs.get("file", case.model))
    wind_speed, rpm, pitch_deg = operating_inputs(case)
    ways = set(case.analysis.leave_out) | ({"--rpm"} if rpm is not None else set())
    deck = read_openfast_deck(path, leave_out=ways)
    if deck.aerodyn is None:
        raise InputError("the deck has no aerodynamics (CompAero 0)", file=deck.path, field="CompAero")
    switches, conditions = deck_conditions(deck.elastodyn.path, rigid_foundation="--foundation rigid" in ways)
    dofs = dof_names(deck.elastodyn.num_blades)
    free = free_from_switches(dofs, switches)
    servo = deck.servodyn
    generator = Generator.from_servodyn(servo) if servo is not None else None
    gen = dofs.index("generator_azimuth")
    try:
        speed, _ = rotor_speed(rpm, bool(free[gen]), generator, conditions.rotor_speed)
    except ValueError as error:
        raise InputError(f"{error}: give rpm", file=deck.path, field="rpm") from None
    free[gen] = free[gen] and speed is None

    def structure(pitch: float) -> TurbineModel:
        return TurbineModel(turbine_from_elastodyn(
            deck.elastodyn.path, "fe", rpm=rpm, pitch=pitch,
            yaw_stiffness=servo.yaw_spring if servo is not None else NREL5MW_YAW_STIFFNESS,
            yaw_damping=servo.yaw_damper if servo is not None else NREL5MW_YAW_DAMPING))

    turbine = AeroelasticTurbine(structure=structure, rotor=deck.rotor(), inflow=deck.inflow, free=free,
                                 generator=generator)
    request = OperatingRequest(wind_speed=deck.inflow.speed if wind_speed is None else wind_speed,
                               rotor_speed=speed, pitch=deck.pitch[0] if pitch_deg is None else math.radians(pitch_deg),
                               azimuth=conditions.azimuth)
    linear = linearize_point(turbine, request, case.analysis.induction)
    point = linear.point
    return [{"wind_speed_m_s": point.wind_speed, "rpm": point.rpm, "pitch_deg": point.pitch_deg, "mode": i + 1,
             "name": mode.name, "frequency_hz": mode.frequency_hz, "damping_ratio": mode.damping_ratio}
            for i, mode in enumerate(linear.modes)]


def check_turbine_case(case: Any) -> None:
    """Refuse inputs a turbine case cannot take (section scale factors, tip mass, precone)."""
    blade_only = sorted(k for k in case.inputs if k.endswith("_scale") or k in ("tip_mass_kg", "precone_deg"))
    if blade_only:
        raise InputError(f"{', '.join(blade_only)}: blade inputs, not for a turbine analysis", field=blade_only[0])


TURBINE_ANALYSES = {"turbine_simulate": simulate_rows, "turbine_linearize": linearize_rows}
