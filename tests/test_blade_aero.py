"""Quasi-steady aerodynamic damping and stiffness of the blade sections, induction frozen at the operating point.

- The rigid blade flapping about a root hinge on the rotor axis (constant chord and lift slope, no drag, no loss,
  no inflow, so no induction to freeze) against the closed form of the flap equation
  b'' + (gamma / 8) b' + nu^2 b = 0 in azimuth time: damping ratio gamma / (16 nu), gamma the Lock number.
- The section matrices against central differences of the section loads of the BEM code (bladefem.aero.bem), with
  the section's motion turned into relative air velocity by explicit vector kinematics at the aerodynamic centre
  (NREL 5MW planform: offset aerodynamic centres, precone, pitching moments).
- The command line on the NREL 5MW deck, and its one-line errors.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from bladefem.aero import BEMOptions, Polar, Rotor
from bladefem.aero.section import section_loads
from bladefem.aero.polars import pack_polars
from bladefem.assembly import assemble_blade
from bladefem.cli import main
from bladefem.elements import skew
from bladefem.builders.aerodyn_rotor import aerodyn_rotor
from bladefem.builders.elastodyn_blade import blade_from_elastodyn_main
from bladefem.modal.quadratic import solve_quadratic_modes
from bladefem.models.blade_aero import aero_matrices, operating_point, section_matrices
from bladefem.sections import Blade, uniform_sections

CASE = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw"
MAIN = CASE / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
AERODYN = CASE / "NRELOffshrBsline5MW_Onshore_AeroDyn.dat"


def test_rigid_hinged_blade_flap_damping_is_gamma_over_16_nu():
    L, m, chord, lift_slope, rho = 10.0, 20.0, 0.14, 2 * np.pi, 1.225
    inertia = m * L**3 / 3
    lock = rho * lift_slope * chord * L**4 / inertia                  # gamma = 1.6
    omega = 2.0                                                       # rad/s; nu = 1 (hinge on the axis)
    alpha = np.linspace(-np.pi, np.pi, 5)
    polar = Polar(alpha=alpha, cl=lift_slope * alpha, cd=np.zeros(5), cm=np.zeros(5))
    # nodes from 1 mm (the BEM's solidity is singular on the axis; the missing 1 mm carries 1e-16 of the damping)
    rotor = Rotor(n_blades=3, hub_radius=0.0, span=np.linspace(1e-3, L, 21), chord=np.full(21, chord),
                  twist=np.zeros(21), airfoil=np.zeros(21, dtype=int), polars=(polar,), air_density=rho,
                  options=BEMOptions(tip_loss=False, hub_loss=False, pitching_moment=False))
    # EI keeps the elastic modes far above 1P, so the rigid flap shape holds (the aerodynamic load, ~ x^2, is not
    # proportional to the inertia load, ~ x)
    blade = Blade(uniform_sections(L, m, 1e7, edge_stiffness=3e7), root="hinged")
    matrices = assemble_blade(blade, 10)
    damping, stiffness = aero_matrices(matrices, operating_point(rotor, 0.0, omega, 0.0))
    result = solve_quadratic_modes(matrices, omega * 30 / np.pi, 4, damping=damping, stiffness=stiffness)
    flap = result.first("flap")
    nu = 1.0
    # exact but for the elastic deflection under the x^2 load (the damping per length, ~ x, is linear between the
    # AeroDyn nodes as interpolated): measured 4.5e-7, ten times less at ten times the EI; far below the 1 % asked
    assert flap.damping_ratio == pytest.approx(lock / (16 * nu), rel=1e-5)
    assert flap.frequency_hz == pytest.approx(nu * omega / (2 * np.pi), rel=1e-5)
    assert np.abs(stiffness.toarray()).max() == 0.0                  # no twist, no precone: no stiffness


@pytest.fixture(scope="module")
def nrel5mw():
    blade = blade_from_elastodyn_main(MAIN)
    rotor = aerodyn_rotor(AERODYN, blade)
    return blade, rotor, operating_point(rotor, 11.4, 12.1 * np.pi / 30, 0.0)


def generalized_loads(op, node: int, rotor: Rotor, d: np.ndarray, rate: np.ndarray) -> np.ndarray:
    """Generalized forces on the kinematic vector of one section for the motion (d, rate): the aerodynamic centre
    at s moves by t + Theta x s; the air's velocity relative to it is the operating point's minus the centre's own
    velocity and minus the rotation of its displacement; the BEM code's section loads at that velocity (induced
    velocities held) act at the centre, the pitching moment about the span axis."""
    s = op.centre[:, node]
    N = np.hstack([np.eye(3), -skew(s)])
    relative = np.array([0.0, -op.Y[node], op.X[node]]) - N @ rate - op.rotor_speed * np.cross(op.shaft_axis, N @ d)
    table = pack_polars(rotor.polars)
    loads = section_loads(relative[2], -relative[1], 0.0, 0.0, op.chord[node], op.theta[node] - d[3],
                          int(rotor.airfoil[node]), *table.arrays, rotor.options.vector(), op.air_density, 0.0, 0.0)
    fn, ft, m = loads[6], loads[7], loads[8]
    return N.T @ np.array([0.0, ft, fn]) + np.array([0.0, 0.0, 0.0, m, 0.0, 0.0])


@pytest.mark.parametrize("wind_speed, pitch_deg", [(11.4, 0.0), (18.0, 14.9)])
def test_section_matrices_equal_differences_of_the_section_loads(nrel5mw, wind_speed, pitch_deg):
    _, rotor, _ = nrel5mw
    op = operating_point(rotor, wind_speed, 12.1 * np.pi / 30, math.radians(pitch_deg))
    D, K = section_matrices(op)
    for node in range(1, len(op.span) - 1):
        step = 1e-6 * np.hypot(op.X[node], op.Y[node])
        numeric_D, numeric_K = np.zeros((6, 6)), np.zeros((6, 6))
        for j in range(6):
            e = np.zeros(6)
            e[j] = step
            numeric_D[:, j] = -(generalized_loads(op, node, rotor, 0 * e, e)
                                - generalized_loads(op, node, rotor, 0 * e, -e)) / (2 * step)
            numeric_K[:, j] = -(generalized_loads(op, node, rotor, e, 0 * e)
                                - generalized_loads(op, node, rotor, -e, 0 * e)) / (2 * step)
        scale = np.abs(numeric_D).max()
        # central differences with a relative step of 1e-6 (within one interval of the linear polars): truncation
        # and rounding, measured 1.3e-10 (D) and 7.6e-10 (K)
        np.testing.assert_allclose(D[:, :, node], numeric_D, atol=1e-7 * scale)
        np.testing.assert_allclose(K[:, :, node], numeric_K, atol=1e-7 * scale * op.rotor_speed)
    assert np.abs(K[:, 3]).max() > 0 and np.abs(D[3]).max() > 0       # pitching moments and offsets exercised


def test_nrel5mw_first_flap_and_edge_are_damped(nrel5mw):
    blade, _, op = nrel5mw
    from bladefem.modal import blade_matrices
    matrices = blade_matrices(blade, 48, 6, 12.1)
    damping, stiffness = aero_matrices(matrices, op)
    result = solve_quadratic_modes(matrices, 12.1, 6, damping=damping, stiffness=stiffness)
    assert result.first("flap").damping_ratio > 0.3 and 0.005 < result.first("edge").damping_ratio < 0.05
    assert max(mode.residual for mode in result.modes) < 1e-6


def test_aerodynamics_act_on_the_whole_deflection_of_a_shear_flexible_blade(nrel5mw):
    """The 5MW blade as six-by-six sections (GJ, EA and rotary inertias added, shear stiffness k GA = s EA): the
    aerodynamic matrices act on the section's motion, the shear deflection included. With the shear 1e4 times EA
    the shear-flexible blade's aero-damped flap and edge modes are the condensed blade's (frequency and damping
    ratio within 1e-6, measured 2e-9); with k GA = 1e-4 EA (0.1 EI per m^2) shear deformation lowers the first
    flap frequency (measured 1.9 %) and the damping still acts on it (flap damping ratio within 10 % of the
    condensed blade's, measured +2.0 %)."""
    from dataclasses import replace

    from bladefem.modal import blade_matrices
    from bladefem.sections import full_sections_from_table

    blade, rotor, op = nrel5mw
    table = replace(blade.sections, torsion_stiffness=blade.sections.flap_stiffness,
                    axial_stiffness=1e3 * blade.sections.flap_stiffness, flap_inertia=0.01 * blade.sections.mass,
                    edge_inertia=0.1 * blade.sections.mass)

    def flap_edge(shear: float, flexible: bool):
        full = full_sections_from_table(table, shear * table.axial_stiffness).with_shear(flexible)
        matrices = blade_matrices(blade.with_(sections=full.table()), 48, 6, 12.1)
        damping, stiffness = aero_matrices(matrices, op)
        result = solve_quadratic_modes(matrices, 12.1, 6, damping=damping, stiffness=stiffness)
        return [(result.first(kind).frequency_hz, result.first(kind).damping_ratio) for kind in ("flap", "edge")]

    condensed = np.array(flap_edge(1.0, False))
    np.testing.assert_allclose(np.array(flap_edge(1e4, True)), condensed, rtol=1e-6)
    soft = np.array(flap_edge(1e-4, True))
    assert soft[0, 0] < condensed[0, 0] * (1 - 1e-2)
    assert soft[0, 1] == pytest.approx(condensed[0, 1], rel=0.1)


def run(capsys, *argv: object) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_modes_with_aerodynamics_on_the_command_line(capsys):
    code, out, _ = run(capsys, "modes", MAIN, "--rpm", "12.1", "--aero", AERODYN, "--wind-speed", "11.4",
                       "--coriolis", "--n-modes", "3", "--elements", "48", "--json")
    data = json.loads(out)
    assert code == 0
    flap, edge = data["modes"][0], data["modes"][1]
    assert flap["kind"] == "flap" and flap["damping_ratio"] > 0.3
    assert edge["kind"] == "edge" and edge["damping_ratio"] > 0.005
    assert any("aerodynamic damping" in note for note in data["notes"])


@pytest.mark.parametrize("argv, field", [
    (["--aero", AERODYN], "--wind-speed"),
    (["--wind-speed", "11"], "--aero"),
    (["--aero", CASE / "missing.dat", "--wind-speed", "11"], None),
    (["--aero", AERODYN, "--wind-speed", "11", "--method", "galerkin"], "--aero"),
    (["--quasi-steady"], "--quasi-steady"),
], ids=["no-wind", "no-aerodyn", "missing-file", "galerkin", "quasi-steady-alone"])
def test_aero_option_errors_are_one_line(capsys, argv, field):
    code, out, err = run(capsys, "modes", MAIN, "--rpm", "12", "--elements", "48", *argv)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    if field:
        assert field in err


def test_an_unsteady_deck_runs_quasi_steady_when_asked(capsys):
    """The IEA-22MW deck asks for unsteady airfoil aerodynamics (UA_Mod 4): ``modes --aero`` refuses it on one line
    naming file, line and field and the option that runs without it, and runs it with ``--quasi-steady`` (these
    modes are quasi-steady by construction), saying what it left out."""
    root = Path(__file__).resolve().parents[1] / "tests" / "data" / "iea22"
    blade, aerodyn = root / "beamdyn" / "IEA-22-280-RWT_BeamDyn.dat", root / "IEA-22-280-RWT-Monopile" / \
        "IEA-22-280-RWT_AeroDyn15.dat"
    argv = ("modes", blade, "--hub-radius", "3.97", "--rpm", "7", "--aero", aerodyn, "--wind-speed", "10",
            "--n-modes", "3", "--elements", "30", "--json")
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert f"{aerodyn}:7" in err and "UA_Mod" in err and "--quasi-steady" in err
    code, out, _ = run(capsys, *argv, "--quasi-steady")
    data = json.loads(out)
    assert code == 0 and [mode["kind"] for mode in data["modes"]][:2] == ["flap", "edge"]
    assert any(note.startswith("left out (--quasi-steady)") and "UA_Mod" in note for note in data["notes"])


def test_pitch_enters_the_operating_point(nrel5mw):
    _, rotor, op = nrel5mw
    pitched = operating_point(rotor, 11.4, 12.1 * np.pi / 30, math.radians(5.0))
    np.testing.assert_allclose(pitched.theta - op.theta, math.radians(5.0))
    assert np.all(pitched.alpha[2:-2] < op.alpha[2:-2])               # feathering lowers the angle of attack


def test_first_flap_damping_near_openfast_collective_flap():
    """OpenFAST v4.2.1's linearization of the whole 5MW (frozen wake, tests/data/openfast/aero_linearization.json)
    at the five Table 7-1 points: its 1st collective flap is the turbine mode nearest a single blade's first flap.
    The blade alone differs by the static deflection OpenFAST linearizes about (5.6 m at rated), the coupling to
    tower and drivetrain, the 0.48 % structural damping of the deck and the shaft tilt: within 10 % (measured
    -2.2 % to +5.1 %); frequencies within 7 % (measured up to 6.5 % at 25 m/s)."""
    from bladefem.modal import blade_matrices
    data = json.loads((Path(__file__).parent / "data" / "openfast" / "aero_linearization.json").read_text())
    for point in data["variants"]["frozen_wake"]["points"]:
        reference = next(m for m in point["modes"] if m["name"] == "1st collective flap")
        blade = blade_from_elastodyn_main(MAIN).with_(pitch=math.radians(point["pitch_deg"]))
        rpm = point["rotor_speed_rpm"]
        matrices = blade_matrices(blade, 48, 6, rpm)
        op = operating_point(aerodyn_rotor(AERODYN, blade), point["wind_speed_m_s"], rpm * np.pi / 30, blade.pitch)
        damping, stiffness = aero_matrices(matrices, op)
        flap = solve_quadratic_modes(matrices, rpm, 4, damping=damping, stiffness=stiffness).first("flap")
        assert flap.damping_ratio == pytest.approx(reference["damping_ratio"], rel=0.10), point["wind_speed_m_s"]
        assert flap.frequency_hz == pytest.approx(reference["natural_frequency_hz"], rel=0.07)


@pytest.mark.parametrize("pitch_deg", [0.0, 30.0, 90.0])
def test_the_aerodynamic_centres_arm_is_measured_from_the_reference_axis(pitch_deg):
    """The structure's degrees of freedom are the motion of its reference axis, so the lift's arm is the
    aerodynamic centre's offset from that axis: AeroDyn's offsets (0, -BlSwpAC, BlCrvAC), turned with the blade
    by the pitch, less the curved axis's own offset. A planform whose aerodynamic centres lie on the blade's
    prebent, swept axis has no arm at any pitch (1e-12 m); on a straight blade the arm is AeroDyn's offset,
    pitched: (0, curve sin p - sweep cos p, curve cos p + sweep sin p). Before, the arm was the whole offset,
    unpitched: 4.0 m at the IEA-15MW's tip, where its AeroDyn centres sit within 0.065 m of the BeamDyn axis."""
    from dataclasses import replace

    from bladefem.models.blade_aero import aerodynamic_centres
    from bladefem.sections import ReferenceAxis
    span = np.linspace(0.0, 60.0, 13)
    prebend, sweep = -3.0 * (span / 60.0) ** 2, 0.8 * (span / 60.0) ** 3
    blade = Blade(uniform_sections(60.0, 300.0, 2e9), axis=ReferenceAxis(span, sweep, prebend))
    polar = Polar(alpha=np.radians([-180.0, 180.0]), cl=np.zeros(2), cd=np.zeros(2), cm=np.zeros(2))
    along = blade.axis.along_pitch_axis(span)                # AeroDyn's BlSpn of the axis points
    rotor = Rotor(n_blades=3, hub_radius=2.0, span=along, chord=np.full(13, 2.0), twist=np.zeros(13),
                  airfoil=np.zeros(13, dtype=int), polars=(polar,), curve=prebend, sweep=-sweep)
    pitch = math.radians(pitch_deg)
    on_axis = aerodynamic_centres(rotor, pitch, blade)
    assert np.abs(on_axis).max() < 1e-12
    straight = aerodynamic_centres(replace(rotor, curve=prebend, sweep=-sweep), pitch)
    c, s = math.cos(pitch), math.sin(pitch)
    np.testing.assert_allclose(straight, np.stack([np.zeros(13), s * prebend + c * sweep, c * prebend - s * sweep]),
                               rtol=0, atol=1e-15)


@pytest.mark.parametrize("formulation", [1, 2])
def test_a_blade_on_a_tilted_axis_is_the_coned_blade(formulation):
    """A straight blade whose reference axis leaves the pitch axis at a constant 5 deg downwind (a curved-axis input
    without curvature; AeroDyn's nodes on that axis: BlSpn s cos 5 deg, BlCrvAC s sin 5 deg, BlCrvAng 5 deg) is the
    same blade as the straight one with 5 deg more precone: its aeroelastic modes at 12 rpm in 10 m/s (quasi-steady
    damping and stiffness, Coriolis) agree, both projections: frequencies to 1e-6 (measured 1.8e-7; the structure
    alone agrees to 2e-7), damping ratios to 1e-5 (measured 1.4e-6). The sections' loads and motion are taken in the
    curved axis's local frame, the nodes at the arc length of their BlSpn (:func:`on_the_axis`); with the shaft
    axis in the blade frame and BlSpn taken as arc length, the damping ratios differed by 1.9e-3 and the
    frequencies by 8.5e-4."""
    from bladefem.modal import blade_matrices
    from bladefem.sections import ReferenceAxis
    length, tilt, cone = 60.0, math.radians(5.0), math.radians(-2.5)
    sections = uniform_sections(length, 300.0, 2e9, edge_stiffness=5e9, torsion_stiffness=5e8,
                                axial_stiffness=5e10, flap_inertia=2.0, edge_inertia=20.0)
    stations = np.linspace(0.0, length, 7)
    coned = Blade(sections, precone=cone + tilt)
    tilted = Blade(sections, precone=cone, axis=ReferenceAxis(stations, np.zeros(7), stations * math.sin(tilt)))
    knots = np.radians([-180.0, -15.0, 15.0, 180.0])
    polar = Polar(alpha=knots, cl=np.array([0.0, -2 * np.pi * knots[2], 2 * np.pi * knots[2], 0.0]),
                  cd=np.full(4, 0.01), cm=np.array([0.0, 0.02, -0.05, 0.0]))
    s = np.linspace(2.0, length, 30)
    common = dict(n_blades=3, hub_radius=0.0, chord=3.0 - s / 40, twist=np.radians(np.linspace(12.0, 0.0, 30)),
                  airfoil=np.zeros(30, dtype=int), polars=(polar,), hub_height=90.0,
                  options=BEMOptions(formulation=formulation))
    rotors = (Rotor(span=s, precone=cone + tilt, **common),
              Rotor(span=s * math.cos(tilt), curve=s * math.sin(tilt), curve_angle=np.full(30, tilt), precone=cone,
                    **common))
    modes = []
    for blade, rotor in zip((coned, tilted), rotors):
        matrices = blade_matrices(blade, 40, 6, 12.0)
        damping, stiffness = aero_matrices(matrices, operating_point(rotor, 10.0, 12.0 * np.pi / 30, 0.0, blade))
        result = solve_quadratic_modes(matrices, 12.0, 6, (), damping, stiffness, True)
        modes.append(np.array([[mode.frequency_hz, mode.damping_ratio] for mode in result.modes]))
    np.testing.assert_allclose(modes[1][:, 0], modes[0][:, 0], rtol=1e-6)
    np.testing.assert_allclose(modes[1][:, 1], modes[0][:, 1], rtol=0, atol=1e-5)
