"""What the models can answer: bounds on rotor speed, numbers of modes, mesh elements and sweep speeds, and the
physical bounds of a turbine deck's values and the turbine command's options (yaw spring and damper, wind speed,
shear, inflow angles, BEM iterations, layout lengths, integration tolerance).

The Python API raises :class:`~bladefem.errors.LimitError` (a ``ValueError``) and the command line prints it on one
line (exit 2), before any computation starts; the readers name the file, line and label of a deck value past its
bound. Each bound says why it is where it is.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from numbers import Integral

from .errors import LimitError

#: Largest magnitude of any number in an input file (SI values of real blades, towers and turbines stay below 1e14;
#: far beyond, element matrices approach overflow and the lowest modes drown in round-off). Nonzero section
#: properties must also exceed its inverse.
MAX_MAGNITUDE = 1e30
#: Fastest rotor speed, rpm. Wind-turbine rotors turn below 100 rpm and small test rigs below a few thousand; above
#: 1e5 rpm the linear small-deflection beam is meaningless, and toward 1e8 rpm the centrifugal stiffness buries the
#: bending stiffness below round-off (Omega^2 K2 / K0 ~ 1e16).
MAX_RPM = 1e5
#: Most modes computed. Hermite elements resolve about one mode per few elements: 100 modes are resolved well
#: within the automatic mesh's limit, more would be mesh artefacts.
MAX_MODES = 100
#: Most elements along a beam: twice the automatic mesh's limit (1600), enough to check its convergence; beyond
#: it round-off, which grows as h^-4, gains on the discretisation error and the cost grows for nothing.
MAX_ELEMENTS = 3200
#: Most rotor speeds in one sweep (a Campbell diagram needs tens).
MAX_SPEEDS = 1000
#: Largest memory a sweep's mode shapes may take, bytes (estimated before it starts).
MAX_SWEEP_BYTES = 2 * 2**30
#: Longest time simulation of the turbine model, s: a day of turbine time (design load cases last 10 min; at the
#: 30 to 50 times real time of the compiled model a day takes about an hour of CPU).
MAX_SIMULATION_SECONDS = 86400.0
#: Most output rows of a time simulation: each row holds about 80 numbers (states, loads, channels), so 2e6 rows
#: take about 1.3 GB in memory and 1 GB as a CSV table.
MAX_OUTPUT_ROWS = 2_000_000
#: Stiffest nacelle-yaw spring, N m/rad: 10^4 times the NREL 5MW's 9.03e9 (multi-MW yaw drives lie within a
#: factor of ten of it). Past it the yaw mode (frequency sqrt(k / I), I ~ 4e7 kg m^2) leaves structural dynamics
#: for kHz, and toward 1e300 the linearized matrices overflow: a stiffer spring is a locked yaw (--dof yaw=off).
MAX_YAW_STIFFNESS = 1e14
#: Strongest nacelle-yaw damper, N m s/rad: 10^5 times the NREL 5MW's 1.916e7. A stronger one is a locked yaw;
#: its time constant I / c would fall below 1e-4 s and make the time integration stiff.
MAX_YAW_DAMPING = 1e12
#: Most iterations of the BEM induction solve (AeroDyn MaxIter; its default is 100). Brent's method needs at most
#: about (log2(bracket / tolerance))^2 ~ 4000 steps in its worst case: more cannot change the answer.
MAX_BEM_ITERATIONS = 10_000
#: Largest upflow angle (InflowWind VFlowAng), deg: at 90 deg the wind blows straight up; real upflow over complex
#: terrain stays below about 20 deg. Largest propagation direction (PropagationDir), deg: one turn either way.
MAX_UPFLOW_DEG = 90.0
MAX_DIRECTION_DEG = 360.0
#: Largest wind speed, m/s: above the strongest 3 s gusts measured at hub heights (about 90 m/s in typhoons); the
#: IEC class T extreme gust is 80 m/s.
MAX_WIND_SPEED = 100.0
#: Largest power-law shear exponent magnitude (PLExp, --shear-exp): measured exponents lie between about -0.3 (low-
#: level jets) and 1 (stable nights); IEC uses 0.2 and 0.11 to 0.14.
MAX_SHEAR_EXPONENT = 1.0
#: Relative tolerance of a time simulation (--rtol): at most 1e-2 (a per cent of error per step leaves no answer to
#: speak of), at least 1e-13 (below, round-off of double precision, 2.2e-16 per operation, sets the error).
MIN_RTOL, MAX_RTOL = 1e-13, 1e-2
#: Largest length of a turbine's layout (ElastoDyn TipRad, TowerHt, OverHang, ...), m: 1 km, four times the largest
#: rotor radius (IEA 22 MW: 142 m) and tower (about 170 m) designed so far.
MAX_TURBINE_LENGTH = 1000.0
#: Largest gearbox ratio (GBRatio): multi-MW gearboxes step up about 100 times (the NREL 5MW's 97).
MAX_GEARBOX_RATIO = 1000.0
#: Elements assumed for the estimate when the mesh is chosen automatically (its upper limit).
AUTOMATIC_MESH_ELEMENTS = 1600
#: Most DOFs per node of a blade (flap value and slope, edge value and slope, twist, axial).
DOFS_PER_NODE = 6


def check_rpm(rpm: object, name: str = "rpm") -> float:
    """``rpm`` as a float in [0, :data:`MAX_RPM`]."""
    value = _number(rpm, name)
    if not 0 <= value <= MAX_RPM:
        raise LimitError(f"rotor speed must lie between 0 and {MAX_RPM:g} rpm, got {rpm}", field=name)
    return value


def check_n_modes(n_modes: object, name: str = "n_modes") -> int:
    """``n_modes`` as an int in [1, :data:`MAX_MODES`]."""
    return _count(n_modes, MAX_MODES, name, "modes")


def check_elements(elements: object, name: str = "elements") -> int | None:
    """``elements`` (None: automatic) as an int in [1, :data:`MAX_ELEMENTS`]."""
    return None if elements is None else _count(elements, MAX_ELEMENTS, name, "elements")


def check_speeds(rpm: Sequence[float] | object, n_modes: int, elements: int | None, name: str = "rpm") -> list[float]:
    """A sweep's rotor speeds (rpm): 1 to :data:`MAX_SPEEDS` of them, each valid, and mode shapes that fit in
    :data:`MAX_SWEEP_BYTES`."""
    try:
        speeds = [float(value) for value in rpm]  # type: ignore[union-attr]
    except (TypeError, ValueError):
        raise LimitError(f"expected a sequence of rotor speeds (rpm), got {rpm!r}", field=name) from None
    if not 1 <= len(speeds) <= MAX_SPEEDS:
        raise LimitError(f"a sweep takes 1 to {MAX_SPEEDS} rotor speeds, got {len(speeds)}", field=name)
    for value in speeds:
        check_rpm(value, name)
    size = sweep_bytes(len(speeds), n_modes, elements)
    if size > MAX_SWEEP_BYTES:
        raise LimitError(f"{len(speeds)} speeds x {n_modes} modes on {elements or AUTOMATIC_MESH_ELEMENTS} elements "
                         f"would hold about {size / 2**30:.1f} GB of mode shapes (at most {MAX_SWEEP_BYTES / 2**30:g}"
                         " GB): use fewer speeds, modes or elements", field=name)
    return speeds


def sweep_bytes(speeds: int, n_modes: int, elements: int | None) -> float:
    """Upper estimate of a sweep's memory: eigenvectors and nodal shapes of every mode at every speed, bytes."""
    nodes = (elements or AUTOMATIC_MESH_ELEMENTS) + 1
    return 8.0 * speeds * (n_modes + 4) * nodes * DOFS_PER_NODE * 2


def _number(value: object, name: str) -> float:
    if isinstance(value, bool):
        raise LimitError(f"expected a number, got {value!r}", field=name)
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError, OverflowError):
        raise LimitError(f"expected a number, got {value!r}", field=name) from None
    if not math.isfinite(number):
        raise LimitError(f"expected a finite number, got {value!r}", field=name)
    return number


def _count(value: object, largest: int, name: str, what: str) -> int:
    if isinstance(value, bool) or not isinstance(value, Integral) and not (
            isinstance(value, float) and value.is_integer()):
        raise LimitError(f"expected a whole number of {what}, got {value!r}", field=name)
    if not 1 <= value <= largest:
        raise LimitError(f"must lie between 1 and {largest} {what}, got {value}", field=name)
    return int(value)  # type: ignore[arg-type]
