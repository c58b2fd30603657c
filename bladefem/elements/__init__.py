"""Element definitions and the kinematics of a section (rigid slice) in a rotating frame."""

from .beam import (
           ALL_FIELDS,
           BENDING_FIELDS,
           FIELD_KINDS,
           SectionMotion,
           basis_motions,
           beam_element,
           interpolated_motion,
)
from .rigid_slice import projected_inertia, rotation_second_order, skew

__all__ = ["ALL_FIELDS", "BENDING_FIELDS", "FIELD_KINDS", "SectionMotion", "basis_motions", "beam_element",
           "interpolated_motion", "projected_inertia", "rotation_second_order", "skew"]
