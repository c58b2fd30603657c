"""Assembly of the blade's global matrices from the weak forms in :mod:`bladefem.assembly.terms`."""

from .blade import BladeMatrices, assemble_blade, model_fields
from .dofs import DofMap
from .mesh import span_mesh, span_nodes
from .parameters import centrifugal_tension, section_parameters

__all__ = ["BladeMatrices", "DofMap", "assemble_blade", "centrifugal_tension", "model_fields",
           "section_parameters", "span_mesh", "span_nodes"]
