"""TurbSim binary full-field wind files (``.bts``), read and written.

The layout is the one OpenFAST's InflowWind reads (``modules/inflowwind/src/InflowWind_IO.f90``,
``IfW_TurbSim_Init``; TurbSim's ``WrBinTURBSIM``), little-endian and packed: a header of

    int16 FileID (7: not periodic, 8: periodic); int32 NZ, NY, NTwr, NT;
    float32 dz, dy, dt (m, m, s), mean hub-height speed (m/s), hub height (m), height of the grid's bottom (m);
    float32 (slope, offset) of u, v, w; int32 length of the description; the description (ASCII)

then, for each time step, int16 counts of u, v, w at every grid point (components fastest, then y from -y to +y,
then z upwards) and at the NTwr tower points below the grid; velocity = (count - offset) / slope, m/s.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..files import read_input, write_atomic

HEADER = np.dtype([("id", "<i2"), ("nz", "<i4"), ("ny", "<i4"), ("ntwr", "<i4"), ("nt", "<i4"), ("dz", "<f4"),
                   ("dy", "<f4"), ("dt", "<f4"), ("mean_speed", "<f4"), ("hub_height", "<f4"), ("z0", "<f4"),
                   ("slope_u", "<f4"), ("offset_u", "<f4"), ("slope_v", "<f4"), ("offset_v", "<f4"),
                   ("slope_w", "<f4"), ("offset_w", "<f4"), ("description_length", "<i4")])
#: a grid larger than this many numbers is refused (about 4 GB as float32)
MAX_VALUES = 10**9


@dataclass(frozen=True)
class TurbSimBox:
    """A full-field box: ``velocity`` (nt, ny, nz, 3) m/s (float32) at times ``k dt``, y from ``-(ny - 1) dy / 2``,
    heights ``z0 + i dz``; ``tower`` (nt, ntwr, 3) below the grid; mean speed (m/s) at ``hub_height`` (m)."""

    velocity: NDArray
    tower: NDArray
    dt: float
    dy: float
    dz: float
    z0: float
    mean_speed: float
    hub_height: float
    periodic: bool
    description: str = ""


def read_turbsim(path: str | os.PathLike) -> TurbSimBox:
    """Read a ``.bts`` file; :class:`InputError` naming the file and the header field for anything else."""
    path = str(path)
    data = read_input(path)
    if len(data) < HEADER.itemsize:
        raise InputError(f"too short for a TurbSim header ({len(data)} of {HEADER.itemsize} bytes)", path)
    head = np.frombuffer(data[:HEADER.itemsize], HEADER)[0]

    def refuse(field: str, message: str) -> InputError:
        return InputError(f"TurbSim header {field} = {head[field]}: {message}", path, field=field)

    if head["id"] not in (7, 8):
        raise refuse("id", "not a TurbSim full-field file (7: not periodic, 8: periodic)")
    for field in ("nz", "ny", "nt"):
        if head[field] < 1:
            raise refuse(field, "must be at least 1")
    if head["ntwr"] < 0:
        raise refuse("ntwr", "must not be negative")
    for field in ("dz", "dy", "dt", "mean_speed", "slope_u", "slope_v", "slope_w"):
        if not np.isfinite(head[field]) or head[field] <= 0:
            raise refuse(field, "must be positive")
    for field in ("hub_height", "z0", "offset_u", "offset_v", "offset_w"):
        if not np.isfinite(head[field]):
            raise refuse(field, "must be finite")
    nz, ny, ntwr, nt = (int(head[k]) for k in ("nz", "ny", "ntwr", "nt"))
    length = int(head["description_length"])
    step = 3 * (ny * nz + ntwr)
    if step * nt > MAX_VALUES:
        raise refuse("nt", f"{step * nt} values is more than bladefem reads ({MAX_VALUES})")
    expected = HEADER.itemsize + length + 2 * step * nt
    if length < 0 or len(data) != expected:
        raise InputError(f"{len(data)} bytes, the header ({nz} x {ny} grid, {ntwr} tower points, {nt} steps, a "
                         f"description of {length} bytes) needs {expected}", path, field="nt")
    description = data[HEADER.itemsize:HEADER.itemsize + length].decode("ascii", "replace")
    counts = np.frombuffer(data, "<i2", offset=HEADER.itemsize + length).reshape(nt, step)
    slope = np.array([head["slope_u"], head["slope_v"], head["slope_w"]], dtype=np.float32)
    offset = np.array([head["offset_u"], head["offset_v"], head["offset_w"]], dtype=np.float32)
    grid = (counts[:, :3 * ny * nz].reshape(nt, nz, ny, 3).astype(np.float32) - offset) / slope
    tower = (counts[:, 3 * ny * nz:].reshape(nt, ntwr, 3).astype(np.float32) - offset) / slope
    return TurbSimBox(velocity=np.ascontiguousarray(grid.transpose(0, 2, 1, 3)), tower=tower, dt=float(head["dt"]),
                      dy=float(head["dy"]), dz=float(head["dz"]), z0=float(head["z0"]),
                      mean_speed=float(head["mean_speed"]), hub_height=float(head["hub_height"]),
                      periodic=bool(head["id"] == 8), description=description)


def write_turbsim(path: str | os.PathLike, box: TurbSimBox) -> None:
    """Write ``box`` as a ``.bts`` file (whole or not at all), scaled as TurbSim does: each component's range onto
    the int16 counts."""
    velocity = np.asarray(box.velocity, dtype=np.float64).transpose(0, 2, 1, 3)     # (nt, nz, ny, 3)
    tower = np.asarray(box.tower, dtype=np.float64).reshape(velocity.shape[0], -1, 3)
    nt, nz, ny, _ = velocity.shape
    both = np.concatenate([velocity.reshape(nt, -1, 3), tower], axis=1)
    low, high = both.min(axis=(0, 1)), both.max(axis=(0, 1))
    span = np.where(high - low > 0, high - low, 1.0)
    slope = 65535.0 / span
    offset = -32768.0 - slope * low
    counts = np.clip(np.rint(both * slope + offset), -32768, 32767).astype("<i2")
    text = box.description.encode("ascii", "replace")
    head = np.zeros((), HEADER)
    head["id"], head["nz"], head["ny"], head["ntwr"], head["nt"] = 8 if box.periodic else 7, nz, ny, \
        tower.shape[1], nt
    head["dz"], head["dy"], head["dt"], head["mean_speed"] = box.dz, box.dy, box.dt, box.mean_speed
    head["hub_height"], head["z0"] = box.hub_height, box.z0
    for c, name in enumerate("uvw"):
        head[f"slope_{name}"], head[f"offset_{name}"] = slope[c], offset[c]
    head["description_length"] = len(text)
    write_atomic(path, head.tobytes() + text + counts.tobytes())
