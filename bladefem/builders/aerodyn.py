"""AeroDyn v15 blade file: the planform (span, chord, aerodynamic twist), the aerodynamic-centre offsets and the
airfoil of each node; used to draw a blade read from an ElastoDyn file as a surface and for the BEM.

``NumBlNds`` and the first seven columns of the table ``BlSpn BlCrvAC BlSwpAC BlCrvAng BlTwist BlChord BlAFID``
(units m, m, m, deg, deg, m, -) are read; later columns (t_c, buoyancy and added-mass coefficients of recent
OpenFAST versions) are ignored. ``BlSpn`` runs along the blade from its root, like the span of the section table.
For drawing, the chord is placed at the structural twist of the section table (the mechanics' section frame).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..sections import Blade
from ..formats._fast_format import FastText

COLUMNS = ("BlSpn", "BlCrvAC", "BlSwpAC", "BlCrvAng", "BlTwist", "BlChord", "BlAFID")
#: relative shortfall of the AeroDyn span against the blade length that is still accepted (rounding in files)
SPAN_RTOL = 1e-3


@dataclass(frozen=True)
class AeroDynBlade:
    """Blade planform from an AeroDyn blade file.

    span : BlSpn, distance from the blade root along the blade, m
    chord : BlChord, m
    twist : BlTwist, aerodynamic twist, rad
    source : the file
    lines : 1-based line of each node in the file
    airfoil : BlAFID, 1-based airfoil number of each node (None if not read)
    curve, sweep : BlCrvAC (out of plane, positive downwind) and BlSwpAC (in plane, positive opposite to the
        rotation), offsets of the aerodynamic centre from the pitch axis, m
    curve_angle : BlCrvAng, rad
    """

    span: NDArray[np.float64]
    chord: NDArray[np.float64]
    twist: NDArray[np.float64]
    source: str = ""
    lines: tuple[int, ...] = ()
    airfoil: NDArray[np.int64] | None = None
    curve: NDArray[np.float64] | None = None
    sweep: NDArray[np.float64] | None = None
    curve_angle: NDArray[np.float64] | None = None


def read_aerodyn_blade(path: str | os.PathLike) -> AeroDynBlade:
    """Read the node table of an AeroDyn blade file; errors name the file, line and column."""
    text = FastText.read(path)
    count = text.int("NumBlNds", minimum=2)
    header = text.header_line("BlSpn", after=text.line_of("NumBlNds"))
    first = header + 2                                   # the header and the units line
    rows = np.array(text.table(first, count, COLUMNS))
    lines = tuple(range(first, first + count))
    span, chord = rows[:, 0], rows[:, 5]
    steps = np.flatnonzero(np.diff(span) <= 0)
    if span[0] < 0:
        raise text.error(f"must not be negative, got {span[0]}", lines[0], "BlSpn")
    if steps.size:
        raise text.error(f"must increase strictly ({span[steps[0]]} then {span[steps[0] + 1]})",
                         lines[steps[0] + 1], "BlSpn")
    bad = np.flatnonzero(chord <= 0)
    if bad.size:
        raise text.error(f"must be positive, got {chord[bad[0]]}", lines[bad[0]], "BlChord")
    airfoil = rows[:, 6]
    bad = np.flatnonzero((airfoil < 1) | (airfoil != np.round(airfoil)))
    if bad.size:
        raise text.error(f"must be a positive whole number, got {airfoil[bad[0]]:g}", lines[bad[0]], "BlAFID")
    return AeroDynBlade(span, chord, np.radians(rows[:, 4]), str(path), lines, airfoil.astype(np.int64),
                        rows[:, 1], rows[:, 2], np.radians(rows[:, 3]))


def with_planform(blade: Blade, aero: AeroDynBlade) -> Blade:
    """The blade with the AeroDyn chord interpolated (linearly) at its section stations; the pitch axis is kept
    from the section table (ElastoDyn's PitchAxis) if it has one."""
    sections = blade.sections
    if aero.span[-1] < sections.length * (1 - SPAN_RTOL) or aero.span[0] > SPAN_RTOL * sections.length:
        raise InputError(f"the AeroDyn nodes span {aero.span[0]:g}-{aero.span[-1]:g} m but the blade's flexible "
                         f"length is {sections.length:g} m", file=aero.source or None,
                         line=aero.lines[-1] if aero.lines else None, field="BlSpn")
    chord = np.interp(sections.span, aero.span, aero.chord)
    note = f"chord drawn from {aero.source or 'an AeroDyn blade file'} (geometry only)"
    return replace(blade, sections=replace(sections, chord=chord), notes=blade.notes + (note,))

