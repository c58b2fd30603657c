"""A bladefem :class:`Blade` from a HAWC2 structural file (``.st``) and, for the twist and the reference axis, the
``c2_def`` of the blade's main body in the ``.htc``.

Axes (taken as fact from openfast_toolbox converters/hawc2ToBeamDyn.py and beamDynToHawc2.py): HAWC2's section
``x``, ``y`` are BeamDyn's ``-y``, ``x`` (``x_BD = y_H2``, ``y_BD = -x_H2``), ``z`` the same; the c2_def twist is
minus BeamDyn's (and bladefem's); the structural ``pitch`` turns the principal axes about +z in both. In the
isotropic layout ``E I_y`` is the bending stiffness about BeamDyn's ``x`` (edgewise) and ``E I_x`` about ``y``
(flapwise), ``k_y``, ``k_x`` the shear factors along BeamDyn's ``x``, ``y``. The radii of gyration ``ri_x``, ``ri_y``
are about the elastic centre, for rotation about the principal bending axes ``x_e``, ``y_e`` (the st format as the
DTU Wind Energy Toolbox, wetb, documents it; ``ri_y`` for rotation about BeamDyn's ``x``): they are moved to the
centre of mass by the parallel-axis theorem. The IEA-22MW st file follows this (its rotary inertias then match
windIO's); the IEA-15MW one holds them about the centre of gravity (openfast_toolbox's converters read and write
them so), and is read as the format says: docs/formats.md gives the difference. The
fully populated layout's 6x6 is given about the elastic centre ``(x_e, y_e)`` in the axes turned by the pitch
(beamDyn2Hawc2FPM_raw writes it so); it is taken back to the half-chord reference point. The st file's sections sit
on the half-chord line (c2_def); bladefem's reference axis is the pitch axis, the body's z axis, so each section is
moved along its chord by ``-x / cos(twist)`` (the half-chord point on the chord line through the pitch axis, whose
in-plane projection is c2_def's ``x``; in the IEA-15MW files c2_def's ``y`` less the BeamDyn key points' prebend is
that distance times ``sin(twist)``, as this assumes). c2_def's ``y`` less that is the prebend of the blade's curved
reference axis (:meth:`~bladefem.builders.section6x6.SixBySixBlade.on_axis`).
Everything then goes through :mod:`bladefem.builders.section6x6`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import InputError
from ..formats.hawc2_htc import MainBody
from ..formats.hawc2_st import StSubset
from ..sections import Blade
from .beamdyn import key_point_arc_length
from ..sections.full_section import about_reference, mass_matrix, stiffness_matrix
from .section6x6 import SixBySixBlade
from .section_axes import from_beamdyn_axes, to_beamdyn_axes

#: HAWC2 section axes -> BeamDyn's, for vectors (forces, moments): (x, y, z)_BD = Q (x, y, z)_H2
Q3 = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
Q = np.kron(np.eye(2), Q3)


def _inertia_about_centre_of_mass(subset: StSubset) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rotary inertias per length about the centre of mass in the section axes (kg m): edgewise (rotation about
    BeamDyn's ``x``), flapwise (about ``y``) and the product term (BeamDyn's mass-matrix entry ``M45``), from the
    radii of gyration, which the format gives about the elastic centre in the principal bending axes (``ri_y`` for
    rotation about BeamDyn's ``x``): turned to the section axes and moved to the centre of mass by the
    parallel-axis theorem (which adds a product of inertia)."""
    c = subset.column
    m, pitch = c("m"), np.radians(c("pitch"))
    cos, sin = np.cos(pitch), np.sin(pitch)
    about_elastic = np.zeros((len(m), 2, 2))
    about_elastic[:, 0, 0], about_elastic[:, 1, 1] = m * c("ri_y") ** 2, m * c("ri_x") ** 2
    turn = np.zeros_like(about_elastic)
    turn[:, 0, 0], turn[:, 0, 1], turn[:, 1, 0], turn[:, 1, 1] = cos, sin, -sin, cos
    section = np.swapaxes(turn, 1, 2) @ about_elastic @ turn          # the mass matrix's rotary block about E
    dx, dy = c("y_cg") - c("y_e"), -(c("x_cg") - c("x_e"))           # centre of mass from the elastic centre
    return section[:, 0, 0] - m * dy**2, section[:, 1, 1] - m * dx**2, section[:, 0, 1] + m * dx * dy


def sections_in_beamdyn_axes(subset: StSubset) -> tuple[np.ndarray, np.ndarray]:
    """(n, 6, 6) stiffness and mass of a subset, about the half-chord point in BeamDyn's axes. Built in
    bladefem's section axes (:mod:`bladefem.sections.full_section`), where HAWC2's ``(x, y)`` is ``(eta, zeta)``
    and its structural pitch, a turn about +z, is minus bladefem's principal angle."""
    c = subset.column
    angle = -np.radians(c("pitch"))
    m = c("m")
    edge, flap, product = _inertia_about_centre_of_mass(subset)
    mass = np.array([mass_matrix(m[i], (c("x_cg")[i], c("y_cg")[i]), flap[i], edge[i], product[i])
                     for i in range(len(m))])
    if subset.fpm:
        local = from_beamdyn_axes(Q @ subset.stiffness() @ Q.T)
        stiffness = np.array([about_reference(k, (e, z), a) for k, e, z, a in zip(local, c("x_e"), c("y_e"), angle)])
    else:
        E, G, A = c("E"), c("G"), c("A")
        stiffness = np.array([stiffness_matrix(
            E[i] * A[i], G[i] * c("I_p")[i], E[i] * c("I_x")[i], E[i] * c("I_y")[i], c("k_x")[i] * G[i] * A[i],
            c("k_y")[i] * G[i] * A[i], tension_centre=(c("x_e")[i], c("y_e")[i]), principal_angle=angle[i],
            shear_centre=(c("x_sh")[i], c("y_sh")[i]), shear_angle=angle[i]) for i in range(len(m))])
    return to_beamdyn_axes(stiffness), to_beamdyn_axes(mass)


def hawc2_sections(subset: StSubset, body: MainBody | None, st_path: str = "") -> SixBySixBlade:
    """The six-by-six sections of an st subset about the pitch axis (moved from the half chord by the body's c2_def;
    without a body: about the half chord, untwisted, straight)."""
    r = subset.column("r")
    span = r - r[0]
    stiffness, mass = sections_in_beamdyn_axes(subset)
    axis = np.zeros((len(span), 3))
    axis[:, 2] = span
    twist = np.zeros_like(span)
    if body is not None:
        points = body.c2_def
        arc = key_point_arc_length(points)
        if abs(arc[-1] - span[-1]) > 0.01 * arc[-1]:
            raise InputError(f"the st file's r runs to {span[-1]:.6g} m but body '{body.name}''s c2_def is "
                             f"{arc[-1]:.6g} m long: not this blade's st file?", file=st_path or None, field="r")
        at = span / span[-1]
        twist = -np.radians(np.interp(at, arc / arc[-1], points[:, 3]))
        # the half-chord point lies on the chord line through the pitch axis (body z): c2_def's in-plane x is the
        # projection of its chordwise distance d toward the trailing edge (BeamDyn's y), -x = d cos(twist); the
        # pitch axis is then at the c2 point less d along the chord, (y - d sin(twist), 0) in BeamDyn's root axes
        chordwise = -np.interp(at, arc / arc[-1], points[:, 0]) / np.cos(twist)
        stiffness, mass = (to_beamdyn_axes(np.array([about_reference(k, (-d, 0.0)) for k, d in
                                                     zip(from_beamdyn_axes(matrices), chordwise)]))
                           for matrices in (stiffness, mass))
        axis[:, 0] = np.interp(at, arc / arc[-1], points[:, 1]) - chordwise * np.sin(twist)
        axis[:, 2] = np.interp(at, arc / arc[-1], points[:, 2])
    return SixBySixBlade(span, stiffness, mass, twist, axis, source=st_path, lines=subset.lines)


def blade_from_hawc2(subset: StSubset, body: MainBody | None, st_path: str = "", hub_radius: float = 0.0,
                     precone: float = 0.0, pitch: float = 0.0, sections: str = "full",
                     axis: str = "curved") -> Blade:
    """The blade of a HAWC2 st subset; the twist and reference axis from the main body's c2_def (None: untwisted,
    named in the notes); ``sections`` ``"full"``, ``"condensed"`` or ``"reduced"`` (:meth:`SixBySixBlade.table`);
    ``axis`` ``"curved"`` (c2_def's prebend) or ``"straight"`` (:meth:`SixBySixBlade.on_axis`)."""
    six, reference, axis_note = hawc2_sections(subset, body, st_path).on_axis(axis)
    table, reduction = six.table(sections)
    layout = "fully populated (FPM)" if subset.fpm else "isotropic"
    notes = [f"HAWC2 {layout} st file {Path(st_path).name or 'memory'}"]
    if body is not None:
        notes.append(f"HAWC2 blade (body '{body.name}', c2_def): {axis_note}"
                     + "; sections moved along the chord from the half-chord line to the pitch axis (body z)")
    else:
        notes.append("HAWC2 st file without its htc: untwisted (give the .htc with the blade's c2_def for the twist)")
    if hub_radius == 0.0:
        notes.append("hub radius 0 (the st file does not give it: --hub-radius sets it)")
    return Blade(sections=table, hub_radius=hub_radius, precone=precone, pitch=pitch,
                 name=f"{body.name if body else 'HAWC2'} blade", notes=tuple(notes + reduction), axis=reference)
