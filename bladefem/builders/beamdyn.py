"""A bladefem :class:`Blade` from BeamDyn's primary and blade files.

The length is the arc length of the key points' polyline (BeamDyn fits a curve through them; the difference is the
chord error of that polyline); the stations sit at ``eta`` times that length. The twist is BeamDyn's
``initial_twist`` interpolated in arc length: positive turns the leading edge upwind in both codes (BeamDyn twists
about -z, docs/source/user/beamdyn/input_files.rst). The 6x6 sections go to the FE whole (or, on request,
reduced) by :mod:`bladefem.builders.section6x6`; the curvature of the reference axis (prebend ``kp_xr``, sweep
``kp_yr``) is the blade's curved reference axis through the key points (BeamDyn's ``x`` toward the suction side is
bladefem's downwind ``z``, its ``y`` toward the trailing edge bladefem's ``-y``), or straightened on request.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..formats.beamdyn import BeamDynBlade, BeamDynPrimary
from ..sections import Blade
from .section6x6 import SixBySixBlade


def key_point_arc_length(points: np.ndarray) -> np.ndarray:
    """Arc length along the key points' polyline, m."""
    return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points[:, :3], axis=0), axis=1))])


def beamdyn_sections(primary: BeamDynPrimary, blade: BeamDynBlade) -> SixBySixBlade:
    """The six-by-six sections of a BeamDyn blade at its stations, with the key points' axis and twist."""
    arc = key_point_arc_length(primary.key_points)
    span = blade.eta * arc[-1]
    axis = np.stack([np.interp(span, arc, primary.key_points[:, k]) for k in range(3)], axis=1)
    twist = np.radians(np.interp(span, arc, primary.key_points[:, 3]))
    points = np.column_stack([arc, primary.key_points[:, :3]])
    return SixBySixBlade(span, blade.stiffness, blade.mass, twist, axis, source=blade.path, lines=blade.lines,
                         axis_points=points)


def blade_from_beamdyn(primary: BeamDynPrimary, blade: BeamDynBlade, hub_radius: float = 0.0,
                       precone: float = 0.0, pitch: float = 0.0, sections: str = "full",
                       axis: str = "curved") -> Blade:
    """The blade of a BeamDyn primary and blade file; hub radius in m (BeamDyn has none), angles in rad;
    ``sections`` ``"full"`` (the whole 6x6 in the FE), ``"condensed"`` or ``"reduced"``
    (:meth:`SixBySixBlade.table`); ``axis`` ``"curved"`` (the key points' prebend and sweep) or ``"straight"``
    (:meth:`SixBySixBlade.on_axis`)."""
    six, reference, axis_note = beamdyn_sections(primary, blade).on_axis(axis)
    table, notes = six.table(sections)
    notes = [f"BeamDyn blade from {Path(primary.path).name or 'memory'} and {Path(blade.path).name or 'memory'}: "
             + axis_note] + notes
    if hub_radius == 0.0:
        notes.append("hub radius 0 (BeamDyn files do not give it: --hub-radius sets it)")
    return Blade(sections=table, hub_radius=hub_radius, precone=precone, pitch=pitch,
                 name=f"{primary.title or 'BeamDyn'} blade", notes=tuple(notes), axis=reference)
