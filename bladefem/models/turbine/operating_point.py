"""Operating point of the turbine in steady wind: rotor speed, pitch and the static deflections of blades, tower,
drivetrain and yaw under aerodynamic, centrifugal and gravity loads.

**Which steady state.** The azimuth-averaged equilibrium: every blade takes the same static deflection, the tower,
drivetrain twist and yaw are static, the rotor turns at a constant speed, and the generalized forces (Kane's
forcing at zero accelerations with the quasi-steady BEM loads and the generator torque) vanish on average over the
rotor azimuth. It is the constant part of the periodic steady state that OpenFAST's ``CalcSteady`` finds, and
exactly the state the azimuth-averaged multi-blade linear model describes: in multi-blade coordinates it is
the constant collective and fixed-frame deflection. What it leaves out are the once-per-revolution swings of the
periodic state (gravity's edgewise swing, the tilt's flapwise one), whose effect on the averaged linear model is
of second order in their amplitude (measured in docs/aeroelastic.md). It needs no time integration, no artificial
damping and no transient to die out: a few Newton steps on a dozen unknowns.

**Averaging.** With B alike blades all free alike, a blade-symmetric state repeats every ``2 pi / B`` of azimuth,
so the average over a revolution is the average over ``N`` azimuths spread over one blade passage of the
blades' mean (exact for the harmonics below ``B N`` per revolution); the blade unknowns are then the collective
deflections. Otherwise every free coordinate is an unknown and the average runs over ``B N`` azimuths over a
revolution.

**Rotor speed.** Given (the generator azimuth turns at that speed; OpenFAST's fixed-speed linearization with
``GenDOF`` False), or, with the generator free and a torque law, trimmed so that the generator torque holds the
mean aerodynamic torque (:class:`~bladefem.models.turbine.control.Generator`). The pitch is fixed (ServoDyn's
``PCMode`` 0) and already in the blade shapes of the model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ...errors import InputError
from .aero import TurbineAero, aero_loads
from .control import Generator
from .kane import TurbineModel

#: the Newton steps stop when the largest change of a coordinate is below this, relative to the largest value
#: (m or rad): far below what moves a frequency or a damping ratio (measured in docs/aeroelastic.md)
TOLERANCE = 1e-9
MAX_ITERATIONS = 40
#: relative step of the central differences of the stiffness and of the torque over the rotor speed
STEP = 1e-6


@dataclass(frozen=True)
class OperatingPoint:
    """A steady operating point (SI, rad).

    wind_speed : m/s; rotor_speed : rad/s; pitch : rad
    q : (n,) the static coordinates at rotor azimuth 0 (``generator_azimuth`` = minus the drivetrain twist)
    azimuths : rotor azimuths of the average, rad; symmetric : blades alike (the average spans one blade passage)
    thrust, torque, power : azimuth-averaged aerodynamic rotor thrust (N), torque (N m) and power (W)
    generator_torque : on the high-speed shaft, N m (0 without a torque law or with the speed imposed)
    trimmed : the rotor speed was found from the torque law (else imposed)
    iterations : Newton steps taken
    """

    wind_speed: float
    rotor_speed: float
    pitch: float
    q: NDArray
    azimuths: NDArray
    symmetric: bool
    thrust: float = 0.0
    torque: float = 0.0
    power: float = 0.0
    generator_torque: float = 0.0
    trimmed: bool = False
    iterations: int = 0

    @property
    def rpm(self) -> float:
        return self.rotor_speed * 30.0 / math.pi

    @property
    def pitch_deg(self) -> float:
        return math.degrees(self.pitch)

    def deflections(self, model: TurbineModel) -> dict[str, float]:
        """The static deflections in OpenFAST ElastoDyn's channels and signs: blade tip ``OoPDefl`` (downwind) and
        ``IPDefl`` (toward the trailing edge), tower top ``TTDspFA`` (downwind) and ``TTDspSS`` (to the left
        looking downwind), m; nacelle yaw and drivetrain twist, deg."""
        p = model.params
        tip = self.q[model.blade_columns[0]] @ p.blade.tip_value
        top = self.q[model.tower_columns] @ p.tower.tip_value
        return {"OoPDefl": float(tip[1]), "IPDefl": float(-tip[0]), "TTDspFA": float(top[0]),
                "TTDspSS": float(top[1]), "NacYaw_deg": math.degrees(self.q[model.dofs.index("yaw")]),
                "drivetrain_twist_deg": math.degrees(self.q[model.dofs.index("drivetrain")])}

    def state(self, model: TurbineModel, azimuth: float) -> tuple[NDArray, NDArray]:
        """(q, u) with the rotor at ``azimuth`` (rad): the static deflections, the rotor at speed."""
        return rotated(model, self.q, azimuth), spinning(model, self.rotor_speed)


def rotated(model: TurbineModel, q: NDArray, azimuth: float) -> NDArray:
    """``q`` with the rotor azimuth (generator azimuth plus drivetrain twist) set to ``azimuth`` (rad)."""
    q = q.copy()
    q[model.dofs.index("generator_azimuth")] = azimuth - q[model.dofs.index("drivetrain")]
    return q


def spinning(model: TurbineModel, rotor_speed: float) -> NDArray:
    """Generalized speeds of the rotor turning at ``rotor_speed`` (rad/s), everything else at rest."""
    u = np.zeros(model.n)
    u[model.dofs.index("generator_azimuth")] = rotor_speed
    return u


def blades_alike(model: TurbineModel, free: NDArray) -> bool:
    """Every blade has the same free modes (and there is more than one blade)."""
    blade = np.asarray(free)[model.blade_columns]
    return model.params.n_blades > 1 and bool((blade == blade[0]).all())


def average_azimuths(model: TurbineModel, free: NDArray, per_passage: int) -> tuple[NDArray, bool]:
    """The azimuths of the average (rad) and whether they span one blade passage (blades alike) or a revolution."""
    symmetric = blades_alike(model, free)
    count = per_passage if symmetric else per_passage * model.params.n_blades
    span = 2 * np.pi / model.params.n_blades if symmetric else 2 * np.pi
    return span * np.arange(count) / count, symmetric


def static_unknowns(model: TurbineModel, free: NDArray, symmetric: bool) -> NDArray:
    """(n, m) map from the static unknowns to the coordinates: every free coordinate but the generator azimuth;
    with ``symmetric`` blades one collective unknown per free blade mode."""
    columns = []
    gen = model.dofs.index("generator_azimuth")
    for i in np.flatnonzero(free):
        if i == gen or (symmetric and i in model.blade_columns[1:]):
            continue
        column = np.zeros(model.n)
        if symmetric and i in model.blade_columns[0]:
            column[model.blade_columns[:, list(model.blade_columns[0]).index(i)]] = 1.0
        else:
            column[i] = 1.0
        columns.append(column)
    return np.array(columns).T.reshape(model.n, len(columns))


@dataclass(frozen=True)
class MeanLoads:
    """Generalized forces averaged over the azimuths (n,) and the averaged rotor loads (N, N m, W)."""

    forcing: NDArray
    thrust: float
    torque: float
    power: float


def mean_forcing(structure: TurbineModel, aero: TurbineAero | None, generator: Generator | None, q: NDArray,
                 rotor_speed: float, azimuths: NDArray) -> MeanLoads:
    """Kane's forcing at zero accelerations with the quasi-steady BEM loads and the generator torque, averaged over
    the rotor ``azimuths`` (rad) at the static coordinates ``q``; ``structure`` carries no loads of its own."""
    equations = structure.fast_equations()
    u = spinning(structure, rotor_speed)
    total = np.zeros(structure.n)
    thrust = torque = power = 0.0
    for psi in azimuths:
        qq = rotated(structure, q, psi)
        total += equations(qq, u)[1]
        if aero is not None:
            loads = aero_loads(structure, aero, qq, u)
            total += loads.generalized
            thrust, torque, power = thrust + loads.thrust, torque + loads.torque, power + loads.power
    count = len(azimuths)
    total /= count
    if generator is not None:
        ratio = structure.params.gearbox_ratio
        total[structure.dofs.index("generator_azimuth")] -= ratio * generator.torque(ratio * rotor_speed)
    return MeanLoads(total, thrust / count, torque / count, power / count)


def static_stiffness(structure: TurbineModel, q: NDArray, rotor_speed: float, azimuths: NDArray,
                     P: NDArray) -> NDArray:
    """-P^T d(mean forcing)/dq P of the structure alone (elastic, centrifugal and gravity stiffness), central
    differences of the compiled equations."""
    equations = structure.fast_equations()
    u = spinning(structure, rotor_speed)
    K = np.zeros((P.shape[1], P.shape[1]))
    for j, direction in enumerate(P.T):
        h = STEP * max(1.0, float(np.abs(q @ direction)))
        for sign in (1.0, -1.0):
            for psi in azimuths:
                f = equations(rotated(structure, q + sign * h * direction, psi), u)[1]
                K[:, j] -= sign * (P.T @ f) / (2 * h * len(azimuths))
    return K


def steady_state(structure: TurbineModel, aero: TurbineAero | None, free: NDArray, rotor_speed: float | None,
                 generator: Generator | None = None, per_passage: int = 4, q0: NDArray | None = None,
                 azimuth: float = 0.0) -> OperatingPoint:
    """The azimuth-averaged equilibrium (module description) of ``structure`` (a model without loads of its own)
    with the aerodynamics ``aero`` (None: none) and the free coordinates ``free``.

    rotor_speed : rad/s, imposed; None trims it with ``generator``'s torque law (the generator azimuth must be
        free). per_passage : azimuths per blade passage; q0 : a starting guess (e.g. a neighbouring point's).
    azimuth : rad, where a parked rotor (``rotor_speed`` 0) stands: its equilibrium is the static one there, every
        blade on its own.
    """
    free = np.asarray(free, dtype=bool)
    gen = structure.dofs.index("generator_azimuth")
    trim = rotor_speed is None
    if trim and (generator is None or not generator.torque_law or not free[gen]):
        raise InputError("the rotor speed is found from the generator torque law, which needs the generator free "
                         "and ServoDyn's VSContrl 1: give the rotor speed instead", field="--rpm")
    azimuths, symmetric = average_azimuths(structure, free, per_passage)
    if rotor_speed == 0.0:
        azimuths, symmetric = np.array([float(azimuth)]), False
    P = static_unknowns(structure, free, symmetric)
    q = np.zeros(structure.n) if q0 is None else np.array(q0, dtype=float)
    x = P.T @ q / P.sum(axis=0) if P.size else np.zeros(0)
    speed = trim_guess(structure, aero, generator) if trim else float(rotor_speed)
    law = generator if trim else None
    K = static_stiffness(structure, P @ x, speed, azimuths, P)
    reach = structure.params.blade.length                 # a modal amplitude (m) beyond it is no equilibrium
    mean = None
    for iteration in range(1, MAX_ITERATIONS + 1):
        mean = mean_forcing(structure, aero, law, P @ x, speed, azimuths)
        residual = P.T @ mean.forcing
        if trim:
            h = STEP * speed
            slope = (mean_forcing(structure, aero, law, P @ x, speed + h, azimuths).forcing[gen]
                     - mean_forcing(structure, aero, law, P @ x, speed - h, azimuths).forcing[gen]) / (2 * h)
            if slope >= 0:
                raise InputError(f"the torque law finds no stable rotor speed at {aero.inflow.speed:g} m/s near "
                                 f"{speed * 30 / math.pi:.3g} rpm: give the rotor speed", field="--rpm")
            step_speed = -mean.forcing[gen] / slope
            speed = max(speed + step_speed, 0.5 * speed)
        dx = np.linalg.solve(K, residual) if P.size else np.zeros(0)
        x = x + dx
        if not (np.isfinite(x).all() and np.isfinite(speed)) or np.abs(P @ x).max(initial=0.0) > reach:
            raise InputError(f"no steady state at {aero.inflow.speed if aero else 0.0:g} m/s and "
                             f"{speed * 30 / math.pi:.4g} rpm: the static deflections grow beyond the blade "
                             "length (a small-deflection model cannot hold the loads there)", field="--wind-speed")
        scale = max(float(np.abs(x).max(initial=0.0)), 1e-3)
        if np.abs(dx).max(initial=0.0) <= TOLERANCE * scale and (not trim or abs(step_speed) <= TOLERANCE * speed):
            break
    else:
        raise InputError(f"no steady state found at {aero.inflow.speed if aero else 0.0:g} m/s within "
                         f"{MAX_ITERATIONS} steps", field="--wind-speed")
    q = P @ x
    mean = mean_forcing(structure, aero, law, q, speed, azimuths)
    ratio = structure.params.gearbox_ratio
    return OperatingPoint(wind_speed=aero.inflow.speed if aero is not None else 0.0, rotor_speed=speed,
                          pitch=aero.pitch if aero is not None else structure.params.pitch,
                          q=rotated(structure, q, 0.0),
                          azimuths=azimuths, symmetric=symmetric, thrust=mean.thrust, torque=mean.torque,
                          power=mean.power, generator_torque=generator.torque(ratio * speed) if trim else 0.0,
                          trimmed=trim, iterations=iteration)


def trim_guess(structure: TurbineModel, aero: TurbineAero | None, generator: Generator) -> float:
    """The rotor speed (rad/s) where the rigid rotor's aerodynamic torque meets the torque law."""
    from scipy.optimize import brentq

    from ...aero.performance import performance_at

    if aero is None:
        raise InputError("the rotor speed is found from the aerodynamic torque: the deck needs aerodynamics",
                         field="--rpm")
    ratio = structure.params.gearbox_ratio
    rotor = aero.rotor

    def imbalance(speed: float) -> float:
        torque = performance_at(rotor, aero.inflow, speed, aero.pitch, 0.0, np.zeros(1)).torque
        return torque - ratio * generator.torque(ratio * speed)

    top = 2.0 * generator.rated_speed / ratio if math.isfinite(generator.rated_speed) else 10.0
    low = 1e-3 * top
    speeds = np.linspace(low, top, 41)
    values = [imbalance(s) for s in speeds]
    for (a, fa), (b, fb) in zip(zip(speeds, values), zip(speeds[1:], values[1:])):
        if fa > 0 >= fb:
            return float(brentq(imbalance, a, b, xtol=1e-10))
    raise InputError(f"the generator torque law holds the rotor nowhere below {top * 30 / math.pi:.3g} rpm at "
                     f"{aero.inflow.speed:g} m/s with pitch {math.degrees(aero.pitch):g} deg: give the rotor speed "
                     "(--rpm), the pitch (--pitch-deg) or both against wind speed (--schedule; the NREL 5MW's: "
                     "cases/nrel5mw/table_7_1_schedule.csv)", field="--wind-speed")

