"""Section properties along a beam's span, linearly interpolated between stations.

Two stations at the same span position mark a step: the properties jump there (the first of the pair holds the
values below the step, the second those above it), e.g. at a monopile's pile-to-tower flange.

All quantities are SI: span positions in m measured along the reference (pitch) axis from the root of the flexible
part, mass per length in kg/m, bending and torsional stiffness in N m^2, axial stiffness in N, structural twist in
rad, mass moments of inertia per length in kg m, chordwise offsets in m.

Section frame: ``eta`` along the chord (positive toward the leading edge), ``zeta`` through the thickness (positive
toward the pressure side, i.e. downwind). The section is rotated by the structural twist (plus blade pitch) about the
span axis; see :mod:`bladefem.sections.moments`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields, replace
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError

if TYPE_CHECKING:
    from .full_section import FullSections

#: Columns that must be given and strictly positive.
POSITIVE = ("mass", "flap_stiffness", "edge_stiffness")
#: Optional stiffness columns; ``None`` means rigid (the DOF is removed from the model).
OPTIONAL_STIFFNESS = ("torsion_stiffness", "axial_stiffness")
#: Smallest station interval accepted, as a fraction of the length
MIN_STATION_GAP = 1e-6
#: Optional planform geometry (not used by the mechanics)
GEOMETRY = ("chord", "pitch_axis")
#: Columns that default to zero.
ZERO_DEFAULT = ("twist", "flap_inertia", "edge_inertia", "cm_offset", "shear_centre_offset",
                "tension_centre_offset")


@dataclass(frozen=True)
class SectionTable:
    """Section properties at span stations.

    Attributes
    ----------
    span : station positions along the reference axis from the root, m (increasing, first 0; an interior position
        given twice is a step in the properties)
    mass : mass per unit length, kg/m
    flap_stiffness : EI about the section's chordwise principal axis (flapwise bending), N m^2
    edge_stiffness : EI about the thickness principal axis (edgewise bending), N m^2
    torsion_stiffness : GJ, N m^2, or None for a torsionally rigid beam
    axial_stiffness : EA, N, or None for an inextensible beam
    twist : structural twist, rad (positive rotates the leading edge upwind, like pitch to feather)
    flap_inertia : mass moment of inertia per length about the chordwise axis through the centre of mass
        (int rho zeta^2 dA), kg m; resists flapwise section rotation
    edge_inertia : mass moment of inertia per length about the thickness axis through the centre of mass
        (int rho eta^2 dA), kg m; resists edgewise section rotation
    cm_offset : chordwise offset of the centre of mass from the reference axis, m (positive toward leading edge)
    shear_centre_offset : chordwise offset of the shear centre, m (kept for reference: in Euler-Bernoulli bending
        with St-Venant torsion the strain energy does not depend on it)
    tension_centre_offset : chordwise offset of the tension (elastic) centre, m
    chord : chord length, m (geometry only: for drawing the planform; None if unknown)
    pitch_axis : chordwise position of the reference (pitch) axis as a fraction of the chord from the leading
        edge (geometry only; None if unknown)
    inertia_per_mass : False: ``flap_inertia`` and ``edge_inertia`` vary linearly between stations, like every other
        column; True: the squared radii of gyration about the reference axis vary linearly, ``flap_inertia / mass``
        and ``(edge_inertia + mass cm_offset^2) / mass``, and the inertias follow from them and the interpolated
        mass and offset (BModes' convention)
    full : the whole six-by-six sections (:class:`~bladefem.sections.full_section.FullSections`, made by its
        ``table()``): when given, the finite elements take stiffness and mass from them, with every coupling, and
        the columns are their summary (:meth:`~bladefem.sections.full_section.FullSections.summary`), which must
        match
    """

    span: NDArray[np.float64]
    mass: NDArray[np.float64]
    flap_stiffness: NDArray[np.float64]
    edge_stiffness: NDArray[np.float64]
    torsion_stiffness: NDArray[np.float64] | None = None
    axial_stiffness: NDArray[np.float64] | None = None
    twist: NDArray[np.float64] | None = None
    flap_inertia: NDArray[np.float64] | None = None
    edge_inertia: NDArray[np.float64] | None = None
    cm_offset: NDArray[np.float64] | None = None
    shear_centre_offset: NDArray[np.float64] | None = None
    tension_centre_offset: NDArray[np.float64] | None = None
    chord: NDArray[np.float64] | None = None
    pitch_axis: NDArray[np.float64] | None = None
    inertia_per_mass: bool = False
    full: FullSections | None = field(default=None, compare=False, repr=False)
    source: str = field(default="", compare=False)
    #: 1-based line number of each station in ``source`` (for error messages), if known
    lines: tuple[int, ...] | None = field(default=None, compare=False)

    def __post_init__(self) -> None:
        span = np.asarray(self.span, dtype=float)
        object.__setattr__(self, "span", span)
        for name in POSITIVE + OPTIONAL_STIFFNESS + ZERO_DEFAULT + GEOMETRY:
            value = getattr(self, name)
            if value is None:
                if name in ZERO_DEFAULT:
                    object.__setattr__(self, name, np.zeros_like(span))
                continue
            array = np.broadcast_to(np.asarray(value, dtype=float), span.shape).copy()
            object.__setattr__(self, name, array)
        self.validate()

    @property
    def length(self) -> float:
        """Length of the beam, m."""
        return float(self.span[-1])

    @property
    def stations(self) -> int:
        return len(self.span)

    @property
    def nodes(self) -> NDArray[np.float64]:
        """The distinct station positions, m (a step's two stations are one position)."""
        return np.unique(self.span)

    def _error(self, message: str, index: int | None, name: str) -> InputError:
        line = self.lines[index] if (self.lines is not None and index is not None) else None
        if line is None and index is not None and not self.source:
            message = f"{message} (station {index + 1})"
        return InputError(message, file=self.source or None, line=line, field=name)

    def validate(self) -> None:
        """Raise :class:`InputError` naming the station and column of the first bad value."""
        if self.span.ndim != 1 or len(self.span) < 2:
            raise self._error("need at least two stations", None, "span")
        for f in fields(self):
            value = getattr(self, f.name)
            if not isinstance(value, np.ndarray):
                continue
            bad = np.flatnonzero(~np.isfinite(value))
            if bad.size:
                raise self._error(f"value is not a finite number ({value[bad[0]]})", int(bad[0]), f.name)
        if abs(self.span[0]) > 1e-12 * max(1.0, abs(self.span[-1])):
            raise self._error(f"first station must be at the root (0), got {self.span[0]}", 0, "span")
        gaps = np.diff(self.span)
        bad = gaps < 0
        bad[0] |= gaps[0] == 0                                  # no step at the root
        bad[-1] |= gaps[-1] == 0                                # nor at the tip
        bad[1:] |= (gaps[1:] == 0) & (gaps[:-1] == 0)           # a position at most twice
        steps = np.flatnonzero(bad)
        if steps.size:
            i = int(steps[0]) + 1
            raise self._error(f"stations must increase ({self.span[i - 1]} then {self.span[i]}; an interior position "
                              "may be given twice for a step, the root and the tip once)", i, "span")
        close = np.flatnonzero((gaps > 0) & (gaps < MIN_STATION_GAP * self.span[-1]))
        if close.size:
            i = int(close[0]) + 1
            raise self._error(f"stations {self.span[i - 1]} and {self.span[i]} are closer than {MIN_STATION_GAP:g} "
                              "of the length: merge them (a sliver element ruins the conditioning)", i, "span")
        for name in POSITIVE + OPTIONAL_STIFFNESS + ("chord",):
            value = getattr(self, name)
            if value is None:
                continue
            bad = np.flatnonzero(value <= 0)
            if bad.size:
                raise self._error(f"must be positive, got {value[bad[0]]}", int(bad[0]), name)
        if self.axial_stiffness is None and np.any(self.tension_centre_offset != 0):
            i = int(np.flatnonzero(self.tension_centre_offset)[0])
            raise self._error("a tension-centre offset needs the axial stiffness (EA): with the axial DOF removed the "
                              "reference axis, not the tension centre, would be held inextensible", i,
                              "tension_centre_offset")
        for name in ("flap_inertia", "edge_inertia"):
            bad = np.flatnonzero(getattr(self, name) < 0)
            if bad.size:
                raise self._error(f"must not be negative, got {getattr(self, name)[bad[0]]}", int(bad[0]), name)
        if self.full is not None:
            self._validate_full()

    def _validate_full(self) -> None:
        """The columns must be the summary of the six-by-six sections they carry (a column changed alone would
        leave the finite elements on the matrices)."""
        full = self.full
        if full.span.shape != self.span.shape or np.any(full.span != self.span):
            raise self._error("the six-by-six sections' stations differ from the table's", None, "span")
        if self.inertia_per_mass:
            raise self._error("six-by-six sections interpolate their matrices, not radii of gyration", None,
                              "inertia_per_mass")
        for name, value in full.summary().items():
            column = getattr(self, name)
            bad = np.flatnonzero(~np.isclose(column, value, rtol=1e-12, atol=1e-12 * np.max(np.abs(value))))
            if bad.size:
                raise self._error(f"differs from the six-by-six sections' {value[bad[0]]} (change the matrices, "
                                  "not the column)", int(bad[0]), name)

    def at(self, x: NDArray[np.float64], name: str) -> NDArray[np.float64]:
        """Column ``name`` at span positions ``x`` (m), any shape: linear between stations (the inertias per
        :attr:`inertia_per_mass`); at a step, the value above it."""
        if self.inertia_per_mass and name in ("flap_inertia", "edge_inertia"):
            mass = np.interp(x, self.span, self.mass)
            if name == "flap_inertia":
                return mass * np.interp(x, self.span, self.flap_inertia / self.mass)
            about_reference = self.edge_inertia / self.mass + self.cm_offset**2
            return mass * (np.interp(x, self.span, about_reference) - np.interp(x, self.span, self.cm_offset) ** 2)
        return np.interp(x, self.span, getattr(self, name))

    def scaled(self, mass: float = 1.0, stiffness: float = 1.0, flap_stiffness: float = 1.0,
               edge_stiffness: float = 1.0) -> SectionTable:
        """A copy with mass (and mass inertias) and stiffnesses multiplied by the given factors."""
        def times(value: NDArray | None, k: float) -> NDArray | None:
            return None if value is None else value * k
        if self.full is not None:
            if flap_stiffness != 1.0 or edge_stiffness != 1.0:
                raise InputError("six-by-six sections scale their whole stiffness, not flap or edge alone",
                                 field="sections")
            return self.full.scaled(mass=mass, stiffness=stiffness).table()
        return replace(
            self,
            mass=self.mass * mass,
            flap_inertia=self.flap_inertia * mass,
            edge_inertia=self.edge_inertia * mass,
            flap_stiffness=self.flap_stiffness * stiffness * flap_stiffness,
            edge_stiffness=self.edge_stiffness * stiffness * edge_stiffness,
            torsion_stiffness=times(self.torsion_stiffness, stiffness),
            axial_stiffness=times(self.axial_stiffness, stiffness),
        )

    def mass_moments(self, offset: float = 0.0) -> tuple[float, float, float]:
        """Total mass (kg), first (kg m) and second (kg m^2) mass moments about a point ``offset`` m inboard
        of the root, integrated exactly for the piecewise-linear mass distribution."""
        x0, x1 = self.span[:-1], self.span[1:]
        m0, m1 = self.mass[:-1], self.mass[1:]
        h = x1 - x0
        r0, r1 = x0 + offset, x1 + offset
        total = np.sum(h * (m0 + m1) / 2)
        first = np.sum(h / 6 * (m0 * (2 * r0 + r1) + m1 * (r0 + 2 * r1)))
        second = np.sum(h / 12 * (m0 * (3 * r0**2 + 2 * r0 * r1 + r1**2) + m1 * (r0**2 + 2 * r0 * r1 + 3 * r1**2)))
        return float(total), float(first), float(second)


def uniform_sections(length: float, mass: float, flap_stiffness: float, edge_stiffness: float | None = None,
                     torsion_stiffness: float | None = None, axial_stiffness: float | None = None,
                     flap_inertia: float = 0.0, edge_inertia: float = 0.0) -> SectionTable:
    """Uniform beam of the given length (m) and properties (see :class:`SectionTable` for units)."""
    return SectionTable(
        span=np.array([0.0, length]), mass=mass, flap_stiffness=flap_stiffness,
        edge_stiffness=flap_stiffness if edge_stiffness is None else edge_stiffness,
        torsion_stiffness=torsion_stiffness, axial_stiffness=axial_stiffness,
        flap_inertia=flap_inertia, edge_inertia=edge_inertia, source="uniform")
