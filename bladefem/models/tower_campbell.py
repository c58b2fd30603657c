"""The tower designer's rotor-speed chart: tower frequencies against the rotor's 1P and blade-passing (3P) bands.

A tower's natural frequencies do not depend on the rotor speed in this model (no gyroscopic coupling), so the
chart is the tower's modes as constant lines over rotor speed, the excitation lines ``n Omega`` and the *bands*
they sweep over the operating range ``[rpm_low, rpm_high]``: 1P from ``rpm_low / 60`` to ``rpm_high / 60`` Hz and
3P (blade passing of a three-bladed rotor) from three times that. The first tower bending frequency ``f1``
classifies the design (with a relative separation ``margin`` from each band, 10 % by default, as design
guidelines ask):

- *soft-soft*: ``f1`` below the 1P band;
- *soft-stiff*: between the 1P and the 3P band (the usual choice for large turbines);
- *stiff-stiff*: above the 3P band;
- *resonant*: inside a band or within the margin of it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..modal.results import ModalResult, Mode
from ..sections.tower import Tower
from .tower import tower_modes

__all__ = ["BENDING", "MARGIN", "Band", "TowerCampbell", "tower_campbell"]

#: relative separation asked between the first tower frequency and the edges of the 1P and 3P bands
MARGIN = 0.10
#: tower kinds that count as bending for the classification
BENDING = ("fore-aft", "side-side")


@dataclass(frozen=True)
class Band:
    """The frequencies an excitation ``harmonic`` x rotor speed sweeps over the operating range, Hz."""

    harmonic: int
    low_hz: float
    high_hz: float

    def contains(self, frequency_hz: float, margin: float = 0.0) -> bool:
        """True when ``frequency_hz`` lies inside the band widened by ``margin`` (relative) on both sides."""
        return self.low_hz * (1 - margin) <= frequency_hz <= self.high_hz * (1 + margin)


@dataclass(frozen=True)
class TowerCampbell:
    """Tower modes over a sweep of rotor speeds, with the rotor's excitation bands.

    rpm : swept rotor speeds, rpm (the chart's axis; the frequencies are the same at every speed)
    modes : the tower's modes
    operating_rpm : (low, high) operating range of the rotor, rpm
    blades : number of blades (the blade-passing harmonic)
    margin : relative separation asked from each band
    """

    rpm: NDArray[np.float64]
    modes: ModalResult
    operating_rpm: tuple[float, float]
    blades: int = 3
    margin: float = MARGIN

    @property
    def bands(self) -> tuple[Band, Band]:
        """The 1P band and the blade-passing band over the operating range."""
        low, high = self.operating_rpm
        return tuple(Band(n, n * low / 60.0, n * high / 60.0) for n in (1, self.blades))  # type: ignore[return-value]

    @property
    def first_bending(self) -> Mode:
        """The lowest fore-aft or side-side mode."""
        return next(mode for mode in self.modes.modes if mode.kind in BENDING)

    def bands_hit(self, mode: Mode) -> list[str]:
        """Names ('1P', '3P') of the bands, widened by the margin, that contain the mode's frequency."""
        return [f"{band.harmonic}P" for band in self.bands if band.contains(mode.frequency_hz, self.margin)]

    @property
    def verdict(self) -> str:
        """'soft-soft', 'soft-stiff', 'stiff-stiff' or 'resonant' (see the module docstring)."""
        f1 = self.first_bending.frequency_hz
        one, passing = self.bands
        if one.contains(f1, self.margin) or passing.contains(f1, self.margin):
            return "resonant"
        if f1 < one.low_hz:
            return "soft-soft"
        return "soft-stiff" if f1 < passing.low_hz else "stiff-stiff"

    def statement(self) -> str:
        """One sentence: the classification, where the first frequency lies, and the bands."""
        f1 = self.first_bending.frequency_hz
        one, passing = self.bands
        bands = (f"1P band {one.low_hz:.4g}-{one.high_hz:.4g} Hz, {passing.harmonic}P band {passing.low_hz:.4g}-"
                 f"{passing.high_hz:.4g} Hz over the operating range {self.operating_rpm[0]:g}-"
                 f"{self.operating_rpm[1]:g} rpm")
        hit = next((band for band in self.bands if band.contains(f1, self.margin)), None)
        if hit is None:
            where = "below the 1P band" if f1 < one.low_hz else (
                "between the 1P and the blade-passing band" if f1 < passing.low_hz else "above the blade-passing band")
        elif hit.contains(f1):
            where = f"inside the {hit.harmonic}P band"
        else:
            where = f"within the {self.margin:.0%} margin of the {hit.harmonic}P band"
        return f"{self.verdict}: the first tower frequency {f1:.4g} Hz lies {where} ({bands})"


def tower_campbell(tower: Tower, rpm: Sequence[float], n_modes: int = 6, elements: int | None = None,
                   operating_rpm: tuple[float, float] | None = None, blades: int = 3,
                   margin: float = MARGIN) -> TowerCampbell:
    """The chart of ``tower`` over rotor speeds ``rpm`` (rpm). ``operating_rpm``: the rotor's (low, high)
    operating range, rpm (default: the swept range)."""
    speeds = np.asarray(rpm, dtype=float)
    if speeds.size == 0 or not np.all(np.isfinite(speeds)) or np.any(speeds < 0):
        raise ValueError("rotor speeds must be finite and non-negative")
    if blades < 1:
        raise ValueError(f"need at least one blade, got {blades}")
    low, high = operating_rpm if operating_rpm is not None else (float(speeds.min()), float(speeds.max()))
    if not 0 <= low <= high:
        raise ValueError(f"need 0 <= low <= high for the operating range, got {low}, {high}")
    return TowerCampbell(rpm=speeds, modes=tower_modes(tower, n_modes, elements), operating_rpm=(low, high),
                         blades=blades, margin=margin)
