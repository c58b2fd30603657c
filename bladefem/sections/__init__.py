"""Section properties, their interpolation along the span, and blade geometry (the bottom layer)."""

from .axis import AxisFrame, ReferenceAxis
from .blade import ROOTS, Blade, Gravity, Root, TipMass, tip_mass_at_section
from .full_section import FullSections, full_sections_from_table, mass_matrix, stiffness_matrix
from .moments import (
           MassMoments,
           bending_stiffness,
           extension_bending_stiffness,
           mass_moments,
           shear_flexible_stiffness,
           torsion_stiffness,
           total_angle,
           twist_coupling_stiffness,
)
from .table import SectionTable, uniform_sections

__all__ = ["ROOTS", "AxisFrame", "Blade", "FullSections", "Gravity", "MassMoments", "ReferenceAxis", "Root",
           "SectionTable", "TipMass", "bending_stiffness", "extension_bending_stiffness", "full_sections_from_table", "mass_matrix",
           "mass_moments", "shear_flexible_stiffness", "stiffness_matrix", "tip_mass_at_section", "torsion_stiffness",
           "total_angle",
           "twist_coupling_stiffness", "uniform_sections"]
