"""A blade's curved reference axis: prebend and sweep off the pitch axis, as a smooth curve in arc length.

The axis runs from the blade root (on the pitch axis) with offsets ``y0(s)`` (in the rotor plane, sweep, positive
toward the leading edge) and ``z0(s)`` (out of the rotor plane, prebend, positive downwind) in the blade frame at
zero pitch, ``s`` the arc length. Both are cubic splines through the stations (not-a-knot); the position along the
pitch axis follows from the unit tangent, ``x0' = sqrt(1 - y0'^2 - z0'^2)``, so ``s`` is the curve's arc length.

Each point carries a local frame ``Lambda = (e1, e2, e3)`` (columns in the blade frame): ``e1`` the tangent, ``e2``
and ``e3`` the pitch axis's ``y`` and ``z`` turned by the least rotation that takes ``x`` to ``e1`` (for an axis
curved in one plane, the frame of the curve: ``e2 = y`` for prebend alone). The frame turns along the axis at the
rate ``K = (0, K2, K3)`` in its own components: ``e1' = K3 e2 - K2 e3``, so ``K2 = -e1'.e3`` (prebend: ``-z0''``
for small slopes) and ``K3 = e1'.e2`` (sweep: ``y0''``). The frame's own twist rate ``K1 = e2'.e3`` is zero for a
plane axis and of the order of the slope times the curvature otherwise; it is left out (docs/THEORY.md).
Blade pitch turns the whole axis about the pitch axis (positive to feather turns the leading edge upwind).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError

#: largest slope of the axis off the pitch axis accepted (sin of the angle): beyond it the blade is not a blade
MAX_SLOPE = 0.5
_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(6)


@dataclass(frozen=True)
class AxisFrame:
    """The axis at some arc lengths (trailing axes of every array).

    position : (3, ...) the axis point from the blade root in the blade frame, m
    rotation : (3, 3, ...) ``Lambda``, columns ``e1, e2, e3`` in the blade frame
    curvature : (2, ...) ``(K2, K3)``, 1/m
    curvature_rate : (2, ...) their arc-length derivatives, 1/m^2
    """

    position: NDArray
    rotation: NDArray
    curvature: NDArray
    curvature_rate: NDArray

    def to_local(self, vector: NDArray) -> NDArray:
        """Blade-frame vectors (3, ...) or one vector (3,) in the local frame: ``Lambda^T v``."""
        return np.einsum("ji...,j...->i...", self.rotation, vector)

    def tensor_to_local(self, tensor: NDArray) -> NDArray:
        """A 3x3 tensor (3, 3) or (3, 3, ...) in the local frame: ``Lambda^T Q Lambda``."""
        return np.einsum("ai...,ab...,bj...->ij...", self.rotation, tensor, self.rotation)


def _pitch_rotation(pitch: float) -> NDArray:
    """The rotation about the pitch axis ``x`` by ``-pitch`` (pitch to feather turns ``y`` toward ``-z``)."""
    c, s = np.cos(pitch), np.sin(pitch)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, s], [0.0, -s, c]])


@dataclass(frozen=True)
class ReferenceAxis:
    """The reference axis off the pitch axis.

    span : (n,) arc-length stations from the root, m (increasing, first 0, last the blade's length)
    sweep : (n,) in-plane offset ``y0``, m (positive toward the leading edge)
    prebend : (n,) out-of-plane offset ``z0``, m (positive downwind; an upwind rotor's prebend is negative)
    """

    span: NDArray[np.float64]
    sweep: NDArray[np.float64]
    prebend: NDArray[np.float64]
    _splines: tuple = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        values = [np.asarray(getattr(self, name), dtype=float) for name in ("span", "sweep", "prebend")]
        for name, v in zip(("span", "sweep", "prebend"), values):
            object.__setattr__(self, name, v)
            if v.ndim != 1 or len(v) != len(values[0]) or not np.all(np.isfinite(v)):
                raise InputError(f"the reference axis's {name} must be finite numbers, one per station",
                                 field=f"axis.{name}")
        if len(self.span) < 2 or self.span[0] != 0.0 or np.any(np.diff(self.span) <= 0):
            raise InputError("the reference axis's arc lengths must increase from 0", field="axis.span")
        if abs(self.sweep[0]) > 0 or abs(self.prebend[0]) > 0:
            raise InputError("the reference axis must start on the pitch axis (offsets 0 at the root)",
                             field="axis.prebend")
        kind = "not-a-knot" if len(self.span) > 3 else "natural"
        from scipy.interpolate import CubicSpline    # here: scipy.interpolate brings scipy.optimize
        splines = (CubicSpline(self.span, self.sweep, bc_type=kind), CubicSpline(self.span, self.prebend,
                                                                                  bc_type=kind))
        fine = np.linspace(0.0, self.span[-1], 50 * len(self.span))
        slope = np.hypot(splines[0](fine, 1), splines[1](fine, 1))
        if np.max(slope) > MAX_SLOPE:
            k = int(np.argmax(slope))
            raise InputError(f"the reference axis turns {np.degrees(np.arcsin(min(slope[k], 1.0))):.3g} deg off the "
                             f"pitch axis at {fine[k]:.6g} m (at most {np.degrees(np.arcsin(MAX_SLOPE)):.3g} deg)",
                             field="axis.prebend")
        object.__setattr__(self, "_splines", splines)

    @property
    def length(self) -> float:
        """Arc length, m."""
        return float(self.span[-1])

    @property
    def curved(self) -> bool:
        """Whether the axis leaves the pitch axis anywhere."""
        return bool(np.any(self.sweep != 0) or np.any(self.prebend != 0))

    def _derivatives(self, s: NDArray, order: int) -> list[NDArray]:
        """(x0, y0, z0) derivatives of orders 1 to ``order`` (at most 3) at ``s``, each of shape (3, ...)."""
        y = [spline(s, 1) for spline in self._splines]
        x1 = np.sqrt(1.0 - y[0] ** 2 - y[1] ** 2)
        derivatives = [np.stack([x1, y[0], y[1]])]
        if order == 1:
            return derivatives
        y2 = [spline(s, 2) for spline in self._splines]
        x2 = -(y[0] * y2[0] + y[1] * y2[1]) / x1
        derivatives.append(np.stack([x2, y2[0], y2[1]]))
        if order == 2:
            return derivatives
        y3 = [spline(s, 3) for spline in self._splines]
        x3 = -(y2[0] ** 2 + y[0] * y3[0] + y2[1] ** 2 + y[1] * y3[1] + x2**2) / x1
        return [*derivatives, np.stack([x3, y3[0], y3[1]])]

    def along_pitch_axis(self, s: NDArray) -> NDArray:
        """``x0(s) = int_0^s x0' ds``, m (Gauss quadrature on each spline piece)."""
        s = np.asarray(s, dtype=float)
        knots = self.span

        def integral(a: NDArray, b: NDArray) -> NDArray:
            half = 0.5 * (b - a)
            points = (0.5 * (a + b))[..., None] + half[..., None] * _GAUSS_X
            return half * np.sum(self._derivatives(points, 1)[0][0] * _GAUSS_W, axis=-1)

        pieces = np.concatenate([[0.0], np.cumsum(integral(knots[:-1], knots[1:]))])
        k = np.clip(np.searchsorted(knots, s, side="right") - 1, 0, len(knots) - 2)
        return pieces[k] + integral(knots[k], s)

    def arc_length(self, along: NDArray) -> NDArray:
        """The arc lengths (m) at which the axis reaches ``along`` (m) along the pitch axis (``x0(s) = along``; x0 is
        increasing), clipped to the axis: a table of x0 inverted, then one Newton step."""
        fine = np.linspace(0.0, self.length, 64 * len(self.span))
        target = np.clip(np.asarray(along, dtype=float), 0.0, float(self.along_pitch_axis(np.array(self.length))))
        s = np.interp(target, self.along_pitch_axis(fine), fine)
        return np.clip(s - (self.along_pitch_axis(s) - target) / self._derivatives(s, 1)[0][0], 0.0, self.length)

    def frame(self, s: NDArray, pitch: float = 0.0) -> AxisFrame:
        """The axis's position, frame and curvatures at arc lengths ``s`` (m), the blade pitched by ``pitch``
        (rad)."""
        s = np.asarray(s, dtype=float)
        R = _pitch_rotation(pitch)
        turn = lambda a: np.einsum("ij,j...->i...", R, a)   # noqa: E731
        position = turn(np.stack([self.along_pitch_axis(s), self._splines[0](s), self._splines[1](s)]))
        t, t1, t2 = (turn(derivative) for derivative in self._derivatives(s, 3))
        # least rotation taking x to t: Lambda = I + [v]x + [v]x^2 / (1 + c), v = x cross t, c = t_x
        v = np.stack([np.zeros_like(t[0]), -t[2], t[1]])
        V = np.zeros((3, 3) + s.shape)
        V[0, 1], V[0, 2], V[1, 0], V[1, 2], V[2, 0], V[2, 1] = -v[2], v[1], v[2], -v[0], -v[1], v[0]
        rotation = np.eye(3).reshape((3, 3) + (1,) * s.ndim) + V + np.einsum("ij...,jk...->ik...", V, V) / (1 + t[0])
        e2, e3 = rotation[:, 1], rotation[:, 2]
        dot = lambda a, b: np.einsum("i...,i...->...", a, b)   # noqa: E731
        curvature = np.stack([-dot(t1, e3), dot(t1, e2)])
        curvature_rate = np.stack([-dot(t2, e3), dot(t2, e2)])
        return AxisFrame(position, rotation, curvature, curvature_rate)

    def displaced(self, s: NDArray, displacement: NDArray, pitch: float = 0.0) -> ReferenceAxis:
        """The axis moved by ``displacement`` (3, n) at arc lengths ``s`` (m, from 0 to the length), given in the
        blade frame of a blade pitched by ``pitch`` (rad): its in-plane and out-of-plane parts added to the offsets
        at the same arc length (the stretch along the axis left out: it changes the offsets at second order)."""
        s = np.asarray(s, dtype=float)
        moved = _pitch_rotation(pitch).T @ np.asarray(displacement, dtype=float)
        return ReferenceAxis(s, self._splines[0](s) + moved[1] - moved[1][0],
                             self._splines[1](s) + moved[2] - moved[2][0])
