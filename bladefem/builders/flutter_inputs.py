"""What the flutter analysis takes from an AeroDyn deck beyond the quasi-steady rotor: the deck settings it replaces
with its own model, and the aerodynamic centre's chordwise place on the blade (the one convention decided here)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from ..aero.rotor import Rotor
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
