"""Unsteady wind: InflowWind's uniform wind files (WindType 2) and TurbSim full fields (WindType 3) against the
formulas of OpenFAST's InflowWind written out here (``IfW_FlowField.f90``), the TurbSim file made here by OpenFAST's
TurbSim against TurbSim's own summary, the wind reaching the turbine's loads at the time asked in both paths, and
bad wind files refused with their file, line and field."""

from __future__ import annotations

import contextlib
import io
import math
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

from bladefem.aero.rotor import Inflow
from bladefem.aero.wind import GridWind, UniformWind, point_wind
from bladefem.cli import main
from bladefem.errors import InputError
from bladefem.formats.turbsim import TurbSimBox, read_turbsim, write_turbsim
from bladefem.formats.uniform_wind import read_uniform_wind

ROOT = Path(__file__).resolve().parents[1]
CASE = ROOT / "cases" / "nrel5mw"
INFLOW = "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat"
BOX = ROOT / "tests" / "data" / "turbsim" / "nrel5mw_11p4_short.bts"

#: rows: time, speed, direction (rad), vertical, horizontal shear, exponent, vertical linear shear, gust, upflow (rad)
TABLE = np.array([[0.0, 10.0, 0.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0],
                  [2.0, 11.0, 0.1, 0.3, 0.2, 0.15, 0.1, 0.5, 0.04],
                  [9.0, 12.5, -0.14, -0.2, 0.4, 0.2, 0.3, 1.5, -0.05]])


def inflowwind_uniform(x, y, z, t, table, height, length):
    """OpenFAST's UniformField_InterpLinear and UniformField_GetVel, written out."""
    if t <= table[0, 0]:
        row = table[0]
    elif t >= table[-1, 0]:
        row = table[-1]
    else:
        i = np.searchsorted(table[:, 0], t, side="right")
        a = (t - table[i - 1, 0]) / (table[i, 0] - table[i - 1, 0])
        row = (1 - a) * table[i - 1] + a * table[i]
    _, V, D, VZ, HS, VS, LV, G, UP = row
    V1 = V * ((z / height) ** VS + (HS * (y * math.cos(D) + x * math.sin(D)) + LV * (z - height)) / length) + G
    V1r = math.cos(UP) * V1 - math.sin(UP) * VZ
    return np.array([V1r * math.cos(D), -V1r * math.sin(D), math.sin(UP) * V1 + math.cos(UP) * VZ])


def wind_at(inflow: Inflow, x, y, z, t) -> np.ndarray:
    out = np.zeros(3)
    point_wind(x, y, z, t, *inflow.arrays(), out)
    return out


@pytest.mark.parametrize("t", [-1.0, 0.0, 1.3, 2.0, 5.7, 9.0, 30.0])
def test_uniform_wind_is_inflowwinds(t):
    """Every column of the table moving; before, inside and after the table; points off the hub in x, y, z."""
    inflow = Inflow(10.0, 90.0, uniform=UniformWind(TABLE, 90.0, 125.0))
    for x, y, z in ((0.0, 0.0, 90.0), (-5.0, 40.0, 130.0), (3.0, -60.0, 30.0)):
        np.testing.assert_allclose(wind_at(inflow, x, y, z, t), inflowwind_uniform(x, y, z, t, TABLE, 90.0, 125.0),
                                   rtol=1e-13)
        np.testing.assert_allclose(inflow.velocity_at(np.array([x, y, z]), t),
                                   inflowwind_uniform(x, y, z, t, TABLE, 90.0, 125.0), rtol=1e-13)
    assert np.all(wind_at(inflow, 0.0, 0.0, -1.0, t) == 0)


def grid(periodic: bool, seed: int = 0) -> GridWind:
    rng = np.random.default_rng(seed)
    return GridWind(velocity=rng.normal(10.0, 2.0, size=(40, 5, 4, 3)).astype(np.float32), dt=0.5, dy=20.0, dz=15.0,
                    z0=50.0, mean_speed=10.0, periodic=periodic)


@pytest.mark.parametrize("periodic", [False, True])
def test_grid_nodes_cells_and_taylor_shift(periodic):
    """At a grid point and a grid time the grid's value; in a cell the mean of its 8 corners at its centre; a point
    ``d`` upwind of InflowWind's start position reads the grid ``d / U`` later (frozen turbulence)."""
    field = grid(periodic)
    inflow = Inflow(10.0, 90.0, grid=field)
    x0 = 0.0 if periodic else 40.0                          # InitXPosition: half the 80 m grid width, or 0
    assert field.x_start == x0
    v = field.velocity
    for it, iy, iz in ((3, 0, 0), (10, 4, 3), (21, 2, 1)):
        y, z = -40.0 + 20.0 * iy, 50.0 + 15.0 * iz
        np.testing.assert_allclose(wind_at(inflow, x0, y, z, 0.5 * it), v[it, iy, iz], rtol=1e-6)
        np.testing.assert_allclose(wind_at(inflow, x0 - 25.0, y, z, 0.5 * it), v[it + 5, iy, iz], rtol=1e-6)
    corners = v[7:9, 1:3, 2:4].reshape(-1, 3).mean(axis=0)
    np.testing.assert_allclose(wind_at(inflow, x0, -10.0, 87.5, 3.75), corners, rtol=1e-6)


def test_periodic_grid_wraps_and_an_edge_holds():
    field = grid(True)
    inflow = Inflow(10.0, 90.0, grid=field)
    np.testing.assert_allclose(wind_at(inflow, 0.0, 0.0, 80.0, 20.0 + 1.25), wind_at(inflow, 0.0, 0.0, 80.0, 1.25),
                               rtol=1e-6)
    np.testing.assert_allclose(wind_at(inflow, 0.0, 0.0, 80.0, 19.75), 0.5 * (field.velocity[39, 2, 2]
                                                                            + field.velocity[0, 2, 2]), rtol=1e-6)


def test_grid_that_misses_the_rotor_or_the_run_is_refused():
    inflow = Inflow(10.0, 90.0, grid=grid(False))                # y +-40 m, z 50..95 m, 19.5 s of wind
    inflow.check_covers(72.0, 20.0, 10.0)
    with pytest.raises(InputError, match="does not hold the rotor disk"):
        inflow.check_covers(90.0, 63.0, 10.0)
    with pytest.raises(InputError, match="holds 19.5 s of wind"):
        inflow.check_covers(72.0, 20.0, 18.0)
    Inflow(10.0, 90.0, grid=grid(True)).check_covers(72.0, 20.0, 600.0)        # periodic: any duration


def test_turbsim_file_against_turbsims_summary():
    """The box made here by OpenFAST v5's TurbSim (tests/data/turbsim/README.md): the grid of its input file and,
    at the hub, the mean speed and turbulence intensity of TurbSim's own summary (11.400 m/s, 9.939 %; the counts
    are 16-bit, so 0.01 %)."""
    box = read_turbsim(BOX)
    assert box.velocity.shape == (300, 5, 5, 3) and box.tower.shape == (300, 0, 3)
    assert (box.dt, box.dy, box.dz, box.z0, box.hub_height, box.periodic) == pytest.approx(
        (0.1, 35.0, 35.0, 20.0, 90.0, True))
    u = box.velocity[:, 2, 2, 0].astype(float)
    assert u.mean() == pytest.approx(11.400, abs=5e-4)
    assert 100 * u.std() / u.mean() == pytest.approx(9.939, abs=0.01)


def test_turbsim_written_and_read_back(tmp_path):
    box = read_turbsim(BOX)
    write_turbsim(tmp_path / "copy.bts", box)
    back = read_turbsim(tmp_path / "copy.bts")
    span = box.velocity.max(axis=(0, 1, 2)) - box.velocity.min(axis=(0, 1, 2))
    assert np.all(np.abs(back.velocity - box.velocity) <= span / 65535 * 0.51 + 1e-5)
    assert back.periodic and back.description == box.description


@pytest.mark.parametrize("damage, match", [
    (lambda b: b[:100], "bytes, the header"),
    (lambda b: b"\x05\x00" + b[2:], "not a TurbSim full-field file"),
    (lambda b: b[:26] + b"\x00\x00\x00\x00" + b[30:], "dt = 0.0: must be positive"),
    (lambda b: b[:10], "too short for a TurbSim header"),
])
def test_bad_turbsim_file_refused(tmp_path, damage, match):
    path = tmp_path / "bad.bts"
    path.write_bytes(damage(BOX.read_bytes()))
    with pytest.raises(InputError, match=match) as error:
        read_turbsim(path)
    assert str(path) in str(error.value)


@pytest.mark.parametrize("text, line, field", [
    ("0 10 0 0 0 0 0\n", 1, None),
    ("! header\n0 10 0 0 0 0 0 0\n1 x 0 0 0 0 0 0\n", 3, "speed [m/s]"),
    ("0 10 0 0 0 0 0 0\n0 11 0 0 0 0 0 0\n", 2, "time [s]"),
    ("0 10 0 0 0 0 0 nan\n", 1, "gust speed [m/s]"),
])
def test_bad_uniform_wind_file_refused(tmp_path, text, line, field):
    path = tmp_path / "bad.uni"
    path.write_text(text)
    with pytest.raises(InputError) as error:
        read_uniform_wind(path)
    assert (error.value.line, error.value.field) == (line, field)


def deck(tmp_path: Path, labels: dict[str, str], files: dict[str, bytes] = {}) -> Path:
    folder = tmp_path / "deck"
    shutil.copytree(CASE, folder)
    for name, content in files.items():
        (folder / name).write_bytes(content)
    text = (folder / INFLOW).read_text()
    for label, value in labels.items():
        text, count = re.subn(rf"^(\s*)\S+(\s+{label}\s)", rf"\g<1>{value}\g<2>", text, count=1, flags=re.M)
        assert count == 1
    (folder / INFLOW).write_text(text)
    return folder / "NRELOffshrBsline5MW_Onshore.fst"


def cli(*argv) -> tuple[int, str]:
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        code = main([str(a) for a in argv])
    return code, err.getvalue()


@pytest.mark.parametrize("labels, files, expected", [
    ({"WindType": "4"}, {}, r"InflowWind_Steady11p4mps.dat:5: field 'WindType': WindType 4 \(Bladed"),
    ({"WindType": "3", "FileName_BTS": '"none.bts"'}, {}, r":22: field 'FileName_BTS'"),
    ({"WindType": "3", "FileName_BTS": '"box.bts"', "PropagationDir": "10"}, {"box.bts": BOX.read_bytes()},
     r":6: field 'PropagationDir': must be 0 with WindType 3"),
    ({"WindType": "2", "FileName_Uni": '"w.uni"'}, {"w.uni": b"0 10 0 0 0 0 0 0\n1 10 0 0 0 0 0 zz\n"},
     r"w.uni:2: field 'gust speed \[m/s\]': not a number"),
    ({"WindType": "3", "FileName_BTS": '"box.bts"'}, {"box.bts": BOX.read_bytes()[:500]}, r"box.bts: field 'nt'"),
])
def test_bad_wind_in_a_deck_exits_2_naming_it(tmp_path, labels, files, expected):
    code, err = cli("turbine", deck(tmp_path, labels, files), "--simulate", "1", "--quiet")
    assert code == 2, err
    assert len(err.strip().splitlines()) == 1 and re.search(expected, err), err


def test_a_run_longer_than_the_box_is_refused(tmp_path):
    """The stored box is periodic: made non-periodic (FileID 7) its 30 s of wind do not last a 40 s run."""
    data = bytearray(BOX.read_bytes())
    data[0:2] = (7).to_bytes(2, "little")
    code, err = cli("turbine", deck(tmp_path, {"WindType": "3", "FileName_BTS": '"box.bts"'},
                                    {"box.bts": bytes(data)}), "--simulate", "40", "--quiet")
    assert code == 2 and "holds 29.9 s of wind" in err, err


def loaded_models(tmp_path: Path, labels: dict[str, str], files: dict[str, bytes]):
    from bladefem.builders.turbine_deck import read_turbine_deck
    from bladefem.models.turbine import TurbineModel
    steady = read_turbine_deck(CASE / "NRELOffshrBsline5MW_Onshore.fst", blade_shapes="polynomial", wind_speed=11.0)
    other = read_turbine_deck(deck(tmp_path, labels, files), blade_shapes="polynomial")
    return (TurbineModel(steady.params, aero=steady.aero, generator=steady.generator),
            TurbineModel(other.params, aero=other.aero, generator=other.generator))


def state(model):
    rng = np.random.default_rng(3)
    q, u = rng.normal(scale=0.02, size=model.n), rng.normal(scale=0.02, size=model.n)
    u[model.dofs.index("generator_azimuth")] = 1.2
    return q, u


def test_the_loads_see_the_uniform_wind_at_the_time_asked(tmp_path):
    """A table going from 9 to 13 m/s over 0-4 s is 11 m/s at t = 2 s: there the loads of both paths equal those in
    steady 11 m/s wind, at t = 1 s they do not."""
    table = b"0 9 0 0 0 0 0 0\n4 13 0 0 0 0 0 0\n"
    steady, uniform = loaded_models(tmp_path, {"WindType": "2", "FileName_Uni": '"ramp.uni"'}, {"ramp.uni": table})
    q, u = state(steady)
    _, f = steady.equations(q, u)
    for model_f in (lambda t: uniform.equations(q, u, t=t)[1], lambda t: uniform.fast_equations()(q, u, t=t)[1]):
        np.testing.assert_allclose(model_f(2.0), f, rtol=1e-10, atol=1e-9 * np.abs(f).max())
        assert np.abs(model_f(1.0) - f).max() > 1e-3 * np.abs(f).max()


def test_the_loads_in_a_constant_box_are_the_steady_ones(tmp_path):
    """A periodic TurbSim box holding 11 m/s everywhere gives the steady 11 m/s loads at any time, in both paths."""
    box = read_turbsim(BOX)
    constant = np.zeros_like(box.velocity)
    constant[..., 0] = 11.0
    write_turbsim(tmp_path / "flat.bts", TurbSimBox(constant, box.tower[:, :0], box.dt, box.dy, box.dz, box.z0,
                                                    11.0, 90.0, True))
    steady, flat = loaded_models(tmp_path, {"WindType": "3", "FileName_BTS": '"flat.bts"'},
                                 {"flat.bts": (tmp_path / "flat.bts").read_bytes()})
    q, u = state(steady)
    _, f = steady.equations(q, u)
    for t in (0.0, 13.7):
        np.testing.assert_allclose(flat.equations(q, u, t=t)[1], f, rtol=1e-6, atol=1e-6 * np.abs(f).max())
        np.testing.assert_allclose(flat.fast_equations()(q, u, t=t)[1], f, rtol=1e-6, atol=1e-6 * np.abs(f).max())


def test_wind_speed_options_are_refused_with_a_wind_file(tmp_path):
    """The file sets the wind: --wind-speed (and --shear-exp) with WindType 2 exit 2 naming the option."""
    uniform = deck(tmp_path, {"WindType": "2", "FileName_Uni": '"w.uni"'}, {"w.uni": b"0 10 0 0 0 0 0 0\n"})
    code, err = cli("turbine", uniform, "--simulate", "1", "--wind-speed", "8", "--quiet")
    assert code == 2 and "field '--wind-speed'" in err and "uniform wind file sets the wind" in err, err
