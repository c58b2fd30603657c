"""Unsteady wind of InflowWind: a uniform wind table (``WindType`` 2) and a full-field grid (``WindType`` 3, TurbSim),
evaluated at a point (x, y, z) of the inertial frame (x downwind, z up from the ground, y to the left looking
downwind; m) and a time t (s).

One scalar kernel, :func:`point_wind` (compiled as the BEM's, :mod:`bladefem.aero._jit`), is the wind of both
paths: the numpy reference calls it point by point, the compiled turbine kernels call it directly, so the two
cannot drift apart. It follows
OpenFAST's InflowWind (``modules/inflowwind/src/IfW_FlowField.f90``):

- steady (``kind`` 1): ``V (z / RefHt)^PLExp`` along the propagation direction and upflow;
- uniform (``kind`` 2, ``UniformField_GetVel``): the table's columns interpolated linearly in time (the first and
  last rows held outside it), then ``V1 = V [(z/RefHt)^VShr + (HShr (y cos D + x sin D) + VLinShr (z - RefHt)) /
  RefLength] + VGust``, turned by the upflow angle (with the vertical speed) and then by the direction D
  (positive turns the wind towards -y);
- grid (``kind`` 3, ``Grid3DField_GetCell``/``GetVelLinear``): trilinear in (y, z, t) on the grid's velocities, with
  Taylor's frozen turbulence: the point at x reads the grid at ``t + (x_start - x) / U`` (``x_start`` half the
  grid width for a non-periodic file, 0 for a periodic one, which wraps in time). Points outside the grid take the
  nearest edge; :meth:`bladefem.aero.rotor.Inflow.check_covers` refuses a rotor or a duration the grid does not
  cover before a run starts, as OpenFAST stops on the first point outside.

Everything is zero at and below the ground (z <= 0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ._jit import kernel

#: columns of a uniform wind table: time (s), horizontal speed (m/s), direction (rad), vertical speed (m/s),
#: linear horizontal shear, power-law exponent, linear vertical shear (-), gust speed (m/s), upflow (rad)
UNIFORM_COLUMNS = ("time", "speed", "direction", "vertical", "horizontal_shear", "shear_exponent",
                   "vertical_shear", "gust", "upflow")
#: slots of the parameter vector of :func:`point_wind`
PARAMETERS = ("kind", "speed", "reference_height", "shear_exponent", "ux", "uy", "uz", "reference_length", "dt",
              "dy", "dz", "y0", "z0", "mean_speed", "x_start", "periodic")


@dataclass(frozen=True)
class UniformWind:
    """An InflowWind uniform wind table (SI, rad): rows of :data:`UNIFORM_COLUMNS` with increasing times, the
    reference height of the power law (m) and the reference length of the linear shears (m)."""

    table: NDArray
    reference_height: float
    reference_length: float


@dataclass(frozen=True)
class GridWind:
    """A full-field wind grid: velocities (nt, ny, nz, 3) in m/s (float32, as InflowWind stores them) at times
    ``k dt``, lateral positions ``y0 + j dy`` (y0 = -half the grid width), heights ``z0 + i dz`` above the ground
    (m); the mean speed that carries the field downwind (m/s), and whether it repeats in time."""

    velocity: NDArray
    dt: float
    dy: float
    dz: float
    z0: float
    mean_speed: float
    periodic: bool

    @property
    def half_width(self) -> float:
        return 0.5 * (self.velocity.shape[1] - 1) * self.dy

    @property
    def x_start(self) -> float:
        """InflowWind's ``InitXPosition``: 0 for a periodic field, else half the grid width (m)."""
        return 0.0 if self.periodic else self.half_width

    @property
    def top(self) -> float:
        return self.z0 + (self.velocity.shape[2] - 1) * self.dz

    def time_span(self) -> float:
        """Seconds of wind in the file: ``nt dt`` periodic, ``(nt - 1) dt`` otherwise."""
        n = self.velocity.shape[0]
        return n * self.dt if self.periodic else (n - 1) * self.dt


@kernel
def point_wind(x: float, y: float, z: float, t: float, params: NDArray, table: NDArray, grid: NDArray,
               out: NDArray) -> None:
    """The wind velocity (m/s) at (x, y, z) and time t into ``out`` (3,): see the module's text. ``params`` is
    :data:`PARAMETERS`, ``table`` the uniform rows, ``grid`` the full field."""
    out[0], out[1], out[2] = 0.0, 0.0, 0.0
    if z <= 0.0:
        return
    kind = params[0]
    if kind == 3.0:
        grid_velocity(x, y, z, t, params, grid, out)
    elif kind == 2.0:
        uniform_velocity(x, y, z, t, params, table, out)
    else:
        speed = params[1]
        if params[3] != 0.0:
            speed = params[1] * (z / params[2]) ** params[3]
        out[0], out[1], out[2] = speed * params[4], speed * params[5], speed * params[6]


@kernel
def uniform_velocity(x: float, y: float, z: float, t: float, params: NDArray, table: NDArray, out: NDArray) -> None:
    """InflowWind's ``UniformField_InterpLinear`` and ``UniformField_GetVel``."""
    n = table.shape[0]
    lo, alpha = 0, 0.0
    if n > 1 and t >= table[n - 1, 0]:
        lo = n - 1
    elif n > 1 and t >= table[0, 0]:
        hi = 1
        while t >= table[hi, 0]:
            hi += 1
        lo = hi - 1
        alpha = (t - table[lo, 0]) / (table[hi, 0] - table[lo, 0])
    speed, angle_h, vertical = _blend(table, lo, alpha, 1), _blend(table, lo, alpha, 2), _blend(table, lo, alpha, 3)
    shear_h, exponent, shear_v = _blend(table, lo, alpha, 4), _blend(table, lo, alpha, 5), _blend(table, lo, alpha, 6)
    gust, angle_v = _blend(table, lo, alpha, 7), _blend(table, lo, alpha, 8)
    height, length = params[2], params[7]
    cos_h, sin_h, cos_v, sin_v = math.cos(angle_h), math.sin(angle_h), math.cos(angle_v), math.sin(angle_v)
    v1 = speed * ((z / height) ** exponent + (shear_h * (y * cos_h + x * sin_h) + shear_v * (z - height)) / length) \
        + gust
    along = cos_v * v1 - sin_v * vertical
    out[0], out[1], out[2] = along * cos_h, -along * sin_h, sin_v * v1 + cos_v * vertical


@kernel
def _blend(table: NDArray, lo: int, alpha: float, column: int) -> float:
    """Column ``column`` of the table between rows ``lo`` and ``lo + 1`` at the fraction ``alpha``."""
    if alpha == 0.0:
        return table[lo, column]
    return (1.0 - alpha) * table[lo, column] + alpha * table[lo + 1, column]


@kernel
def grid_velocity(x: float, y: float, z: float, t: float, params: NDArray, grid: NDArray, out: NDArray) -> None:
    """Trilinear interpolation in (y, z, Taylor-shifted t) of the full field, as InflowWind's
    ``Grid3DField_GetVelLinear`` (edges held outside the grid)."""
    nt, ny, nz = grid.shape[0], grid.shape[1], grid.shape[2]
    shifted = (t + (params[14] - x) / params[13]) / params[8]
    if params[15] != 0.0:
        shifted = shifted % nt
        it = min(int(math.floor(shifted)), nt - 1)
        ft, it_hi = shifted - it, (it + 1) % nt
    else:
        shifted = min(max(shifted, 0.0), nt - 1.0)
        it = min(int(math.floor(shifted)), nt - 2) if nt > 1 else 0
        ft, it_hi = shifted - it, min(it + 1, nt - 1)
    iy, fy = _cell((y - params[11]) / params[9], ny)
    iz, fz = _cell((z - params[12]) / params[10], nz)
    iy_hi, iz_hi = min(iy + 1, ny - 1), min(iz + 1, nz - 1)
    for c in range(3):
        low = ((1 - fy) * (1 - fz) * grid[it, iy, iz, c] + fy * (1 - fz) * grid[it, iy_hi, iz, c]
               + (1 - fy) * fz * grid[it, iy, iz_hi, c] + fy * fz * grid[it, iy_hi, iz_hi, c])
        high = ((1 - fy) * (1 - fz) * grid[it_hi, iy, iz, c] + fy * (1 - fz) * grid[it_hi, iy_hi, iz, c]
                + (1 - fy) * fz * grid[it_hi, iy, iz_hi, c] + fy * fz * grid[it_hi, iy_hi, iz_hi, c])
        out[c] = (1 - ft) * low + ft * high


@kernel
def _cell(position: float, count: int) -> tuple[int, float]:
    """Lower index and fraction of ``position`` (in grid steps) on ``count`` points, held at the edges."""
    if count == 1:
        return 0, 0.0
    position = min(max(position, 0.0), count - 1.0)
    index = min(int(math.floor(position)), count - 2)
    return index, position - index


def wind_arrays(speed: float, reference_height: float, shear_exponent: float, direction: float, upflow: float,
                uniform: UniformWind | None, grid: GridWind | None) -> tuple[NDArray, NDArray, NDArray]:
    """``(params, table, grid)`` of :func:`point_wind` (the arrays the compiled kernels take; empty stand-ins for
    the kinds not used, of fixed types so that the kernels compile once)."""
    params = np.zeros(len(PARAMETERS))
    params[:7] = (1.0, speed, reference_height, shear_exponent, math.cos(upflow) * math.cos(direction),
                  -math.cos(upflow) * math.sin(direction), math.sin(upflow))
    table, field = np.zeros((1, len(UNIFORM_COLUMNS))), np.zeros((1, 1, 1, 3), dtype=np.float32)
    if uniform is not None:
        params[0], params[2], params[7] = 2.0, uniform.reference_height, uniform.reference_length
        table = np.ascontiguousarray(uniform.table, dtype=float)
    if grid is not None:
        params[0] = 3.0
        params[8:16] = (grid.dt, grid.dy, grid.dz, -grid.half_width, grid.z0, grid.mean_speed, grid.x_start,
                        float(grid.periodic))
        field = np.ascontiguousarray(grid.velocity, dtype=np.float32)
    return params, table, field


def velocities(points: NDArray, t: float, arrays: tuple[NDArray, NDArray, NDArray]) -> NDArray:
    """The wind (..., 3) at ``points`` (..., 3) and time t: :func:`point_wind` point by point (numpy reference)."""
    points = np.asarray(points, dtype=float)
    flat = points.reshape(-1, 3)
    out = np.zeros_like(flat)
    for i, (x, y, z) in enumerate(flat):
        point_wind(float(x), float(y), float(z), float(t), *arrays, out[i])
    return out.reshape(points.shape)
