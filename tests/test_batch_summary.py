"""What batch-summary shows a reader: each statistic with its unit, histograms with axis labels and a title, and
the Dask dashboard's address only where there is a dashboard."""

from __future__ import annotations

import re

import pytest

pa = pytest.importorskip("pyarrow")
pytest.importorskip("dask.distributed")

from bladefem.batch import format_summary, plot_summary, summarize  # noqa: E402
from bladefem.batch.runner import dashboard_address  # noqa: E402


def modes_table() -> object:
    rows = [{"case_index": i, "case_hash": str(i), "status": "ok", "error": None, "mass_scale": m, "mode": k + 1,
             "name": name, "kind": name.split()[0], "frequency_hz": f / m ** 0.5}
            for i, m in enumerate((0.95, 1.0, 1.05, 1.1)) for k, (name, f) in enumerate((("flap 1", 0.7),
                                                                                          ("edge 1", 1.1)))]
    rows.append({"case_index": 4, "case_hash": "4", "status": "error", "error": "InputError: x", "mass_scale": 1.2})
    return pa.Table.from_pylist(rows)


def channels_table() -> object:
    return pa.Table.from_pylist([
        {"case_index": i, "case_hash": str(i), "status": "ok", "error": None, "wind_speed_m_s": u, "channel": c,
         "unit": unit, "mean": v, "std": 0.0, "min": v, "max": v}
        for i, u in enumerate((8.0, 10.0)) for c, unit, v in (("RotPwr", "kW", 100 * u), ("GenTq", "kN-m", u))])


def test_the_statistics_table_gives_each_quantity_its_unit():
    text = format_summary(summarize(modes_table()))
    assert re.search(r"^quantity\s+unit\s+n\s+mean", text, re.MULTILINE)
    assert re.search(r"^flap 1\s+Hz\s+4\s", text, re.MULTILINE) and re.search(r"^edge 1\s+Hz\s+4\s", text,
                                                                            re.MULTILINE)
    text = format_summary(summarize(channels_table()))
    assert re.search(r"^RotPwr mean\s+kW\s+2\s+900\s", text, re.MULTILINE), text
    assert re.search(r"^GenTq mean\s+kN-m\s+2\s", text, re.MULTILINE)
    assert "mean over the window" in text


def test_histograms_have_labelled_axes_and_a_title(tmp_path, monkeypatch):
    import matplotlib.figure
    drawn = []
    original = matplotlib.figure.Figure.savefig
    monkeypatch.setattr(matplotlib.figure.Figure, "savefig",
                        lambda self, *a, **k: drawn.append(self) or original(self, *a, **k))
    paths = plot_summary(summarize(modes_table()), tmp_path, title="uq")
    assert [p.name for p in paths] == ["histograms.png", "tornado.png"] and all(p.stat().st_size for p in paths)
    histograms, tornado = drawn
    panels = [axis for axis in histograms.axes if axis.get_visible()]
    assert [axis.get_title() for axis in panels] == ["flap 1", "edge 1"]
    assert {axis.get_ylabel() for axis in panels} == {"cases"}
    assert {axis.get_xlabel() for axis in panels} == {"frequency (Hz)"}
    assert histograms.get_suptitle() == "uq: each quantity over 5 cases, 1 failed"
    assert all(tick.is_integer() for axis in panels for tick in axis.get_yticks())    # counts of cases
    assert tornado.get_suptitle().startswith("uq: sensitivity of each quantity to each varied input")


class FakeClient:
    def __init__(self, services: dict, bokeh: bool) -> None:
        self.services, self.bokeh = services, bokeh
        self.dashboard_link = "http://127.0.0.1:8787/status"

    def scheduler_info(self) -> dict:
        return {"services": self.services}

    def run_on_scheduler(self, function) -> bool:
        return self.bokeh


def test_the_dashboard_address_only_where_the_scheduler_serves_a_dashboard():
    assert dashboard_address(FakeClient({"dashboard": 8787}, bokeh=True)) == "http://127.0.0.1:8787/status"
    assert dashboard_address(FakeClient({"dashboard": 8787}, bokeh=False)) is None   # a page asking for bokeh
    assert dashboard_address(FakeClient({}, bokeh=True)) is None                     # --no-dashboard
