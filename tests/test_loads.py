"""Fatigue loads of a DLC 1.2 batch: the damage-equivalent load of series of known cycles in closed form, the
Weibull weights of the wind-speed bins from the distribution's CDF, the lifetime DEL, and a small DLC plan (two
wind speeds, two turbulence boxes, short runs) through ``bladefem batch`` and ``bladefem batch-loads``."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from bladefem.batch.loads import damage_equivalent_load, lifetime_loads, rainflow_cycles, weibull_weights

DECK = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"


@pytest.mark.parametrize("m", [3.0, 4.0, 10.0])
def test_del_of_a_cosine_is_its_range(m):
    """N whole periods of ``mean + A cos`` over T s: N cycles of range 2A, so DEL = (N (2A)^m / (1 Hz T))^(1/m)."""
    t = np.linspace(0.0, 100.0, 200_001)
    series = 3.0 + 2.0 * np.cos(2 * np.pi * 0.5 * t)                 # 50 periods
    ranges, counts = rainflow_cycles(series)
    assert np.sum(counts) == pytest.approx(50.0) and np.allclose(ranges, 4.0)
    assert damage_equivalent_load(series, m, 100.0) == pytest.approx((50 * 4.0**m / 100.0) ** (1 / m), rel=1e-9)


def test_del_of_two_blocks_adds_damage():
    """30 cycles of range 2 then 10 of range 6 over 80 s, joined at a valley of -1 rising to 3: ASTM counting
    leaves the join as a half cycle of range 4 in place of one of range 2, so DEL^m = (30 2^m + 10 6^m +
    (4^m - 2^m) / 2) / 80 (to the 4e-4 by which the sampled cosines miss their peaks)."""
    a = np.cos(2 * np.pi * np.linspace(0, 30, 30 * 400 + 1))
    b = 3 * np.cos(2 * np.pi * np.linspace(0, 10, 10 * 400 + 1))
    series = np.concatenate([a, b[1:]])
    m = 4.0
    _, counts = rainflow_cycles(series)
    expected = (30 * 2.0**m + 10 * 6.0**m + (4.0**m - 2.0**m) / 2) / 80.0
    assert damage_equivalent_load(series, m, 80.0) ** m == pytest.approx(expected, rel=1e-3)
    assert np.sum(counts) == pytest.approx(40.0)
    assert damage_equivalent_load(np.full(10, 5.0), 4.0, 10.0) == 0.0


def test_weibull_weights_are_the_cdf_over_the_bins():
    speeds = np.array([4.0, 6.0, 8.0, 10.0, 12.0])
    weights = weibull_weights(speeds, 10.0)
    scale = 10.0 / math.gamma(1.5)                                      # Rayleigh: A = 2 V / sqrt(pi)
    edges = np.array([3.0, 5.0, 7.0, 9.0, 11.0, 13.0])
    cdf = 1 - np.exp(-(edges / scale) ** 2)
    assert scale == pytest.approx(2 * 10.0 / math.sqrt(math.pi))
    np.testing.assert_allclose(weights, np.diff(cdf) / (cdf[-1] - cdf[0]), rtol=1e-12)
    assert weights.sum() == pytest.approx(1.0)


def test_lifetime_del_weights_speeds_and_averages_boxes():
    rows = [{"channel": "X", "unit": "kN", "wind_speed_m_s": v, "del": d, "wohler_m": 4.0, "min": -d, "max": d}
            for v, d in ((6.0, 1.0), (6.0, 3.0), (10.0, 2.0), (10.0, 2.0))]
    (x,) = lifetime_loads(rows, 8.5)
    np.testing.assert_allclose(x.dels, [((1 + 81) / 2) ** 0.25, 2.0])
    w = weibull_weights(np.array([6.0, 10.0]), 8.5)
    assert x.lifetime_del == pytest.approx((w[0] * 41 + w[1] * 16) ** 0.25)
    assert (x.maximum, x.maximum_speed, x.minimum, x.minimum_speed) == (3.0, 6.0, -3.0, 6.0)


def test_a_small_dlc_plan_runs_and_gives_loads(tmp_path):
    """Two wind speeds x two boxes, 12 s each on a coarse box: every case ok, a DEL per channel, boxes that differ
    (different loads), and batch-loads writing its table and figures."""
    pytest.importorskip("pyconturb")
    pytest.importorskip("numba")
    from bladefem.batch import read_plan, run_case
    from bladefem.cli import main

    plan_path = tmp_path / "plan.yaml"
    plan_path.write_text(f"""model: {DECK}
analysis: {{type: turbine_simulate, seconds: 12, dt: 0.05, statistics_from_s: 4, turbulence_class: A,
           turbulence_grid: 5, turbulence_dt: 0.5, rtol: 1.0e-5}}
grid: {{wind_speed_m_s: [7, 10], turbulence_seed: [1, 2]}}
""")
    plan = read_plan(plan_path)
    assert len(plan.cases) == 4 and plan.analysis.turbulence == ("A", None, 5, 0.5) and plan.analysis.rtol == 1e-5
    rows = [run_case(case) for case in plan.cases[:2]]
    assert all(r["status"] == "ok" for case in rows for r in case), rows[0][0]
    dels = [{r["channel"]: r["del"] for r in case} for case in rows]
    assert dels[0]["RootMOoP1"] > 0 and dels[0]["RootMOoP1"] != dels[1]["RootMOoP1"]
    assert {r["channel"]: r["wohler_m"] for r in rows[0]}["RootMOoP1"] == 10.0
    out = tmp_path / "out"
    assert main(["batch", str(plan_path), "-o", str(out), "--workers", "1", "--quiet"]) == 0
    table = tmp_path / "loads.csv"
    assert main(["batch-loads", str(out), "--iec-class", "II", "-o", str(table), "--plot", str(tmp_path / "fig")]) == 0
    text = table.read_text()
    assert "RootMOoP1,kN m,10,lifetime,1," in text and (tmp_path / "fig" / "del.png").stat().st_size > 0


def test_bad_turbulence_plans_are_refused(tmp_path):
    from bladefem.batch import read_plan
    from bladefem.errors import InputError

    def plan(analysis: str, grid: str = "wind_speed_m_s: [8]") -> Path:
        path = tmp_path / "p.yaml"
        path.write_text(f"model: {DECK}\nanalysis: {{type: turbine_simulate, seconds: 10, {analysis}}}\n"
                        f"grid: {{{grid}}}\n")
        return path

    for analysis, grid, field in (
            ("dt: 0.05", "turbulence_seed: [1]", "grid.turbulence_seed"),
            ("turbulence_class: B, turbulence_intensity_percent: 10", "wind_speed_m_s: [8]",
             "analysis.turbulence_intensity_percent"),
            ("turbulence_grid: 5", "wind_speed_m_s: [8]", "analysis.turbulence_grid"),
            ("turbulence_class: D", "wind_speed_m_s: [8]", "analysis.turbulence_class")):
        with pytest.raises(InputError) as error:
            read_plan(plan(analysis, grid))
        assert error.value.field == field and error.value.line is not None, str(error.value)
