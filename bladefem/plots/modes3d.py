"""3-D mode pictures with pyvista, off-screen: the deformed blade over the undeformed one.

The view is a parallel projection looking perpendicular to both the blade axis and the largest displacement, so
the deflection is drawn at its true scaled size: the blade runs left (root) to right (tip) and the largest
displacement points up. Displacements are scaled so that the largest one drawn is ``fraction`` of the blade's
length (mode shapes have no physical amplitude). Rendering uses EGL (no X server); see docs/outputs.md.
"""

from __future__ import annotations

import io
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..io.results import write_atomic
from ..io.vtk_geometry import (
    ModeDisplacement,
    axis_positions,
    has_planform,
    mode_displacement,
    surface_positions,
)
from ..modal.results import ModalResult, Mode
from ..sections import Blade

#: largest drawn displacement as a fraction of the blade length
FRACTION = 0.12
UNDEFORMED = "#b8b8b8"
DEFORMED = "#1f5fa8"
#: view turned about the blade axis away from the plane of the largest displacement, degrees
TILT_DEG = 20.0
#: height of the band kept free above the blade for the title, pixels
TITLE_PIXELS = 40
#: tube radius of a blade drawn without a chord, as a fraction of its length
TUBE = 0.006


def pyvista():
    """pyvista, imported with EGL off-screen rendering unless the environment chose another window."""
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv
    return pv


def ordinal(n: int) -> str:
    """1st, 2nd, 3rd, 4th, ... 11th, 12th, 13th, 21st."""
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"


def mode_labels(modes: list[Mode]) -> list[str]:
    """'1st flap', '1st edge', '2nd flap', ... counting each kind in frequency order."""
    counts: dict[str, int] = {}
    labels = []
    for mode in modes:
        counts[mode.kind] = counts.get(mode.kind, 0) + 1
        labels.append(f"{ordinal(counts[mode.kind])} {mode.kind}")
    return labels


def mode_title(number: int, label: str, mode: Mode, rpm: float) -> str:
    return f"Mode {number}: {label}, {mode.frequency_hz:.4g} Hz at {rpm:g} rpm"


def blade_mesh(blade: Blade, x: NDArray, offset: NDArray | None = None):
    """pyvista mesh of the blade at span positions ``x``: the planform ribbon, or a tube along the axis without a
    chord; ``offset`` (rotor-frame displacement of the points, shaped like the ribbon's or the axis's) moves it."""
    pv = pyvista()
    if has_planform(blade):
        points = surface_positions(blade, x) + (0.0 if offset is None else offset)
        n = len(x)
        flat = points.transpose(1, 0, 2).reshape(-1, 3)
        i = np.arange(n - 1)
        faces = np.column_stack([np.full(n - 1, 4), i, i + 1, n + i + 1, n + i]).ravel()
        return pv.PolyData(flat, faces)
    points = axis_positions(blade, x) + (0.0 if offset is None else offset)
    return pv.lines_from_points(points).tube(radius=TUBE * blade.length, n_sides=24)


def drawn_offset(displacement: ModeDisplacement) -> NDArray:
    """The displacement of the points :func:`blade_mesh` draws."""
    return displacement.axis if displacement.surface is None else displacement.surface


@dataclass(frozen=True)
class View:
    """A parallel-projection camera: image right along ``right``, image up along ``up`` (rotor frame)."""

    focus: NDArray[np.float64]
    right: NDArray[np.float64]
    up: NDArray[np.float64]
    half_height: float

    @property
    def normal(self) -> NDArray[np.float64]:
        return np.cross(self.right, self.up)


def fit_view(blade: Blade, points: NDArray, largest: NDArray, aspect: float, tilt: float = 0.0,
             margin: float = 1.08) -> View:
    """The view looking perpendicular to the blade axis and to the ``largest`` displacement vector, turned by
    ``tilt`` (rad) about the blade axis so that a flat planform is not seen edge-on, framing ``points`` (all drawn
    points, shape (k, 3)) in a window of width/height ``aspect``."""
    right = np.array([np.cos(blade.precone), 0.0, np.sin(blade.precone)])
    across = largest - np.dot(largest, right) * right
    if np.linalg.norm(across) < 1e-9 * max(1.0, np.linalg.norm(largest)):
        across = np.array([-np.sin(blade.precone), 0.0, np.cos(blade.precone)])   # axial mode: view from the side
    across = across / np.linalg.norm(across)
    up = np.cos(tilt) * across + np.sin(tilt) * np.cross(right, across)
    along, height = points @ right, points @ up
    depth = points @ np.cross(right, up)
    focus = (0.5 * (along.min() + along.max()) * right + 0.5 * (height.min() + height.max()) * up
             + 0.5 * (depth.min() + depth.max()) * np.cross(right, up))
    half = 0.5 * margin * max(np.ptp(height), np.ptp(along) / aspect)
    return View(focus, right, up, half)


def with_band_above(view: View, fraction: float) -> View:
    """The same framing with the top ``fraction`` of the image left free (for the title)."""
    half = view.half_height / (1.0 - fraction)
    return View(view.focus + view.up * half * fraction, view.right, view.up, half)


def behind(mesh, view: View, points: NDArray):
    """A copy of ``mesh`` moved away from the camera, behind all ``points``: a parallel projection draws it at the
    same place in the image, and the deformed blade is always drawn over it."""
    depth = points @ view.normal
    return mesh.translate(-(2.0 * np.ptp(depth) + 1e-3 * view.half_height) * view.normal, inplace=False)


def camera(plotter, view: View) -> None:
    plotter.enable_parallel_projection()
    distance = 10.0 * view.half_height + 1.0
    plotter.camera.focal_point = tuple(view.focus)
    plotter.camera.position = tuple(view.focus + distance * view.normal)
    plotter.camera.up = tuple(view.up)
    plotter.camera.parallel_scale = view.half_height
    plotter.camera.clipping_range = (1e-3 * distance, 100.0 * distance)


@dataclass(frozen=True)
class ModePicture:
    """A rendered mode.

    image : RGB pixels, shape (height, width, 3)
    view : the camera (image right = blade axis, image up = largest displacement)
    metres_per_pixel : scale of the picture, m per pixel
    scale : drawn displacement per unit modal amplitude, m per m
    """

    image: NDArray[np.uint8]
    view: View
    metres_per_pixel: float
    scale: float


def render_frames(blade: Blade, mode: Mode, amplitudes: tuple[float, ...] = (1.0,), title: str = "",
                  window_size: tuple[int, int] = (1400, 420), fraction: float = FRACTION,
                  tilt_deg: float = TILT_DEG) -> list[ModePicture]:
    """Render the undeformed blade (grey) and the mode (blue) at each of ``amplitudes`` times the drawing scale,
    all in one view that frames every frame (the frames of an animation share it)."""
    pv = pyvista()
    x = mode.shape.x
    displacement = mode_displacement(blade, mode.shape, x)
    scale = fraction * blade.length / displacement.largest
    offset = scale * drawn_offset(displacement)
    rest = blade_mesh(blade, x)
    shapes = [blade_mesh(blade, x, a * offset).points for a in amplitudes]
    largest = offset.reshape(-1, 3)[np.argmax(np.linalg.norm(offset.reshape(-1, 3), axis=1))]
    view = fit_view(blade, np.concatenate([rest.points, *shapes]), largest, window_size[0] / window_size[1],
                    np.radians(tilt_deg))
    if title:
        view = with_band_above(view, TITLE_PIXELS / window_size[1])
    plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
    plotter.set_background("white")
    plotter.add_mesh(behind(rest, view, np.concatenate([rest.points, *shapes])), color=UNDEFORMED, opacity=0.55,
                     ambient=0.4, diffuse=0.6, specular=0.0)
    deformed = blade_mesh(blade, x, offset)
    plotter.add_mesh(deformed, color=DEFORMED, ambient=0.4, diffuse=0.6, specular=0.0, smooth_shading=True)
    if title:
        plotter.add_text(title, position="upper_edge", font_size=11, color="black")
    camera(plotter, view)
    pictures = []
    for points in shapes:
        deformed.points = points
        deformed.compute_normals(inplace=True)
        plotter.render()
        image = np.asarray(plotter.screenshot(return_img=True))[..., :3]
        pictures.append(ModePicture(image, view, 2.0 * view.half_height / window_size[1], scale))
    plotter.close()
    return pictures


def render(blade: Blade, mode: Mode, title: str = "", window_size: tuple[int, int] = (1400, 420),
           fraction: float = FRACTION, tilt_deg: float = TILT_DEG) -> ModePicture:
    """One picture of the mode at the drawing scale (see :func:`render_frames`)."""
    return render_frames(blade, mode, (1.0,), title, window_size, fraction, tilt_deg)[0]


def png_bytes(image: NDArray) -> bytes:
    import imageio.v3 as iio
    return iio.imwrite("<bytes>", image, extension=".png")


def save_mode_png(blade: Blade, result: ModalResult, number: int, path: str | Path,
                  window_size: tuple[int, int] = (1400, 420)) -> ModePicture:
    """Write mode ``number`` (1-based) of ``result`` with its frequency and kind in the title."""
    mode = result.modes[number - 1]
    label = mode_labels(result.modes)[number - 1]
    picture = render(blade, mode, mode_title(number, label, mode, result.rotor_speed_rpm), window_size)
    write_atomic(path, png_bytes(picture.image))
    return picture


def save_mode_gif(blade: Blade, result: ModalResult, number: int, path: str | Path, frames: int = 24,
                  window_size: tuple[int, int] = (900, 270), seconds: float = 1.6) -> None:
    """An animated GIF of mode ``number``: the shape swinging through one period, looping."""
    import imageio.v3 as iio

    mode = result.modes[number - 1]
    title = mode_title(number, mode_labels(result.modes)[number - 1], mode, result.rotor_speed_rpm)
    amplitudes = tuple(float(np.cos(2 * np.pi * k / frames)) for k in range(frames))
    images = [picture.image for picture in render_frames(blade, mode, amplitudes, title, window_size)]
    data = iio.imwrite("<bytes>", np.stack(images), extension=".gif", duration=1000.0 * seconds / frames, loop=0)
    write_atomic(path, data)


def save_mode_strip(blade: Blade, result: ModalResult, path: str | Path, n_modes: int = 6,
                    window_size: tuple[int, int] = (1400, 330)) -> None:
    """The first ``n_modes`` modes stacked in one image (PNG, PDF or SVG by extension), each titled."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    modes = result.modes[:n_modes]
    labels = mode_labels(result.modes)
    fig, axes = plt.subplots(len(modes), 1, figsize=(7.0, 1.75 * len(modes)), dpi=200, squeeze=False,
                             layout="constrained")
    for number, (ax, mode) in enumerate(zip(axes[:, 0], modes), 1):
        ax.imshow(render(blade, mode, window_size=window_size).image)
        ax.set_title(f"({chr(96 + number)}) {labels[number - 1]}, {mode.frequency_hz:.4g} Hz", fontsize=9,
                     loc="left")
        ax.set_axis_off()
    fig.suptitle(f"{blade.name}: first {len(modes)} modes at {result.rotor_speed_rpm:g} rpm", fontsize=10)
    fig.text(0.5, 0.0, f"Grey: undeformed blade. Largest displacement drawn at {FRACTION:.0%} of the blade "
             "length; root on the left.", ha="center", va="bottom", fontsize=8)
    buffer = io.BytesIO()
    fig.savefig(buffer, format=Path(path).suffix.lower().lstrip(".") or "png")
    plt.close(fig)
    write_atomic(path, buffer.getvalue())
