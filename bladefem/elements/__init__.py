"""Element definitions and the kinematics of a section (rigid slice) in a rotating frame."""

from .beam import (
           ALL_FIELDS,
           BENDING_FIELDS,
           FIELD_KINDS,
           SectionMotion,
           beam_element,
           section_motion,
)
from .rigid_slice import projected_inertia, rotation_second_order, skew

__all__ = ["ALL_FIELDS", "BENDING_FIELDS", "FIELD_KINDS", "SectionMotion", "beam_element", "projected_inertia",
           "rotation_second_order", "section_motion", "skew"]
