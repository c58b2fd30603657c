"""What a turbine simulation may do before it is stopped: physical bounds checked at input and while it runs, the
step count, and Ctrl-C.

A run that leaves a bound ends early with :class:`SimulationStopped` (one line naming what went wrong and when, the
rows computed up to then kept); Ctrl-C ends it the same way (:class:`Interrupted`). The bounds, each with why:

- the blade tip slower than the speed of sound (:data:`SPEED_OF_SOUND`): the polars are incompressible (low-Mach)
  measurements and the BEM an incompressible theory; a supersonic tip means nothing (the NREL 5MW: 50 rpm, rated
  12.1 rpm);
- the rotor's power coefficient over :data:`WINDOW` (5 s, a revolution of the NREL 5MW at rated and several periods
  of its tower and blade modes), the aerodynamic energy taken over the energy that flows through the disk,
  ``sum P / sum (rho A V^3 / 2)`` (V the disk-averaged wind of ``RtAeroCp``), at most :data:`CP_MAX` = 1: over a
  window the rotor cannot take from the wind more than the kinetic energy that flows through its disk. A ratio of
  sums, not a mean of ``RtAeroCp``: in turbulence the instantaneous ``RtAeroCp`` spikes where the disk-averaged
  wind dips for a moment, and its mean is no energy balance.
  Not at every instant: a blade swinging upwind as it releases elastic energy gives more (OpenFAST's own run of
  the NREL 5MW from a 2 m tip deflection reaches 1.15 for an instant, 0.52 at most over 5 s); and not Betz's 16/27,
  which bounds the steady momentum disk but not a rotor without induction (Wake_Mod 0);
- the thrust coefficient ``|RtAeroCt|`` over the window alike (``sum |T| / sum (rho A V^2 / 2)``), at most :data:`CT_MAX` = 4 while the generator is free:
  momentum theory with the empirical high-induction thrust gives at most 2 at a = 1, and AeroDyn's bound a <= 1.5
  (propeller brake) ``4 a (a - 1) = 3``. A generator held at its speed (a motor) may drive the rotor as a fan,
  whose thrust on a slow wind has no such bound;
- both coefficients only where the disk-averaged relative wind exceeds :data:`MIN_DISK_WIND` (they divide by it);
- at most :data:`MAX_RATE` right-hand sides per simulated second: the NREL 5MW takes 300 to 600 (rtol 1e-6), 3000
  at rtol 1e-10; a thousandfold is a diverging or absurdly stiff system (a generator torque of 2e9 N m took
  330 000 per second), which would otherwise run for hours;
- the generator's rated power ``VS_RtTq VS_RtGnSp`` at most the rotor's Betz power at :data:`MAX_WIND` (checked at
  input): no turbine is rated for more than its rotor takes from a 70 m/s wind (the 50-year 3-second gust of IEC
  class I); beyond, the torque law stops the rotor in milliseconds.
"""

from __future__ import annotations

import math
import signal
import threading
from contextlib import contextmanager

import numpy as np

from ...errors import InputError

#: Speed of sound in air at 15 deg C, m/s (OpenFAST's SpdSound: 335 to 340).
SPEED_OF_SOUND = 340.3
#: Largest rotor power coefficient on the disk-averaged relative wind.
CP_MAX = 1.0
#: Largest rotor thrust coefficient on the disk-averaged relative wind.
CT_MAX = 4.0
#: Time over which RtAeroCp and RtAeroCt are averaged before they are checked, s.
WINDOW = 5.0
#: Disk-averaged relative wind below which RtAeroCp and RtAeroCt are not counted, m/s.
MIN_DISK_WIND = 1.0
#: Most right-hand sides per simulated second.
MAX_RATE = 1e5
#: Wind speed of the generator's power bound, m/s.
MAX_WIND = 70.0
#: Right-hand sides of one compiled integrator call: about 0.15 s (a few tenths on a loaded machine), so that Ctrl-C
#: and the bounds are checked often; the Python between calls (numba's typing of the kernel's arguments: about
#: 1.6 ms for the controlled loop's) costs about 1 % of it (4 % with 500, the NREL 5MW's ROSCO run).
BUDGET = 2000


class SimulationStopped(RuntimeError):
    """A run that ended early: why (one line), at which simulated time (s), the result up to then (rows computed
    whole), and the exit code the command line gives it."""

    exit_code = 1

    def __init__(self, message: str, time: float, result=None) -> None:
        super().__init__(message)
        self.time, self.result = time, result


class Interrupted(SimulationStopped):
    """Ctrl-C (SIGINT) during a run."""

    exit_code = 130


def tip_radius(model) -> float:
    """Distance of the blade tip from the shaft axis, m (hub radius plus blade length; precone neglected)."""
    return model.params.hub_radius + model.params.blade.length


def check_rotor_speed(model, speed: float, field: str) -> None:
    """Refuse a rotor speed (rad/s) whose blade tip would be supersonic."""
    limit = SPEED_OF_SOUND / tip_radius(model)
    if abs(speed) >= limit:
        raise InputError(f"{abs(speed) * 30 / math.pi:g} rpm puts the blade tip ({tip_radius(model):g} m) at "
                         f"{abs(speed) * tip_radius(model):.4g} m/s, past the speed of sound ({SPEED_OF_SOUND:g} "
                         f"m/s): at most {limit * 30 / math.pi:.4g} rpm", field=field)


def check_generator(model, air_density: float = 1.225) -> None:
    """Refuse a torque law rated for more power than the rotor's Betz power at :data:`MAX_WIND`."""
    generator = model.generator
    if generator is None or not generator.torque_law:
        return
    rated = generator.rated_torque * min(generator.rated_speed, 1e300)
    if model.aero is not None:
        air_density = model.aero.rotor.air_density
    betz = 16 / 27 * 0.5 * air_density * math.pi * tip_radius(model) ** 2 * MAX_WIND ** 3
    if not rated <= betz:
        raise InputError(f"the generator's rated power VS_RtTq x VS_RtGnSp = {rated:.3g} W exceeds the rotor's Betz "
                         f"power at {MAX_WIND:g} m/s ({betz:.3g} W): not a turbine's generator", field="VS_RtTq")


class Monitor:
    """The bounds checked on the rows of a running simulation (:meth:`rows`) and on the step count
    (:meth:`steps`); each returns (the reason to stop, the simulated time it happened), or None."""

    def __init__(self, model, loads_columns: tuple[str, ...], generator_free: bool) -> None:
        self.model, self.generator_free = model, generator_free
        self.radius = tip_radius(model)
        self.column = {name: loads_columns.index(name)
                       for name in ("cp", "ct", "disk_velocity", "aero_power", "aero_thrust")}
        #: time, counted (disk wind), aerodynamic power, |thrust|, V^3, V^2 (V the disk-averaged wind) of every row
        self.history = np.zeros((0, 6))
        #: 1/2 rho A of RtAeroCp and RtAeroCt (P / (Cp V^3), T / (Ct V^2)), read off the first rows that give them
        self.scale: dict[str, float] = {}

    def rows(self, times: np.ndarray, u: np.ndarray, loads: np.ndarray | None) -> tuple[str, float] | None:
        """The first bound left by the new output rows (times (T,), rates (T, n), load columns (T, ...))."""
        speed = np.abs(u @ self.model.azimuth) * self.radius
        bad = ~(speed < SPEED_OF_SOUND)
        if bad.any():
            i = int(np.argmax(bad))
            return (f"the blade tip reached {speed[i]:.4g} m/s at t = {times[i]:.4g} s, past the speed of sound "
                    f"({SPEED_OF_SOUND:g} m/s; rotor speed {speed[i] / self.radius * 30 / math.pi:.4g} rpm)",
                    float(times[i]))
        if loads is None or self.model.aero is None or not len(times):
            return None
        column = {name: loads[:, i] for name, i in self.column.items()}
        wind = column["disk_velocity"]
        counted = np.abs(wind) > MIN_DISK_WIND
        for name, load, coefficient, power in (("cp", column["aero_power"], column["cp"], 3),
                                               ("ct", column["aero_thrust"], column["ct"], 2)):
            given = counted & (np.abs(coefficient) > 1e-12) & np.isfinite(load)
            if name not in self.scale and given.any():
                self.scale[name] = float(np.median(load[given] / (coefficient[given] * wind[given] ** power)))
        new = np.column_stack([times, counted, column["aero_power"], np.abs(column["aero_thrust"]),
                               np.abs(wind) ** 3, wind ** 2])
        self.history = np.vstack([self.history, new])
        t, weight = self.history[:, 0], self.history[:, 1]
        rows = np.arange(len(t) - len(times), len(t))
        rows = rows[t[rows] - t[0] >= WINDOW - 1e-9]
        first = np.searchsorted(t, t[rows] - WINDOW - 1e-9)

        def window_sum(column: int) -> np.ndarray:
            total = np.concatenate([[0.0], np.cumsum(np.where(weight > 0, self.history[:, column], 0.0))])
            return total[rows + 1] - total[first]

        for name, label, load, flux, bound, applies in (
                ("cp", "power coefficient RtAeroCp", 2, 4, CP_MAX, True),
                ("ct", "thrust coefficient |RtAeroCt|", 3, 5, CT_MAX, self.generator_free)):
            if not applies or not len(rows) or name not in self.scale:
                continue
            ratio = window_sum(load) / np.maximum(abs(self.scale[name]) * window_sum(flux), 1e-300)
            bad = ~(ratio <= bound)
            if bad.any():
                i = int(np.argmax(bad))
                return (f"the rotor's {label} over the {WINDOW:g} s to t = {t[rows[i]]:.4g} s was {ratio[i]:.4g} "
                        f"(above {bound:g}" + (": more power than the wind brings through the disk)" if name == "cp"
                                               else ")"), float(t[rows[i]]))
        return None

    @staticmethod
    def steps(evaluations: int, start: float, end: float) -> tuple[str, float] | None:
        """The step-count bound over a stretch of ``evaluations`` right-hand sides from ``start`` to ``end`` (s)."""
        if evaluations >= BUDGET and evaluations > MAX_RATE * (end - start):
            return (f"the integrator took {evaluations} right-hand sides for {end - start:.3g} s from t = {start:.4g} "
                    f"s (more than {MAX_RATE:.0e} per simulated second): the motion diverges, the system is far "
                    "too stiff, or the loads jump (check rotor speed, generator torque and stiffnesses; a start-up "
                    "transient whose aerodynamic loads jump runs with ElastoDyn's fixed step: --method RK4 --step "
                    "0.005)", end)
        return None


@contextmanager
def interruptible():
    """While the block runs, Ctrl-C (SIGINT) only sets a flag, which the block polls (``flag()``); outside the
    main thread, or where signals cannot be handled, the flag stays False and Ctrl-C acts as usual. A flag rather
    than KeyboardInterrupt: a compiled kernel must not see an exception raised in its middle."""
    hit = [False]
    if threading.current_thread() is not threading.main_thread():
        yield lambda: False
        return

    def handler(signum, frame) -> None:
        hit[0] = True

    previous = signal.signal(signal.SIGINT, handler)
    try:
        yield lambda: hit[0]
    finally:
        signal.signal(signal.SIGINT, previous)
