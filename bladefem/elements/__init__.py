"""Element definitions and the kinematics of a section (rigid slice) in a rotating frame."""

from .beam import (
           ALL_FIELDS,
           BENDING_FIELDS,
           FIELD_KINDS,
           SHEAR_FIELDS,
           SectionMotion,
           basis_functions,
           beam_element,
           interpolated_components,
           pair_motions,
)
from .curved import curved_motion, linear_projection
from .rigid_slice import (
           gyroscopic_inertia,
           projected_inertia,
           rotation_second_order,
           skew,
)

__all__ = ["ALL_FIELDS", "BENDING_FIELDS", "FIELD_KINDS", "SHEAR_FIELDS", "SectionMotion", "basis_functions",
           "beam_element", "curved_motion", "gyroscopic_inertia", "interpolated_components", "linear_projection",
           "pair_motions", "projected_inertia", "rotation_second_order", "skew"]
