"""Off-screen mode pictures: not blank, and the deformed blade's extent in pixels is the scaled tip displacement
(the camera is a parallel projection with a known scale, so pixels and metres are related exactly)."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

pytest.importorskip("pyvista")
iio = pytest.importorskip("imageio.v3")

from bladefem.modal import modes  # noqa: E402
from bladefem.plots.modes3d import (  # noqa: E402
    TUBE,
    mode_labels,
    ordinal,
    render,
    save_mode_gif,
    save_mode_png,
    save_mode_strip,
)
from bladefem.sections import Blade, uniform_sections  # noqa: E402

LENGTH = 30.0


def blade(chord: bool = False) -> Blade:
    sections = uniform_sections(LENGTH, mass=80.0, flap_stiffness=3e8, edge_stiffness=9e8)
    if chord:
        sections = replace(sections, chord=np.array([3.0, 1.0]), pitch_axis=0.3)
    return Blade(sections, hub_radius=2.0, name="test blade")


@pytest.fixture(scope="module")
def result():
    return modes(blade(), rpm=0.0, n_modes=3, elements=16)


def deformed_pixels(image: np.ndarray) -> np.ndarray:
    """Mask of the blue (deformed) pixels: blue well above red, unlike the white background, the grey undeformed
    blade and the black title."""
    rgb = image.astype(int)
    return (rgb[..., 2] - rgb[..., 0] > 40) & (rgb[..., 2] > 80)


def extent(mask: np.ndarray) -> tuple[int, int]:
    rows, cols = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
    return int(rows.max() - rows.min() + 1), int(cols.max() - cols.min() + 1)


def image_position(picture, point: np.ndarray) -> tuple[float, float]:
    """(row, column) of a rotor-frame point in the picture, counted from the top-left pixel's centre: a parallel
    projection centred on the focus, ``metres_per_pixel`` in both directions."""
    height, width = picture.image.shape[:2]
    relative = point - picture.view.focus
    column = width / 2 + relative @ picture.view.right / picture.metres_per_pixel - 0.5
    row = height / 2 - relative @ picture.view.up / picture.metres_per_pixel - 0.5
    return row, column


@pytest.mark.parametrize("tilt_deg", [0.0, 20.0])
def test_deformed_blade_sits_at_the_scaled_displacement_in_pixels(result, tilt_deg):
    b = blade()
    mode = result.first("flap")
    picture = render(b, mode, window_size=(1200, 400), tilt_deg=tilt_deg)
    image = picture.image
    assert image.shape == (400, 1200, 3)
    assert (image < 250).any(axis=2).mean() > 0.02                  # not blank
    mask = deformed_pixels(image)
    for fraction in (0.5, 0.75, 0.95):
        x = fraction * LENGTH
        w = float(mode.shape.at(np.array([x]))["flap"][0])
        centre = np.array([b.hub_radius + x, 0.0, picture.scale * w])    # no precone: rotor frame = blade frame
        row, column = image_position(picture, centre)
        blue = np.flatnonzero(mask[:, int(round(column))])
        # the tube is symmetric about its centreline, so the middle of the blue run is the centreline: within
        # 1 px (pixel quantisation of each edge, 0.5 px, and anti-aliasing that is the same on both edges)
        assert 0.5 * (blue.min() + blue.max()) == pytest.approx(row, abs=1.0)
        # and the run spans the tube's diameter, whatever the tilt
        assert blue.max() - blue.min() + 1 == pytest.approx(2 * TUBE * LENGTH / picture.metres_per_pixel, abs=2.5)
    rest_row, _ = image_position(picture, np.array([b.hub_radius + 0.95 * LENGTH, 0.0, 0.0]))
    tip_pixels = picture.scale * float(mode.shape.at(np.array([0.95 * LENGTH]))["flap"][0]) / picture.metres_per_pixel
    assert rest_row - row == pytest.approx(tip_pixels * math.cos(math.radians(tilt_deg)), rel=1e-12)
    rows, cols = extent(mask)
    assert cols == pytest.approx(LENGTH / picture.metres_per_pixel, abs=3)  # root to tip, +-1.5 px per end


def test_edge_mode_deflects_in_the_picture_too(result):
    edge = modes(blade(chord=True), rpm=0.0, n_modes=3, elements=16).first("edge")
    picture = render(blade(chord=True), edge, window_size=(1200, 400), tilt_deg=0.0)
    rows, _ = extent(deformed_pixels(picture.image))
    # viewed along the flapwise axis the ribbon shows its chord (3 m at the root) and the tip moves sideways
    tip = picture.scale * np.abs(edge.shape.edge[-1])
    assert rows * picture.metres_per_pixel > tip
    assert rows * picture.metres_per_pixel < tip + 3.0 + 4 * picture.metres_per_pixel


def test_mode_png_strip_and_gif_files(tmp_path, result):
    picture = save_mode_png(blade(), result, 1, tmp_path / "mode1.png")
    png = iio.imread(tmp_path / "mode1.png")
    np.testing.assert_array_equal(png[..., :3], picture.image)
    title_rows = (png[:40, :, :3] < 100).all(axis=2).any(axis=1)      # black title text at the top
    assert title_rows.any()
    save_mode_strip(blade(), result, tmp_path / "strip.png", n_modes=3)
    strip = iio.imread(tmp_path / "strip.png")
    assert deformed_pixels(strip[..., :3]).sum() > 1000
    save_mode_gif(blade(), result, 1, tmp_path / "mode1.gif", frames=6, window_size=(300, 100))
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


def test_title_band_is_kept_free(result):
    """With a title the blade is framed below a free band at the top: no blue pixel there, and the scale still
    maps the blade's root-to-tip length."""
    from bladefem.plots.modes3d import TITLE_PIXELS
    sections = uniform_sections(4.0, mass=80.0, flap_stiffness=3e8, edge_stiffness=9e8)
    stubby = Blade(replace(sections, chord=2.0, pitch_axis=0.5), name="stubby")   # extent set by the height
    mode = modes(stubby, 0.0, 1, elements=8).modes[0]
    picture = render(stubby, mode, title="Mode 1: 1st flap", window_size=(1200, 200))
    mask = deformed_pixels(picture.image)
    assert not mask[:TITLE_PIXELS].any()
    assert mask[TITLE_PIXELS:].any()
    _, cols = extent(mask)
    assert cols * picture.metres_per_pixel <= 4.0 + 2 * picture.metres_per_pixel
