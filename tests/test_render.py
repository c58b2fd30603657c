"""Off-screen mode pictures: one fixed camera per structure, so flap and edge modes (fore-aft and side-side) deflect
in different directions of the picture; the deformed shape sits where the parallel projection puts it (pixels and
metres are related exactly), is coloured by its displacement magnitude, never thinner than the minimum line width;
the tip mass is drawn; titles and captions stay clear of the structure."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

pytest.importorskip("pyvista")
iio = pytest.importorskip("imageio.v3")

from bladefem.modal import modes  # noqa: E402
from bladefem.plots.camera import BLADE_CAMERA, TOWER_CAMERA  # noqa: E402
from bladefem.plots.modes3d import (  # noqa: E402
    FOOTER_PIXELS,
    MIN_LINE_PIXELS,
    TITLE_PIXELS,
    TUBE,
    caption,
    drawing,
    mode_labels,
    ordinal,
    render,
    save_mode_gif,
    save_mode_png,
    save_mode_strip,
)
from bladefem.sections import Blade, TipMass, uniform_sections  # noqa: E402

LENGTH = 30.0
SIZE = (1200, 460)


def blade(chord: bool = False, **options) -> Blade:
    sections = uniform_sections(LENGTH, mass=80.0, flap_stiffness=3e8, edge_stiffness=9e8)
    if chord:
        sections = replace(sections, chord=np.array([3.0, 1.0]), pitch_axis=0.3)
    return Blade(sections, hub_radius=2.0, name="test blade", **options)


@pytest.fixture(scope="module")
def result():
    return modes(blade(), rpm=0.0, n_modes=3, elements=16)


def coloured(image: np.ndarray) -> np.ndarray:
    """Mask of the deformed structure's pixels: saturated colour (viridis), unlike the white background, the grey
    undeformed structure, the dark-grey triad and the black text. The colour bar's band at the bottom is cut."""
    rgb = image.astype(int)
    mask = rgb.max(axis=2) - rgb.min(axis=2) > 40
    mask[-FOOTER_PIXELS:] = False
    return mask


def image_position(picture, point: np.ndarray) -> tuple[float, float]:
    """(row, column) of a drawing-frame point in the picture, counted from the top-left pixel's centre: a parallel
    projection centred on the focus, ``metres_per_pixel`` in both directions."""
    height, width = picture.image.shape[:2]
    relative = point - picture.view.focus
    column = width / 2 + relative @ picture.view.right / picture.metres_per_pixel - 0.5
    row = height / 2 - relative @ picture.view.up / picture.metres_per_pixel - 0.5
    return row, column


def centreline(b: Blade, mode, picture, x: float) -> np.ndarray:
    """Drawing-frame position of the deformed reference axis at span x (no precone: rotor frame = blade frame)."""
    at = mode.shape.at(np.array([x]))
    return np.array([b.hub_radius + x, picture.scale * at["edge"][0], picture.scale * at["flap"][0]])


def test_deformed_blade_sits_at_the_scaled_displacement_in_pixels(result):
    b = blade()
    mode = result.first("flap")
    picture = render(b, mode, window_size=SIZE)
    assert picture.image.shape == (SIZE[1], SIZE[0], 3)
    mask = coloured(picture.image)
    for fraction in (0.5, 0.75, 0.95):
        x = fraction * LENGTH
        row, column = image_position(picture, centreline(b, mode, picture, x))
        run = np.flatnonzero(mask[:, int(round(column))])
        # the tube is symmetric about its centreline in a parallel projection, so the middle of the coloured run
        # in a column is the centreline: within 1.5 px (pixel quantisation of each edge and the column rounding
        # on a centreline sloped by under 30 degrees)
        assert 0.5 * (run.min() + run.max()) == pytest.approx(row, abs=1.5)
        # the run spans the tube's diameter divided by the cosine of the projected centreline's slope
        ahead = image_position(picture, centreline(b, mode, picture, x + 0.5))
        slope = (ahead[0] - row) / (ahead[1] - column)
        diameter = 2 * TUBE * LENGTH / picture.metres_per_pixel * math.sqrt(1 + slope**2)
        assert run.max() - run.min() + 1 == pytest.approx(diameter, abs=2.5)


def tip_shift(picture, b: Blade, mode) -> np.ndarray:
    """Image displacement (rows, columns) of the tip from its undeformed position."""
    rest = np.array(image_position(picture, np.array([b.hub_radius + LENGTH, 0.0, 0.0])))
    return np.array(image_position(picture, centreline(b, mode, picture, LENGTH))) - rest


def test_flap_and_edge_modes_deflect_in_different_directions_of_one_fixed_view():
    b = blade()
    result = modes(b, rpm=0.0, n_modes=2, elements=16)
    flap, edge = result.first("flap"), result.first("edge")
    pictures = {mode.kind: render(b, mode, window_size=SIZE) for mode in (flap, edge)}
    # the same camera for both modes: the same image directions
    np.testing.assert_allclose(pictures["flap"].view.right, pictures["edge"].view.right, atol=1e-12)
    np.testing.assert_allclose(pictures["flap"].view.up, pictures["edge"].view.up, atol=1e-12)
    shifts = {kind: tip_shift(picture, b, mode) for (kind, picture), mode in zip(pictures.items(), (flap, edge))}
    cosine = shifts["flap"] @ shifts["edge"] / np.linalg.norm(shifts["flap"]) / np.linalg.norm(shifts["edge"])
    # as lines (a mode's sign is a convention) the two directions are 40 degrees apart with this camera: the
    # third direction, the span, takes the horizontal
    assert abs(cosine) < math.cos(math.radians(35))
    assert shifts["flap"][0] < 0                          # flapwise (downwind) deflection is drawn upward
    for kind, picture in pictures.items():               # and the pixels are where the geometry says
        row, column = image_position(picture, centreline(b, {"flap": flap, "edge": edge}[kind], picture, LENGTH
                                                         - 0.3))
        r, c = int(round(row)), int(round(column))
        assert coloured(picture.image)[r - 2:r + 3, c - 2:c + 3].any(), kind


def test_colour_follows_the_displacement_magnitude(result):
    b = blade()
    mode = result.first("flap")
    picture = render(b, mode, window_size=SIZE)
    near_root, near_tip = (image_position(picture, centreline(b, mode, picture, f * LENGTH)) for f in (0.08, 0.97))
    root_rgb = picture.image[int(round(near_root[0])), int(round(near_root[1]))].astype(int)
    tip_rgb = picture.image[int(round(near_tip[0])), int(round(near_tip[1]))].astype(int)
    # viridis: dark purple (68, 1, 84) at no displacement, yellow (253, 231, 37) at the largest (lit, so scaled)
    assert tip_rgb[1] > root_rgb[1] + 100 and tip_rgb[0] > root_rgb[0] + 60 and root_rgb[2] > root_rgb[1]


def test_an_edge_on_ribbon_keeps_the_minimum_line_width():
    sections = replace(uniform_sections(LENGTH, mass=80.0, flap_stiffness=3e8, edge_stiffness=9e8), chord=1e-4)
    thin = Blade(sections, hub_radius=2.0)
    mode = modes(thin, 0.0, 1, elements=12).modes[0]
    picture = render(thin, mode, window_size=SIZE)
    mask = coloured(picture.image)
    _, column = image_position(picture, centreline(thin, mode, picture, 0.6 * LENGTH))
    run = np.flatnonzero(mask[:, int(round(column))])
    assert run.size >= MIN_LINE_PIXELS - 1          # anti-aliasing may pale one edge pixel below the threshold


def test_the_tip_mass_is_drawn_where_it_moves():
    b = blade(tip_mass=TipMass(400.0))
    mode = modes(b, 0.0, 1, elements=16).modes[0]
    picture = render(b, mode, window_size=SIZE)
    row, column = image_position(picture, centreline(b, mode, picture, LENGTH))     # no offset: at the tip
    r, c = int(round(row)), int(round(column))
    patch = picture.image[r - 3:r + 4, c - 3:c + 4].astype(int)
    reddish = (patch[..., 0] > patch[..., 1] + 40) & (patch[..., 0] > patch[..., 2] + 40)
    assert reddish.sum() > 10
    assert "tip mass 400 kg" in caption(drawing(b))


def test_a_tower_stands_upright_with_its_top_mass_and_its_own_labels():
    from bladefem.builders.tower_case import read_tower_case
    from bladefem.models.tower import tower_modes
    from pathlib import Path
    tower = read_tower_case(str(Path(__file__).resolve().parents[1] / "cases" / "uniform_tower.yaml"))
    result = tower_modes(tower, 2, elements=16)
    pictures = [render(tower, mode) for mode in result.modes]
    height, width = pictures[0].image.shape[:2]
    assert height > width                                           # upright
    axis = np.array([1.0, 0.0, 0.0])
    assert abs(pictures[0].view.right @ axis) < 1e-12 and pictures[0].view.up @ axis > 0.8   # drawn upright
    assert drawing(tower).camera is TOWER_CAMERA and TOWER_CAMERA.axis_labels[2].startswith("fore-aft")
    assert "top mass" in caption(drawing(tower))
    fore_aft, side_side = (result.modes[0], result.modes[1]) if result.modes[0].kind == "fore-aft" else \
        (result.modes[1], result.modes[0])
    top = np.array([tower.height, 0.0, 0.0])
    directions = []
    for mode, picture in zip(result.modes, pictures):
        at = mode.shape.at(np.array([tower.height]))
        moved = top + picture.scale * np.array([0.0, at["edge"][0], at["flap"][0]])
        directions.append(np.array(image_position(picture, moved)) - np.array(image_position(picture, top)))
    assert {fore_aft.kind, side_side.kind} == {"fore-aft", "side-side"}
    cosine = directions[0] @ directions[1] / np.linalg.norm(directions[0]) / np.linalg.norm(directions[1])
    assert abs(cosine) < math.cos(math.radians(45))          # 51 degrees apart as lines with this camera


def test_mode_png_strip_and_gif_files(tmp_path, result):
    picture = save_mode_png(blade(), result, 1, tmp_path / "mode1.png")
    png = iio.imread(tmp_path / "mode1.png")
    np.testing.assert_array_equal(png[..., :3], picture.image)
    title_rows = (png[:TITLE_PIXELS, :, :3] < 100).all(axis=2).any(axis=1)      # black title text at the top
    assert title_rows.any()
    save_mode_strip(blade(), result, tmp_path / "strip.png", n_modes=3)
    strip = iio.imread(tmp_path / "strip.png")
    assert coloured(strip[..., :3]).sum() > 1000
    save_mode_gif(blade(), result, 1, tmp_path / "mode1.gif", frames=6, window_size=(300, 120))
    frames = iio.imread(tmp_path / "mode1.gif", index=None)
    assert frames.shape[0] == 6
    assert not np.array_equal(frames[0], frames[3])                  # the blade swings
    assert not any(p.name.startswith(".") for p in tmp_path.iterdir())


def test_labels_count_each_kind(result):
    assert [ordinal(n) for n in (1, 2, 3, 4, 11, 12, 13, 21, 22)] == \
        ["1st", "2nd", "3rd", "4th", "11th", "12th", "13th", "21st", "22nd"]
    kinds = ["flap", "edge", "flap", "torsion", "flap"]
    fake = [replace(result.modes[0], kind=kind) for kind in kinds]
    assert mode_labels(fake) == ["1st flap", "1st edge", "2nd flap", "1st torsion", "3rd flap"]
    assert BLADE_CAMERA.axis_labels == ("span", "edge (to LE)", "flap (downwind)")
    assert caption(drawing(blade())).startswith("view from the trailing-edge side")


def test_title_and_footer_bands_are_kept_free():
    """With a title the structure is framed between a free band at the top and the colour bar's band at the
    bottom: no coloured pixel of the structure there."""
    sections = uniform_sections(4.0, mass=80.0, flap_stiffness=3e8, edge_stiffness=9e8)
    stubby = Blade(replace(sections, chord=2.0, pitch_axis=0.5), name="stubby")   # extent set by the height
    mode = modes(stubby, 0.0, 1, elements=8).modes[0]
    picture = render(stubby, mode, title="Mode 1: 1st flap", window_size=(1200, 300))
    mask = coloured(picture.image)
    assert not mask[:TITLE_PIXELS].any()
    assert mask[TITLE_PIXELS:].any()
