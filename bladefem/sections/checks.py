"""Checks every reader applies, whatever the format: rotor geometry, and section values a double-precision solve
can answer.

The geometry functions return why a value is not acceptable (a sentence for an :class:`~bladefem.errors.InputError`
the reader raises with its own file, line and field), or None. :func:`check_section_values` raises itself, naming
the station's line and the column.
"""

from __future__ import annotations

import math
from dataclasses import fields

import numpy as np

from ..errors import InputError
from ..limits import MAX_MAGNITUDE
from .table import SectionTable

#: Smallest flexible length (tip radius - hub radius), m
MIN_LENGTH = 1e-3
#: Smallest flexible length as a fraction of the tip radius (a blade shorter than this is a typing slip)
MIN_LENGTH_FRACTION = 1e-3
#: |precone| must stay below this, rad: ElastoDyn's own rule (ED_ValidateInput: PreCone in (-pi/2, pi/2))
MAX_PRECONE = math.pi / 2


def length_problem(hub_radius: float, tip_radius: float) -> str | None:
    """Why a blade from ``hub_radius`` to ``tip_radius`` (m, from the rotor apex) is not a blade, or None."""
    if not (math.isfinite(hub_radius) and math.isfinite(tip_radius)):
        return f"tip radius {tip_radius} and hub radius {hub_radius} must be finite numbers"
    if hub_radius < 0:
        return f"hub radius must not be negative, got {hub_radius}"
    length = tip_radius - hub_radius
    if length <= 0:
        return f"tip radius ({tip_radius} m) must exceed the hub radius ({hub_radius} m)"
    if length < MIN_LENGTH or length < MIN_LENGTH_FRACTION * tip_radius:
        return (f"tip radius {tip_radius} m is only {length:.3g} m beyond the hub radius {hub_radius} m: the blade "
                f"must be at least {MIN_LENGTH:g} m and {MIN_LENGTH_FRACTION:g} of the tip radius long")
    return None


def precone_problem(precone: float) -> str | None:
    """Why a precone angle (rad) is not acceptable, or None."""
    if not math.isfinite(precone) or abs(precone) >= MAX_PRECONE:
        return f"precone must lie strictly between -90 and 90 degrees, got {math.degrees(precone):g} degrees"
    return None


#: Largest structural twist, rad: beyond a half turn it is a slip (degrees read as radians, or a typing error)
MAX_TWIST = math.pi
#: Largest offset (centre of mass, shear or tension centre, tip or top body) and radius of gyration, in beam
#: lengths: a body ten lengths away from its beam is a slip, and it leaves the solve at round-off
MAX_REACH = 10.0
#: Offsets measured from the reference axis in the section table
OFFSETS = ("cm_offset", "shear_centre_offset", "tension_centre_offset")
#: Section properties that must be positive (or zero, for the inertias) and are checked for jumps
PROPERTIES = ("mass", "flap_stiffness", "edge_stiffness", "torsion_stiffness", "axial_stiffness", "flap_inertia",
              "edge_inertia")
#: Largest ratio of a positive property between neighbouring stations: a jump of more than six decades is a unit
#: slip, and it leaves the lowest modes at round-off level (the eigen-residual reaches 1e-1 from about 1e8 on)
MAX_JUMP = 1e6


def check_section_values(sections: SectionTable) -> None:
    """An InputError (naming the station's line and the column) for a value a double-precision solve cannot answer
    or a real beam does not have: beyond :data:`~bladefem.limits.MAX_MAGNITUDE` (or a nonzero property below its
    inverse), a twist beyond :data:`MAX_TWIST`, an offset or radius of gyration beyond :data:`MAX_REACH` lengths, a
    property that jumps by more than :data:`MAX_JUMP` between neighbouring stations, or flap and edge stiffness that
    differ by more than that."""
    for f in fields(sections):
        values = getattr(sections, f.name)
        if isinstance(values, np.ndarray) and values.dtype.kind == "f":
            for check in (_magnitude, _twist, _reach, _jump):
                problem = check(sections, f.name, values)
                if problem is not None:
                    raise _station_error(sections, *problem, f.name)
    problem = _jump(sections, "edge_stiffness", sections.edge_stiffness / sections.flap_stiffness, across=True)
    if problem is not None:
        raise _station_error(sections, *problem, "edge_stiffness")


def _station_error(sections: SectionTable, message: str, index: int, name: str) -> InputError:
    line = sections.lines[index] if sections.lines and index < len(sections.lines) else None
    where = "" if line else f" (station {index + 1})"
    return InputError(message + where, file=sections.source or None, line=line or None, field=name)


def _first(mask: np.ndarray) -> int | None:
    found = np.flatnonzero(mask)
    return int(found[0]) if found.size else None


def _magnitude(sections: SectionTable, name: str, values: np.ndarray) -> tuple[str, int] | None:
    tiny = (values != 0) & (np.abs(values) < 1 / MAX_MAGNITUDE) if name in PROPERTIES else False
    i = _first((np.abs(values) > MAX_MAGNITUDE) | tiny)
    if i is None:
        return None
    return f"{values[i]:g} is beyond any real blade or tower (SI magnitudes {1 / MAX_MAGNITUDE:g} to " \
           f"{MAX_MAGNITUDE:g})", i


def _twist(sections: SectionTable, name: str, values: np.ndarray) -> tuple[str, int] | None:
    i = _first(np.abs(values) > MAX_TWIST) if name == "twist" else None
    if i is None:
        return None
    return f"twist {math.degrees(values[i]):g} degrees is beyond a half turn (degrees read as radians?)", i


def _reach(sections: SectionTable, name: str, values: np.ndarray) -> tuple[str, int] | None:
    reach = MAX_REACH * sections.length
    if name in OFFSETS and (i := _first(np.abs(values) > reach)) is not None:
        return f"offset {values[i]:g} m is more than {MAX_REACH:g} beam lengths ({sections.length:g} m)", i
    if name in ("flap_inertia", "edge_inertia") and (i := _first(values > sections.mass * reach**2)) is not None:
        return f"radius of gyration sqrt({values[i]:g} / {sections.mass[i]:g}) is beyond {MAX_REACH:g} beam lengths", i
    return None


def _jump(sections: SectionTable, name: str, values: np.ndarray, across: bool = False) -> tuple[str, int] | None:
    """Neighbouring stations (or, ``across``, two columns at one station) more than :data:`MAX_JUMP` apart. A
    property step (a station given twice) is a deliberate jump: BModes decks of monopiles make the tower above the
    pile axially rigid that way."""
    if not across and (name not in PROPERTIES or not np.all(values > 0)):
        return None
    ratio = values if across else values[1:] / values[:-1]
    step = np.zeros(ratio.shape, dtype=bool) if across else np.diff(np.asarray(sections.span)) == 0
    i = _first(((ratio > MAX_JUMP) | (ratio < 1 / MAX_JUMP)) & ~step)
    if i is None:
        return None
    if across:
        return (f"edge stiffness {sections.edge_stiffness[i]:g} and flap stiffness {sections.flap_stiffness[i]:g} "
                f"differ by more than {MAX_JUMP:g} times (a unit slip?)", i)
    return (f"jumps from {values[i]:g} to {values[i + 1]:g} between neighbouring stations (more than {MAX_JUMP:g} "
            "times: a unit slip?)", i + 1)


def body_problem(mass: float, offset: np.ndarray, inertia: np.ndarray, length: float) -> str | None:
    """Why a tip or top body (kg; centre-of-mass offset, m; inertia tensor about it, kg m^2) on a beam of
    ``length`` m is absurd, or None: an offset or a radius of gyration beyond :data:`MAX_REACH` lengths, or a value
    beyond :data:`~bladefem.limits.MAX_MAGNITUDE`."""
    reach = MAX_REACH * length
    if np.any(np.abs(offset) > reach):
        return f"offset {np.max(np.abs(offset)):g} m is more than {MAX_REACH:g} beam lengths ({length:g} m) away"
    largest = float(np.max(np.abs(inertia))) if np.size(inertia) else 0.0
    if largest > MAX_MAGNITUDE or (mass > 0 and largest > mass * reach**2):
        return (f"inertia {largest:g} kg m^2 gives a radius of gyration beyond {MAX_REACH:g} beam lengths for "
                f"{mass:g} kg")
    return None
