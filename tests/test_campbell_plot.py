"""Campbell diagram: crossings of families with nP lines (closed form for linear families), the marks drawn where
they are computed, no overlapping text anywhere in the figure, and the file written atomically."""

from __future__ import annotations

import itertools
from pathlib import Path

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

from bladefem.modal.results import CampbellResult, ModeFamily  # noqa: E402
from bladefem.plots.campbell import (  # noqa: E402
    campbell_figure,
    crossings,
    excitation_crossings,
    family_labels,
    save_campbell_plot,
    spread,
)

RPM = np.linspace(0.0, 15.0, 16)


def linear_sweep(lines: list[tuple[str, float, float]]) -> CampbellResult:
    """Families f(rpm) = f0 + slope * rpm (Hz): crossings with n rpm / 60 are known in closed form."""
    families = [ModeFamily(kind, f0 + slope * RPM, np.zeros(len(RPM), dtype=np.int64), np.ones(len(RPM)))
                for kind, f0, slope in lines]
    return CampbellResult(rpm=RPM, families=families, results=[])


SWEEP = linear_sweep([("flap", 0.69, 0.005), ("edge", 1.1, 0.001), ("flap", 2.0, 0.006), ("edge", 4.1, 0.002),
                      ("flap", 4.7, 0.004), ("torsion", 8.3, 0.003)])


def test_crossings_of_linear_families_are_exact():
    for n in (1, 3, 6, 9):
        for family in SWEEP.families:
            f0, slope = family.frequencies_hz[0], (family.frequencies_hz[1] - family.frequencies_hz[0]) / RPM[1]
            expected = f0 / (n / 60.0 - slope)                    # f0 + slope r = n r / 60
            found = excitation_crossings(RPM, family.frequencies_hz, n)
            if 0 < expected <= RPM[-1]:
                (speed, frequency), = found
                assert speed == pytest.approx(expected, rel=1e-12)   # linear in rpm: interpolation is exact
                assert frequency == pytest.approx(n * expected / 60.0, rel=1e-12)
            else:
                assert found == []
    assert {(c.family, c.harmonic) for c in crossings(SWEEP)} == {(0, 6), (0, 9), (1, 6), (1, 9), (2, 9)}


def test_labels_and_spread():
    assert family_labels(SWEEP) == ["1st flap", "1st edge", "2nd flap", "2nd edge", "3rd flap", "1st torsion"]
    placed = spread([0.25, 0.75, 0.8, 0.82, 2.0], 0.2)
    assert np.all(np.diff(placed) >= 0.2 - 1e-12)
    assert placed.mean() == pytest.approx(np.mean([0.25, 0.75, 0.8, 0.82, 2.0]))
    assert placed[-1] == 2.0                                    # far labels stay where they are


def drawn_texts(fig):
    """Every text the figure draws: titles, axis labels, tick labels within the view limits, legend entries and
    annotations (the nP labels)."""
    texts = []
    for ax in fig.axes:
        texts += [ax.title, ax.xaxis.label, ax.yaxis.label, *ax.texts]
        for axis, (low, high) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
            texts += [tick.label1 for tick in axis.get_major_ticks() if low <= tick.get_loc() <= high]
        if ax.get_legend():
            texts += ax.get_legend().get_texts()
    return texts


def text_boxes(fig):
    """Window extents of the drawn, non-empty texts."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    return [(text.get_text(), text.get_window_extent(renderer)) for text in drawn_texts(fig)
            if text.get_visible() and text.get_text().strip()]


@pytest.mark.parametrize("top", [None, 2.5, 12.0, 40.0])   # 40 Hz crowds the nP labels
def test_no_text_overlaps_and_marks_sit_on_the_crossings(top):
    fig = campbell_figure(SWEEP, title="test blade", operating_rpm=12.1, max_frequency_hz=top)
    boxes = text_boxes(fig)
    for (a, box_a), (b, box_b) in itertools.combinations(boxes, 2):
        assert not box_a.overlaps(box_b), f"'{a}' overlaps '{b}'"
    names = [t for t, _ in boxes]
    for label in ("Rotor speed (rpm)", "Natural frequency (Hz)", "1P", "3P", "6P", "9P",
                  "operating speed (12.1 rpm)", "crossing with nP (n marked)", "1st flap"):
        assert label in names
    ax = fig.axes[0]
    marks = next(line for line in ax.get_lines() if line.get_label() == "crossing with nP (n marked)")
    shown = [c for c in crossings(SWEEP) if c.frequency_hz <= ax.get_ylim()[1]]
    np.testing.assert_allclose(marks.get_xdata(), [c.rpm for c in shown])
    # every text stays inside the figure
    width, height = fig.canvas.get_width_height()
    for name, box in boxes:
        assert box.x0 >= 0 and box.y0 >= 0 and box.x1 <= width and box.y1 <= height, name
    matplotlib.pyplot.close(fig)


def test_families_above_the_frequency_limit_are_left_out():
    fig = campbell_figure(SWEEP, max_frequency_hz=2.5)
    labels = fig.axes[0].get_legend_handles_labels()[1]
    assert "2nd edge" not in labels and "1st torsion" not in labels and "2nd flap" in labels
    matplotlib.pyplot.close(fig)


def test_plot_file_is_written_whole(tmp_path):
    iio = pytest.importorskip("imageio.v3")
    path = tmp_path / "campbell.png"
    save_campbell_plot(SWEEP, path, title="test", operating_rpm=12.1)
    image = iio.imread(path)
    assert image.shape[0] > 500 and image.shape[1] > 900
    assert (image[..., :3] < 200).any(axis=2).mean() > 0.01        # lines and text drawn on white
    save_campbell_plot(SWEEP, tmp_path / "campbell.pdf")
    assert (tmp_path / "campbell.pdf").read_bytes().startswith(b"%PDF")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["campbell.pdf", "campbell.png"]


def test_a_write_failing_midway_leaves_the_old_file_intact(tmp_path, monkeypatch):
    """The writer dies after half the bytes (a full disk, a crash): the previous diagram stays as it was and no
    partial or temporary file is left behind."""
    path = tmp_path / "campbell.png"
    save_campbell_plot(SWEEP, path, title="old")
    old = path.read_bytes()
    written = []

    def half_then_fail(self: Path, data: bytes) -> int:
        with open(self, "wb") as handle:
            written.append(handle.write(data[: len(data) // 2]))
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(Path, "write_bytes", half_then_fail)
    with pytest.raises(OSError, match="No space"):
        save_campbell_plot(SWEEP, path, title="new", operating_rpm=12.1)
    assert written and written[0] > 10_000                        # the failure did strike mid-way through the image
    monkeypatch.undo()
    assert path.read_bytes() == old
    assert [p.name for p in tmp_path.iterdir()] == ["campbell.png"]
