"""AeroDyn airfoil files (AirfoilInfo v1.0x, the ``Airfoils/*.dat`` of the OpenFAST decks): polar tables.

The file is read like AeroDyn reads it: lines whose first character is ``!`` are comments; ``InterpOrd``
("DEFAULT" = 1, linear; 3, cubic spline) applies to every table; each of the ``NumTabs`` tables has a ``Re``
(millions), optional unsteady-aerodynamics constants (not used: quasi-steady), then ``NumAlf`` and that many rows.
The columns of angle of attack (deg), Cl, Cd and Cm are those the AeroDyn primary file names (InCol_Alfa,
InCol_Cl, InCol_Cd, InCol_Cm; 1, 2, 3, 4 by default; InCol_Cm = 0: no moment column, Cm = 0). Every problem is an
:class:`InputError` naming the file, line and field.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

import numpy as np

from ..aero.polars import CUBIC, LINEAR, Polar
from ..formats._fast_format import KEY_LINE, FastText, to_float, to_int


@dataclass(frozen=True)
class PolarColumns:
    """1-based columns of the airfoil tables (AeroDyn InCol_Alfa, InCol_Cl, InCol_Cd, InCol_Cm; 0 = absent)."""

    alpha: int = 1
    cl: int = 2
    cd: int = 3
    cm: int = 4


def read_airfoil(path: str | os.PathLike, columns: PolarColumns = PolarColumns()) -> tuple[Polar, ...]:
    """Every table of an AeroDyn airfoil file, angles in rad, in file order."""
    text = FastText.read(path)
    order = _interpolation_order(text)
    count = text.int("NumTabs", minimum=1)
    polars: list[Polar] = []
    reynolds = math.nan
    number = text.line_of("NumTabs")
    while len(polars) < count:
        number += 1
        if number > len(text.lines):
            raise text.error(f"expected {count} tables, found {len(polars)}", len(text.lines), "NumAlf")
        match = KEY_LINE.match(text.lines[number - 1])
        if match is None or text.lines[number - 1].lstrip().startswith("!"):
            continue
        value = match["value"].strip("\"'")
        if match["key"] == "Re":
            reynolds = 1e6 * to_float(value, text.error, number, "Re")
        elif match["key"] == "NumAlf":
            rows = to_int(value, text.error, number, "NumAlf")
            if rows < 1:
                raise text.error(f"must be at least 1, got {rows}", number, "NumAlf")
            polar, number = _table(text, number, rows, columns, reynolds, order, len(polars) + 1)
            polars.append(polar)
    return tuple(polars)


def _interpolation_order(text: FastText) -> int:
    if not text.has("InterpOrd") or text.string("InterpOrd").strip().lower() == "default":
        return LINEAR
    order = text.int("InterpOrd")
    if order not in (LINEAR, CUBIC):
        raise text.error(f"must be 1 (linear) or 3 (cubic spline), got {order}", text.line_of("InterpOrd"),
                         "InterpOrd")
    return order


def _table(text: FastText, header: int, rows: int, columns: PolarColumns, reynolds: float, order: int,
           index: int) -> tuple[Polar, int]:
    """The table whose NumAlf line is ``header``; returns it and the number of its last line."""
    needed = max(columns.alpha, columns.cl, columns.cd, columns.cm)
    names = {columns.alpha: "Alpha", columns.cl: "Cl", columns.cd: "Cd", columns.cm: "Cm"}
    data, lines = [], []
    number = header
    while len(data) < rows:
        number += 1
        if number > len(text.lines):
            raise text.error(f"table {index} ends early: expected {rows} rows, found {len(data)}", len(text.lines),
                             "NumAlf")
        words = text.lines[number - 1].split()
        if not words or words[0].startswith("!"):
            continue
        if len(words) < needed:
            raise text.error(f"expected at least {needed} columns, found {len(words)}", number,
                             names.get(len(words) + 1, f"column {len(words) + 1}"))
        data.append([to_float(words[c - 1], text.error, number, names[c]) if c else 0.0
                     for c in (columns.alpha, columns.cl, columns.cd, columns.cm)])
        lines.append(number)
    table = np.array(data)
    steps = np.flatnonzero(np.diff(table[:, 0]) <= 0)
    if steps.size:
        i = steps[0]
        raise text.error(f"angles of attack must increase strictly ({table[i, 0]:g} then {table[i + 1, 0]:g} deg)",
                         lines[i + 1], "Alpha")
    name = f"{os.path.basename(text.path)} table {index}"
    return Polar(np.radians(table[:, 0]), table[:, 1], table[:, 2], table[:, 3], reynolds, order, name), number
