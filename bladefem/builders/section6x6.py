"""Six-by-six beam sections in BeamDyn's axes, and their reduction to bladefem's diagonal :class:`SectionTable`.

Axes (OpenFAST docs/source/user/beamdyn/input_files.rst): ``x`` toward the suction side (downwind for an upwind
rotor), ``y`` toward the trailing edge, ``z`` along the reference axis; rows and columns (shear x, shear y,
extension, bending about x = edgewise, bending about y = flapwise, torsion); matrices about the reference axis in the
frame turned by the twist. bladefem's section frame is ``eta = -y`` (toward the leading edge), ``zeta = x``
(downwind), so chordwise offsets change sign.

The reduction (what today's beam can hold, per station):

1. The transverse shear is condensed (shear forces zero, the slender-beam limit):
   ``Kc = K[2:, 2:] - K[2:, :2] K[:2, :2]^-1 K[:2, 2:]``; without shear stiffness the block is kept as it is
   (:func:`bladefem.sections.full_section.condensed`, the one definition, through the axes' mapping).
2. Tension centre from the axial-bending coupling, ``y_C = Kc34 / EA``, ``x_C = -Kc35 / EA`` (the convention of
   openfast_toolbox converters/beam.py ``KK``: ``K34 = EA y_C``, ``K35 = -EA x_C``); the bending stiffness about it
   is the Schur complement ``H = Kc[4:6, 4:6] - Kc[4:6, 3] Kc[3, 4:6] / EA``.
3. Principal axes: ``H`` turned by the angle ``theta`` (about +z, at most 45 degrees) that makes it diagonal:
   ``EI_edge``, ``EI_flap`` its diagonal; bladefem's structural twist is ``twist - theta`` (bladefem's twist turns
   the leading edge upwind, a rotation about -z).
4. GJ = ``Kc66`` (about the shear centre once the shear is condensed).
5. Mass (openfast_toolbox ``MM``: ``M34 = m y_G``, ``M35 = -m x_G``): ``m = M11``, the centre of mass, and the
   rotary inertias about it ``M44 - m y_G^2`` (edgewise, about x) and ``M55 - m x_G^2`` (flapwise, about y).
6. Shear centre (kept for reference in the table) from ``K[:3, :3]^-1 K[:3, 3:]`` (openfast_toolbox
   ``ComputeShearCenter``).

:class:`SixBySixBlade` is every format's blade in these terms (whole matrices, twist, curved reference axis). Its
``table()`` gives the FE the whole matrices with the transverse shear by default (:meth:`SixBySixBlade.full`, through
:mod:`bladefem.builders.section_axes` onto :class:`~bladefem.sections.FullSections`), ``table("condensed")`` with the
shear condensed; ``table("reduced")`` is this
reduction.

Dropped, and named with their size in :func:`reduction_notes`: the extension-twist and bend-twist couplings left in
``Kc`` (36, 46, 56 after the principal rotation), the thickness-wise tension-centre and centre-of-mass offsets
``x_C``, ``x_G``, the product of inertia and the shear flexibility. The reference axis (prebend, sweep) goes to
the blade as it is (:meth:`SixBySixBlade.on_axis`), or straightened onto the pitch axis on request.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..sections import FullSections, ReferenceAxis, SectionTable, full_section
from ..sections.principal import principal_axes
from .section_axes import from_beamdyn_axes, full_sections_from_beamdyn

#: How six-by-six sections reach the FE: the whole matrices with the transverse shear (default, a Timoshenko beam),
#: the whole matrices with the shear condensed (Euler-Bernoulli), or bladefem's diagonal reduction
SECTION_MODELS = ("full", "condensed", "reduced")
#: How the reference axis reaches the FE: curved as the file gives it (default), or straightened onto the pitch axis
AXIS_MODELS = ("curved", "straight")
#: Couplings and offsets smaller than this (fraction of sqrt(K_ii K_jj), or m) are not mentioned in the notes.
NOTE_THRESHOLD = 0.01


@dataclass(frozen=True)
class Reduced:
    """bladefem's diagonal section at each station (SI; chordwise offsets positive toward the leading edge)."""

    mass: NDArray[np.float64]
    flap_stiffness: NDArray[np.float64]
    edge_stiffness: NDArray[np.float64]
    torsion_stiffness: NDArray[np.float64]
    axial_stiffness: NDArray[np.float64]
    principal_angle: NDArray[np.float64]
    flap_inertia: NDArray[np.float64]
    edge_inertia: NDArray[np.float64]
    cm_offset: NDArray[np.float64]
    tension_centre_offset: NDArray[np.float64]
    shear_centre_offset: NDArray[np.float64]
    #: what is dropped, per station: name -> magnitude (fraction of sqrt(K_ii K_jj), or m, or kg m)
    dropped: dict[str, NDArray[np.float64]]


def _classical_in_beamdyn_axes(K: NDArray[np.float64]) -> NDArray[np.float64]:
    """The 4x4 (extension, bending x, bending y, torsion) in BeamDyn's axes with the shear condensed out, shape
    (n, 4, 4): :func:`bladefem.sections.full_section.condensed` taken through the axes' mapping."""
    C = np.moveaxis(full_section.condensed(np.moveaxis(from_beamdyn_axes(K), 0, -1)), -1, 0)
    # bladefem's classical strains (epsilon, kappa_x, kappa_eta, kappa_zeta) are BeamDyn's (extension, torsion,
    # -bending about y, bending about x)
    S = np.zeros((4, 4))
    S[0, 0], S[1, 3], S[2, 2], S[3, 1] = 1.0, 1.0, -1.0, 1.0
    return S @ C @ S.T


def reduce(K: NDArray[np.float64], M: NDArray[np.float64]) -> Reduced:
    """Reduce (n, 6, 6) stiffness and mass matrices (BeamDyn's axes) to bladefem's diagonal section."""
    K = np.asarray(K, dtype=float)
    M = np.asarray(M, dtype=float)
    Kc = _classical_in_beamdyn_axes(K)
    EA = Kc[:, 0, 0]
    axial = EA > 0
    safe = np.where(axial, EA, 1.0)
    y_c = np.where(axial, Kc[:, 0, 1] / safe, 0.0)
    x_c = np.where(axial, -Kc[:, 0, 2] / safe, 0.0)
    H = Kc[:, 1:3, 1:3] - np.where(axial, 1.0, 0.0)[:, None, None] * (
        Kc[:, 1:3, 0][:, :, None] * Kc[:, 0, 1:3][:, None, :]) / safe[:, None, None]
    # bladefem's (kappa_eta, kappa_zeta) are BeamDyn's (-bending about y, bending about x); theta turns about +z,
    # the principal angle about -z (like the twist)
    B = np.stack([np.stack([H[:, 1, 1], -H[:, 0, 1]], -1), np.stack([-H[:, 0, 1], H[:, 0, 0]], -1)], -2)
    angle, flap, edge = principal_axes(B)
    theta = -angle
    c, s = np.cos(theta), np.sin(theta)
    m = M[:, 0, 0]
    y_g = M[:, 2, 3] / m
    x_g = -M[:, 2, 4] / m
    edge_inertia = M[:, 3, 3] - m * y_g**2
    flap_inertia = M[:, 4, 4] - m * x_g**2
    product = M[:, 3, 4] + m * x_g * y_g
    shear_centre = np.zeros_like(m)
    for i, k in enumerate(K):
        if np.linalg.det(k[:2, :2]) > 0 and k[2, 2] > 0:
            Y = np.linalg.solve(k[:3, :3], -k[:3, 3:])
            shear_centre[i] = -Y[0, 2]                 # -(y_S): chordwise toward the leading edge
    rotation = np.zeros((len(m), 4, 4))
    rotation[:, 0, 0] = rotation[:, 3, 3] = 1
    rotation[:, 1, 1] = rotation[:, 2, 2] = c
    rotation[:, 1, 2], rotation[:, 2, 1] = s, -s
    principal = rotation @ Kc @ np.swapaxes(rotation, 1, 2)
    dropped = {
        "extension-twist coupling K36": _ratio(principal, 0, 3),
        "edgewise bend-twist coupling K46": _ratio(principal, 1, 3),
        "flapwise bend-twist coupling K56": _ratio(principal, 2, 3),
        "shear-torsion coupling K16": _ratio(K, 0, 5, shift=0),
        "shear-torsion coupling K26": _ratio(K, 1, 5, shift=0),
        "thickness-wise tension-centre offset (m)": np.abs(x_c),
        "thickness-wise centre-of-mass offset (m)": np.abs(x_g),
        "product of inertia (kg m)": np.abs(product),
    }
    return Reduced(mass=m, flap_stiffness=flap, edge_stiffness=edge, torsion_stiffness=Kc[:, 3, 3],
                   axial_stiffness=EA, principal_angle=theta, flap_inertia=flap_inertia, edge_inertia=edge_inertia,
                   cm_offset=-y_g, tension_centre_offset=-y_c, shear_centre_offset=shear_centre, dropped=dropped)


def _ratio(K: NDArray, i: int, j: int, shift: int = 0) -> NDArray[np.float64]:
    scale = np.sqrt(np.abs(K[:, i, i] * K[:, j, j]))
    return np.abs(K[:, i, j]) / np.where(scale > 0, scale, np.inf)


def reduction_notes(reduced: Reduced) -> list[str]:
    """One sentence per dropped term that matters (above :data:`NOTE_THRESHOLD`), and the principal-axis turn."""
    notes = []
    big = [f"{name} up to {np.max(values):.2g}" + ("" if "(" in name else " of sqrt(K_ii K_jj)")
           for name, values in reduced.dropped.items() if np.max(values) > NOTE_THRESHOLD]
    if big:
        notes.append("6x6 section reduced to bladefem's diagonal beam; neglected: " + "; ".join(big))
    angle = np.degrees(np.max(np.abs(reduced.principal_angle)))
    notes.append(f"transverse shear condensed (slender beam, no shear flexibility); bending about the tension centre "
                 f"and the principal axes (turned up to {angle:.2g} deg from the chord, added to the twist)")
    return notes


def section_table(span: NDArray[np.float64], K: NDArray[np.float64], M: NDArray[np.float64],
                  twist: NDArray[np.float64], source: str = "", lines: tuple[int, ...] | None = None,
                  field: str = "") -> tuple[SectionTable, list[str]]:
    """bladefem's section table from six-by-six sections (BeamDyn's axes) at arc lengths ``span`` (m) with the
    chord's twist ``twist`` (rad, bladefem's sign: the leading edge upwind); and the notes on what is dropped.
    A section whose reduced bending stiffness or mass is not positive is an :class:`InputError` at its station's
    line (``lines``) naming ``field`` (default the column)."""
    r = reduce(K, M)
    for name, values, what in (("edge_stiffness", r.edge_stiffness, "edgewise EI about the tension centre"),
                               ("flap_stiffness", r.flap_stiffness, "flapwise EI about the tension centre"),
                               ("mass", r.mass, "mass per length")):
        bad = np.flatnonzero(~(values > 0))
        if bad.size:
            i = int(bad[0])
            raise InputError(f"station {i + 1} (span {span[i]:.6g} m): {what} is {values[i]:.6g}: the 6x6 section "
                             "is not positive definite", file=source or None,
                             line=lines[i] if lines else None, field=field or name)
    positive = np.all(r.axial_stiffness > 0)
    table = SectionTable(
        span=span, mass=r.mass, flap_stiffness=r.flap_stiffness, edge_stiffness=r.edge_stiffness,
        torsion_stiffness=r.torsion_stiffness if np.all(r.torsion_stiffness > 0) else None,
        axial_stiffness=r.axial_stiffness if positive else None,
        twist=twist - r.principal_angle, flap_inertia=np.maximum(r.flap_inertia, 0.0),
        edge_inertia=np.maximum(r.edge_inertia, 0.0), cm_offset=r.cm_offset,
        tension_centre_offset=r.tension_centre_offset if positive else None,
        shear_centre_offset=r.shear_centre_offset, source=source, lines=lines)
    notes = reduction_notes(r)
    if not positive:
        notes.append("no axial stiffness (K33) at every station: inextensible, tension-centre offsets dropped")
    if table.torsion_stiffness is None:
        notes.append("no torsional stiffness (K66) at every station: torsionally rigid")
    return table, notes


@dataclass(frozen=True, eq=False)
class SixBySixBlade:
    """A blade as six-by-six sections in BeamDyn's axes, whichever file it came from (BeamDyn, HAWC2, windIO): what
    a full six-by-six beam model needs, and what :meth:`table` reduces to today's beam.

    span : (n,) station positions along the reference axis's arc length from the root, m
    stiffness, mass : (n, 6, 6) about the reference (pitch) axis in the section axes turned by ``twist``
    twist : (n,) the chord's twist, rad (bladefem's sign: positive turns the leading edge upwind)
    axis : (n, 3) the reference axis at the stations in the blade-root axes: x toward the suction side (prebend,
        negative upwind), y toward the trailing edge (sweep), z along the pitch axis, m
    source, lines, field : where the sections were read, for error messages
    axis_points : (k, 4) the points that define the reference axis, when finer than the stations (BeamDyn's key
        points): arc length (m, the stations' scale), then x, y, z as ``axis``
    """

    span: NDArray[np.float64]
    stiffness: NDArray[np.float64]
    mass: NDArray[np.float64]
    twist: NDArray[np.float64]
    axis: NDArray[np.float64]
    source: str = ""
    lines: tuple[int, ...] | None = None
    field: str = ""
    axis_points: NDArray[np.float64] | None = None

    def reference_axis(self) -> ReferenceAxis:
        """The reference axis in bladefem's blade frame (:class:`~bladefem.sections.ReferenceAxis`): the prebend is
        ``x`` (toward the suction side: downwind, so an upwind rotor's prebend is negative), the sweep ``-y``
        (toward the leading edge), both from the root point, over the stations' arc length."""
        points = (np.column_stack([self.span, self.axis]) if self.axis_points is None
                  else np.asarray(self.axis_points, dtype=float))
        arc = points[:, 0] * (self.span[-1] / points[-1, 0])
        return ReferenceAxis(arc, -(points[:, 2] - points[0, 2]), points[:, 1] - points[0, 1])

    def straightened(self) -> SixBySixBlade:
        """The blade on its pitch axis as a straight-blade code holds it (ElastoDyn; BeamDyn with ``kp_xr = kp_yr =
        0``): the stations at the same fractions of the length along the pitch axis (the axis's last ``z`` less its
        first), the sections and twist unchanged."""
        points = self.axis if self.axis_points is None else np.asarray(self.axis_points)[:, 1:]
        span = self.span * ((points[-1, 2] - points[0, 2]) / self.span[-1])
        axis = np.zeros_like(self.axis)
        axis[:, 2] = span
        return replace(self, span=span, axis=axis, axis_points=None)

    def on_axis(self, model: str = "curved") -> tuple[SixBySixBlade, ReferenceAxis | None, str]:
        """The blade for an axis ``model`` (:data:`AXIS_MODELS`): itself with its reference axis, or
        :meth:`straightened` without one; and the note that says which."""
        if model not in AXIS_MODELS:
            raise InputError(f"the reference axis must be one of {', '.join(AXIS_MODELS)}, got '{model}'",
                             field="--straight-axis")
        prebend = np.max(np.abs(self.axis[:, 0] - self.axis[0, 0]))
        sweep = np.max(np.abs(self.axis[:, 1] - self.axis[0, 1]))
        if model == "straight":
            straight = self.straightened()
            return straight, None, (f"reference axis straightened onto the pitch axis (--straight-axis): "
                                    f"{straight.span[-1]:.6g} m long (prebend up to {prebend:.3g} m, sweep up to "
                                    f"{sweep:.3g} m left out)")
        axis = self.reference_axis()
        if not axis.curved:
            return self, None, f"straight reference axis, {self.span[-1]:.6g} m long"
        return self, axis, (f"curved reference axis {self.span[-1]:.6g} m long (prebend up to {prebend:.3g} m, sweep "
                            f"up to {sweep:.3g} m): curved-beam strains, centrifugal and gyroscopic terms on the "
                            "curve (--straight-axis straightens it onto the pitch axis)")

    def full(self, chord: NDArray[np.float64] | None = None) -> FullSections:
        """The whole six-by-six sections in bladefem's section frame (:mod:`bladefem.builders.section_axes`), with
        the chord (m) at the stations for drawing."""
        return full_sections_from_beamdyn(self.span, self.stiffness, self.mass, self.twist, source=self.source,
                                          chord=chord)

    def table(self, model: str = "full", chord: NDArray[np.float64] | None = None) -> tuple[SectionTable, list[str]]:
        """The section table the FE takes and the notes on what it keeps and drops. ``model``: ``"full"`` (the
        default) carries the whole six-by-six matrices (:class:`~bladefem.sections.FullSections`: every coupling
        and the transverse shear, a Timoshenko beam); ``"condensed"`` the same with the shear condensed (an
        Euler-Bernoulli beam); ``"reduced"`` is bladefem's diagonal beam (:func:`section_table`), which drops the
        couplings the notes name."""
        if model not in SECTION_MODELS:
            raise InputError(f"sections must be one of {', '.join(SECTION_MODELS)}, got '{model}'",
                             field="--sections")
        reduced, dropped = section_table(self.span, self.stiffness, self.mass, self.twist, self.source, self.lines,
                                         self.field)
        if model == "reduced":
            if chord is not None:
                reduced = replace(reduced, chord=chord)
            return reduced, ["sections reduced (--sections reduced): " + dropped[0]] + dropped[1:]
        kept = [note.split("neglected: ", 1)[1] for note in dropped if "neglected: " in note]
        shear = ("transverse shear kept (Timoshenko beam; --sections condensed condenses it)" if model == "full"
                 else "transverse shear condensed (slender beam; --sections full keeps it)")
        notes = ["full six-by-six sections in the FE (tension and shear centres, principal axes, extension-twist "
                 f"and bend-twist couplings, the whole section mass); {shear}"
                 + (f"; --sections reduced (bladefem's diagonal beam) would drop {kept[0]}" if kept else "")]
        try:
            full = self.full(chord).with_shear(model == "full")
        except InputError as error:
            station = re.search(r"\(station (\d+)\)", error.message)
            line = self.lines[int(station.group(1)) - 1] if station and self.lines else error.line
            raise InputError(f"{error.message}: the whole section cannot go into the FE (--sections reduced "
                             "condenses it to bladefem's diagonal beam)", file=error.file, line=line,
                             field=self.field or error.field) from None
        return full.table(), notes
