"""A 16-DOF flexible multibody turbine model by Kane's method, fed by bladefem's modes (ElastoDyn's structure).

Numeric Kane formulation: partial velocities are evaluated at each state (``kinematics``), generalized inertia
and active forces summed over span nodes and bodies (``kane``), the equations integrated in time (``simulate``) or
linearized (``linearize``, ``campbell``). See docs/turbine.md.
"""

from .kane import TurbineModel
from .parameters import BLADE_DOFS, PLATFORM_DOFS, TurbineParameters, dof_names
from .shapes import (
           ModalBeam,
           closed_form_cantilever,
           hermite_evaluator,
           polynomial_evaluator,
           sample_beam,
)
from .system import FreeSystem, select_dofs

__all__ = ["BLADE_DOFS", "PLATFORM_DOFS", "FreeSystem", "ModalBeam", "TurbineModel", "TurbineParameters",
           "closed_form_cantilever", "dof_names", "hermite_evaluator", "polynomial_evaluator", "sample_beam",
           "select_dofs"]
