"""Operating schedule file: rotor speed and blade pitch against wind speed (a controller's steady-state curve).

Plain text, one point per line: wind speed (m/s), rotor speed (rpm), pitch (deg), separated by commas or blanks;
lines starting with ``#`` and a header line of words are skipped. Wind speeds strictly increasing. Between points
the rotor speed and pitch are interpolated linearly; outside them the file says nothing and a wind speed there is
refused. Example: ``cases/nrel5mw/table_7_1_schedule.csv``, the NREL 5MW's steady operation of Jonkman et al.
(2009), Table 7-1.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..files import decode_utf8, read_input


@dataclass(frozen=True)
class Schedule:
    """Rotor speed (rad/s) and pitch (rad) at increasing wind speeds (m/s); ``path`` the file it came from."""

    wind_speed: NDArray
    rotor_speed: NDArray
    pitch: NDArray
    path: str = "<schedule>"

    def at(self, wind_speed: float) -> tuple[float, float]:
        """(rotor speed rad/s, pitch rad) at ``wind_speed`` (m/s), interpolated linearly."""
        low, high = float(self.wind_speed[0]), float(self.wind_speed[-1])
        if not low - 1e-9 <= wind_speed <= high + 1e-9:
            raise InputError(f"the schedule covers {low:g} to {high:g} m/s, not {wind_speed:g} m/s", file=self.path,
                             field="--wind-speed")
        return (float(np.interp(wind_speed, self.wind_speed, self.rotor_speed)),
                float(np.interp(wind_speed, self.wind_speed, self.pitch)))


def read_schedule(path: str | os.PathLike) -> Schedule:
    """The schedule of a file (module description); every mistake is an :class:`InputError` naming its line."""
    path = str(path)
    text = decode_utf8(read_input(path), path)
    rows: list[tuple[float, float, float]] = []
    for number, line in enumerate(text.splitlines(), start=1):
        words = line.replace(",", " ").split()
        if not words or words[0].startswith("#"):
            continue
        try:
            values = [float(word) for word in words]
        except ValueError:
            if rows:
                raise InputError(f"expected three numbers (wind speed m/s, rotor speed rpm, pitch deg), got "
                                 f"'{line.strip()}'", file=path, line=number) from None
            continue                                                     # a header line
        if len(values) != 3 or not all(math.isfinite(v) for v in values):
            raise InputError(f"expected three numbers (wind speed m/s, rotor speed rpm, pitch deg), got "
                             f"'{line.strip()}'", file=path, line=number)
        if values[0] < 0 or values[1] < 0:
            raise InputError("wind speed and rotor speed must not be negative", file=path, line=number)
        if rows and values[0] <= rows[-1][0]:
            raise InputError("wind speeds must increase from line to line", file=path, line=number)
        rows.append((values[0], values[1], values[2]))
    if not rows:
        raise InputError("no schedule points (wind speed m/s, rotor speed rpm, pitch deg)", file=path)
    data = np.array(rows)
    return Schedule(wind_speed=data[:, 0], rotor_speed=data[:, 1] * math.pi / 30.0, pitch=np.radians(data[:, 2]),
                    path=path)
