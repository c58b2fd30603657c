"""Gravity on the blade (:class:`bladefem.sections.Gravity`) against independent references: Greenhill's heavy
standing column (it buckles under its weight at m g L^3 / EI = 7.837), the frequencies of a uniform cantilever
standing up and hanging down (shooting on the differential equation, tests/heavy_beam_exact.py), a horizontal
blade's sag, precone, and a prebent blade hanging under its weight against Castigliano's theorem."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sl
from heavy_beam_exact import frequency_parameters, greenhill_parameter
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import jv

from bladefem.assembly import assemble_blade
from bladefem.errors import InputError
from bladefem.modal import modes
from bladefem.modal.operating_point import deflected_blade, operating_point
from bladefem.sections import Blade, Gravity, ReferenceAxis, uniform_sections

L, MASS, EI = 10.0, 10.0, 1.0e5              # the flap plane; the edge plane is 4 EI (frequencies twice as high)
UP, DOWN, HORIZONTAL = 0.0, np.pi, np.pi / 2


def heavy_beam(gamma: float, **changes) -> Blade:
    """A uniform cantilever under its weight along its axis, ``gamma = m g_x L^3 / EI``: standing up (gamma < 0)
    or hanging down (gamma > 0)."""
    g = abs(gamma) * EI / (MASS * L**3)
    return Blade(uniform_sections(L, MASS, EI, 4 * EI), gravity=Gravity(UP if gamma < 0 else DOWN, g), **changes)


def flap_parameters(blade: Blade, elements: int) -> np.ndarray:
    """``lambda = m omega^2 L^4 / EI`` of the first two flap modes (modes 1 and 3: edge 1 lies between)."""
    f = modes(blade, 0.0, 4, elements=elements).frequencies_hz
    return (2 * np.pi * f[[0, 2]]) ** 2 * MASS * L**4 / EI


def test_greenhill_standing_column_buckles_under_its_weight():
    """The FE's buckling load under the weight (K0 is linear in g: the critical g makes it singular) converges as
    h^4 to Greenhill's 9 j^2 / 4 = 7.8373 (j the first zero of J_-1/3); the first frequency falls to zero there and
    turns negative (unstable) beyond."""
    exact = greenhill_parameter()
    assert exact == pytest.approx(7.837, abs=5e-4)
    errors = []
    for elements in (10, 20):             # 40 elements reach the round-off floor (about 5e-9, seen at 80 elements)
        K0 = assemble_blade(heavy_beam(0.0), elements).free_parts[0].toarray()
        Kg = assemble_blade(heavy_beam(-1.0), elements).free_parts[0].toarray() - K0   # per unit gamma, standing
        values = sl.eigvals(K0, -Kg)
        errors.append(np.min(values.real[np.isfinite(values) & (values.real > 0)]) / exact - 1)
    assert np.log2(errors[0] / errors[1]) == pytest.approx(4.0, abs=0.1)
    assert 0 < errors[1] < 5e-7                                                  # measured 3.4e-7
    near = flap_parameters(heavy_beam(-0.999 * exact), 40)[0]
    assert 0 < near < 2e-3 * 1.875104068711961**4                  # lambda nearly linear in gamma: ~1e-3 of 12.36
    assert modes(heavy_beam(-1.01 * exact), 0.0, 1, elements=40).frequencies_hz[0] < 0


@pytest.mark.parametrize("gamma", [-7.0, -4.0, 4.0, 10.0])
def test_standing_and_hanging_frequencies_against_the_exact_solution(gamma):
    """Flap 1 and 2 of the heavy cantilever against the shooting solution of ``EI w'''' - (N w')' = m omega^2 w``:
    the FE converges as h^4 (from 20 elements) and is within 5e-7 at 40 elements (measured 3.1e-7, flap 2 standing
    at gamma = -7). Standing up lowers the frequencies, hanging down raises them (lambda_1 = 12.36 without weight)."""
    exact = frequency_parameters(gamma, 2)
    coarse, fine = (np.abs(flap_parameters(heavy_beam(gamma), n) / exact - 1) for n in (20, 40))
    assert np.log2(coarse / fine) == pytest.approx([4.0, 4.0], abs=0.15)
    assert np.max(fine) < 5e-7
    assert np.sign(exact[0] - 1.875104068711961**4) == np.sign(gamma)


def test_the_weight_has_an_exact_frequency_curve():
    """The reference itself: without weight the Euler-Bernoulli cantilever's (beta L)^4, and at Greenhill's load
    the first root gone to zero."""
    assert frequency_parameters(0.0, 2) == pytest.approx(np.array([1.875104068711961, 4.694091132974175]) ** 4,
                                                         rel=1e-10)
    assert abs(frequency_parameters(-greenhill_parameter(), 1)[0]) < 1e-9


def test_gravity_direction_in_the_blade_frame():
    """Azimuth 0 points the blade up (the weight along -x), 180 down, 90 horizontal with the weight toward the
    leading edge (+y); precone beta turns the radial direction to (cos b, 0, -sin b)."""
    g, beta = 9.80665, np.radians(5.0)
    sections = uniform_sections(L, MASS, EI)
    for azimuth, expected in ((UP, [-np.cos(beta), 0, np.sin(beta)]), (DOWN, [np.cos(beta), 0, -np.sin(beta)]),
                              (HORIZONTAL, [0, 1, 0])):
        blade = Blade(sections, precone=beta, gravity=Gravity(azimuth))
        assert blade.gravity_vector == pytest.approx(g * np.array(expected), abs=1e-12)
    assert Blade(sections).gravity_vector.tolist() == [0.0, 0.0, 0.0]
    with pytest.raises(InputError, match="acceleration"):
        Gravity(0.0, -1.0)


def test_precone_takes_the_axial_share_of_the_weight():
    """Standing up under precone beta the axial force is the weight times cos(beta); its flapwise share is a load
    that does not change the frequencies of the straight beam: the same modes as a blade without precone under
    g cos(beta), to round-off."""
    beta, g = np.radians(8.0), 40.0
    sections = uniform_sections(L, MASS, EI, 4 * EI)
    coned = modes(Blade(sections, precone=beta, gravity=Gravity(UP, g)), 0.0, 4, elements=30).frequencies_hz
    plain = modes(Blade(sections, gravity=Gravity(UP, g * np.cos(beta))), 0.0, 4, elements=30).frequencies_hz
    assert coned == pytest.approx(plain, rel=1e-10)


def test_horizontal_blade_sags_edgewise_and_keeps_its_frequencies():
    """At 90 deg azimuth the weight is across the blade: no axial force, so the frequencies are the weightless
    ones, and the parked blade sags toward its leading edge by m g L^4 / (8 EI_edge) at the tip (the Hermite
    cubics hold the nodal values of the uniformly loaded cantilever exactly)."""
    g = 9.80665
    sections = uniform_sections(L, MASS, EI, 4 * EI)
    blade = Blade(sections, gravity=Gravity(HORIZONTAL))
    assert modes(blade, 0.0, 4, elements=20).frequencies_hz == pytest.approx(
        modes(Blade(sections), 0.0, 4, elements=20).frequencies_hz, rel=1e-12)
    tip = operating_point(blade, 0.0, elements=8).displacement[:, -1]
    assert tip[1] == pytest.approx(MASS * g * L**4 / (8 * 4 * EI), rel=1e-10)
    assert abs(tip[2]) < 1e-12 * tip[1]


def test_the_weight_of_an_offset_centre_of_mass_twists_the_blade():
    """Horizontal (no axial force), pitched 90 deg so that the chordwise centre-of-mass offset e lies across the
    weight: each section carries the torque m g e about the axis, T(x) = m g e (L - x), and the tip twists by
    m g e L^2 / (2 GJ) (the quadratic twist field holds it exactly) while the blade sags in the rotor plane as
    without the offset, by m g L^4 / (8 EI) with the flapwise stiffness turned into that plane by the pitch."""
    from dataclasses import replace

    g, e, torsion = 9.80665, 0.2, 3e4
    sections = replace(uniform_sections(L, MASS, EI, 4 * EI, torsion, 1e9, flap_inertia=0.01, edge_inertia=0.05),
                       cm_offset=np.full(2, e))
    point = operating_point(Blade(sections, pitch=np.pi / 2, gravity=Gravity(HORIZONTAL)), 0.0, elements=8)
    assert point.twist[-1] == pytest.approx(MASS * g * e * L**2 / (2 * torsion), rel=1e-10)
    assert point.displacement[1, -1] == pytest.approx(MASS * g * L**4 / (8 * EI), rel=1e-10)


def test_a_tip_mass_weighs_on_the_blade():
    """A tip mass M: hanging down, the axial force is g (m (L - x) + M) (tapered sections integrated exactly); lying
    horizontal, its weight adds M g L^3 / (3 EI_edge) to the sag."""
    from bladefem.assembly.parameters import gravity_tension
    from bladefem.sections import SectionTable, TipMass

    g, tip = 9.80665, 25.0
    tapered = SectionTable(span=np.array([0.0, 4.0, L]), mass=np.array([16.0, 10.0, 4.0]),
                           flap_stiffness=np.full(3, EI), edge_stiffness=np.full(3, 4 * EI))
    x = np.array([0.0, 2.0, 4.0, 7.0, L])
    outboard = np.where(x < 4.0, 0.5 * (4.0 - x) * (16.0 - 1.5 * x + 10.0), 0.0) + 0.5 * (
        L - np.maximum(x, 4.0)) * (10.0 - (np.maximum(x, 4.0) - 4.0) + 4.0)
    hanging = Blade(tapered, tip_mass=TipMass(tip), gravity=Gravity(DOWN))
    assert gravity_tension(hanging, x) == pytest.approx(g * (outboard + tip), rel=1e-13)
    lying = Blade(uniform_sections(L, MASS, EI, 4 * EI), tip_mass=TipMass(tip), gravity=Gravity(HORIZONTAL))
    sag = operating_point(lying, 0.0, elements=8).displacement[1, -1]
    assert sag == pytest.approx(MASS * g * L**4 / (8 * 4 * EI) + tip * g * L**3 / (3 * 4 * EI), rel=1e-10)


R, ALPHA, EA = 10.0, 0.5, 4.0e6              # an arc curving downwind: 5 m long, turning 29 deg


def arc_blade(azimuth: float, acceleration: float) -> Blade:
    length = R * ALPHA
    s = np.linspace(0.0, length, 81)
    axis = ReferenceAxis(s, np.zeros_like(s), R * (1 - np.cos(s / R)))
    return Blade(uniform_sections(length, MASS, 2.0e5, 6.0e5, 1.0e5, EA), axis=axis,
                 gravity=Gravity(azimuth, acceleration))


def test_prebent_blade_under_its_weight_against_castigliano():
    """A prebent (circular-arc) cantilever under its weight along the pitch axis, parked: the weight of the part
    beyond the arc length s bends it, M(s) = m g int_s^L (z(t) - z(s)) dt, and stretches it, N(s) = m g (L - s)
    cos(s / R); a tip force P along z makes M_P = -P (x(L) - x(s)) and N_P = P sin(s / R), so the tip moves by
    int M M_P / (P EI) + N N_P / (P EA) ds (Castigliano). The operating point carries the weight's geometric
    stiffness (tension hanging, compression standing: the even powers of g), so the linear part is the half
    difference of the blade hanging and standing, less the third-order term, 5.6e-5 of it at 9.81 m/s^2 (measured,
    falling as g^2): at a tenth of that, 5.8e-7, within 2e-5 of Castigliano (the arc's own FE error, as for the
    tip loads of tests/test_curved_axis.py). Hanging straightens the curve (the tip moves upwind) and its tension
    stiffens it: it moves less than the standing blade's sag."""
    g, length, EI_flap = 0.980665, R * ALPHA, 2.0e5

    def x(s: float) -> float:
        return R * np.sin(s / R)

    def z(s: float) -> float:
        return R * (1 - np.cos(s / R))

    def moment(s: float) -> float:                   # int_s^L (z(t) - z(s)) dt
        return MASS * g * (R * (length - s) - R**2 * (np.sin(ALPHA) - np.sin(s / R)) - (length - s) * z(s))

    expected = quad(lambda s: -moment(s) * (x(length) - x(s)) / EI_flap
                    + MASS * g * (length - s) * np.cos(s / R) * np.sin(s / R) / EA, 0.0, length, epsabs=0,
                    epsrel=1e-13)[0]
    hanging, standing = (operating_point(arc_blade(azimuth, g), 0.0, 120).displacement[2, -1]
                         for azimuth in (DOWN, UP))
    assert 0.5 * (hanging - standing) == pytest.approx(expected, rel=2e-5)
    assert expected < 0 and 0 < hanging / -standing < 1


@pytest.mark.parametrize("shear_flexible", [False, True])
def test_six_by_six_sections_carry_the_weight(shear_flexible):
    """The same heavy cantilever through six-by-six sections (condensed, and shear-flexible with a shear stiffness
    that leaves out 3 EI / (k GA L^2) = 3e-8 of the flexibility): the hanging frequencies of the exact solution
    within 5e-7 at 40 elements."""
    from bladefem.sections import FullSections, mass_matrix, stiffness_matrix

    K = stiffness_matrix(1e9, 3e5, EI, 4 * EI, 1e11, 1e11)
    M = mass_matrix(MASS)
    M[3, 3] += 0.5
    sections = FullSections([0.0, L], [K, K], [M, M], shear_flexible=shear_flexible).table()
    g = 10.0 * EI / (MASS * L**3)
    blade = Blade(sections, gravity=Gravity(DOWN, g))
    assert np.max(np.abs(flap_parameters(blade, 40) / frequency_parameters(10.0, 2) - 1)) < 5e-7


def test_zero_gravity_is_no_gravity():
    """A weight of zero acceleration assembles the weightless blade's matrices (the geometric stiffness scales with
    g, nothing else changes)."""
    sections = uniform_sections(L, MASS, EI, 4 * EI, 3e5, 1e9)
    a = assemble_blade(Blade(sections, precone=0.1), 12)
    b = assemble_blade(Blade(sections, precone=0.1, gravity=Gravity(UP, 0.0)), 12)
    for name in ("K0", "K2", "M"):
        assert abs(getattr(a, name) - getattr(b, name)).max() == 0.0, name


# --- the command line ------------------------------------------------------------------------------------------

CASES = Path(__file__).resolve().parent.parent / "cases"


def run(capsys, *argv: str) -> tuple[int, str, str]:
    from bladefem.cli import main

    code = main([str(a) for a in argv])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


NONDIMENSIONAL = """kind: blade
name: heavy beam
sections:
  columns: [span_m, mass_kg_per_m, flap_stiffness_N_m2, edge_stiffness_N_m2]
  rows:
    - [0.0, 1.0, 1.0, 4.0]
    - [1.0, 1.0, 1.0, 4.0]
"""


def test_modes_of_the_hanging_nondimensional_blade_on_the_command_line(capsys, tmp_path):
    """``--gravity --azimuth-deg 180`` on a uniform blade with m = EI = L = 1: gamma = 9.80665, the first flap
    frequency the shooting solution's within the automatic mesh's 1e-6; the note names the weight."""
    case = tmp_path / "heavy.yaml"
    case.write_text(NONDIMENSIONAL)
    code, out, _ = run(capsys, "modes", case, "--gravity", "--azimuth-deg", "180", "--n-modes", "1", "--json")
    data = json.loads(out)
    assert code == 0 and data["modes"][0]["kind"] == "flap"
    expected = np.sqrt(frequency_parameters(9.80665, 1)[0]) / (2 * np.pi)
    assert data["frequencies_hz"][0] == pytest.approx(expected, rel=2e-6)
    assert any("gravity 9.80665 m/s^2 at 180 deg azimuth" in note for note in data["notes"])


def test_a_blade_buckling_under_its_weight_is_no_result(capsys, tmp_path):
    """Standing up (azimuth 0, the default) the same blade is past Greenhill's load (9.81 > 7.84): exit 1, one
    line saying so."""
    case = tmp_path / "heavy.yaml"
    case.write_text(NONDIMENSIONAL)
    code, out, err = run(capsys, "modes", case, "--gravity", "--n-modes", "2")
    assert code == 1 and out == ""
    assert "buckles under its own weight" in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("argv,field", [
    (("modes", CASES / "nrel5mw_blade.yaml", "--azimuth-deg", "90"), "--azimuth-deg"),
    (("modes", CASES / "nrel5mw_blade.yaml", "--gravity", "--method", "galerkin"), "--gravity"),
    (("modes", CASES / "uniform_tower.yaml", "--gravity"), "--gravity"),
    (("campbell", CASES / "nrel5mw_blade.yaml", "--rpm", "0:12:3", "--gravity", "--azimuth-deg", "nan"),
     "--azimuth-deg"),
])
def test_gravity_options_refused_where_they_do_not_apply(capsys, argv, field):
    code, _, err = run(capsys, *argv)
    assert code == 2 and field in err and len(err.strip().splitlines()) == 1, err


def test_campbell_and_operating_point_with_gravity(capsys, tmp_path):
    """The 5MW blade pointing down over a sweep stiffens flap 1 at every speed. At the operating point, parked and
    horizontal, the blade with EA sags edgewise by m g L^4 / (8 EI_edge) (the note says so) and is drawn on that
    axis."""
    base, down = (json.loads(run(capsys, "campbell", CASES / "nrel5mw_blade.yaml", "--rpm", "0:12:3", "--n-modes",
                                 "2", "--json", "--quiet", *extra)[1])
                  for extra in ((), ("--gravity", "--azimuth-deg", "180")))
    flap = [np.array(data["families"][0]["frequencies_hz"]) for data in (base, down)]
    assert np.all(flap[1] > flap[0])
    case = tmp_path / "heavy.yaml"
    case.write_text(NONDIMENSIONAL.replace("edge_stiffness_N_m2]", "edge_stiffness_N_m2, axial_stiffness_N]")
                    .replace("4.0]", "4.0, 1.0e6]"))
    code, out, _ = run(capsys, "modes", case, "--gravity", "--azimuth-deg", "90", "--operating-point", "--n-modes",
                       "2", "--json")
    sag = 9.80665 / (8 * 4.0)
    assert code == 0 and any(f"and the weight at 0 rpm (tip moved +0 m out of plane, {sag:+.3g} m in plane)" in note
                             for note in json.loads(out)["notes"])


def test_horizontal_blade_buckles_laterally_under_its_weight():
    """On its operating point (the deflected axis, the weight's static moments in the stiffness) a horizontal
    cantilever, stiff edgewise, buckles out of its plane and twists under its weight at Timoshenko's q L^3 = 6 j
    sqrt(EI_flap GJ) = 12.854 sqrt(EI_flap GJ) (load through the axis; j the first zero of J_-1/6: Timoshenko &
    Gere, Theory of Elastic Stability, sec. 6.3, 12.85). The classical value leaves out the sag before buckling,
    of relative size EI_flap / EI_edge: the FE's critical weight is above it by 5.7e-5 at EI_edge = 1e4 EI_flap and
    by 6.2e-6 at 1e5 (measured), a tenth as much. Without the moments (the blade about its undeflected axis) the
    weight across it changes nothing (test above)."""
    flap, torsion = 1e5, 5e4
    j = brentq(lambda z: jv(-1.0 / 6.0, z), 1.0, 3.0, xtol=1e-15)
    classical = 6 * j * np.sqrt(flap * torsion) / (MASS * L**3)
    assert 6 * j == pytest.approx(12.85, abs=5e-3)
    excess = []
    for ratio in (1e4, 1e5):
        sections = uniform_sections(L, MASS, flap, ratio * flap, torsion, 1e3 * ratio * flap, flap_inertia=0.01,
                                    edge_inertia=0.05)

        def lowest(g: float, sections=sections) -> float:
            bent = deflected_blade(Blade(sections, gravity=Gravity(HORIZONTAL, g)), 0.0)[0]
            f = modes(bent, 0.0, 1, elements=40).frequencies_hz[0]
            return np.sign(f) * f**2

        excess.append(brentq(lowest, 0.8 * classical, 1.2 * classical, rtol=1e-10) / classical - 1)
    assert 0 < excess[1] < 1e-5 and excess[0] / excess[1] == pytest.approx(10.0, rel=0.15)


def test_stiffness_sums_at_the_quadrature_points_hold_the_weights_moments():
    """The solver's round-off-free ``V^T K0 V`` (summed at the quadrature points) is K0's own form: on a prestressed
    blade under its weight, with the weight's static moments, it equals K0 applied to the same vectors."""
    sections = uniform_sections(L, MASS, EI, 1e3 * EI, 0.5 * EI, 1e5 * EI, flap_inertia=0.01, edge_inertia=0.05)
    bent = deflected_blade(Blade(sections, gravity=Gravity(HORIZONTAL, 9.81)), 0.0)[0]
    matrices = assemble_blade(bent, 20)
    assert matrices.parameters.gravity_static is not None
    K0 = matrices.free_parts[0]
    vectors = np.random.default_rng(1).standard_normal((K0.shape[0], 3))
    direct = vectors.T @ (K0 @ vectors)
    assert np.allclose(matrices.stiffness_gram(vectors), direct, rtol=1e-10, atol=1e-10 * np.abs(direct).max())
