"""What the models can answer: bounds on rotor speed, numbers of modes, mesh elements and sweep speeds.

The Python API raises :class:`~bladefem.errors.LimitError` (a ``ValueError``) and the command line prints it on one
line (exit 2), before any computation starts. Each bound says why it is where it is.
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
