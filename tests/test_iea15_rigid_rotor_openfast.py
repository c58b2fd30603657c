"""The IEA-15MW's rigid rotor against OpenFAST v5.0.0: the aerodynamic loads of its prebent blades
(tests/data/openfast/iea15_rigid_rotor/rigid_rotor.json, written by write_decks.py there: every ElastoDyn DOF off,
fixed speed and pitch, steady sheared wind, quasi-steady BEM with the deck's legacy projection, BEM_Mod 1, and with
the polar projection, BEM_Mod 2), at 8 m/s (5.68 rpm, pitch 0) and 16 m/s (7.56 rpm, pitch 12.95 deg).

AeroDyn cants each blade node by the blade file's ``BlCrvAng`` (the prebent blade's local slope, up to -5.8 deg at
the IEA-15MW's tip, toward upwind): its reference orientation, which the structural deflection then turns. The
projection resolves the inflow along the canted normal, so the cant adds to the precone in the cosine losses of
the normal inflow. Without it bladefem's rotor at 8 m/s carried 1.0 % more thrust and 1.3 % more torque than
OpenFAST's (BEM_Mod 1; 0.9 % and 1.0 % with BEM_Mod 2).

Still open: with the legacy projection at 16 m/s and 12.95 deg pitch bladefem's rotor carries 0.93 % more thrust
and 1.0 % more torque than OpenFAST's (0.08 % with the polar projection at the same point; without the cant the
legacy gap was 2.5 %, the polar's 1.6 %). Turning the cant about the pitched chord axis, as AeroDyn composes the
node's reference orientation with the root's pitch, moves it by 0.05 % only. About half is the legacy projection's
twist: AeroDyn (``Calculate_MeshOrientation_NoSweepPitchTwist``) takes the section's twist as the Euler angle
extracted from the canted section pitched about the root's axis, R_z(-twist) R_y(cant) R_z(-pitch), which exceeds
twist + pitch by up to 0.064 deg at the tip (cant -5.8 deg, pitch 12.95 deg); the rigid rotor with that twist (and
the extracted cant, cant cos(pitch)) carries +0.49 % thrust and +0.54 % torque, not yet modelled; the rest is not
found.

The flexible turbine held at its speed at 8 m/s carries OpenFAST's loads (thrust, torque, root moment within
0.13 %) and its tip deflection (+0.25 %). The tip deflection was 1.09 % low while the nodes' arms were turned to
first order only (their motion along the blade axis): OpenFAST maps AeroDyn's loads onto ElastoDyn's nodes with the
moments of the arms as turned, so the thrust at a node upwind of the axis also works through the arm's motion
downwind, -o (1 - cos theta), second order in the slope (bladefem.models.turbine.kinematics.turned_arms)."""

from __future__ import annotations

import json
import os
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from bladefem.aero import rotor_performance
from bladefem.builders.openfast_fst import read_openfast_deck
from bladefem.cli import main

ROOT = Path(__file__).resolve().parents[1]
DECK = ROOT / "tests" / "data" / "iea15" / "IEA-15-240-RWT-Monopile" / "IEA-15-240-RWT-Monopile.fst"
REFERENCE = json.loads((ROOT / "tests" / "data" / "openfast" / "iea15_rigid_rotor" / "rigid_rotor.json").read_text())
#: the structure held rigid: only the yaw spring (the deck's, 6e9 N m/rad) moves, by under 1e-6 rad
RIGID = ["FlapDOF1=off", "FlapDOF2=off", "EdgeDOF=off", "TwFADOF1=off", "TwFADOF2=off", "TwSSDOF1=off",
         "TwSSDOF2=off"]
#: OpenFAST channel -> bladefem channel, unit factor (bladefem's RtAero* in N and N m, as OpenFAST's)
CHANNELS = {"RtAeroFxh": ("RtAeroFxh", 1.0), "RtAeroMxh": ("RtAeroMxh", 1.0), "RootMyc1": ("RootMOoP1", 1.0)}



#: (wind, BEM_Mod) -> (relative tolerance on thrust and torque, why)
TOLERANCE = {(8.0, 1): (1e-4, "the same BEM on the same canted sections: measured 1e-6"),
             (8.0, 2): (1e-3, "as the NREL 5MW's rotor with tilt and cone (tests/test_aero_openfast.py): 2.4e-4"),
             (16.0, 2): (1e-3, "as the NREL 5MW's rotor with tilt and cone: measured 7.8e-4")}
#: (wind, BEM_Mod) outside the acceptance today, with the measured difference: an open defect, not a tolerance
KNOWN = {(16.0, 1): "legacy projection at 12.95 deg pitch: thrust +0.93 %, torque +1.0 %; +0.49 %, +0.54 % with "
                    "AeroDyn's Euler-extracted twist of the canted pitched section (module docstring)"}
POINTS = [(c["wind_speed_m_s"], c["bem_mod"]) for c in REFERENCE["cases"]]


@pytest.fixture(scope="module")
def rotor():
    return read_openfast_deck(DECK, unmodelled="keep").rotor()


def performance(rotor, point: dict, **changes):
    options = replace(rotor.options, formulation=point["bem_mod"])
    return rotor_performance(replace(rotor, options=options, **changes), point["wind_speed_m_s"],
                             point["rotor_speed_rpm"], point["pitch_deg"], shear_exponent=0.12, azimuths=16)


def reference_point(wind: float, bem: int) -> dict:
    return next(c for c in REFERENCE["cases"] if (c["wind_speed_m_s"], c["bem_mod"]) == (wind, bem))


@pytest.mark.parametrize("wind, bem", POINTS, ids=[f"{w:g}m_s-bem{b}" for w, b in POINTS])
def test_prebent_rotor_thrust_and_torque_are_openfasts(rotor, wind, bem, request):
    """The rigid-rotor BEM (averaged over 16 azimuths of a third of a revolution, as the reference over a whole
    one) against OpenFAST's RtAeroFxh and RtAeroMxh (tolerances: :data:`TOLERANCE`); the pairs in :data:`KNOWN`
    fail today and are marked so (strict)."""
    if (wind, bem) in KNOWN:
        request.applymarker(pytest.mark.xfail(strict=True, reason=KNOWN[wind, bem]))
    point = reference_point(wind, bem)
    result = performance(rotor, point)
    tolerance = TOLERANCE.get((wind, bem), (1e-3, ""))[0]
    assert result.thrust == pytest.approx(point["means"]["RtAeroFxh"], rel=tolerance)
    assert result.torque == pytest.approx(point["means"]["RtAeroMxh"], rel=tolerance)


@pytest.mark.parametrize("bem", [1, 2])
def test_the_sections_cant_is_what_the_reference_sees(rotor, bem):
    """Without ``BlCrvAng`` the rotor at 8 m/s carries 0.9-1.3 % more thrust and torque than OpenFAST's: the
    comparison above can tell the cant."""
    point = reference_point(8.0, bem)
    flat = performance(rotor, point, curve_angle=None)
    assert flat.thrust / point["means"]["RtAeroFxh"] - 1 > 0.008
    assert flat.torque / point["means"]["RtAeroMxh"] - 1 > 0.008


def run(tmp_path: Path, point: dict, extra: tuple[str, ...] = ()) -> dict[str, float]:
    """bladefem's means over the first whole revolution (every 0.005 s, as the reference's)."""
    out = tmp_path / "rigid.csv"
    rpm = point["rotor_speed_rpm"]
    assert main(["turbine", str(DECK), "--simulate", f"{60.0 / rpm + 0.05:g}", "--foundation", "rigid",
                 "--quasi-steady", "--wind-speed", f"{point['wind_speed_m_s']:g}", "--rpm", f"{rpm:g}",
                 "--pitch-deg", f"{point['pitch_deg']:g}", "--method", "RK4", "--step", "0.005", "--dt", "0.005",
                 "--elastodyn-compatible", "--quiet", "--dof", *RIGID, *extra, "-o", str(out)]) == 0
    lines = out.read_text().splitlines()
    names = [name.rsplit("_", 1)[0] for name in lines[0].split(",")]
    data = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    revolution = data[:, 0] < 60.0 / rpm - 1e-9
    return {name: float(data[revolution, i].mean()) for i, name in enumerate(names)}


@pytest.mark.slow
@pytest.mark.skipif(bool(os.environ.get("BLADEFEM_NO_NUMBA")), reason="the fixed-step run needs numba")
@pytest.mark.parametrize("wind", [8.0])
def test_prebent_rigid_rotor_loads_in_the_turbine_are_openfasts(tmp_path, wind):
    """Thrust, torque and the blade-root out-of-plane moment over a revolution within 1e-4 of OpenFAST's at the
    operating point below rated (8 m/s, 5.68 rpm, pitch 0; measured 1e-6, 3e-6, 7e-6: the same BEM on the same
    canted sections), where the cant left out costs 1 %."""
    point = reference_point(wind, 1)
    ours = run(tmp_path, point)
    for theirs, (name, factor) in CHANNELS.items():
        assert ours[name] * factor == pytest.approx(point["means"][theirs], rel=1e-4), theirs


#: channel -> (bladefem channel, relative tolerance) of the flexible turbine held at its speed
FLEXIBLE = {"RtAeroFxh": ("RtAeroFxh", 2e-3), "RtAeroMxh": ("RtAeroMxh", 2e-3), "RootMyc1": ("RootMOoP1", 2e-3),
            "TTDspFA": ("TTDspFA", 5e-3), "OoPDefl1": ("OoPDefl1", 5e-3)}


@pytest.fixture(scope="module")
def flexible_run(tmp_path_factory):
    point = REFERENCE["flexible"]
    out = tmp_path_factory.mktemp("iea15_flexible") / "flexible.csv"
    assert main(["turbine", str(DECK), "--simulate", f"{point['run_s']:g}", "--foundation", "rigid",
                 "--quasi-steady", "--wind-speed", f"{point['wind_speed_m_s']:g}",
                 "--rpm", f"{point['rotor_speed_rpm']:g}", "--pitch-deg", f"{point['pitch_deg']:g}", "--method",
                 "RK4", "--step", "0.005", "--elastodyn-compatible", "--quiet", "-o", str(out)]) == 0
    lines = out.read_text().splitlines()
    names = [name.rsplit("_", 1)[0] for name in lines[0].split(",")]
    data = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    window = data[:, 0] >= point["window_s"][0] - 1e-9
    return {name: float(data[window, i].mean()) for i, name in enumerate(names)}


@pytest.mark.slow
@pytest.mark.skipif(bool(os.environ.get("BLADEFEM_NO_NUMBA")), reason="the fixed-step run needs numba")
@pytest.mark.parametrize("channel", list(FLEXIBLE))
def test_flexible_prebent_turbine_at_fixed_speed_against_openfast(flexible_run, channel):
    """The flexible turbine (ElastoDyn's structure) held at 5.68 rpm in 8 m/s, means over the last three of 60 s:
    aerodynamic thrust, torque and the blade-root out-of-plane moment within 0.2 % (measured +0.11 %, +0.12 %,
    +0.09 %), the tower-top fore-aft displacement and the tip deflection within 0.5 % (measured -0.45 %, +0.25 %).
    The nodes' rigid arms turn with the bent sections: carried without turning (the prebend's 4 m arm held along
    the undeflected normal) the root moment was 0.47 % low and the tower top 1.4 %; without the sections' cant
    as well, 1.3 % and 4.3 %; turned to first order only (along the axis), the tip deflection was 1.09 % low."""
    name, tolerance = FLEXIBLE[channel]
    theirs = REFERENCE["flexible"]["means"][channel]
    assert flexible_run[name] == pytest.approx(theirs, rel=tolerance)
