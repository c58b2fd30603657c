"""What the flutter analysis takes from an AeroDyn deck beyond the quasi-steady rotor: the deck settings it replaces
with its own model, and the aerodynamic centre's chordwise place on the blade (the one convention decided here)."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from ..aero.rotor import Rotor
    from ..assembly import BladeMatrices
    from ..sections import Blade

#: AeroDyn settings that the flutter analysis accepts, and what it does instead
UNSTEADY = "the airfoils' unsteady model is replaced by Theodorsen's attached-flow theory about the operating point"
FROZEN = "the induction is frozen at the operating point (the linearization's frozen wake)"
ALONE = "the blade alone in the wind: tower, nacelle and buoyancy loads are not part of a blade's flutter"
REPLACED = {"UA_Mod": UNSTEADY, "AFAeroMod": UNSTEADY, "DBEMT_Mod": FROZEN, "WakeMod": FROZEN,
            **{label: ALONE for label in ("TwrPotent", "TwrShadow", "TwrAero", "Buoyancy", "NacelleDrag",
                                          "TFinAero", "CavitCheck", "CompAA")}}
#: the aerodynamic centre's chordwise position, fraction of the chord from the leading edge (thin-airfoil theory)
AC_FRACTION = 0.25


def chordwise_centre(blade: Blade, rotor: Rotor, notes: list[str]) -> NDArray | float:
    """The aerodynamic centre ahead of AeroDyn's reference line (m, per AeroDyn node): the quarter chord when the
    blade input gives the reference axis's chordwise position, else 0 (OpenFAST's convention)."""
    sections = blade.sections
    if sections.pitch_axis is None:
        notes.append("aerodynamic centre on AeroDyn's reference line (the blade input gives no pitch-axis position)")
        return 0.0
    axis = np.interp(rotor.span, sections.span - sections.span[0], sections.pitch_axis)
    notes.append("aerodynamic centre at the quarter chord, ahead of the reference axis by (pitch_axis - 0.25) "
                 "chord")
    return (axis - AC_FRACTION) * rotor.chord


def flutter_rotor(aerodyn: str | os.PathLike, blade: Blade, n_blades: int, still_air: bool
                  ) -> tuple[Rotor, NDArray | float, list[str]]:
    """The rotor a flutter sweep of ``blade`` runs on: the AeroDyn primary file's blade and polars with the
    settings of :data:`REPLACED` named, without induction when every operating point is in ``still_air`` (the
    relative velocity is the rotation alone); the aerodynamic centre ahead of AeroDyn's reference line
    (:func:`chordwise_centre`, m) and the notes of both, as ``bladefem flutter`` and a batch case run it."""
    from dataclasses import replace

    from .aerodyn_rotor import aerodyn_rotor, require_root_off_axis

    rotor = aerodyn_rotor(aerodyn, blade, n_blades, replaced=REPLACED)
    require_root_off_axis(rotor)
    notes = list(rotor.notes) + list(blade.notes)
    if still_air and rotor.options.induction:
        rotor = replace(rotor, options=replace(rotor.options, induction=False))
        notes.append("still air: no induction (the relative velocity is the blade's rotation)")
    centre = chordwise_centre(blade, rotor, notes)
    return rotor, centre, notes


def structure_notes(matrices: BladeMatrices) -> list[str]:
    """What the flutter sweep says of the blade's matrices: their own notes, a torsion-rigid input, no structural
    damping."""
    notes = list(matrices.notes)
    if "phi" not in matrices.dofs.fields:
        notes.append("torsion is rigid in this input (no torsion stiffness): no flap-torsion flutter can appear; a "
                     "BeamDyn, HAWC2 or windIO input, or a case file with torsion_stiffness_N_m2, has it")
    notes.append("no structural damping: a mode whose damping ratio turns negative is unstable (flutter)")
    return notes
