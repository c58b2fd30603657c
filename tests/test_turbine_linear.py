"""Linearization, multi-blade coordinates, mode names and the full-system modes of the Kane turbine model.

- An isotropic 3-blade rotor on a fixed hub seen in multi-blade coordinates: the collective mode keeps the
  blade's own frequency w, the asymmetric pair splits into whirls at exactly w - Omega and w + Omega (the Coleman
  transform's frequency shift), named backward and forward from the phase of their cosine and sine coordinates.
- Parked (0 rpm) the turbine is linearized at one azimuth: the same eigenvalues as in blade coordinates, and
  different ones at another azimuth (gravity on the blades depends on it).
- Modes are named by the participation that dominates (the cases of issue 10).
- Each choice bladefem makes differently from ElastoDyn, measured on the parked NREL 5MW (documented in
  docs/turbine.md, "bladefem vs OpenFAST/FAST, each choice").
- Damping ratios: ElastoDyn's convention and the rotor-nacelle-inclusive one against their closed forms.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.turbine_elastodyn import turbine_from_elastodyn
from bladefem.models.turbine import TurbineModel, select_dofs
from bladefem.models.turbine.linearize import linearize

MAIN = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"


@pytest.fixture(scope="module")
def elastodyn():
    return turbine_from_elastodyn(MAIN, "polynomial", elastodyn_compatible=True)


def frequency(result, name: str) -> float:
    return next(mode.frequency_hz for mode in result.modes if mode.name == name)


def parked(params, locked=("generator_azimuth",), azimuth: float = 0.0):
    model = TurbineModel(params)
    free = np.ones(model.n, dtype=bool)
    for dof in locked:
        free[model.dofs.index(dof)] = False
    return linearize(model, free, 0.0, azimuth)


def test_multiblade_whirl_splits_by_the_rotor_speed(elastodyn):
    rotor = elastodyn.with_(gravity=0.0, precone=0.0).without_damping()
    model = TurbineModel(rotor)
    rpm = 12.1
    omega_hz = rpm / 60.0
    single = linearize(model, select_dofs(model.dofs, ["blade1_flap1"]), rpm)
    w = single.modes[0].frequency_hz
    rotor_modes = linearize(model, select_dofs(model.dofs, ["flap1"]), rpm)
    # exact in theory; the finite-difference Jacobian and the azimuth average leave ~1e-8
    assert frequency(rotor_modes, "1st blade collective flap") == pytest.approx(w, rel=1e-6)
    assert frequency(rotor_modes, "1st blade asymmetric flap (backward whirl)") == pytest.approx(w - omega_hz,
                                                                                                 rel=1e-6)
    assert frequency(rotor_modes, "1st blade asymmetric flap (forward whirl)") == pytest.approx(w + omega_hz,
                                                                                                rel=1e-6)
    assert rotor_modes.azimuth_deg is None                   # averaged over the azimuth


def test_parked_linearization_is_at_one_azimuth(elastodyn):
    model = TurbineModel(elastodyn)
    free = np.ones(model.n, dtype=bool)
    free[model.dofs.index("generator_azimuth")] = False
    named = linearize(model, free, 0.0, azimuth=0.0)
    plain = linearize(model, free, 0.0, azimuth=0.0, mbc=False)
    # multi-blade coordinates at rest are a constant change of basis: the same eigenvalues
    np.testing.assert_allclose([m.frequency_hz for m in named.modes], [m.frequency_hz for m in plain.modes],
                               rtol=1e-9)
    assert named.azimuth_deg == 0.0 and {m.name for m in plain.modes} >= {"1st flap of blade 1"}
    # blade 1 no longer vertical: gravity loads the blades differently, the asymmetric pair moves
    turned = linearize(model, free, 0.0, azimuth=np.radians(60.0))
    a = sorted(m.frequency_hz for m in named.modes if "asymmetric flap" in m.name)
    b = sorted(m.frequency_hz for m in turned.modes if "asymmetric flap" in m.name)
    assert not np.allclose(a, b, rtol=1e-5)
    assert turned.azimuth_deg == pytest.approx(60.0)


def test_names_follow_the_dominant_participation(elastodyn):
    """Issue 10, defect 5: with the generator locked the 0.62 Hz mode is the drivetrain torsion and the 3.7 Hz one
    the collective edge (the names of Jonkman et al. 2009 and of the OpenFAST reference); with the yaw
    spring off no whirl names at rest, the free yaw is a rigid-body motion (plus the damper's decay) and the
    asymmetric edge mode coupled to it keeps its blade name; participations are energy shares summing to 1."""
    locked = parked(elastodyn)
    assert frequency(locked, "1st drivetrain torsion") == pytest.approx(0.62, abs=0.005)
    # the blades' collective edge against the hub shares its energy with the drivetrain twist (0.43 / 0.54) but
    # the twist names one mode only, the 0.62 Hz one it dominates more (0.58); the name says that the twist holds
    # the larger share of this one too (issue 23, item 6: it was named "1st blade collective edge" alone)
    edge = next(m for m in locked.modes if m.name == "1st blade collective edge / drivetrain")
    assert edge.frequency_hz > 3.0 and edge.participation["drivetrain"] > 0.5
    assert sum("drivetrain torsion" in m.name for m in locked.modes) == 1
    names = {m.name for m in locked.modes}
    assert {"1st blade asymmetric flap (yaw)", "1st blade asymmetric flap (pitch)",
            "1st blade asymmetric edge (yaw)", "1st blade asymmetric edge (pitch)", "nacelle yaw"} <= names
    for mode in locked.modes:
        assert 0.98 < sum(mode.participation.values()) <= 1 + 1e-9          # shares < 0.1 % are left out
    # the edge mode with a lateral hub force (cosine) couples to the tower side-side; the flap mode tilting the
    # rotor (cosine) to the tower fore-aft
    edge_yaw = next(m for m in locked.modes if m.name == "1st blade asymmetric edge (yaw)")
    assert edge_yaw.participation["cosine_edge1"] > 0.9 and edge_yaw.participation["tower_ss1"] > 0.005
    free_yaw = parked(elastodyn.with_(yaw_stiffness=0.0))
    assert free_yaw.rigid == ["rigid nacelle yaw"]
    assert not any("whirl" in m.name for m in free_yaw.modes)
    # the yaw damper alone: a decaying, non-oscillating yaw motion (a real eigenvalue, damping ratio 1)
    decay = [m for m in free_yaw.modes if m.name == "nacelle yaw (decaying)"]
    assert [m.damping_ratio for m in decay] == [pytest.approx(1.0)] and not decay[0].oscillating
    assert sum("asymmetric edge" in m.name for m in free_yaw.modes) == 2
    spinning = linearize(TurbineModel(elastodyn), np.ones(16, dtype=bool), 12.1)
    assert spinning.rigid == ["rigid rotor rotation"]
    assert sum("whirl" in m.name for m in spinning.modes) == 6


#: Jonkman et al. (2009), Table 9-1: FAST (v7) full-system frequencies of the parked NREL 5MW, Hz
TABLE_9_1 = {"1st tower fore-aft": 0.3240, "1st tower side-side": 0.3120, "1st drivetrain torsion": 0.6205,
             "1st blade asymmetric flap (yaw)": 0.6664, "1st blade asymmetric flap (pitch)": 0.6675,
             "1st blade collective flap": 0.6993, "1st blade asymmetric edge (pitch)": 1.0793,
             "1st blade asymmetric edge (yaw)": 1.0898, "2nd blade asymmetric flap (yaw)": 1.9337,
             "2nd blade asymmetric flap (pitch)": 1.9223, "2nd blade collective flap": 2.0205,
             "2nd tower fore-aft": 2.9003, "2nd tower side-side": 2.9361}


OPENFAST = Path(__file__).resolve().parent / "data" / "openfast" / "turbine_linearizations_elastodyn.json"


@pytest.mark.parametrize("case", range(4))
def test_elastodyn_compatible_nrel5mw_against_openfast(elastodyn, case):
    """The NREL 5MW with ElastoDyn's choices against OpenFAST v4.2.1 linearized on the same deck (generator locked,
    yaw spring, gravity): parked at azimuth 0 and 60 deg, and the instantaneous state matrix at 12.1 rpm (blade
    coordinates at azimuth 0 and 30 deg: centrifugal, Coriolis and gyroscopic terms). Target 0.3 % per mode;
    measured within 0.051 % (the largest: 1st tower side-side, +0.04 to +0.05 %), damping ratios within 5.3e-5
    absolute. The eigenvalues are compared in frequency order."""
    reference = json.loads(OPENFAST.read_text())["cases"][case]
    model = TurbineModel(elastodyn)
    free = np.ones(model.n, dtype=bool)
    free[model.dofs.index("generator_azimuth")] = False
    linear = linearize(model, free, reference["rpm"], np.radians(reference["azimuth_deg"]), mbc=False)
    values = np.linalg.eigvals(linear.A)
    values = values[values.imag > 1e-9]
    values = values[np.argsort(np.abs(values))]
    expected = reference["modes"]
    assert len(values) == len(expected) == 15
    np.testing.assert_allclose(np.abs(values) / (2 * np.pi), [m["frequency_hz"] for m in expected], rtol=1e-3)
    np.testing.assert_allclose(-values.real / np.abs(values), [m["damping_ratio"] for m in expected], atol=1e-4)


#: the OpenFAST reference's mode names (Table 9-1's wording; BW / FW whirls) -> bladefem's
OPENFAST_NAMES = {"side-to-side": "side-side", "asymmetric flapwise yaw": "blade asymmetric flap (yaw)",
                  "asymmetric flapwise pitch": "blade asymmetric flap (pitch)",
                  "asymmetric edgewise yaw": "blade asymmetric edge (yaw)",
                  "asymmetric edgewise pitch": "blade asymmetric edge (pitch)", "collective flap": "blade collective flap",
                  "collective edge": "blade collective edge", "flap backward whirl (BW)":
                  "blade asymmetric flap (backward whirl)", "flap forward whirl (FW)":
                  "blade asymmetric flap (forward whirl)", "edge backward whirl (BW)":
                  "blade asymmetric edge (backward whirl)", "edge forward whirl (FW)":
                  "blade asymmetric edge (forward whirl)"}


def openfast_name(name: str) -> str:
    for theirs, ours in OPENFAST_NAMES.items():
        name = name.replace(theirs, ours)
    return name


@pytest.mark.parametrize("case, rpm", [(0, 0.0), (4, 12.1)])
def test_modes_and_names_match_openfast(elastodyn, case, rpm):
    """Named modes against the OpenFAST reference's, which names them independently (MBC3 participation assigned
    one-to-one to the coordinates): parked at azimuth 0, and at 12.1 rpm the multi-blade state matrix averaged
    over the azimuth (OpenFAST: 36 azimuths at its periodic steady state, static deflections included; bladefem: 8
    azimuths, undeflected): every mode under the same name, within 0.06 % (measured 0.05 %, the nacelle yaw at
    12.1 rpm), damping ratios within 1e-4 (measured 2e-5)."""
    reference = json.loads(OPENFAST.read_text())["cases"][case]
    model = TurbineModel(elastodyn)
    free = np.ones(model.n, dtype=bool)
    free[model.dofs.index("generator_azimuth")] = False
    # OpenFAST names a mode by its blade family alone ("1st blade collective edge" for bladefem's "... / drivetrain")
    ours = {m.name.split(" / ")[0]: m for m in linearize(model, free, rpm).modes}
    for mode in reference["modes"]:
        match = ours[openfast_name(mode["name"])]
        assert match.frequency_hz == pytest.approx(mode["frequency_hz"], rel=6e-4), mode["name"]
        assert match.damping_ratio == pytest.approx(mode["damping_ratio"], abs=1e-4), mode["name"]


def test_elastodyn_compatible_nrel5mw_against_fast_table_9_1(elastodyn):
    """The parked NREL 5MW (gravity, yaw spring, generator locked) with ElastoDyn's choices against FAST v7's
    Table 9-1, mode by mode under the same names. Table 9-1 comes from FAST v7, itself up to 0.7 % from current
    OpenFAST on the second flap and tower modes: measured here within 0.66 % (the largest: 2nd collective flap
    -0.65 %, 2nd tower side-side +0.61 %, 1st tower side-side +0.61 %), the first flap and edge families within
    0.13 %."""
    result = parked(elastodyn)
    for name, value in TABLE_9_1.items():
        tolerance = 0.0015 if name.startswith("1st blade") else 0.007
        assert frequency(result, name) == pytest.approx(value, rel=tolerance), name


#: the effect of each bladefem choice on the parked NREL 5MW (percent), as documented in docs/turbine.md:
#: 'integration': Gauss at the section stations (exact for the tabulated data and the polynomials) instead of
#: ElastoDyn's 17 / 20 element midpoints and its twisted-shape rule, against --elastodyn-compatible; 'blade
#: shapes': bladefem's FE blade modes instead of the file's polynomials, both integrated exactly; 'tower shapes':
#: bladefem's tower FE modes (rotor-nacelle on top) instead of the file's polynomials, both integrated exactly
EFFECTS = {
    "integration": {"1st tower side-side": 0.16, "1st drivetrain torsion": 0.65, "1st blade collective flap": 1.54,
                    "1st blade asymmetric flap (yaw)": 1.59, "1st blade asymmetric edge (pitch)": 1.23,
                    "2nd blade collective flap": 0.59, "nacelle yaw": -0.47},
    "blade shapes": {"1st drivetrain torsion": -0.19, "1st blade collective flap": -0.72,
                     "1st blade asymmetric flap (yaw)": -0.70, "1st blade asymmetric edge (pitch)": -0.55,
                     "2nd blade collective flap": -1.96, "nacelle yaw": -0.79},
    "tower shapes": {"1st tower fore-aft": -3.28, "1st tower side-side": -0.82, "1st drivetrain torsion": -1.06,
                     "2nd tower fore-aft": 4.53},
}


def test_each_bladefem_choice_moves_the_frequencies_as_documented(elastodyn):
    exact = turbine_from_elastodyn(MAIN, "polynomial", gauss_points=2)
    cases = {"integration": (elastodyn, exact),
             "blade shapes": (exact, turbine_from_elastodyn(MAIN, "fe", gauss_points=2, rpm=0.0)),
             "tower shapes": (exact, turbine_from_elastodyn(MAIN, "polynomial", gauss_points=2, tower_shapes="fe"))}
    for choice, effects in EFFECTS.items():
        base, changed = (parked(params) for params in cases[choice])
        for name, percent in effects.items():
            change = 100 * (frequency(changed, name) / frequency(base, name) - 1)
            # the documented figures are rounded to 0.01 %; the FE blade modes come from the automatic mesh choice,
            # whose refinements have moved them by up to 0.02 %
            tolerance = 0.031 if choice == "blade shapes" else 0.011
            assert change == pytest.approx(percent, abs=tolerance), (choice, name)


def test_damping_conventions_against_their_closed_forms(elastodyn):
    """One mode alone, no gravity: ElastoDyn's convention gives c = 2 zeta K / w_beam with w_beam the frequency of
    the beam alone, so a mode that carries an end mass has the damping ratio zeta w / w_beam; the 'rna' convention
    gives zeta itself."""
    params = elastodyn.with_(gravity=0.0)
    blade = linearize(TurbineModel(params), select_dofs(TurbineModel(params).dofs, ["blade1_flap1"]), 0.0)
    # ElastoDyn's w_beam comes from the untwisted polynomial's mass, the motion from the twisted shape's
    beam = params.blade
    twisted = beam.generalized_mass()[0, 0]
    assert blade.modes[0].damping_ratio == pytest.approx(
        beam.damping_ratio[0] * np.sqrt(beam.damping_mass[0] / twisted), rel=1e-6)
    model = TurbineModel(params)
    tower = linearize(model, select_dofs(model.dofs, ["tower_fa1"]), 0.0).modes[0]
    K = params.tower.generalized_stiffness()[0, 0]
    beam_alone = np.sqrt(K / params.tower.generalized_mass()[0, 0]) / (2 * np.pi)
    zeta = params.tower.damping_ratio[0]
    assert tower.damping_ratio == pytest.approx(zeta * tower.frequency_hz / beam_alone, rel=1e-6)
    assert tower.damping_ratio < 0.4 * zeta                 # the heavy top: 0.35 % for the file's 1 %
    rna = TurbineModel(params.with_(damping="rna"))
    # 'rna': c = 2 zeta sqrt(K m) with m the tower's modal mass plus the rotor-nacelle mass as a point at the top;
    # the motion's modal mass M also carries the assembly's rotary inertia and offsets: zeta sqrt(m / M)
    m = params.tower.generalized_mass(params.rotor_nacelle_mass)[0, 0]
    M = rna.equations(np.zeros(rna.n), np.zeros(rna.n))[0][0, 0]
    assert linearize(rna, select_dofs(rna.dofs, ["tower_fa1"]), 0.0).modes[0].damping_ratio == pytest.approx(
        zeta * np.sqrt(m / M), rel=1e-6)
    assert 0.95 < np.sqrt(m / M) < 1.0


def test_a_sextic_is_a_stiffer_ritz_shape_than_the_fe_mode_of_the_5mw_blade():
    """Why fitted polynomials do not reproduce the FE frequencies in bladefem's exactly integrated model: the
    curvature of a sextic (a quartic) cannot follow the NREL 5MW blade's M / EI, whose stiffness falls by two
    orders of magnitude from the root; the lowest Rayleigh quotient of any sextic (twisted shapes, 400 nodes) is
    above the FE frequency: flap 1 +1.3 %, edge 1 +0.6 % (measured). A uniform blade's modes are met (control)."""
    import math

    import scipy.linalg

    from bladefem.builders.elastodyn_blade import blade_from_elastodyn_main
    from bladefem.modal import modes
    from bladefem.modal.elastodyn_fit import BeamIntegrals
    from bladefem.sections import Blade, uniform_sections

    for blade, low, high in ((blade_from_elastodyn_main(MAIN), 0.005, 0.015), (Blade(uniform_sections(
            60.0, 300.0, 5e9, edge_stiffness=1e10)), -1e-6, 1e-4)):
        fe = modes(blade, 0.0, 6)
        beam = BeamIntegrals(blade.sections, 0.0, blade.hub_radius, blade.precone, pitch=blade.pitch)
        for kind in ("flap", "edge"):
            lowest = scipy.linalg.eigh(*beam.forms(kind, 400), eigvals_only=True)[0]
            excess = math.sqrt(lowest) / (2 * math.pi) / fe.first(kind, 1).frequency_hz - 1
            assert low < excess < high, (kind, excess)


def test_fe_shapes_and_their_fitted_polynomials_give_close_system_modes():
    """The same turbine with bladefem's FE blade shapes and with ElastoDyn polynomials fitted to them (tower
    polynomials of the file in both): every system mode of the polynomials is stiffer (Rayleigh-Ritz, the cause
    above) by at most 2.1 % (measured +0.0 to +2.0 % at 12.1 rpm; the displacement-only fit was 8 % high on the
    second flap family, issue 10 defect 9)."""
    fe = TurbineModel(turbine_from_elastodyn(MAIN, "fe", gauss_points=1))
    fitted = TurbineModel(turbine_from_elastodyn(MAIN, "fe-polynomial", gauss_points=1))
    a = {m.name: m.frequency_hz for m in linearize(fe, np.ones(fe.n, dtype=bool), 12.1).modes}
    b = {m.name: m.frequency_hz for m in linearize(fitted, np.ones(fitted.n, dtype=bool), 12.1).modes}
    assert set(a) == set(b)
    for name in a:
        assert -5e-4 < b[name] / a[name] - 1 < 0.021, name
