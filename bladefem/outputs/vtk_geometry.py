"""The blade placed in the rotor frame, and its mode shapes as 3-D displacements (for VTK files and pictures).

Rotor frame (used for every exported point and vector): origin at the rotor apex; ``z`` along the shaft axis,
downwind; ``x`` radial, in the plane of rotation, through the blade drawn at azimuth zero; ``y = z x x``, in the
plane of rotation toward the blade's leading edge (the direction of motion). With precone ``beta`` the blade
frame of docs/THEORY.md (``x`` along the preconed pitch axis, ``y`` edgewise, ``z`` flapwise downwind) is the
rotor frame turned by ``beta`` about ``y``: the blade-frame axis ``(1, 0, 0)`` is ``(cos beta, 0, sin beta)`` and
the shaft axis ``(sin beta, 0, cos beta)`` of the blade frame is ``(0, 0, 1)``. A tower (a non-rotating beam with
no hub radius and no precone) keeps its own frame: ``x`` up, ``z`` fore-aft, ``y`` side-side.

Section points follow the rigid-section kinematics of docs/THEORY.md: a point at chord coordinate ``eta`` (toward
the leading edge) on the chord line sits at ``s = (0, eta cos(theta), -eta sin(theta))`` from the reference axis
(``theta`` = structural twist + pitch) and moves by ``(u, v, w) + Theta x s`` with ``Theta = (phi, -w', v')``.
On a curved reference axis (prebend, sweep) the axis points lie on the curve and every section offset and
displacement, given in the section's local frame, is turned by that frame (:mod:`bladefem.sections.axis`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..modal.results import ModeShape
from ..sections import Blade, total_angle

#: chordwise position of the pitch axis assumed for drawing when the input gives a chord but no pitch axis
DEFAULT_PITCH_AXIS = 0.25


def blade_to_rotor(vectors: NDArray, precone: float) -> NDArray:
    """Components of blade-frame vectors (shape (..., 3)) in the rotor frame (rotation by the precone, rad)."""
    c, s = np.cos(precone), np.sin(precone)
    vectors = np.asarray(vectors, dtype=float)
    X, Y, Z = vectors[..., 0], vectors[..., 1], vectors[..., 2]
    return np.stack([c * X - s * Z, Y, s * X + c * Z], axis=-1)


def axis_points(blade: Blade, x: NDArray) -> NDArray:
    """Blade-frame positions (m, shape (n, 3)) of the reference axis at span positions ``x`` (m from the root; arc
    lengths on a curved axis)."""
    x = np.asarray(x, dtype=float)
    frame = blade.axis_frame(x)
    if frame is None:
        return np.stack([blade.hub_radius + x, np.zeros_like(x), np.zeros_like(x)], axis=-1)
    return np.moveaxis(frame.position, 0, -1) + np.array([blade.hub_radius, 0.0, 0.0])


def local_to_blade(blade: Blade, x: NDArray, vectors: NDArray) -> NDArray:
    """Vectors (shape (n, ..., 3)) given in the sections' local frames at ``x`` (m), in the blade frame: the same on
    a straight axis, turned by each point's frame on a curved one."""
    frame = blade.axis_frame(np.asarray(x, dtype=float))
    if frame is None:
        return vectors
    rotation = np.moveaxis(frame.rotation, -1, 0)                    # (n, 3, 3)
    vectors = np.asarray(vectors, dtype=float)
    turned = np.einsum("nij,n...j->n...i", rotation, vectors.reshape(len(rotation), -1, 3))
    return turned.reshape(vectors.shape)


def axis_positions(blade: Blade, x: NDArray) -> NDArray:
    """Rotor-frame positions (m, shape (n, 3)) of the reference axis at span positions ``x`` (m from the root)."""
    return blade_to_rotor(axis_points(blade, x), blade.precone)


def has_planform(blade: Blade) -> bool:
    """True when the section table gives a chord, so the blade can be drawn as a surface."""
    return blade.sections.chord is not None


def chord_edges(blade: Blade, x: NDArray) -> NDArray:
    """Chord coordinates ``eta`` (m, toward the leading edge) of the leading and trailing edges, shape (n, 2)."""
    sections = blade.sections
    chord = sections.at(x, "chord")
    fraction = sections.at(x, "pitch_axis") if sections.pitch_axis is not None else DEFAULT_PITCH_AXIS
    return np.stack([fraction * chord, -(1.0 - fraction) * chord], axis=-1)


def chord_offsets(blade: Blade, x: NDArray, eta: NDArray) -> NDArray:
    """Blade-frame offsets ``s = (0, y, z)`` (m, shape (n, k, 3)) of chord points ``eta`` (shape (n, k))."""
    theta = total_angle(blade.sections, np.asarray(x, dtype=float), blade.pitch)[:, None]
    return np.stack([np.zeros_like(eta), eta * np.cos(theta), -eta * np.sin(theta)], axis=-1)


def surface_positions(blade: Blade, x: NDArray) -> NDArray:
    """Rotor-frame positions (m, shape (n, 2, 3)) of the leading and trailing edges at span positions ``x``."""
    s = local_to_blade(blade, x, chord_offsets(blade, x, chord_edges(blade, x)))
    return blade_to_rotor(axis_points(blade, x)[:, None, :] + s, blade.precone)


def axis_displacement(shape: ModeShape, x: NDArray) -> NDArray:
    """Blade-frame displacement ``(u, v, w)`` (m per unit modal amplitude, shape (n, 3)) of the reference axis."""
    at = shape.at(x)
    return np.stack([at["axial"], at["edge"], at["flap"]], axis=-1)


def section_rotation(shape: ModeShape, x: NDArray) -> NDArray:
    """Section rotation vector ``Theta = (phi, -w', v')`` (rad per unit modal amplitude, shape (n, 3))."""
    at = shape.at(x)
    return np.stack([at["twist"], -at["flap_slope"], at["edge_slope"]], axis=-1)


def surface_displacement(blade: Blade, shape: ModeShape, x: NDArray) -> NDArray:
    """Rotor-frame displacement (shape (n, 2, 3)) of the leading and trailing edges: ``(u, v, w) + Theta x s``."""
    s = chord_offsets(blade, x, chord_edges(blade, x))
    rotation = section_rotation(shape, x)[:, None, :]
    moved = axis_displacement(shape, x)[:, None, :] + np.cross(rotation, s)
    return blade_to_rotor(local_to_blade(blade, x, moved), blade.precone)


@dataclass(frozen=True)
class ModeDisplacement:
    """One mode drawn on the blade: rotor-frame displacements per unit modal amplitude.

    axis : displacement of the reference-axis points, m, shape (n, 3)
    surface : displacement of the leading- and trailing-edge points, m, shape (n, 2, 3), or None without a chord
    twist : elastic twist at the axis points, rad, shape (n,)
    """

    axis: NDArray[np.float64]
    surface: NDArray[np.float64] | None
    twist: NDArray[np.float64]

    @property
    def largest(self) -> float:
        """Largest displacement magnitude over the drawn points, m."""
        points = self.axis if self.surface is None else np.concatenate([self.axis, self.surface.reshape(-1, 3)])
        return float(np.max(np.linalg.norm(points, axis=-1)))


def mode_displacement(blade: Blade, shape: ModeShape, x: NDArray) -> ModeDisplacement:
    """A mode shape's displacements at span positions ``x`` (m), in the rotor frame."""
    axis = blade_to_rotor(local_to_blade(blade, x, axis_displacement(shape, x)), blade.precone)
    surface = surface_displacement(blade, shape, x) if has_planform(blade) else None
    return ModeDisplacement(axis=axis, surface=surface, twist=shape.at(x)["twist"])


def tip_body_position(blade: Blade) -> NDArray:
    """Rotor-frame position (m, shape (3,)) of the tip mass's centre: the tip of the reference axis plus the
    body's offset (blade frame)."""
    offset = blade.tip_mass.offset if blade.tip_mass is not None else np.zeros(3)
    tip = np.array([blade.length])
    return blade_to_rotor(axis_points(blade, tip)[0] + local_to_blade(blade, tip, offset[None])[0], blade.precone)


def tip_body_displacement(blade: Blade, shape: ModeShape) -> NDArray:
    """Rotor-frame displacement (shape (3,)) of the tip mass's centre, moving rigidly with the tip section:
    ``(u, v, w) + Theta x offset``."""
    offset = blade.tip_mass.offset if blade.tip_mass is not None else np.zeros(3)
    tip = np.array([blade.length])
    moved = axis_displacement(shape, tip)[0] + np.cross(section_rotation(shape, tip)[0], offset)
    return blade_to_rotor(local_to_blade(blade, tip, moved[None])[0], blade.precone)
