"""The fixed cameras of the mode pictures: one view per structure for all its modes, so that directions compare.

Each camera is a parallel projection looking from a fixed direction of the beam frame (``x`` along the beam:
span of a blade, up a tower; ``y`` edgewise toward the leading edge, or side-side; ``z`` flapwise downwind, or
fore-aft downwind). A blade is seen obliquely from the trailing-edge side, from upwind and a little from the root:
its span runs left (root) to right (tip), flapwise (downwind) deflection points up in the picture and edgewise
deflection toward the leading edge points down and to the left. A tower is seen from downwind, from the side and
a little from above: it stands upright, fore-aft (downwind) deflection goes to the right and side-side deflection
to the left. The triad in each picture shows these directions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["BLADE_CAMERA", "TOWER_CAMERA", "Camera", "View", "fixed_view", "with_bands"]


def _unit(vector: tuple[float, float, float]) -> NDArray[np.float64]:
    array = np.asarray(vector, dtype=float)
    return array / np.linalg.norm(array)


@dataclass(frozen=True)
class Camera:
    """A fixed viewing direction in the beam frame.

    toward_camera : unit vector from the structure to the camera (beam frame)
    up : the beam-frame direction drawn upward (projected on the image plane)
    axis_labels : labels of the beam frame's x, y and z axes for the triad
    window_size : picture size in pixels (width, height)
    """

    toward_camera: NDArray[np.float64]
    up: NDArray[np.float64]
    axis_labels: tuple[str, str, str]
    window_size: tuple[int, int]

    @property
    def description(self) -> str:
        """The viewing direction in words, with its angles (stated in every picture)."""
        x, y, z = self.toward_camera
        along = math.degrees(math.asin(abs(x)))
        if self.axis_labels[0] == "span":
            return (f"view from the trailing-edge side, {math.degrees(math.atan2(abs(z), abs(y))):.0f} deg toward "
                    f"upwind and {along:.0f} deg toward the root")
        return (f"view from downwind, {math.degrees(math.atan2(abs(y), abs(z))):.0f} deg toward the side and "
                f"{along:.0f} deg from above")


BLADE_CAMERA = Camera(_unit((-0.45, -1.0, -0.7)), np.array([0.0, 0.0, 1.0]),
                      ("span", "edge (to LE)", "flap (downwind)"), (1400, 480))
TOWER_CAMERA = Camera(_unit((0.5, 0.55, 0.7)), np.array([1.0, 0.0, 0.0]),
                      ("up", "side-side", "fore-aft (downwind)"), (640, 1000))


@dataclass(frozen=True)
class View:
    """A parallel-projection camera: image right along ``right``, image up along ``up`` (drawing frame), the
    window's half height ``half_height`` (m) around ``focus``."""

    focus: NDArray[np.float64]
    right: NDArray[np.float64]
    up: NDArray[np.float64]
    half_height: float

    @property
    def normal(self) -> NDArray[np.float64]:
        """Unit vector from the scene toward the camera."""
        return np.cross(self.right, self.up)


def fixed_view(camera: Camera, to_drawing: NDArray, points: NDArray, aspect: float,
               margin: float = 1.06) -> View:
    """The view of ``camera`` framing ``points`` (all drawn points, shape (k, 3)) in a window of width/height
    ``aspect``; ``to_drawing`` (3x3) turns beam-frame vectors into the drawing frame (the rotor frame)."""
    normal = to_drawing @ camera.toward_camera
    up = to_drawing @ camera.up
    up = up - np.dot(up, normal) * normal
    up = up / np.linalg.norm(up)
    right = np.cross(up, normal)
    along, height, depth = points @ right, points @ up, points @ normal
    focus = (0.5 * (along.min() + along.max()) * right + 0.5 * (height.min() + height.max()) * up
             + 0.5 * (depth.min() + depth.max()) * normal)
    half = 0.5 * margin * max(np.ptp(height), np.ptp(along) / aspect, 1e-9)
    return View(focus, right, up, half)


def with_bands(view: View, top: float, bottom: float) -> View:
    """The same framing with the top ``top`` and bottom ``bottom`` fractions of the image left free (title,
    colour bar and caption)."""
    half = view.half_height / (1.0 - top - bottom)
    return View(view.focus + view.up * half * (top - bottom), view.right, view.up, half)


def apply(plotter, view: View) -> None:
    """Point the plotter's camera as ``view`` says."""
    plotter.enable_parallel_projection()
    distance = 10.0 * view.half_height + 1.0
    plotter.camera.focal_point = tuple(view.focus)
    plotter.camera.position = tuple(view.focus + distance * view.normal)
    plotter.camera.up = tuple(view.up)
    plotter.camera.parallel_scale = view.half_height
    plotter.camera.clipping_range = (1e-3 * distance, 100.0 * distance)
