"""Assembly of the blade's global matrices from the weak forms in :mod:`bladefem.assembly.terms`."""

from .blade import BladeMatrices, assemble_blade, blade_graded_nodes, model_fields
from .dofs import DofMap
from .mesh import graded_nodes, span_mesh, span_nodes, subdivide
from .parameters import centrifugal_tension, section_parameters

__all__ = ["BladeMatrices", "DofMap", "assemble_blade", "blade_graded_nodes", "centrifugal_tension", "graded_nodes",
           "model_fields", "section_parameters", "span_mesh", "span_nodes", "subdivide"]
