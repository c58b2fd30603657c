"""Static airfoil polars: lift, drag and pitching-moment coefficients against the angle of attack.

A :class:`Polar` holds one table (one Reynolds number) as AeroDyn reads it: angles in rad, strictly increasing,
normally from -pi to pi. It is interpolated like AeroDyn's ``InterpOrd``: 1 linear (AeroDyn's default), 3 natural
cubic spline; the angle is first wrapped into [-pi, pi) and held at the end values outside the table.

For the compiled kernels the polars of a rotor are packed into one :class:`PolarTable`: every interval of every
table carries cubic coefficients ``c0 + c1 d + c2 d^2 + c3 d^3`` in ``d = alpha - alpha_k`` (linear tables have
``c2 = c3 = 0``), so both interpolation orders run through the same evaluation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ._jit import kernel

#: The interpolation orders AeroDyn knows (InterpOrd).
LINEAR, CUBIC = 1, 3


@dataclass(frozen=True)
class Polar:
    """One airfoil table.

    alpha : angle of attack, rad, strictly increasing
    cl, cd, cm : lift, drag and pitching-moment (about the aerodynamic centre, nose up) coefficients
    reynolds : Reynolds number of the table (AeroDyn's ``Re`` times 1e6); not used by the BEM (AFTabMod 1)
    order : interpolation order, 1 linear or 3 natural cubic spline (AeroDyn's InterpOrd)
    name : where the table came from (file name)
    """

    alpha: NDArray[np.float64]
    cl: NDArray[np.float64]
    cd: NDArray[np.float64]
    cm: NDArray[np.float64]
    reynolds: float = math.nan
    order: int = LINEAR
    name: str = ""

    def __post_init__(self) -> None:
        if self.order not in (LINEAR, CUBIC):
            raise ValueError(f"interpolation order must be 1 or 3, got {self.order}")
        if np.any(np.diff(self.alpha) <= 0):
            raise ValueError("polar angles of attack must increase strictly")

    def coefficients(self, alpha: NDArray | float) -> tuple[NDArray, NDArray, NDArray]:
        """(cl, cd, cm) at the angles ``alpha`` (rad), interpolated as the BEM kernels do."""
        table = pack_polars((self,))
        alpha = np.atleast_1d(np.asarray(alpha, dtype=float))
        out = np.array([polar_lookup(a, 0, *table.arrays) for a in alpha])
        return out[:, 0], out[:, 1], out[:, 2]


@dataclass(frozen=True)
class PolarTable:
    """Polars packed for the kernels.

    knots : angles of every table, one after the other, rad
    values : (knot, [cl, cd, cm]) at the knots
    coefs : (knot, quantity, power) cubic coefficients of the interval starting at the knot (last knot: unused)
    start, count : first knot and number of knots of each table
    """

    knots: NDArray[np.float64]
    values: NDArray[np.float64]
    coefs: NDArray[np.float64]
    start: NDArray[np.int64]
    count: NDArray[np.int64]

    @property
    def arrays(self) -> tuple[NDArray, ...]:
        return self.knots, self.values, self.coefs, self.start, self.count


def pack_polars(polars: tuple[Polar, ...] | list[Polar]) -> PolarTable:
    """The interval coefficients of every polar, stacked for :func:`polar_lookup`."""
    knots, values, coefs, start, count = [], [], [], [], []
    first = 0
    for polar in polars:
        y = np.column_stack([polar.cl, polar.cd, polar.cm]).astype(float)
        knots.append(np.asarray(polar.alpha, dtype=float))
        values.append(y)
        coefs.append(_interval_coefficients(np.asarray(polar.alpha, dtype=float), y, polar.order))
        start.append(first)
        count.append(len(polar.alpha))
        first += len(polar.alpha)
    return PolarTable(np.concatenate(knots), np.concatenate(values), np.concatenate(coefs),
                      np.array(start, dtype=np.int64), np.array(count, dtype=np.int64))


def _interval_coefficients(x: NDArray, y: NDArray, order: int) -> NDArray:
    """(knot, quantity, power) coefficients; the row of the last knot is zero."""
    c = np.zeros((len(x), 3, 4))
    if len(x) < 2:
        c[:, :, 0] = y
        return c
    if order == CUBIC and len(x) >= 3:
        from scipy.interpolate import CubicSpline      # imported here: a linear table (the usual) needs no scipy
        spline = CubicSpline(x, y, axis=0, bc_type="natural")
        c[:-1] = np.transpose(spline.c[::-1], (1, 2, 0))          # scipy: (power descending, interval, quantity)
    else:
        c[:-1, :, 0] = y[:-1]
        c[:-1, :, 1] = np.diff(y, axis=0) / np.diff(x)[:, None]
    return c


@kernel
def polar_lookup(alpha, table, knots, values, coefs, start, count):
    """(cl, cd, cm) of table ``table`` at ``alpha`` (rad): wrapped into [-pi, pi), end values outside the table."""
    two_pi = 2.0 * math.pi
    a = alpha - two_pi * math.floor((alpha + math.pi) / two_pi)
    first = start[table]
    last = first + count[table] - 1
    if a <= knots[first]:
        return values[first, 0], values[first, 1], values[first, 2]
    if a >= knots[last]:
        return values[last, 0], values[last, 1], values[last, 2]
    lo, hi = first, last
    while hi - lo > 1:                                 # knots[lo] <= a < knots[hi]
        mid = (lo + hi) // 2
        if knots[mid] <= a:
            lo = mid
        else:
            hi = mid
    d = a - knots[lo]
    cl = coefs[lo, 0, 0] + d * (coefs[lo, 0, 1] + d * (coefs[lo, 0, 2] + d * coefs[lo, 0, 3]))
    cd = coefs[lo, 1, 0] + d * (coefs[lo, 1, 1] + d * (coefs[lo, 1, 2] + d * coefs[lo, 1, 3]))
    cm = coefs[lo, 2, 0] + d * (coefs[lo, 2, 1] + d * (coefs[lo, 2, 2] + d * coefs[lo, 2, 3]))
    return cl, cd, cm
