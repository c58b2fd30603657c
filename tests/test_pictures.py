"""What a reader needs to see in the pictures: each Campbell crossing says which nP it marks, the operating speed
is unlike any mode's line, a mode line is never hidden under another, the margin bands show, the turbine's modes
are told apart by family and whirl, a simulation figure names its case, the triad labels sit clear of their
arrows, and a strip of mode pictures carries one colour bar."""

from __future__ import annotations

from pathlib import Path

import matplotlib
import numpy as np
import pytest
from matplotlib.colors import to_rgba

matplotlib.use("Agg")

from bladefem.cli import main  # noqa: E402
from bladefem.builders.tower_case import read_tower_case  # noqa: E402
from bladefem.models.tower_campbell import tower_campbell  # noqa: E402
from bladefem.models.turbine.campbell import TurbineCampbell  # noqa: E402
from bladefem.plots.campbell import campbell_figure, crossings  # noqa: E402
from bladefem.plots.camera import View  # noqa: E402
from bladefem.plots.modes3d import add_triad_label  # noqa: E402
from bladefem.plots.style import OPERATING_COLOUR  # noqa: E402
from bladefem.plots.tower_campbell import tower_campbell_figure  # noqa: E402
from bladefem.plots.turbine_campbell import mode_style, turbine_campbell_figure  # noqa: E402
from test_campbell_plot import SWEEP  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
NAMES = ["1st tower side-side", "1st tower fore-aft", "1st blade asymmetric flap (backward whirl)",
         "1st blade asymmetric flap (forward whirl)", "1st blade collective flap",
         "1st blade asymmetric edge (backward whirl)", "1st blade asymmetric edge (forward whirl)",
         "1st drivetrain torsion", "2nd blade asymmetric flap (backward whirl)",
         "2nd blade asymmetric flap (forward whirl)", "2nd blade collective flap", "2nd tower fore-aft",
         "2nd tower side-side", "1st blade collective edge", "nacelle yaw"]


def texts(ax) -> list[str]:
    return [text.get_text() for text in ax.texts]


def test_each_crossing_says_which_harmonic_it_marks():
    fig = campbell_figure(SWEEP, operating_rpm=12.1)
    ax = fig.axes[0]
    marks = [c for c in crossings(SWEEP) if c.frequency_hz <= ax.get_ylim()[1]]
    labels = [t for t in ax.texts if t.xy in {(c.rpm, c.frequency_hz) for c in marks}]
    assert len(labels) == len(marks) > 3
    assert sorted(t.get_text() for t in labels) == sorted(f"{c.harmonic}P" for c in marks)


def test_the_operating_speed_is_unlike_every_mode_line():
    ax = campbell_figure(SWEEP, operating_rpm=12.1).axes[0]
    operating = [line for line in ax.get_lines() if line.get_label().startswith("operating")]
    assert len(operating) == 1 and to_rgba(operating[0].get_color()) == to_rgba(OPERATING_COLOUR)
    families = [line for line in ax.get_lines() if line.get_label()[0].isdigit()]
    for line in families:
        assert np.linalg.norm(np.subtract(to_rgba(line.get_color()), to_rgba(OPERATING_COLOUR))[:3]) > 0.5


def test_tower_chart_lines_are_never_hidden_and_the_margin_shows():
    chart = tower_campbell(read_tower_case(ROOT / "cases" / "nrel5mw_tower.yaml"), np.linspace(0, 15, 4),
                           n_modes=4, operating_rpm=(6.9, 12.1))
    ax = tower_campbell_figure(chart).axes[0]
    fore_aft, side_side = (next(line for line in ax.get_lines() if line.get_label().startswith(name))
                           for name in ("1st fore-aft", "1st side-side"))
    # the two lines are 1 % apart: the solid one is wider and below, so the dashed one on top leaves it visible
    assert fore_aft.get_linestyle() == "-" and side_side.get_linestyle() == "--"
    assert fore_aft.get_linewidth() >= 2 * side_side.get_linewidth() and fore_aft.get_zorder() < side_side.get_zorder()
    hatched = [patch for patch in ax.patches if patch.get_hatch()]
    assert len(hatched) == 4               # the margin below and above each band, hatched in the band's colour
    band_colours = {to_rgba(patch.get_facecolor()) for patch in ax.patches if not patch.get_hatch()}
    for line in (fore_aft, side_side):
        assert to_rgba(line.get_color()) not in band_colours


def test_turbine_modes_are_told_apart_by_family_and_whirl():
    styles = [mode_style(name) for name in NAMES]
    assert len({(s["color"], s["linestyle"], s["marker"]) for s in styles}) == len(NAMES)
    for name, style in zip(NAMES, styles):
        assert style["linestyle"] == ("--" if "backward" in name else "-." if "forward" in name else "-")
    assert len({mode_style(name)["color"] for name in NAMES if "1st blade" in name and "flap" in name}) == 1
    assert mode_style("1st blade collective flap")["color"] != mode_style("1st blade collective edge")["color"]


def test_turbine_campbell_marks_the_operating_speed_and_the_crossings():
    rpm = np.linspace(0.0, 15.0, 6)
    frequencies = np.array([[0.32] * 6, [0.7 + 0.005 * r for r in rpm]])
    result = TurbineCampbell(rpm, ["1st tower fore-aft", "1st blade collective flap"], frequencies,
                             np.zeros_like(frequencies), [])
    ax = turbine_campbell_figure(result, operating_rpm=12.1).axes[0]
    labels = [line.get_label() for line in ax.get_lines()]
    assert "operating speed (12.1 rpm)" in labels and "crossing with nP (n marked)" in labels
    assert {"3P", "6P"} <= set(texts(ax))          # the tower meets 3P at 6.4 rpm and 6P at 3.2 rpm


def test_a_simulation_figure_names_its_case(tmp_path, capsys):
    plot = tmp_path / "sim.png"
    deck = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
    captured = {}
    import bladefem.models.turbine.outputs as outputs
    original = outputs.plot_outputs

    def spy(result, path, *args, **kwargs):
        captured.update(kwargs)
        return original(result, path, *args, **kwargs)

    with pytest.MonkeyPatch.context() as patch:
        import bladefem.models.turbine.simulate as simulate
        patch.setattr(simulate, "plot_outputs", spy)
        code = main(["turbine", str(deck), "--simulate", "0.2", "--dt", "0.1", "--dof", "tower1", "--plot",
                     str(plot), "--quiet", "--output", str(tmp_path / "sim.csv")])
    assert code == 0 and plot.stat().st_size > 10_000
    assert captured["title"].startswith(deck.name) and "0.2 s simulated" in captured["title"]


class Recorder:
    def __init__(self):
        self.calls = []

    def add_point_labels(self, points, labels, **options):
        self.calls.append((points[0], labels[0], options))


@pytest.mark.parametrize("direction,horizontal,vertical", [
    ((1.0, 0.0), "left", "center"), ((-1.0, 0.0), "right", "center"), ((0.0, 1.0), "center", "bottom"),
    ((-0.7, -0.7), "right", "top"),
])
def test_a_triad_label_sits_beyond_its_arrow_head(direction, horizontal, vertical):
    view = View(focus=np.zeros(3), right=np.array([1.0, 0.0, 0.0]), up=np.array([0.0, 1.0, 0.0]), half_height=1.0)
    start = np.zeros(3)
    end = np.array([direction[0], direction[1], 0.5])          # partly toward the camera, as the edge arrow is
    plotter = Recorder()
    add_triad_label(plotter, view, start, end, "edge (to LE)", 13)
    point, label, options = plotter.calls[0]
    assert label == "edge (to LE)"
    assert options["justification_horizontal"] == horizontal and options["justification_vertical"] == vertical
    beyond = np.dot(point - end, view.right) * direction[0] + np.dot(point - end, view.up) * direction[1]
    assert beyond > 0                                      # moved past the tip, along the arrow on the screen
