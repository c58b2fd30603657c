"""NREL 5MW land tower (Jonkman et al. 2009) from the ElastoDyn files of cases/nrel5mw/.

ElastoDyn represents each tower mode by a sextic polynomial from its tower file (TwFAM1Sh .. TwSSM2Sh) and the
rotor-nacelle assembly by a point mass at the top. The two fore-aft (or side-side) polynomials used as Ritz
functions on the same model (point mass, gravity) give upper bounds to the two lowest exact frequencies (Rayleigh-Ritz,
Poincare separation); the converged FE frequencies must lie at or below them.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as la

from bladefem.builders.elastodyn_blade import blade_from_elastodyn, read_elastodyn_blade
from bladefem.formats.elastodyn_main import read_elastodyn_main
from bladefem.builders.elastodyn_tower import read_elastodyn_tower, tower_from_elastodyn_main
from bladefem.builders.tower_elastodyn import elastodyn_top_mass, elastodyn_tower
from bladefem.modal.elastodyn_fit import polynomial
from bladefem.models.tower import tower_modes

CASE = Path(__file__).parent.parent / "cases" / "nrel5mw"
MAIN = CASE / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"


def beam_mass_above(sections, x: np.ndarray) -> np.ndarray:
    """int_x^H m, kg: each station interval clipped to [x, H] and integrated by 2-point Gauss (exact for the mass
    linear between stations); written here independently of the tower model's own ``mass_above``."""
    t, w = np.polynomial.legendre.leggauss(2)
    total = np.zeros_like(x)
    for x0, x1 in zip(sections.span[:-1], sections.span[1:]):
        a = np.clip(x, x0, x1)                      # the part of [x0, x1] above x is [a, x1]
        half = (x1 - a) / 2
        points = (a + x1)[:, None] / 2 + half[:, None] * t
        total += half * (np.interp(points, sections.span, sections.mass) @ w)
    return total


def ritz_frequencies(tower, coefficients: list[np.ndarray], stiffness: str) -> np.ndarray:
    """Rayleigh-Ritz frequencies (Hz) with the given tip-normalised polynomials: generalized mass
    int m phi_i phi_j + M_top phi_i(1) phi_j(1), stiffness int EI phi_i'' phi_j'' - int W phi_i' phi_j' with the
    gravity compression W = g (mass above + M_top); 8-point Gauss per station interval (the integrands are
    polynomials of degree <= 12 times linear properties: exact to rounding)."""
    s = tower.sections
    length = s.length
    xi, wi = np.polynomial.legendre.leggauss(8)
    a, b = s.span[:-1, None], s.span[1:, None]
    x = ((a + b) / 2 + (b - a) / 2 * xi).ravel()
    w = ((b - a) / 2 * wi).ravel()
    shapes = [[polynomial(c, x / length, k) / length**k for k in range(3)] for c in coefficients]
    top = tower.top_mass.mass
    compression = tower.gravity * (beam_mass_above(s, x) + top)
    M = np.array([[np.sum(w * s.at(x, "mass") * p[0] * q[0]) + top for q in shapes] for p in shapes])
    K = np.array([[np.sum(w * (s.at(x, stiffness) * p[2] * q[2] - compression * p[1] * q[1])) for q in shapes]
                  for p in shapes])
    return np.sqrt(la.eigh(K, M, eigvals_only=True)) / (2 * np.pi)


@pytest.fixture(scope="module")
def point_mass_tower():
    return elastodyn_tower(MAIN, point_mass=True)


@pytest.fixture(scope="module")
def point_mass_modes(point_mass_tower):
    return tower_modes(point_mass_tower, 4)


def test_point_mass_is_elastodyn_tower_top_mass(point_mass_tower):
    # the io reader's own sum of blade, hub, nacelle and yaw-bearing masses (ElastoDyn's TwrTpMass)
    assert point_mass_tower.top_mass.mass == pytest.approx(tower_from_elastodyn_main(MAIN).top_mass.mass, rel=1e-12)
    assert point_mass_tower.height == pytest.approx(87.6)


@pytest.mark.parametrize("kind, blocks, stiffness", [("fore-aft", ("fa1", "fa2"), "flap_stiffness"),
                                                     ("side-side", ("ss1", "ss2"), "edge_stiffness")])
def test_fe_is_below_and_within_three_percent_of_elastodyn_ritz(point_mass_tower, point_mass_modes, kind, blocks,
                                                                 stiffness):
    shipped = read_elastodyn_tower(CASE / "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat").modes
    ritz = ritz_frequencies(point_mass_tower, [shipped[name] for name in blocks], stiffness)
    fe = np.array([point_mass_modes.first(kind, n).frequency_hz for n in (1, 2)])
    # FE converged to 1e-6 relative: the bound holds up to that tolerance
    assert np.all(fe <= ritz * (1 + 1e-6))
    assert np.all(fe >= ritz * 0.97)


def test_gravity_lowers_the_first_frequency_by_the_expected_amount(point_mass_tower, point_mass_modes):
    without = tower_modes(point_mass_tower.with_(gravity=0.0), 2)
    drop = point_mass_modes.first("fore-aft").frequency_hz / without.first("fore-aft").frequency_hz
    # Ritz estimate of the same ratio with ElastoDyn's first polynomial: sqrt(1 - K_grav / K_elastic)
    shipped = read_elastodyn_tower(CASE / "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat").modes["fa1"]
    with_g = ritz_frequencies(point_mass_tower, [shipped], "flap_stiffness")[0]
    no_g = ritz_frequencies(point_mass_tower.with_(gravity=0.0), [shipped], "flap_stiffness")[0]
    # the one-term estimate of a ~1.7 % drop is good to a few percent of the drop itself
    assert 1 - drop == pytest.approx(1 - with_g / no_g, rel=0.05)


def test_rigid_rotor_nacelle_body():
    main = read_elastodyn_main(MAIN)
    top, _ = elastodyn_top_mass(main, azimuth=0.0)
    assert top.mass == pytest.approx(tower_from_elastodyn_main(MAIN).top_mass.mass, rel=1e-12)
    # centre of mass by hand: nacelle at (1.9 downwind, 1.75 up); hub at the apex, OverHang along the tilted shaft
    # above Twr2Shft; the three blades' centre of mass on the shaft axis, coned by PreCone
    tilt, precone = np.radians(-5.0), np.radians(-2.5)
    apex = np.array([1.96256 + -5.0191 * np.sin(tilt), -5.0191 * np.cos(tilt)])          # (up, downwind)
    blade_mass = top.mass - 240000.0 - 56780.0
    blade_cm = blade_moments()[1] / blade_moments()[0]
    shaft = np.array([np.sin(tilt), np.cos(tilt)])
    rotor_cm = apex + blade_cm * np.sin(precone) * shaft
    expected = (240000.0 * np.array([1.75, 1.9]) + 56780.0 * apex + blade_mass * rotor_cm) / top.mass
    assert top.offset[[0, 2]] == pytest.approx(expected, abs=1e-9)
    assert top.offset[1] == pytest.approx(0.0, abs=1e-12)


def blade_moments() -> tuple[float, float, float]:
    """One blade's mass, first and second moments about the apex along its axis (AdjBlMs applied)."""
    main = read_elastodyn_main(MAIN)
    blade = blade_from_elastodyn(read_elastodyn_blade(main.blade_files[0]), tip_radius=63.0, hub_radius=1.5)
    return blade.sections.mass_moments(offset=1.5)


def test_three_bladed_rotor_inertia_does_not_depend_on_azimuth():
    main = read_elastodyn_main(MAIN)
    a, _ = elastodyn_top_mass(main, azimuth=0.0, free_to_spin=False)
    b, _ = elastodyn_top_mass(main, azimuth=0.7, free_to_spin=False)
    assert b.inertia == pytest.approx(a.inertia, rel=1e-10, abs=1e-6 * np.abs(a.inertia).max())


def test_free_rotor_drops_its_spin_inertia():
    main = read_elastodyn_main(MAIN)
    locked, _ = elastodyn_top_mass(main, free_to_spin=False)
    free, _ = elastodyn_top_mass(main, free_to_spin=True)
    tilt = np.radians(-5.0)
    shaft = np.array([np.sin(tilt), 0.0, np.cos(tilt)])        # tower frame (up, side, downwind)
    removed = shaft @ (locked.inertia - free.inertia) @ shaft
    # blades about the shaft: 3 rods of second moment J_b about the apex, coned: 3 J_b cos^2(precone), plus HubIner
    second = blade_moments()[2]
    assert removed == pytest.approx(3 * second * np.cos(np.radians(-2.5)) ** 2 + 115926.0, rel=1e-9)
