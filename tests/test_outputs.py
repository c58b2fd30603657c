"""Outputs say what they are: export lists every file it wrote, the report names its software version, date and
input files with their SHA-256 (and links nothing that is not installed), and every figure has one style."""

from __future__ import annotations

import datetime
import hashlib
import itertools
import re
from pathlib import Path

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

import bladefem  # noqa: E402
from bladefem.cli import main  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
CASE = ROOT / "cases" / "uniform_blade.yaml"
MAIN = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"


def written_files(folder: Path) -> set[Path]:
    return {path for path in folder.rglob("*") if path.is_file()}


def test_export_lists_every_file_of_a_sweep(tmp_path, capsys):
    out = tmp_path / "sweep"
    assert main(["export", str(CASE), "--rpm", "0:20:3", "-o", str(out), "--n-modes", "3", "--elements", "12"]) == 0
    captured = capsys.readouterr()
    listed = {Path(line) for line in captured.out.splitlines()}
    assert listed == written_files(out)
    assert len([p for p in listed if p.suffix == ".vtu"]) == 3            # one per speed (no chord: axis only)
    assert captured.err.strip() == f"{len(listed)} files written to {out}"


def test_export_lists_pictures_and_vtk_files_of_one_speed(tmp_path, capsys):
    pytest.importorskip("pyvista")
    out = tmp_path / "one"
    assert main(["export", str(CASE), "-o", str(out), "--n-modes", "2", "--elements", "12", "--png", "--vtk"]) == 0
    captured = capsys.readouterr()
    listed = {Path(line) for line in captured.out.splitlines()}
    assert listed == written_files(out)
    assert {p.name for p in listed} == {"mode01.png", "mode02.png", "modes.png", "modes_000_axis.vtu",
                                        "modes.pvd", "modes.json"}
    assert captured.err.strip() == f"6 files written to {out}"


def sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_report_states_version_date_and_input_hashes(tmp_path, capsys):
    out = tmp_path / "report"
    before = datetime.datetime.now(datetime.timezone.utc).replace(microsecond=0)
    assert main(["report", str(MAIN), "-o", str(out), "--n-modes", "3", "--elements", "24", "--no-pictures",
                 "--sweep", "0:12:3", "--rpm", "12.1", "--quiet"]) == 0
    capsys.readouterr()
    text = (out / "report.md").read_text()
    page = (out / "report.html").read_text()
    assert f"Written by bladefem {bladefem.__version__} on " in text
    stamp = re.search(r"on (\d{4}-\d\d-\d\d \d\d:\d\d:\d\d) UTC", text).group(1)
    written = datetime.datetime.strptime(stamp, "%Y-%m-%d %H:%M:%S").replace(tzinfo=datetime.timezone.utc)
    assert before <= written <= datetime.datetime.now(datetime.timezone.utc)
    # the main file and the blade file it names, each with its hash
    blade_file = MAIN.parent / "NRELOffshrBsline5MW_Blade.dat"
    for path in (MAIN, blade_file):
        assert re.search(rf"\| {re.escape(str(path))} \| {sha256(path)} \|", text), path.name
        assert sha256(path) in page
    # nothing that an installation lacks: no docs/ or repository paths as links
    for document in (text, page):
        assert "THEORY.md" not in document and "docs/" not in document


def test_report_of_a_model_built_in_code_says_so(tmp_path):
    from bladefem.report import write_report
    from bladefem.sections import Blade, uniform_sections
    blade = Blade(uniform_sections(10.0, mass=10.0, flap_stiffness=1e6, edge_stiffness=4e6))
    report = write_report(blade, tmp_path, 0.0, [0.0, 10.0], n_modes=2, elements=8, pictures=False)
    assert "Input: built in code (no input file)." in report.markdown.read_text()


# -- one plotting style -------------------------------------------------------------------------------------------

def drawn_texts(fig):
    """Titles, axis labels, tick labels inside the limits, annotations and legend entries."""
    texts = []
    for ax in fig.axes:
        texts += [ax.title, ax.xaxis.label, ax.yaxis.label, *ax.texts]
        for axis, (low, high) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
            texts += [tick.label1 for tick in axis.get_major_ticks() if low <= tick.get_loc() <= high]
        if ax.get_legend():
            texts += ax.get_legend().get_texts()
    for legend in fig.legends:
        texts += legend.get_texts()
    return [t for t in texts if t.get_visible() and t.get_text().strip()]


def check_style(fig) -> None:
    """The common style: size, unit labels in parentheses, legend and nP labels outside the plotting area, no
    overlapping text, everything inside the figure."""
    from bladefem.plots.style import FIGSIZE, FREQUENCY_LABEL, RPM_LABEL
    assert fig.get_size_inches()[0] == pytest.approx(FIGSIZE[0])
    assert fig.get_size_inches()[1] == pytest.approx(FIGSIZE[1]) or fig.legends    # taller for a legend below
    ax = fig.axes[0]
    assert ax.get_xlabel() == RPM_LABEL == "Rotor speed (rpm)"
    assert ax.get_ylabel() == FREQUENCY_LABEL == "Natural frequency (Hz)"
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    area = ax.get_window_extent(renderer)
    if ax.get_legend() is not None:
        assert ax.get_legend().get_window_extent(renderer).x0 >= area.x1      # the legend covers no curve
    else:
        assert fig.legends[0].get_window_extent(renderer).y1 <= area.y0      # below the axes
    from bladefem.plots.campbell import CROSSING_LABEL
    for text in ax.texts:                            # the nP lines' labels sit outside the plotting area
        if text.get_gid() == CROSSING_LABEL:         # (a crossing's label sits beside its circle)
            continue
        box = text.get_window_extent(renderer)
        assert box.x0 >= area.x1 - 0.5 or box.y0 >= area.y1 - 0.5, text.get_text()
    boxes = [(t.get_text(), t.get_window_extent(renderer)) for t in drawn_texts(fig)]
    for (a, box_a), (b, box_b) in itertools.combinations(boxes, 2):
        assert not box_a.overlaps(box_b), f"'{a}' overlaps '{b}'"
    width, height = fig.canvas.get_width_height()
    for name, box in boxes:
        assert box.x0 >= 0 and box.y0 >= 0 and box.x1 <= width and box.y1 <= height, name
    matplotlib.pyplot.close(fig)


NAMES = ["1st tower fore-aft", "1st tower side-side", "nacelle yaw", "1st blade collective flap",
         "1st blade asymmetric flap (backward whirl)", "1st blade asymmetric flap (forward whirl)",
         "1st blade collective edge / drivetrain", "2nd tower fore-aft", "2nd tower side-side",
         "1st blade asymmetric edge (backward whirl)", "1st blade asymmetric edge (forward whirl)",
         "2nd blade collective flap", "2nd blade asymmetric flap (backward whirl)",
         "2nd blade asymmetric flap (forward whirl)", "1st drivetrain torsion"]


@pytest.mark.parametrize("count", [8, len(NAMES)])       # a few modes, and the full system's fifteen
def test_turbine_campbell_has_the_common_style(count):
    from types import SimpleNamespace

    from bladefem.plots.turbine_campbell import turbine_campbell_figure
    rpm = np.linspace(0.0, 15.0, 11)
    base = np.linspace(0.32, 6.1, count)
    frequencies = base[:, None] + 0.004 * rpm[None, :] * np.arange(1, count + 1)[:, None] / 4
    frequencies[2, :3] = np.nan                                    # a mode not found at some speeds
    # what the figure reads of a bladefem.models.turbine.campbell.TurbineCampbell
    result = SimpleNamespace(rpm=rpm, names=NAMES[:count], frequencies_hz=frequencies)
    check_style(turbine_campbell_figure(result))


def test_blade_and_tower_charts_have_the_common_style():
    from bladefem.plots.campbell import campbell_figure
    from bladefem.plots.tower_campbell import tower_campbell_figure
    blade = bladefem.read(CASE)
    check_style(campbell_figure(bladefem.campbell(blade, np.linspace(0, 30, 4), 3, elements=12), "blade",
                                operating_rpm=12.0))
    tower = bladefem.read(ROOT / "cases" / "uniform_tower.yaml")
    check_style(tower_campbell_figure(bladefem.campbell(tower, np.linspace(0, 20, 3), 3, elements=12,
                                                        operating_rpm=(6.0, 12.0))))
