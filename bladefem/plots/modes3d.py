"""3-D mode pictures with pyvista, off-screen: the deformed blade or tower over the undeformed one.

Every mode of a structure is seen by the same fixed camera (:mod:`bladefem.plots.camera`, stated in each picture),
so flap and edge modes (fore-aft and side-side for a tower) deflect in different directions of the picture; a
triad labels the directions. The deformed shape is coloured by its displacement magnitude (relative to its
largest), its reference axis is drawn at least :data:`MIN_LINE_PIXELS` wide (a ribbon seen edge-on stays
visible), and a tip or tower-top mass is drawn as a sphere moving with the tip section. Displacements are scaled
so that the largest one drawn is ``fraction`` of the length (mode shapes have no physical amplitude). Rendering
uses EGL (no X server); see docs/outputs.md.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..files import write_atomic
from ..outputs.vtk_geometry import (
    ModeDisplacement,
    axis_positions,
    blade_to_rotor,
    has_planform,
    mode_displacement,
    surface_positions,
    tip_body_displacement,
    tip_body_position,
)
from ..modal.results import ModalResult, Mode
from ..sections import Blade
from .camera import BLADE_CAMERA, TOWER_CAMERA, Camera, View, apply, fixed_view, with_bands
from .labels import mode_labels, ordinal

__all__ = ["FRACTION", "ModePicture", "mode_labels", "ordinal", "render", "render_frames", "save_mode_gif",
           "save_mode_png", "save_mode_strip"]

#: largest drawn displacement as a fraction of the length
FRACTION = 0.12
UNDEFORMED = "#b8b8b8"
TIP_MASS = "#8b1a1a"
COLOURMAP = "viridis"
#: the deformed reference axis is never drawn thinner than this, pixels
MIN_LINE_PIXELS = 3
#: height of the bands kept free above the structure (title) and below it (colour bar, caption), pixels
TITLE_PIXELS = 40
FOOTER_PIXELS = 60
#: tube radius of a beam drawn without a chord, as a fraction of its length
TUBE = 0.006
#: radius of the sphere drawn for a tip or top mass, as a fraction of the length
SPHERE = 0.025
#: length of the triad's arrows, as a fraction of the length
TRIAD = 0.1
#: space kept beyond each arrow's tip for its label, in arrow lengths
LABEL_ROOM = 1.5


def pyvista():
    """pyvista, imported with EGL off-screen rendering unless the environment chose another window."""
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv
    return pv


def mode_title(number: int, label: str, mode: Mode, rpm: float) -> str:
    speed = f" at {rpm:g} rpm" if rpm else ""
    return f"Mode {number}: {label}, {mode.frequency_hz:.4g} Hz{speed}"


@dataclass(frozen=True)
class Drawing:
    """What a picture draws: the beam (a tower as its beam), the camera and whether it is a tower."""

    beam: Blade
    camera: Camera
    tower: bool

    @property
    def to_drawing(self) -> NDArray:
        """Beam-frame to drawing-frame rotation (the rotor frame; a tower keeps its own frame)."""
        return blade_to_rotor(np.eye(3), self.beam.precone).T

    @property
    def tip_mass(self) -> float:
        return self.beam.tip_mass.mass if self.beam.tip_mass is not None else 0.0


def drawing(structure: Any) -> Drawing:
    """The drawing of a :class:`Blade` or a tower (:class:`bladefem.sections.tower.Tower`)."""
    if isinstance(structure, Blade):
        return Drawing(structure, BLADE_CAMERA, False)
    return Drawing(structure.as_beam(), TOWER_CAMERA, True)


def beam_mesh(blade: Blade, x: NDArray, offset: NDArray | None = None, reference: float | None = None):
    """pyvista mesh at span positions ``x``: the planform ribbon, or a tube along the axis without a chord;
    ``offset`` (drawing-frame displacement of the points, shaped like the ribbon's or the axis's) moves it, and
    with a ``reference`` length (m) the point array ``displacement`` holds ``|offset| / reference``."""
    pv = pyvista()
    moved = 0.0 if offset is None else offset
    if has_planform(blade):
        n = len(x)
        flat = (surface_positions(blade, x) + moved).transpose(1, 0, 2).reshape(-1, 3)
        i = np.arange(n - 1)
        faces = np.column_stack([np.full(n - 1, 4), i, i + 1, n + i + 1, n + i]).ravel()
        mesh = pv.PolyData(flat, faces)
        if reference is not None and offset is not None:
            mesh.point_data["displacement"] = np.linalg.norm(offset.transpose(1, 0, 2).reshape(-1, 3),
                                                             axis=1) / reference
        return mesh
    line = pv.lines_from_points(axis_positions(blade, x) + moved)
    if reference is not None and offset is not None:
        line.point_data["displacement"] = np.linalg.norm(offset, axis=1) / reference
    return line.tube(radius=TUBE * blade.length, n_sides=24)


def drawn_offset(displacement: ModeDisplacement) -> NDArray:
    """The displacement of the points :func:`beam_mesh` draws."""
    return displacement.axis if displacement.surface is None else displacement.surface


def triad_points(draw: Drawing, origin: NDArray) -> list[tuple[NDArray, NDArray, str]]:
    """(start, end, label) of the triad's arrows along the beam frame's axes, drawn from ``origin``."""
    length = TRIAD * draw.beam.length
    axes = draw.to_drawing.T                            # rows: beam x, y, z in the drawing frame
    return [(origin, origin + length * axis, label) for axis, label in zip(axes, draw.camera.axis_labels)]


def add_triad_label(plotter: Any, view: View, start: NDArray, end: NDArray, label: str, font_size: int) -> None:
    """The label of one triad arrow just beyond its tip on the screen, justified away from the arrow (so the arrow
    head never covers the text, whichever way the arrow points in the picture)."""
    across = np.array([np.dot(end - start, view.right), np.dot(end - start, view.up)])
    screen = across / (np.linalg.norm(across) or 1.0)
    point = end + 0.1 * np.linalg.norm(end - start) * (screen[0] * view.right + screen[1] * view.up)
    horizontal = "left" if screen[0] > 0.3 else ("right" if screen[0] < -0.3 else "center")
    vertical = "bottom" if screen[1] > 0.3 else ("top" if screen[1] < -0.3 else "center")
    plotter.add_point_labels(point[None, :], [label], font_size=font_size, text_color="black", shape=None,
                             show_points=False, always_visible=True, justification_horizontal=horizontal,
                             justification_vertical=vertical)


def triad_origin(draw: Drawing) -> NDArray:
    """Where the triad sits: beside the root, clear of the structure (below a blade, beside a tower)."""
    to = draw.to_drawing
    length = draw.beam.length
    root = axis_positions(draw.beam, np.array([0.0]))[0]
    if draw.tower:
        return root + length * (to @ np.array([0.05, -0.35, -0.1]))
    return root + length * (to @ np.array([-0.02, 0.0, -0.3]))


def caption(draw: Drawing) -> str:
    text = draw.camera.description
    if draw.tip_mass > 0:
        text += f"; sphere: {'top' if draw.tower else 'tip'} mass {draw.tip_mass:.6g} kg"
    return text


@dataclass(frozen=True)
class ModePicture:
    """A rendered mode.

    image : RGB pixels, shape (height, width, 3)
    view : the camera (drawing frame)
    metres_per_pixel : scale of the picture, m per pixel
    scale : drawn displacement per unit modal amplitude, m per m
    """

    image: NDArray[np.uint8]
    view: View
    metres_per_pixel: float
    scale: float


def render_frames(structure: Any, mode: Mode, amplitudes: tuple[float, ...] = (1.0,), title: str = "",
                  window_size: tuple[int, int] | None = None, fraction: float = FRACTION,
                  legend: bool = True) -> list[ModePicture]:
    """Render the undeformed structure (grey) and the mode (coloured by displacement magnitude) at each of
    ``amplitudes`` times the drawing scale, all in one fixed view that frames every frame. Without ``legend`` the
    picture has no colour bar and no caption (a figure of several pictures gives them once) and larger triad
    labels (it is shown smaller)."""
    pv = pyvista()
    draw = drawing(structure)
    beam = draw.beam
    size = window_size or draw.camera.window_size
    x = mode.shape.x
    displacement = mode_displacement(beam, mode.shape, x)
    tip_move = tip_body_displacement(beam, mode.shape) if draw.tip_mass > 0 else np.zeros(3)
    largest = max(displacement.largest, float(np.linalg.norm(tip_move)))
    scale = fraction * beam.length / largest
    reference = fraction * beam.length
    offset = scale * drawn_offset(displacement)
    rest = beam_mesh(beam, x)
    frames = [beam_mesh(beam, x, a * offset, reference) for a in amplitudes]
    rest_axis = axis_positions(beam, x)
    moved_axis = [rest_axis + a * scale * displacement.axis for a in amplitudes]
    radius = SPHERE * beam.length
    sphere_rest = tip_body_position(beam)
    spheres = [sphere_rest + a * scale * tip_move for a in amplitudes]
    arrows = triad_points(draw, triad_origin(draw))
    room = LABEL_ROOM if legend else 2.0 * LABEL_ROOM          # larger labels
    drawn = [rest.points, *[frame.points for frame in frames], arrows[0][0][None],
             np.array([end + room * (end - start) for start, end, _ in arrows])]   # room for the labels
    if draw.tip_mass > 0:
        drawn += [centre + radius * np.vstack([np.eye(3), -np.eye(3)]) for centre in (sphere_rest, *spheres)]
    every = np.concatenate(drawn)
    view = fixed_view(draw.camera, draw.to_drawing, every, size[0] / size[1])
    footer = min(FOOTER_PIXELS / size[1], 0.25) if legend else 0.0
    view = with_bands(view, min(TITLE_PIXELS / size[1], 0.2) if title else 0.0, footer)
    plotter = pv.Plotter(off_screen=True, window_size=list(size))
    plotter.set_background("white")
    behind = -(2.0 * np.ptp(every @ view.normal) + 1e-3 * view.half_height) * view.normal
    plotter.add_mesh(rest.translate(behind, inplace=False), color=UNDEFORMED, opacity=0.55, ambient=0.4,
                     diffuse=0.6, specular=0.0)
    plotter.add_mesh(pv.lines_from_points(rest_axis + behind), color=UNDEFORMED, line_width=2)
    if draw.tip_mass > 0:
        plotter.add_mesh(pv.Sphere(radius=radius, center=sphere_rest + behind), color=UNDEFORMED, opacity=0.55)
    deformed = beam_mesh(beam, x, offset, reference)
    bar = {"title": "displacement magnitude / largest", "vertical": False, "position_x": 0.6, "position_y": 0.01,
           "width": 0.36, "height": 0.06, "n_labels": 2, "fmt": "%.1f", "color": "black", "title_font_size": 12,
           "label_font_size": 11}
    plotter.add_mesh(deformed, scalars="displacement", cmap=COLOURMAP, clim=(0.0, 1.0), ambient=0.45,
                     diffuse=0.6, specular=0.0, smooth_shading=True, scalar_bar_args=bar, show_scalar_bar=legend)
    line = pv.lines_from_points(moved_axis[0])
    line_values = np.linalg.norm(displacement.axis, axis=1) * scale / reference
    line.point_data["displacement"] = line_values
    plotter.add_mesh(line, scalars="displacement", cmap=COLOURMAP, clim=(0.0, 1.0), line_width=MIN_LINE_PIXELS,
                     render_lines_as_tubes=True, show_scalar_bar=False)
    sphere = pv.Sphere(radius=radius, center=spheres[0]) if draw.tip_mass > 0 else None
    if sphere is not None:
        plotter.add_mesh(sphere, color=TIP_MASS, smooth_shading=True)
    for start, end, _ in arrows:
        arrow = pv.Arrow(start=start, direction=end - start, scale="auto", tip_radius=0.12, shaft_radius=0.035)
        plotter.add_mesh(arrow, color="#333333")
    for start, end, label in arrows:
        add_triad_label(plotter, view, start, end, label, 13 if legend else 19)
    if title:
        plotter.add_text(title, position="upper_edge", font_size=11, color="black")
    if legend:
        plotter.add_text(caption(draw), position="lower_left", font_size=8, color="black")
    apply(plotter, view)
    pictures = []
    for k, frame in enumerate(frames):
        deformed.points = frame.points
        deformed.point_data["displacement"] = frame.point_data["displacement"]
        deformed.compute_normals(inplace=True)
        line.points = moved_axis[k]
        line.point_data["displacement"] = abs(amplitudes[k]) * line_values
        if sphere is not None:
            sphere.points = pv.Sphere(radius=radius, center=spheres[k]).points
        plotter.render()
        image = np.asarray(plotter.screenshot(return_img=True))[..., :3]
        pictures.append(ModePicture(image, view, 2.0 * view.half_height / size[1], scale))
    plotter.close()
    return pictures


def render(structure: Any, mode: Mode, title: str = "", window_size: tuple[int, int] | None = None,
           fraction: float = FRACTION, legend: bool = True) -> ModePicture:
    """One picture of the mode at the drawing scale (see :func:`render_frames`)."""
    return render_frames(structure, mode, (1.0,), title, window_size, fraction, legend)[0]


def png_bytes(image: NDArray) -> bytes:
    import imageio.v3 as iio
    return iio.imwrite("<bytes>", image, extension=".png")


def save_mode_png(structure: Any, result: ModalResult, number: int, path: str | Path,
                  window_size: tuple[int, int] | None = None) -> ModePicture:
    """Write mode ``number`` (1-based) of ``result`` with its frequency and kind in the title."""
    mode = result.modes[number - 1]
    label = mode_labels(result.modes)[number - 1]
    picture = render(structure, mode, mode_title(number, label, mode, result.rotor_speed_rpm), window_size)
    write_atomic(path, png_bytes(picture.image))
    return picture


def save_mode_gif(structure: Any, result: ModalResult, number: int, path: str | Path, frames: int = 24,
                  window_size: tuple[int, int] | None = None, seconds: float = 1.6) -> None:
    """An animated GIF of mode ``number``: the shape swinging through one period, looping."""
    import imageio.v3 as iio

    mode = result.modes[number - 1]
    title = mode_title(number, mode_labels(result.modes)[number - 1], mode, result.rotor_speed_rpm)
    width, height = window_size or drawing(structure).camera.window_size
    size = window_size or (int(0.65 * width), int(0.65 * height))
    amplitudes = tuple(float(np.cos(2 * np.pi * k / frames)) for k in range(frames))
    images = [picture.image for picture in render_frames(structure, mode, amplitudes, title, size)]
    data = iio.imwrite("<bytes>", np.stack(images), extension=".gif", duration=1000.0 * seconds / frames, loop=0)
    write_atomic(path, data)


def colour_bar(fig: Any, axes: Any) -> None:
    """One colour bar for all the pictures of a figure (each is drawn without its own)."""
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize

    bar = fig.colorbar(ScalarMappable(Normalize(0.0, 1.0), COLOURMAP), ax=axes.ravel().tolist(), location="bottom",
                       shrink=0.35, aspect=30, pad=0.01, ticks=[0.0, 0.5, 1.0])
    bar.set_label("displacement magnitude / largest", fontsize=7)
    bar.ax.tick_params(labelsize=7)


def save_mode_strip(structure: Any, result: ModalResult, path: str | Path, n_modes: int = 6,
                    window_size: tuple[int, int] | None = None) -> None:
    """The first ``n_modes`` modes in one image (PNG, PDF or SVG by extension), each titled: stacked for a blade,
    side by side for a tower."""
    from .style import pyplot, save_figure

    draw = drawing(structure)
    modes = result.modes[:n_modes]
    labels = mode_labels(result.modes)
    columns = len(modes) if draw.tower else 1
    rows = 1 if draw.tower else len(modes)
    size = (window_size or ((560, 900) if draw.tower else (1400, 400)))
    figsize = (2.2 * columns, 3.8) if draw.tower else (7.0, 2.0 * rows)
    fig, axes = pyplot().subplots(rows, columns, figsize=figsize, dpi=200, squeeze=False, layout="constrained")
    for number, (ax, mode) in enumerate(zip(axes.ravel(), modes), 1):
        ax.imshow(render(structure, mode, window_size=size, legend=False).image)
        ax.set_title(f"({chr(96 + number)}) {labels[number - 1]}, {mode.frequency_hz:.4g} Hz", fontsize=8,
                     loc="left")
        ax.set_axis_off()
    speed = f" at {result.rotor_speed_rpm:g} rpm" if result.rotor_speed_rpm else ""
    fig.suptitle(f"{draw.beam.name}: first {len(modes)} modes{speed}", fontsize=10)
    colour_bar(fig, axes)
    fig.supxlabel(f"Grey: undeformed. Colour: displacement magnitude. Largest displacement drawn at {FRACTION:.0%} "
                  f"of the length.\n{caption(draw)[0].upper() + caption(draw)[1:]}.", fontsize=7)
    save_figure(fig, path)
