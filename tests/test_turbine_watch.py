"""A turbine simulation that leaves what is physical, explodes in step count or is interrupted ends early: one line
naming what and when, the rows computed up to then kept whole, exit 1 (130 for Ctrl-C); absurd inputs (a supersonic
blade tip, a generator rated beyond its rotor) are refused before it starts (exit 2); the numba compile notice
appears only when numba compiles (issue 24 items 6, 7, 10; issue 27 item 2)."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from bladefem.cli import main

ROOT = Path(__file__).resolve().parents[1]
CASE = ROOT / "cases" / "nrel5mw"
FST = "NRELOffshrBsline5MW_Onshore.fst"
SERVO = "NRELOffshrBsline5MW_Onshore_ServoDyn.dat"
ENV = {**os.environ, "PYTHONPATH": str(ROOT)}

needs_numba = pytest.mark.skipif(bool(os.environ.get("BLADEFEM_NO_NUMBA")) or
                                 not __import__("importlib").util.find_spec("numba"), reason="compiled kernels")


def deck_copy(tmp_path: Path, edits: dict[str, dict[str, str]] | None = None) -> Path:
    from test_turbine_twins import edit
    folder = tmp_path / "deck"
    shutil.copytree(CASE, folder)
    for file, labels in (edits or {}).items():
        for label, value in labels.items():
            edit(folder / file, label, value)
    return folder / FST


def whole_rows(path: Path) -> np.ndarray:
    """The table's rows, each complete (as many values as the header has names)."""
    text = path.read_text()
    assert text.endswith("\n")
    lines = text.splitlines()
    width = len(lines[0].split(","))
    assert all(len(line.split(",")) == width for line in lines[1:])
    return np.loadtxt(lines[1:], delimiter=",", ndmin=2)


def one_line(capsys, argv: list[str], code: int, *expected: str) -> str:
    assert main(["turbine", *argv]) == code
    error = capsys.readouterr().err.strip()
    lines = [line for line in error.splitlines() if not line.startswith(("#", "bladefem: compil"))]
    assert len(lines) == 1 and all(text in lines[0] for text in expected), error
    return lines[0]


def test_supersonic_rotor_speed_is_refused(capsys):
    """--rpm 100000 (accepted before, 220 s of CPU to diverge): the 63 m tip would pass the speed of sound above
    51.6 rpm."""
    one_line(capsys, [str(CASE / FST), "--simulate", "1", "--rpm", "100000", "--quiet"], 2, "--rpm",
             "speed of sound", "51.")
    one_line(capsys, [str(CASE / FST), "--simulate", "1", "--initial", "RotSpeed=60", "--quiet"], 2,
             "RotSpeed", "speed of sound")


def test_generator_rated_beyond_its_rotor_is_refused(tmp_path, capsys):
    """ServoDyn VS_RtTq 2147483648 (121 s of CPU for 3 s before): 2.6e11 W of rated power against the rotor's
    1.5e9 W Betz power at 70 m/s."""
    fst = deck_copy(tmp_path, {SERVO: {"VS_RtTq": "2147483648"}})
    one_line(capsys, [str(fst), "--simulate", "3", "--wind-speed", "11.4", "--quiet"], 2, "VS_RtTq", "Betz")


@needs_numba
def test_runaway_rotor_stops_at_the_speed_of_sound(tmp_path, capsys):
    """No torque law (CompServo 0), pitch 0, 40 m/s: the rotor runs away; the run stops when the tip passes the
    speed of sound (51.6 rpm), exit 1, one line naming the time, the rows up to then written whole."""
    fst = deck_copy(tmp_path, {FST: {"CompServo": "0"}})
    out = tmp_path / "out.csv"
    line = one_line(capsys, [str(fst), "--simulate", "120", "--wind-speed", "40", "--pitch-deg", "0", "--quiet",
                             "-o", str(out)], 1, "speed of sound", "t = ", "rows up to t =")
    rows = whole_rows(out)
    stop = float(line.split("t = ")[1].split()[0])
    assert 1 < len(rows) and rows[-1, 0] == stop < 120                # up to the row that passed the bound
    assert rows[:-1, 7].max() < 340.3 / 63 * 30 / np.pi <= rows[-1, 7]   # RotSpeed_rpm


@needs_numba
def test_step_count_explosion_gives_up(monkeypatch):
    """More right-hand sides per simulated second than MAX_RATE (lowered here to 1000, a third of what rtol 1e-9
    needs) stops the run with the reason and the rows so far, instead of running on for hours."""
    from bladefem.builders.turbine_deck import read_turbine_deck
    from bladefem.models.turbine import FreeSystem, TurbineModel
    from bladefem.models.turbine import watch
    from bladefem.models.turbine.initial import free_from_switches, initial_state
    from bladefem.models.turbine.simulate import SimulationStopped, simulate
    deck = read_turbine_deck(CASE / FST, wind_speed=11.4, blade_shapes="polynomial")
    model = TurbineModel(deck.params, aero=deck.aero, generator=deck.generator)
    free = free_from_switches(model.dofs, deck.switches)
    q0, u0, _ = initial_state(model, free, deck.conditions)
    monkeypatch.setattr(watch, "MAX_RATE", 1000.0)
    with pytest.raises(SimulationStopped) as stop:
        simulate(FreeSystem(model, free, q0, u0), 10.0, rtol=1e-9, atol=1e-11)
    assert "right-hand sides" in str(stop.value) and "per simulated second" in str(stop.value)
    assert 0 < stop.value.time < 10 and 1 <= len(stop.value.result.time) < 201


def test_monitor_bounds():
    """The power taken over the energy through the disk above 1 and the thrust over its dynamic-pressure force above 4
    (generator free) over 5 s, and a supersonic tip at any instant, are each named with the time; a one-row spike of
    RtAeroCp (a blade releasing elastic energy: OpenFAST shows 1.15 for an instant) is not; nor is RtAeroCp above 1
    where the disk-averaged wind dips (turbulence: the power falls less than the wind cubed for a moment, the
    energy balance over the window holds); nor a large thrust coefficient with the generator held (a motor)."""
    from types import SimpleNamespace

    from bladefem.models.turbine.outputs import LOAD_COLUMNS
    from bladefem.models.turbine.watch import Monitor
    model = SimpleNamespace(params=SimpleNamespace(hub_radius=1.5, blade=SimpleNamespace(length=61.5)),
                            azimuth=np.array([1.0, 0.0]), aero=object())
    times = np.arange(0.0, 8.01, 0.5)
    u = np.zeros((len(times), 2))
    half_rho_area = 7600.0                                     # 1/2 rho A of the coefficients, kg/m

    def rotor(wind, cp, ct):
        loads = np.zeros((len(times), len(LOAD_COLUMNS)))
        wind, cp, ct = (np.broadcast_to(np.asarray(x, dtype=float), times.shape) for x in (wind, cp, ct))
        for name, value in (("disk_velocity", wind), ("cp", cp), ("ct", ct), ("aero_power", cp * half_rho_area * wind**3),
                            ("aero_thrust", ct * half_rho_area * wind**2)):
            loads[:, LOAD_COLUMNS.index(name)] = value
        return loads

    def check(loads, free=True, u=u):
        monitor = Monitor(model, LOAD_COLUMNS, generator_free=free)
        return monitor.rows(times[:6], u[:6], loads[:6]) or monitor.rows(times[6:], u[6:], loads[6:])

    cp = np.full(times.shape, 0.5)
    assert check(rotor(10.0, cp, 0.8)) is None
    spike = cp.copy()
    spike[3] = 1.3
    assert check(rotor(10.0, spike, 0.8)) is None
    sustained = cp.copy()
    sustained[4:] = 1.2                          # over 0.5-5.5 s: (3 x 0.5 + 8 x 1.2) / 11 = 1.009 of the flux
    reason, when = check(rotor(10.0, sustained, 0.8))
    assert "RtAeroCp" in reason and when == 5.5
    gusty = np.where(np.arange(len(times)) % 4 == 0, 6.0, 11.0)    # the disk wind dips to 6 m/s every 2 s
    power = 0.45 * half_rho_area * 11.0**3 * np.ones(len(times))   # the power holds for a moment: RtAeroCp 2.8
    loads = rotor(gusty, power / (half_rho_area * gusty**3), 0.8)
    assert loads[:, LOAD_COLUMNS.index("cp")].max() > 2.5 and check(loads) is None
    reason, when = check(rotor(10.0, 0.5, -4.5))
    assert "RtAeroCt" in reason and when == 5.0
    assert check(rotor(10.0, 0.5, -4.5), free=False) is None
    fast = u.copy()
    fast[7, 0] = 6.0                                           # 6 rad/s x 63 m
    reason, when = check(rotor(10.0, 0.5, 0.8), u=fast)
    assert "speed of sound" in reason and when == 3.5
    assert Monitor.steps(5000, 1.0, 1.01) and Monitor.steps(5000, 1.0, 2.0) is None


@needs_numba
def test_deflection_past_the_blade_exits_1_with_the_rows(tmp_path, capsys):
    """A blade tip started 1 km out: the integrator stops at its first step (deflection larger than the blade),
    exit 1 (not 2: the input is valid, the answer is not), the initial row kept."""
    out = tmp_path / "out.csv"
    one_line(capsys, [str(CASE / FST), "--simulate", "1", "--initial", "blade1_flap1=1000", "--quiet", "-o",
                      str(out)], 1, "diverged", "blade1_flap1", "rows up to t = 0 s")
    assert len(whole_rows(out)) == 1


@needs_numba
def test_ctrl_c_ends_the_run_within_a_second(tmp_path):
    """SIGINT during a long --simulate: exit 130 within a second, one line, the rows computed so far written
    whole (the compiled kernel returns every 500 right-hand sides to look for it)."""
    out = tmp_path / "out.csv"
    command = [sys.executable, "-m", "bladefem", "turbine", str(CASE / FST), "--wind-speed", "11.4", "--quiet"]
    subprocess.run([*command, "--simulate", "0.1", "-o", str(out)], env=ENV, check=True, capture_output=True,
                   timeout=600)                                             # compiled kernels in the cache
    process = subprocess.Popen([*command, "--simulate", "3000", "-o", str(out)], env=ENV, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    time.sleep(8.0)
    assert process.poll() is None
    sent = time.perf_counter()
    process.send_signal(signal.SIGINT)
    _, err = process.communicate(timeout=30)
    elapsed = time.perf_counter() - sent
    assert process.returncode == 130 and elapsed < 1.0, (elapsed, err)
    lines = [line for line in err.splitlines() if line.strip()]
    assert len(lines) == 1 and "interrupted" in lines[0] and "Traceback" not in err, err
    rows = whole_rows(out)
    assert len(rows) > 1 and rows[-1, 0] < 3000


def test_compile_notice_only_when_numba_compiles(tmp_path):
    """The notice comes with a first call that compiles, not with one that loads machine code from numba's cache
    (a fresh process with a warm cache) nor with a later call in the same process."""
    pytest.importorskip("numba")
    module = tmp_path / "kernel_module.py"
    module.write_text("from numba import njit\n\n@njit(cache=True)\ndef twice(x):\n    return 2.0 * x\n")
    script = ("import sys; sys.path.insert(0, sys.argv[1]); import kernel_module as k\n"
              "from bladefem.models.turbine.compiled import first_call\n"
              "for _ in range(2):\n"
              "    with first_call('twice', 'test kernel', k.twice, (1.0,)):\n"
              "        k.twice(1.0)\n")
    env = {**ENV, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    env.pop("BLADEFEM_NO_NUMBA", None)
    first = subprocess.run([sys.executable, "-c", script, str(tmp_path)], env=env, capture_output=True, text=True,
                           timeout=300)
    assert first.stderr.count("compiling the test kernel with numba") == 1 and "compiled in" in first.stderr
    second = subprocess.run([sys.executable, "-c", script, str(tmp_path)], env=env, capture_output=True, text=True,
                            timeout=300)
    assert second.returncode == 0 and second.stderr == ""


def test_numba_is_a_core_dependency():
    """pip install . brings numba (issue 23 item 2): the 'fast' extra is no longer needed."""
    import tomllib
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert any(requirement.startswith("numba") for requirement in project["dependencies"])


def test_the_slow_path_says_so(monkeypatch, capsys):
    """Without the compiled kernels (BLADEFEM_NO_NUMBA, or numba missing) --simulate says at start that it runs the
    numpy equations, about 100 times slower (issue 23 item 2: it was silent)."""
    monkeypatch.setenv("BLADEFEM_NO_NUMBA", "1")
    assert main(["turbine", str(CASE / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"), "--simulate", "0.05",
                 "--elastodyn-compatible", "--dof", "tower1", "--quiet", "--method", "RK45"]) == 0
    assert "numpy equations, about 100 times slower" in capsys.readouterr().err


def test_kernel_cache_goes_stale_with_any_kernel_source():
    """numba stamps a cached function with its own file only: a kernel calling another file's kernel kept the old
    callee after that file changed (the compiled path then ran old physics). bladefem's kernels carry the hash of
    every kernel source in their cache stamp, and a change of any of them changes it."""
    pytest.importorskip("numba")
    from bladefem import numba_cache
    from bladefem.models.turbine import compiled_loads
    locator = compiled_loads.add_aero._cache._impl.locator
    assert getattr(type(locator), "bladefem", False)
    assert locator.get_source_stamp()[1] == numba_cache.sources_hash()
    paths = [path for pattern in numba_cache.KERNEL_SOURCES for path in numba_cache.PACKAGE.glob(pattern)]
    assert {"bem.py", "compiled_loads.py", "control.py"} <= {path.name for path in paths}


def test_kernels_compile_once_for_constant_arguments():
    """numba compiles, and links into every caller, one version of a kernel per constant value it is called with
    (the frame rotation about axis 0, 1, 2: three); bladefem's compiler types such calls by their plain types: one
    version, the same result."""
    njit = pytest.importorskip("bladefem.numba_cache").cached_njit()

    @njit
    def scaled(x, factor):
        return x * factor

    @njit
    def twice(x):
        return scaled(x, 2) + scaled(x, 3)

    assert twice(1.5) == 7.5
    assert [str(signature) for signature in scaled.signatures] == ["(float64, int64)"]
