"""Stall-induced vibration of a parked blade (``models/standstill.py``, ``bladefem standstill``).

- A uniform cantilever blade with one airfoil against the textbook aerodynamic damping of a section vibrating
  normal to its chord (Hansen 2007, Wind Energy 10:551; Petersen et al. 1998, Risoe-R-1045), per length
  ``c_flap = (rho c W / 2) [cd (1 + sin^2 phi) + cl' cos^2 phi + (cl + cd') sin phi cos phi]`` with ``phi`` the
  inflow angle from the chord, written here from the section's lift and drag, and the modal damping ratio
  ``c_flap / (2 m omega)`` of the uniform beam (damping and mass both uniform): in attached flow from the leading
  edge (positive) and in the stall range of the polar (negative lift slope: negative).
- The independence principle: a blade along the wind (horizontal, wind in the rotor plane) gets no damping.
- The negative sectors' ends interpolated.
- The NREL 5MW and IEA-15MW parked and feathered at 50 m/s against the yaw sectors of the edgewise instability
  reported for them (docs/standstill.md quotes the sources); the command line and its one-line errors.
"""

from __future__ import annotations

import json
import math
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

from bladefem.aero import BEMOptions, Polar, Rotor
from bladefem.assembly import assemble_blade
from bladefem.cli import main
from bladefem.models.standstill import negative_intervals, parked_point, standstill_sweep
from bladefem.sections import Blade, uniform_sections

ROOT = Path(__file__).resolve().parents[1]
CASE = ROOT / "cases" / "nrel5mw"
MAIN = CASE / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
AERODYN = CASE / "NRELOffshrBsline5MW_Onshore_AeroDyn.dat"
IEA15 = ROOT / "tests" / "data" / "iea15"
BEAMDYN = IEA15 / "beamdyn" / "IEA-15-240-RWT_BeamDyn.dat"
IEA_AERODYN = IEA15 / "IEA-15-240-RWT-Monopile" / "IEA-15-240-RWT-Monopile_AeroDyn15.dat"

L, MASS, EI, CHORD, RHO, U = 40.0, 300.0, 2e9, 2.0, 1.225, 30.0
#: the polar: attached (slope 2 pi) to 10 deg, stalled (lift falling, drag rising) from 10 to 30 deg
KNOTS = np.radians([-180.0, -10.0, 10.0, 30.0, 180.0])
CL = np.array([0.0, -2 * np.pi * math.radians(10), 2 * np.pi * math.radians(10), 0.4, 0.0])
CD = np.array([0.02, 0.02, 0.02, 0.5, 0.02])


def uniform_case() -> tuple[Blade, Rotor]:
    blade = Blade(uniform_sections(L, MASS, EI, edge_stiffness=100 * EI))
    polar = Polar(alpha=KNOTS, cl=CL, cd=CD, cm=np.zeros(5))
    n = 41
    rotor = Rotor(n_blades=3, hub_radius=2.0, span=np.linspace(0.0, L, n), chord=np.full(n, CHORD),
                  twist=np.zeros(n), airfoil=np.zeros(n, dtype=int), polars=(polar,), air_density=RHO,
                  options=BEMOptions(pitching_moment=False))
    return blade, rotor


def flap_damping_per_length(phi: float) -> float:
    """Textbook damping per length of a section moving normal to its chord, inflow ``phi`` (rad) from the chord."""
    cl, cd = np.interp(phi, KNOTS, CL), np.interp(phi, KNOTS, CD)
    i = np.searchsorted(KNOTS, phi) - 1
    slope_l = (CL[i + 1] - CL[i]) / (KNOTS[i + 1] - KNOTS[i])
    slope_d = (CD[i + 1] - CD[i]) / (KNOTS[i + 1] - KNOTS[i])
    s, c = math.sin(phi), math.cos(phi)
    return 0.5 * RHO * CHORD * U * (cd * (1 + s**2) + slope_l * c**2 + (cl + slope_d) * s * c)


@pytest.mark.parametrize("formulation", [1, 2])
@pytest.mark.parametrize("pitch_deg", [0.0, 30.0, 90.0])
def test_the_parked_point_is_the_bem_without_induction(formulation, pitch_deg):
    """A prebent, swept blade (the aerodynamic centres 3 m upwind and 1 m back at the tip, the sections canted by
    the prebend's slope), coned, on a tilted shaft, pitched: the parked point's angles of attack, twist and
    in-plane velocities are those the rigid-rotor BEM (itself checked against OpenFAST,
    tests/test_iea15_rigid_rotor_openfast.py) gives at zero rotor speed without induction, in both projections:
    the pitch turns the offsets and the cant, the section carries what its orientation adds to the twist, and in
    the polar projection it sees the inflow in its own plane. Before, the parked point took the pitch as a twist
    and the polar projection's inflow without the cant: at 30 deg of pitch the angles of attack differed by up
    to 0.24 deg (legacy) and 0.33 deg (polar), at 90 deg by 0.27 deg (polar)."""
    from dataclasses import replace

    from bladefem.aero.performance import performance_at
    from bladefem.aero.rotor import Inflow
    _, rotor = uniform_case()
    shape = (rotor.span / rotor.span[-1]) ** 2
    rotor = replace(rotor, curve=-3.0 * shape, sweep=1.0 * shape, curve_angle=-np.radians(8.0) * shape,
                    precone=math.radians(-4.0), shaft_tilt=math.radians(-6.0), hub_height=100.0,
                    twist=np.radians(np.linspace(12.0, 0.0, len(shape))),
                    options=replace(rotor.options, induction=False, formulation=formulation))
    pitch = math.radians(pitch_deg)
    op = parked_point(rotor, U, 0.0, 0.0, pitch)
    bem = performance_at(rotor, Inflow(U, 100.0), 0.0, pitch, 0.0, np.zeros(1))
    np.testing.assert_allclose(op.alpha, bem.alpha[0, 0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(op.theta, rotor.twist + pitch + bem.section_twist[0, 0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(np.hypot(op.X, op.Y), bem.w[0, 0], rtol=1e-12)


@pytest.mark.parametrize("phi_deg, sign", [(0.0, 1), (20.0, -1)], ids=["attached", "stalled"])
def test_uniform_blade_flap_damping_is_the_textbook_section_damping(phi_deg, sign):
    blade, rotor = uniform_case()
    omega = 1.8751040687**2 * math.sqrt(EI / (MASS * L**4))       # first cantilever bending mode, rad/s
    # blade 1 up: wind in its plane from the leading edge at yaw -90 deg, turned out of it by 90 + yaw
    yaw = -90.0 + phi_deg
    result = standstill_sweep(assemble_blade(blade, 40), rotor, U, 0.0, [yaw], [0.0], n_modes=2)
    flap = next(mode for mode in result.points[0][0].modes if mode.name == "flap 1")
    expected = flap_damping_per_length(math.radians(phi_deg)) / (2 * MASS * omega)
    assert np.sign(expected) == sign and np.sign(flap.total) == sign
    if phi_deg == 0.0:
        # no flap-edge coupling (cl(0) = 0, cd' = 0): exact but for the FE frequency, measured 3e-9
        assert flap.aerodynamic == pytest.approx(expected, rel=1e-6)
    else:
        # the inflow couples flap and edge motion (cross damping ~ cl, cd'); with the edge mode 10 times higher
        # the flap mode's damping moves by second order in it: measured 5.2e-6 relative
        assert flap.aerodynamic == pytest.approx(expected, rel=1e-4)
    # the frequency: FE 3e-9, and the same second-order coupling in the stall, 5.1e-6
    assert flap.frequency_hz == pytest.approx(omega / (2 * np.pi), rel=1e-4)


def test_a_blade_along_the_wind_gets_no_damping():
    """Blade 1 at azimuth 90 deg is horizontal; at yaw -90 deg the wind runs along it: no in-plane component."""
    blade, rotor = uniform_case()
    op = parked_point(rotor, U, math.radians(-90.0), math.radians(90.0), 0.0)
    assert np.abs(op.X).max() < 1e-12 * U and np.abs(op.Y).max() < 1e-12 * U
    result = standstill_sweep(assemble_blade(blade, 20), rotor, U, 0.0, [-90.0], [90.0], n_modes=2)
    assert all(abs(mode.aerodynamic) < 1e-9 for mode in result.points[0][0].modes)


def test_negative_sectors_are_interpolated():
    yaw = np.array([-30.0, -10.0, 10.0, 30.0, 50.0])
    assert negative_intervals(yaw, np.array([1.0, -1.0, -3.0, 1.0, 2.0])) == [(-20.0, 25.0)]
    assert negative_intervals(yaw, np.array([-1.0, 1.0, 1.0, 1.0, -2.0])) == [(-30.0, -20.0), (110 / 3, 50.0)]
    assert negative_intervals(yaw, np.ones(5)) == []


def run(capsys, *argv: object) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def sectors(data: dict, name: str) -> list[list[float]]:
    return data["negative_sectors"][name]["0"]


def test_nrel5mw_feathered_edgewise_instability_in_yaw(capsys):
    """Jonkman and Buhl (2007) found the idling, feathered NREL 5MW unstable in DLC 6.2 at large yaw errors (the
    blade-edgewise mode); the quasi-steady damping puts the first edgewise mode's negative sectors at about
    -55..-13 and 18..36 deg at 50 m/s."""
    code, out, _ = run(capsys, "standstill", MAIN, "--aero", AERODYN, "--wind-speed", 50, "--pitch-deg", 90,
                       "--yaw-deg=-60:60:25", "--tilt-deg", -5, "--elements", 40, "--n-modes", 4,
                       "--structural-damping-percent", "0.477465,0.477465", "--json")
    data = json.loads(out)
    assert code == 0 and data["modes"][:2] == ["flap 1", "edge 1"]
    edge = sectors(data, "edge 1")
    assert any(a <= 30 <= b for a, b in edge) and any(a <= -30 <= b for a, b in edge)
    assert not any(a <= 0 <= b for a, b in edge)          # aligned with the wind: stable
    assert data["minimum"]["total_damping_ratio"] < 0


def test_iea15mw_feathered_edgewise_instability_in_yaw(capsys):
    """The parked, feathered IEA-15MW (BeamDyn six-by-six sections, all 50 polars) at 50 m/s: OpenFAST users find
    it unstable for yaw misalignments of about +-(20 to 60) deg in DLC 6.2
    (github.com/IEAWindSystems/IEA-15-240-RWT/issues/218); the first edgewise mode's quasi-steady total damping is
    negative in both sectors."""
    code, out, _ = run(capsys, "standstill", BEAMDYN, "--aero", IEA_AERODYN, "--quasi-steady", "--damping-only",
                       "--wind-speed", 50, "--pitch-deg", 90, "--precone-deg", -4, "--tilt-deg", -6,
                       "--yaw-deg=-80:80:17", "--elements", 40, "--n-modes", 4,
                       "--structural-damping-percent", "0.48,0.48", "--json")
    data = json.loads(out)
    assert code == 0
    edge = sectors(data, "edge 1")
    for yaw in (-50, -30, 30, 50):
        assert any(a <= yaw <= b for a, b in edge), (yaw, edge)
    assert not any(a <= 0 <= b for a, b in edge)


def test_an_elastodyn_blade_brings_its_structural_damping(capsys):
    """Without --structural-damping-percent an ElastoDyn blade's BldFlDmp(1) and BldEdDmp(1) (0.477465 % in the
    5MW) are added; a BeamDyn blade has none to bring."""
    code, out, _ = run(capsys, "standstill", MAIN, "--aero", AERODYN, "--wind-speed", 50, "--yaw-deg", 30,
                       "--elements", 20, "--n-modes", 2, "--json")
    modes = json.loads(out)["points"][0]["modes"]
    assert code == 0 and all(m["structural_damping_ratio"] == pytest.approx(0.00477465, rel=1e-12) for m in modes)
    assert all(m["total_damping_ratio"] == m["aerodynamic_damping_ratio"] + m["structural_damping_ratio"]
               for m in modes)


def test_nrel5mw_parked_in_yaw_against_openfast(capsys, tmp_path):
    """OpenFAST v5.0.0 linearized the parked, feathered NREL 5MW at 50 m/s (blade DOFs only, no induction, legacy
    projection, no unsteady aerodynamics, no gravity: tests/data/openfast/standstill_linearization.json) at yaw -30,
    0, 30 and 60 deg. Blade 1's three modes against bladefem's: the frequencies within 2 % (the FE's exact shapes
    against ElastoDyn's polynomials, flap 2 the farthest: measured 1.8 %, the first modes 0.6 %), the total damping
    ratios within 7 % of OpenFAST's plus 0.1 percentage point (measured at most 5.5 % on the large ones, 0.05 point on
    the first edgewise mode) and of the same sign at every yaw (the negative sectors agree). bladefem reads the
    deck's AeroDyn file with OpenFAST's ``BEM_Mod`` 1: with the shipped ``BEM_Mod`` 2 the sections, coned by the
    precone, see their own inflow angle in AeroDyn's polar frame, and the second flap mode at 30 deg is -0.68 %
    against the legacy projection's -0.98 % (OpenFAST's -0.86 %: a like-for-like comparison needs the same
    projection)."""
    reference = json.loads((ROOT / "tests" / "data" / "openfast" / "standstill_linearization.json").read_text())
    yaws = ",".join(f"{point['yaw_deg']:g}" for point in reference["points"])
    folder = tmp_path / "nrel5mw"
    shutil.copytree(CASE, folder)
    legacy = folder / AERODYN.name
    text, count = re.subn(r"^(\s*)2(\s+BEM_Mod\s)", r"\g<1>1\g<2>", legacy.read_text(), flags=re.MULTILINE)
    assert count == 1
    legacy.write_text(text)
    code, out, _ = run(capsys, "standstill", MAIN, "--aero", legacy, "--wind-speed", 50, "--pitch-deg", 90,
                       "--tilt-deg", -5, f"--yaw-deg={yaws}", "--n-modes", 3, "--elements", 48, "--json")
    assert code == 0
    names = {"1st flapwise": "flap 1", "1st edgewise": "edge 1", "2nd flapwise": "flap 2"}
    negative = 0
    for theirs, ours in zip(reference["points"], json.loads(out)["points"]):
        for mode in theirs["modes"]:
            name = next(ours_name for key, ours_name in names.items() if key in mode["dof"])
            mine = next(m for m in ours["modes"] if m["name"] == name)
            assert mine["frequency_hz"] == pytest.approx(mode["natural_frequency_hz"], rel=0.02)
            assert abs(mine["total_damping_ratio"] - mode["damping_ratio"]) <= 0.07 * abs(mode["damping_ratio"]) + 1e-3
            assert np.sign(mine["total_damping_ratio"]) == np.sign(mode["damping_ratio"])
            negative += mode["damping_ratio"] < 0
    assert negative == 4                                   # edge 1 at -30 deg; flap 1, edge 1, flap 2 at 30 deg


@pytest.mark.parametrize("argv, field", [
    (["--wind-speed", "50"], "--aero"),
    (["--aero", AERODYN], "--wind-speed"),
    (["--aero", AERODYN, "--wind-speed", "0"], "--wind-speed"),
    (["--aero", AERODYN, "--wind-speed", "50", "--yaw-deg", "10,5"], "--yaw-deg"),
    (["--aero", AERODYN, "--wind-speed", "50", "--structural-damping-percent", "1"], "--structural-damping"),
    (["--aero", IEA_AERODYN, "--wind-speed", "50"], "--quasi-steady"),
], ids=["no-aero", "no-wind", "zero-wind", "decreasing-yaw", "one-damping", "unsteady-deck"])
def test_errors_are_one_line(capsys, argv, field):
    code, out, err = run(capsys, "standstill", MAIN, "--elements", "20", *argv)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert field in err


def test_a_tower_is_refused(capsys):
    tower = ROOT / "tests" / "data" / "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"
    code, out, err = run(capsys, "standstill", tower, "--aero", AERODYN, "--wind-speed", 50)
    assert code == 2 and out == "" and "tower" in err
