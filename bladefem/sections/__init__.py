"""Section properties, their interpolation along the span, and blade geometry (the bottom layer)."""

from .blade import ROOTS, Blade, Root, TipMass, tip_mass_at_section
from .moments import (
           MassMoments,
           bending_stiffness,
           extension_bending_stiffness,
           mass_moments,
           total_angle,
)
from .table import SectionTable, uniform_sections

__all__ = ["ROOTS", "Blade", "MassMoments", "Root", "SectionTable", "TipMass", "bending_stiffness",
           "extension_bending_stiffness", "mass_moments", "tip_mass_at_section", "total_angle", "uniform_sections"]
