"""Flutter: Theodorsen's function, the typical section against an independent determinant solution, the Goland
wing against its published flutter point, the command's onset on the NREL 5MW blade and its refusals.

The typical-section reference is solved here from Theodorsen's classical lift and moment (Bessel functions J and Y,
the 2x2 flutter determinant set to zero for real reduced frequency and speed), independently of
``bladefem.models.flutter_aero`` (blade-frame section matrices) and ``flutter_pk`` (the p-k iteration).
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import shlex
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq, fsolve
from scipy.special import jv, yv

from bladefem.cli import main
from bladefem.models.blade_aero import AeroOperatingPoint
from bladefem.models.flutter_aero import flutter_sections, theodorsen
from bladefem.models.flutter_pk import pk_root

ROOT = Path(__file__).resolve().parents[1]
GOLAND = ROOT / "cases" / "goland_wing"
#: the typical section of Hodges and Pierce (2011), Introduction to Structural Dynamics and Aeroelasticity, 2nd ed.,
#: section 5.5 (a = -1/5, e = -1/10, mu = 20, r^2 = 6/25, sigma = 2/5)
A, E, MU, R2, SIGMA = -0.2, -0.1, 20.0, 6 / 25, 0.4


def run(*argv: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(list(argv))
        except SystemExit as exit_:
            code = exit_.code
    return code, out.getvalue(), err.getvalue()


@pytest.mark.parametrize("k, F, G", [(0.1, 0.8319, -0.1723), (0.5, 0.5979, -0.1507), (1.0, 0.5394, -0.1003)])
def test_theodorsen_function_against_its_table(k, F, G):
    """C(k) = F + iG against the four-digit table of Bisplinghoff, Ashley and Halfman (1955), Table 5-1."""
    c = complex(theodorsen(k))
    assert c.real == pytest.approx(F, abs=1.5e-4) and c.imag == pytest.approx(G, abs=1.5e-4)
    assert complex(theodorsen(0.0)) == 1.0


def determinant_flutter() -> tuple[float, float]:
    """(U_F / (b omega_theta), omega_F / omega_theta) of the typical section: Theodorsen's lift and moment in the
    plunge-pitch equations, det = 0 solved for the real reduced frequency k and frequency (b = rho = omega_theta
    = 1)."""
    m, x_a = MU * math.pi, E - A
    inertia, static = m * R2, m * x_a

    def theodorsen_bessel(k: float) -> complex:
        h1, h0 = jv(1, k) - 1j * yv(1, k), jv(0, k) - 1j * yv(0, k)
        return h1 / (h1 + 1j * h0)

    def residual(x):
        k, w = x
        U, c, s = w / k, theodorsen_bessel(k), 1j * w
        downwash = (s, U + (0.5 - A) * s)                       # h' and alpha terms of h' + U alpha + b(1/2-a) alpha'
        lift = [math.pi * s**2 + 2 * math.pi * U * c * downwash[0],
                math.pi * (U * s - A * s**2) + 2 * math.pi * U * c * downwash[1]]
        moment = [math.pi * A * s**2 + 2 * math.pi * U * (A + 0.5) * c * downwash[0],
                  math.pi * (-U * (0.5 - A) * s - (1 / 8 + A**2) * s**2) + 2 * math.pi * U * (A + 0.5) * c
                  * downwash[1]]
        matrix = np.array([[m * s**2 + m * SIGMA**2 + lift[0], static * s**2 + lift[1]],
                           [static * s**2 - moment[0], inertia * s**2 + inertia - moment[1]]])
        d = np.linalg.det(matrix) / (m * inertia)
        return [d.real, d.imag]

    k, w = fsolve(residual, (0.3, 0.6), xtol=1e-13)
    assert max(abs(v) for v in residual((k, w))) < 1e-10
    return w / k, w


def section_damping(U: float) -> tuple[float, float]:
    """(damping ratio, frequency) of the typical section's pitch branch at speed U from bladefem's section matrices
    and p-k iteration: a one-node section feathered into wind U (plunge along the chord normal, pitch the twist)."""
    one, zero = np.ones(1), np.zeros(1)
    op = AeroOperatingPoint(span=zero, chord=2 * one, centre=np.zeros((3, 1)), X=U * one, Y=zero,
                            theta=math.pi / 2 * one, alpha=zero, cl=zero, cd=zero, cm=zero, dcl=2 * math.pi * one,
                            dcd=zero, dcm=zero, a=zero, ap=zero, air_density=1.0, rotor_speed=0.0,
                            shaft_axis=np.array([0.0, 0.0, 1.0]), wind_speed=U, pitch=math.pi / 2)
    sections = flutter_sections(op, 0.5 + A)                  # quarter chord, b (1/2 + a) ahead of the axis
    T = np.zeros((6, 2))
    T[1, 0], T[3, 1] = -1.0, 1.0                              # h toward the pressure side = -v; alpha = phi

    def aero(p):
        return tuple(T.T @ matrix[:, :, 0] @ T for matrix in sections.matrices(p))

    m = MU * math.pi
    M = np.array([[m, m * (E - A)], [m * (E - A), m * R2]])
    K = np.diag([m * SIGMA**2, m * R2])
    root = pk_root(M, np.zeros((2, 2)), K, aero, 0.7, np.array([0.3, 1.0], complex))
    assert root.converged
    return root.damping_ratio, root.frequency


def test_typical_section_flutter_point_against_the_determinant():
    """Flutter speed and frequency within 0.5 % of the determinant solution (U_F = 2.1839 b omega_theta, omega_F =
    0.6490 omega_theta; the p-k root is exact at zero damping, so the two agree to the root finders' tolerance)."""
    speed, frequency = determinant_flutter()
    assert speed == pytest.approx(2.1839, abs=1e-4) and frequency == pytest.approx(0.6490, abs=1e-4)
    assert section_damping(2.0)[0] > 0 > section_damping(2.4)[0]
    flutter = brentq(lambda U: section_damping(U)[0], 2.0, 2.4, xtol=1e-8)
    assert flutter == pytest.approx(speed, rel=5e-3)
    assert section_damping(flutter)[1] == pytest.approx(frequency, rel=5e-3)


def readme_command() -> list[str]:
    """The first ``bladefem flutter`` command line of cases/goland_wing/README.md, without the program name."""
    line = next(line for line in (GOLAND / "README.md").read_text().splitlines() if line.startswith("bladefem flutter"))
    return shlex.split(line)[1:]


@pytest.fixture(scope="module")
def goland():
    import os
    here = os.getcwd()
    os.chdir(ROOT)
    try:
        code, out, err = run(*readme_command(), "--json")
    finally:
        os.chdir(here)
    assert code == 0, err
    return json.loads(out)


def test_goland_wing_flutter_point(goland):
    """The README's command finds the Goland wing's flutter point within 3 % of Goland's published 137 m/s and
    70.7 rad/s (J. Appl. Mech. 1945), a coupled flap-torsion mode."""
    onset = goland["onset"]
    assert onset["wind_speed_m_s"] == pytest.approx(137.0, rel=0.03)
    assert 2 * math.pi * onset["frequency_hz"] == pytest.approx(70.7, rel=0.03)
    assert onset["shares"]["flap"] > 0.3 and onset["shares"]["torsion"] > 0.3


def test_goland_wing_against_the_exact_strip_theory_solution(goland):
    """Against the exact continuous-wing solution with Theodorsen strip aerodynamics (ContourRoots,
    examples/continuous_wing/VALIDATION.md: 136.984 m/s, 70.033 rad/s, for data rounded differently in the fourth
    digit): within 0.2 % (measured -0.02 % in both; the sweep's 1 m/s steps and linear interpolation of the
    damping leave about 0.01 %)."""
    onset = goland["onset"]
    assert onset["wind_speed_m_s"] == pytest.approx(136.984, rel=2e-3)
    assert 2 * math.pi * onset["frequency_hz"] == pytest.approx(70.033, rel=2e-3)


def test_nrel5mw_blade_onset_in_still_air(tmp_path):
    """The NREL 5MW blade (BeamDyn sections, with torsion) turning in still air: the sweep finds an onset between
    1.5 and 3 times the rated 12.1 rpm, the range reported for multi-megawatt blades (Lobitz 2004: about twice the
    operating speed for a 1.5 MW blade), written as JSON with its plot."""
    plot = tmp_path / "flutter.png"
    code, out, err = run("flutter", str(ROOT / "tests/data/nrel5mw_beamdyn/bd_primary_nrel_5mw.inp"), "--hub-radius",
                         "1.5", "--aero", str(ROOT / "cases/nrel5mw/NRELOffshrBsline5MW_Onshore_AeroDyn.dat"),
                         "--rpm", "15:33:7", "--n-modes", "6", "--json", "--quiet", "--plot", str(plot))
    assert code == 0, err
    result = json.loads(out)
    onset = result["onset"]
    assert onset is not None and 1.5 * 12.1 < onset["rpm"] < 3 * 12.1
    assert len(result["sweep"]) == 7 and plot.stat().st_size > 0
    before = result["sweep"][0]["modes"][onset["mode"] - 1]
    assert before["damping_ratio"] > 0


@pytest.mark.parametrize("extra, field", [
    (("--rpm", "0:10:5", "--wind-speed", "10:20:3"), "--rpm"),
    (("--rpm", "5",), "--rpm"),
    (("--wind-speed", "10:5:3"), "--wind-speed"),
    (("--wind-speed", "-1:5:3"), "--wind-speed"),
])
def test_bad_sweeps_exit_2(extra, field):
    code, out, err = run("flutter", str(GOLAND / "goland_wing.yaml"), "--aero", str(GOLAND / "goland_AeroDyn.dat"),
                         *extra)
    assert code == 2 and out == "" and field in err and "Traceback" not in err


def test_tower_input_is_refused():
    code, _, err = run("flutter", str(ROOT / "cases/uniform_tower.yaml"), "--aero",
                       str(GOLAND / "goland_AeroDyn.dat"), "--wind-speed", "10:20:3")
    assert code == 2 and "blade" in err


def test_the_flutter_document_is_what_its_script_writes(tmp_path):
    """docs/flutter.md and docs/standstill.md are the current output of one run of examples/flutter.py (their
    numbers to the printed last digit: rounding may move it; the yaw sectors' whole degrees exactly), and the
    flutter diagrams and the yaw maps are written beside them."""
    import re
    import subprocess
    import sys

    written = tmp_path / "flutter.md"
    subprocess.run([sys.executable, str(ROOT / "examples" / "flutter.py"), "--output", str(written)], check=True,
                   cwd=ROOT, capture_output=True)
    for name, count in (("flutter.md", 300), ("standstill.md", 20)):
        texts = [(folder / name).read_text() for folder in (tmp_path, ROOT / "docs")]
        numbers = [re.findall(r"-?\d+\.\d+", text) for text in texts]
        assert len(numbers[0]) == len(numbers[1]) > count, name
        assert max(abs(float(a) - float(b)) for a, b in zip(*numbers)) <= 0.011, name
        sectors = [re.findall(r"-?\d+ to -?\d+", text) for text in texts]
        assert sectors[0] == sectors[1], name
    for name in ("flutter-goland.png", "flutter-nrel5mw.png", "flutter-iea15.png", "standstill-nrel5mw.png",
                 "standstill-iea15mw.png"):
        assert (tmp_path / name).stat().st_size > 10_000, name
    assert "## Stall-induced vibration at standstill: the yaw maps" in written.read_text()


def test_the_blades_sections_are_as_the_flutter_page_says():
    """docs/flutter.md names the sections as a cause of differences: OpenFAST's BeamDyn example of the 5MW blade has
    diagonal six-by-six matrices (centre of mass and shear centre on the reference axis, no coupling), the IEA-15MW's
    have off-diagonal stiffness and mass terms (offsets and couplings); neither gives the reference axis's chordwise
    place (the aerodynamic centre then sits on AeroDyn's reference line)."""
    import numpy as np

    from bladefem.builders.detect import Geometry, read_model

    def off_diagonal(matrices):
        return max(float(np.abs(m - np.diag(np.diag(m))).max() / np.abs(np.diag(m)).max()) for m in matrices)

    five = read_model(ROOT / "tests/data/nrel5mw_beamdyn/bd_primary_nrel_5mw.inp", None, Geometry(hub_radius=1.5))
    fifteen = read_model(ROOT / "tests/data/iea15/beamdyn/IEA-15-240-RWT_BeamDyn.dat", None,
                         Geometry(hub_radius=3.97))
    assert off_diagonal(five.sections.full.stiffness) == 0 and off_diagonal(five.sections.full.mass) == 0
    assert off_diagonal(fifteen.sections.full.stiffness) > 0.01 and off_diagonal(fifteen.sections.full.mass) > 0.01
    assert five.sections.pitch_axis is None and fifteen.sections.pitch_axis is None


def test_quasi_steady_limit_of_the_reduction_equals_the_full_quadratic_problem():
    """Twins: with C(k) = 1 and neither apparent mass nor pitch rate, the flutter reduction (sweep basis, section
    matrices integrated at the quadrature points) is the quasi-steady model of ``bladefem modes --aero`` solved on
    all DOFs: NREL 5MW BeamDyn blade at 11.4 m/s and 12.1 rpm, the six lowest modes. Measured with 40 basis vectors:
    frequencies within 1e-5, damping ratios within 1.2e-4 (the Ritz truncation; 1e-3 and 1e-2 at 10 vectors)."""
    from dataclasses import replace

    from bladefem.builders.aerodyn_rotor import aerodyn_rotor
    from bladefem.builders.detect import Geometry, read_model
    from bladefem.modal import blade_matrices
    from bladefem.modal.quadratic import solve_quadratic_modes
    from bladefem.models.blade_aero import aero_matrices, operating_point, section_matrices
    from bladefem.models.flutter_basis import ReducedAero, SweepBasis
    from bladefem.models.flutter_pk import state_roots

    blade = read_model(ROOT / "tests/data/nrel5mw_beamdyn/bd_primary_nrel_5mw.inp", None, Geometry(hub_radius=1.5))
    rotor = aerodyn_rotor(ROOT / "cases/nrel5mw/NRELOffshrBsline5MW_Onshore_AeroDyn.dat", blade, 3)
    matrices = blade_matrices(blade, 60)
    speed = 12.1 * math.pi / 30
    op = operating_point(rotor, 11.4, speed, 0.0)
    full = solve_quadratic_modes(matrices, 12.1, 6, (), *aero_matrices(matrices, op), True)
    sections = flutter_sections(op)
    D, K = section_matrices(op)
    zero = np.zeros_like(D)
    quasi_steady = replace(sections, lift_damping=D - sections.quasi_steady_damping,
                           lift_stiffness=K - sections.quasi_steady_stiffness, apparent_mass=zero,
                           apparent_damping=zero)
    basis = SweepBasis(matrices, [speed], 40)
    M_a, D_a, K_a = ReducedAero(basis, quasi_steady)(0j)
    values, _ = state_roots(np.eye(basis.size) + M_a, speed * basis.G + D_a, basis.stiffness(speed) + K_a)
    values = values[values.imag > 0]
    values = values[np.argsort(np.abs(values))][:6]
    for value, mode in zip(values, full.modes):
        assert abs(value) / (2 * math.pi) == pytest.approx(mode.frequency_hz, rel=1e-4)
        assert -value.real / abs(value) == pytest.approx(mode.damping_ratio, abs=5e-4)


def test_iea15_blade_with_its_deck_settings(tmp_path):
    """The IEA-15MW BeamDyn blade with its AeroDyn deck (unsteady airfoil model, tower influence switched on):
    the settings the flutter analysis replaces are named in the notes, not refused, and in still air an onset is
    found above rated (7.56 rpm) and below three times rated among the six tracked modes of docs/flutter.md (the
    bound is that page's physical range, not a reference value; all 50 polars of the deck are stored)."""
    import sys
    sys.path.insert(0, str(ROOT / "tests"))
    from deck_copies import deck_copy

    deck = deck_copy("iea15", tmp_path)
    code, out, err = run("flutter", str(ROOT / "tests/data/iea15/beamdyn/IEA-15-240-RWT_BeamDyn.dat"),
                         "--hub-radius", "3.97", "--aero",
                         str(deck / "IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_AeroDyn15.dat"),
                         "--rpm", "6:18:7", "--n-modes", "6", "--json", "--quiet")
    assert code == 0, err
    assert "Theodorsen" in err and "the blade alone" in err
    onset = json.loads(out)["onset"]
    assert onset is not None and 7.56 < onset["rpm"] < 3 * 7.56


def test_sweep_basis_serves_the_speeds_between_its_ends():
    """One basis for a rotor-speed sweep (12 modes at each of 10 and 30 rpm) gives, at 20 rpm, the p-k roots of a
    basis of 48 modes made at 20 rpm itself: NREL 5MW BeamDyn blade in still air, four modes. Measured (the Ritz
    truncation): damping ratios within 2.3e-3 (5e-5 for the lightly damped edgewise mode), the frequencies of the
    three lightly or moderately damped modes within 0.3 %; the first flap mode, 98 % damped, has a damped frequency
    of a fifth of its natural one and is left out of the frequency check."""
    from dataclasses import replace

    from bladefem.builders.aerodyn_rotor import aerodyn_rotor
    from bladefem.builders.detect import Geometry, read_model
    from bladefem.modal import blade_matrices
    from bladefem.models.flutter import OperatingCondition, flutter_point
    from bladefem.models.flutter_basis import SweepBasis

    blade = read_model(ROOT / "tests/data/nrel5mw_beamdyn/bd_primary_nrel_5mw.inp", None, Geometry(hub_radius=1.5))
    rotor = aerodyn_rotor(ROOT / "cases/nrel5mw/NRELOffshrBsline5MW_Onshore_AeroDyn.dat", blade, 3)
    rotor = replace(rotor, options=replace(rotor.options, induction=False))
    matrices = blade_matrices(blade, None, 6, 30.0)
    to_rad = math.pi / 30
    condition = OperatingCondition(0.0, 20 * to_rad, 0.0)
    ends = flutter_point(matrices, SweepBasis(matrices, [10 * to_rad, 30 * to_rad], 12), rotor, condition, 4, None)
    local = flutter_point(matrices, SweepBasis(matrices, [20 * to_rad], 48), rotor, condition, 4, None)
    assert ends.converged.all() and local.converged.all()
    assert np.allclose(ends.frequency_hz[1:], local.frequency_hz[1:], rtol=5e-3)
    assert np.allclose(ends.damping_ratio, local.damping_ratio, atol=5e-3)
    assert abs(ends.damping_ratio[1] - local.damping_ratio[1]) < 2e-4


def test_text_table_and_vtk_of_the_unstable_mode(tmp_path):
    """Without --json the sweep prints a table and the onset line; --vtk writes the unstable mode's shape (a .pvd
    collection, VTU meshes and a JSON sidecar naming its frequency)."""
    code, out, err = run("flutter", str(GOLAND / "goland_wing.yaml"), "--aero", str(GOLAND / "goland_AeroDyn.dat"),
                         "--wind-speed", "130:145:4", "--blades", "1", "--n-modes", "3", "--quiet", "--vtk",
                         str(tmp_path / "vtk"))
    assert code == 0, err
    lines = out.splitlines()
    assert lines[-1].startswith("flutter onset: mode 2 at 0 rpm, 13")
    assert sum(line.strip().startswith("0.000") for line in lines) == 4
    sidecar = json.loads((tmp_path / "vtk" / "flutter_mode.json").read_text())
    assert (tmp_path / "vtk" / "flutter_mode.pvd").is_file()
    [mode] = sidecar["speeds"][0]["modes"]
    assert 10.5 < mode["frequency_hz"] < 11.5 and mode["energy_fractions"]["torsion"] > 0.2


def test_a_blade_root_on_the_rotor_axis_is_refused():
    """An AeroDyn node at radius 0 (hub radius 0 and BlSpn 0) has no BEM operating point: one line naming
    --hub-radius, not a division by zero (the Goland wing with its root moved onto the axis)."""
    code, out, err = run("flutter", str(GOLAND / "goland_wing.yaml"), "--hub-radius", "0", "--aero",
                         str(GOLAND / "goland_AeroDyn.dat"), "--wind-speed", "120:140:2", "--blades", "1")
    assert code == 2 and out == "" and "--hub-radius" in err and "Traceback" not in err


@pytest.mark.parametrize("factor, passed", [(1.5, True), (2.0, False)])
def test_check_flutter_margin_requirement(tmp_path, factor, passed):
    """``bladefem check``'s flutter requirement on the NREL 5MW BeamDyn blade in still air (first onset 21.7 rpm,
    1.79 times the rated 12.1): no onset up to 1.5 x rated passes, 2 x rated fails with the onset's ratio measured."""
    spec = tmp_path / "check.yaml"
    spec.write_text(f"""models:
  blade:
    input: {ROOT / "tests/data/nrel5mw_beamdyn/bd_primary_nrel_5mw.inp"}
    hub_radius_m: 1.5
requirements:
  - model: blade
    flutter: {{aero: {ROOT / "cases/nrel5mw/NRELOffshrBsline5MW_Onshore_AeroDyn.dat"}, rated_rpm: 12.1,
              factor: {factor}, points: 9}}
""")
    code, out, err = run("check", str(spec), "--json")
    assert code == (0 if passed else 1), err
    [outcome] = json.loads(out)["outcomes"]
    assert outcome["passed"] is passed
    if passed:
        assert outcome["measured"] == 1.5 and "no onset" in outcome["detail"]
    else:
        assert outcome["measured"] == pytest.approx(21.8 / 12.1, rel=0.02) and outcome["margin"] < 0
