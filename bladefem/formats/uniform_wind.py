"""InflowWind uniform wind files (``WindType`` 2): a table of time-varying wind parameters.

The layout is OpenFAST's (``docs/source/user/inflowwind/examples/inflowwind_uniform_example.dat`` and
``InflowWind_IO.f90``, ``IfW_UniformWind_Init``): lines starting with ``!``, ``#`` or ``%`` are comments; each
data line holds 8 or 9 numbers: time (s), horizontal speed (m/s), direction (deg), vertical speed (m/s),
linear horizontal shear (-), power-law exponent (-), linear vertical shear (-), gust speed (m/s) and, optionally,
the upflow angle (deg; 0 when absent). Times increase strictly. Values are returned as written (degrees);
:mod:`bladefem.builders.inflowwind` converts them.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, shown
from ..files import decode_utf8, read_input

#: the columns in file order, with their units
COLUMNS = ("time [s]", "speed [m/s]", "direction [deg]", "vertical speed [m/s]", "horizontal shear [-]",
           "power-law exponent [-]", "vertical linear shear [-]", "gust speed [m/s]", "upflow [deg]")


@dataclass(frozen=True)
class UniformWindFile:
    """Rows (n, 9) in :data:`COLUMNS` order and the line each row came from."""

    path: str
    rows: NDArray
    lines: tuple[int, ...]


def read_uniform_wind(path: str | os.PathLike) -> UniformWindFile:
    """Parse a uniform wind file; :class:`InputError` (file, line, column) on anything else."""
    path = str(path)
    rows, lines = [], []
    for number, text in enumerate(decode_utf8(read_input(path), path).splitlines(), start=1):
        words = text.split()
        if not words or words[0][0] in "!#%":
            continue
        if len(words) not in (8, 9):
            raise InputError(f"a data line holds 8 or 9 numbers ({', '.join(COLUMNS)}), got {len(words)}",
                             path, number)
        values = []
        for column, word in zip(COLUMNS, words):
            try:
                value = float(word.replace("d", "e").replace("D", "E"))
            except ValueError:
                raise InputError(f"not a number: {shown(word)}", path, number, column) from None
            if not math.isfinite(value):
                raise InputError(f"not finite: {shown(word)}", path, number, column)
            values.append(value)
        if len(values) == 8:
            values.append(0.0)
        if rows and values[0] <= rows[-1][0]:
            raise InputError(f"times must increase, {values[0]:g} s follows {rows[-1][0]:g} s", path, number,
                             COLUMNS[0])
        rows.append(values)
        lines.append(number)
    if not rows:
        raise InputError("no data lines (time, speed, direction, ... per line)", path)
    return UniformWindFile(path=path, rows=np.array(rows), lines=tuple(lines))
