"""Tower supports: floating platform rigid-body modes, foundation springs and masses, wires, soil springs."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from bladefem.errors import InputError
from bladefem.models.tower import tower_modes
from bladefem.sections import uniform_sections
from bladefem.sections.tower import (
    Foundation,
    Platform,
    SoilSprings,
    Supports,
    TopMass,
    Tower,
    Wires,
    openfast_to_tower,
)

# -- floating platform --------------------------------------------------------------------------------------

LENGTH, MASS_PER_LENGTH, TOP, TOP_YAW = 10.0, 100.0, 500.0, 200.0
PLATFORM_MASS, BASE_HEIGHT = 5000.0, 5.0
PLATFORM_INERTIA = (2.0e4, 2.0e4, 1.0e4)               # roll, pitch, yaw about the platform CM, kg m^2
ADDED = np.diag([1000.0, 1000.0, 2000.0, 5.0e3, 5.0e3, 1.0e3])
HYDROSTATIC = np.diag([0.0, 0.0, 5.0e4, 8.0e5, 8.0e5, 0.0])
MOORING = np.diag([2.0e3, 2.0e3, 0.0, 0.0, 0.0, 3.0e4])
TOWER_MASS = LENGTH * MASS_PER_LENGTH
TOTAL_MASS = PLATFORM_MASS + TOWER_MASS + TOP
#: first moment of tower and top mass about the platform reference point, kg m
ABOVE = TOWER_MASS * (BASE_HEIGHT + LENGTH / 2) + TOP * (BASE_HEIGHT + LENGTH)


def floating_tower(platform_cm_depth: float, gravity: float) -> Tower:
    """A very stiff tower (first bending ~300 Hz) on a platform: the rigid-body modes are those of one body."""
    sections = uniform_sections(LENGTH, MASS_PER_LENGTH, 1.0e12)
    platform = Platform(mass=PLATFORM_MASS, centre_of_mass=[0.0, 0.0, -platform_cm_depth],
                        inertia=PLATFORM_INERTIA, added_mass=ADDED, hydrostatic=HYDROSTATIC, mooring=MOORING,
                        base_height=BASE_HEIGHT)
    top = TopMass(TOP, inertia=np.diag([TOP_YAW, 0.0, 0.0]))
    return Tower(sections, top_mass=top, supports=Supports(platform=platform), gravity=gravity)


def pitch_inertia(depth: float) -> float:
    """Pitch inertia of the whole system about the reference point, kg m^2 (independent sum of the parts)."""
    h, L = BASE_HEIGHT, LENGTH
    tower = MASS_PER_LENGTH * ((h + L) ** 3 - h**3) / 3
    return PLATFORM_INERTIA[1] + PLATFORM_MASS * depth**2 + tower + TOP * (h + L) ** 2


@pytest.mark.parametrize("gravity", [0.0, 9.81])
def test_floating_rigid_body_frequencies_match_one_dof_formulas(gravity):
    depth = ABOVE / PLATFORM_MASS       # system centre of mass at the reference point: surge and pitch uncouple
    result = tower_modes(floating_tower(depth, gravity), 6, elements=20)
    assert max(mode.residual for mode in result.modes) < 1e-12
    omega = {mode.kind: 2 * np.pi * mode.frequency_hz for mode in result.modes}
    assert sorted(omega) == ["heave", "pitch", "roll", "surge", "sway", "yaw"]
    # the tower's first bending mode is ~1e4 times stiffer: coupling errors ~ (omega ratio)^2 ~ 1e-7
    tol = 1e-5
    assert omega["surge"] == pytest.approx(np.sqrt(MOORING[0, 0] / (TOTAL_MASS + ADDED[0, 0])), rel=tol)
    assert omega["sway"] == pytest.approx(np.sqrt(MOORING[1, 1] / (TOTAL_MASS + ADDED[1, 1])), rel=tol)
    assert omega["heave"] == pytest.approx(np.sqrt(HYDROSTATIC[2, 2] / (TOTAL_MASS + ADDED[2, 2])), rel=tol)
    assert omega["yaw"] == pytest.approx(np.sqrt(MOORING[5, 5] / (PLATFORM_INERTIA[2] + TOP_YAW + ADDED[5, 5])),
                                         rel=tol)
    # zero net first moment: gravity's destabilising moment cancels, pitch = sqrt(C55 / (I + A55))
    assert omega["pitch"] == pytest.approx(np.sqrt(HYDROSTATIC[4, 4] / (pitch_inertia(depth) + ADDED[4, 4])),
                                           rel=tol)
    assert omega["roll"] == pytest.approx(omega["pitch"], rel=tol)


def test_gravity_reduces_pitch_stiffness_by_the_weight_moment():
    depth, g = 1.0, 9.81
    result = tower_modes(floating_tower(depth, g), 6, elements=20)
    first_moment = ABOVE - PLATFORM_MASS * depth            # of the whole system about the reference point, kg m
    # with a centre of mass above the reference point surge and pitch couple through the mass matrix: solve the
    # 2x2 rigid-body problem (surge, pitch) independently
    M = np.array([[TOTAL_MASS + ADDED[0, 0], first_moment], [first_moment, pitch_inertia(depth) + ADDED[4, 4]]])
    K = np.diag([MOORING[0, 0], HYDROSTATIC[4, 4] - g * first_moment])
    expected = np.sqrt(np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real))
    found = sorted(2 * np.pi * m.frequency_hz for m in result.modes if m.kind in ("surge", "pitch"))
    assert found == pytest.approx(expected, rel=1e-5)


def test_free_floating_platform_has_zero_frequency_rigid_modes():
    depth = ABOVE / PLATFORM_MASS
    tower = floating_tower(depth, 9.81)
    p = tower.supports.platform
    unmoored = Platform(mass=p.mass, centre_of_mass=[0.0, 0.0, -depth], inertia=PLATFORM_INERTIA, added_mass=ADDED,
                        hydrostatic=HYDROSTATIC, base_height=BASE_HEIGHT)
    result = tower_modes(tower.with_(supports=Supports(platform=unmoored)), 6, elements=20)
    omega = {mode.kind: 2 * np.pi * mode.frequency_hz for mode in result.modes}
    # K is singular (no surge, sway, yaw stiffness): the shifted inverse problem resolves omega^2 to ~1e-16 times
    # the shift (~10 rad^2/s^2), so the free motions come out at |omega| < 1e-6 rad/s. The three share omega = 0,
    # so any rotation of them within that null space is as valid: check the space, not each mode's label.
    free = sorted(result.modes, key=lambda mode: abs(mode.frequency_hz))[:3]
    assert all(abs(2 * np.pi * mode.frequency_hz) < 1e-6 for mode in free)
    assert {mode.kind for mode in free} <= {"surge", "sway", "yaw"}
    for kind in ("surge", "sway", "yaw"):
        assert sum(mode.energy_fractions[kind] for mode in free) > 0.5
    assert omega["heave"] == pytest.approx(np.sqrt(HYDROSTATIC[2, 2] / (TOTAL_MASS + ADDED[2, 2])), rel=1e-5)
    assert omega["pitch"] == pytest.approx(np.sqrt(HYDROSTATIC[4, 4] / (pitch_inertia(depth) + ADDED[4, 4])),
                                           rel=1e-5)


def test_openfast_matrices_turn_into_the_tower_frame():
    K = np.zeros((6, 6))
    K[0, 4] = K[4, 0] = 7.0            # surge-pitch coupling
    K[1, 3] = K[3, 1] = 3.0            # sway-roll coupling
    T = openfast_to_tower(K)
    # tower frame: t_z = surge, theta_y = -pitch, t_y = -sway, theta_z = roll
    assert T[2, 4] == -7.0 and T[1, 5] == -3.0
    assert np.count_nonzero(T) == 4


# -- foundation -----------------------------------------------------------------------------------------------

def base_spring_determinant(omega2: float, kt: float, kr: float, c: float, mt: float, jr: float,
                            mu: float) -> float:
    """w'''' = omega^2 w on [0, 1] (m = EI = L = 1) on a foundation with lateral spring kt, rocking spring kr,
    their coupling c (energy 1/2 (kt w^2 + 2 c w p + kr p^2), p = w'(0), the pitch that moves the top downwind) and
    masses mt, jr: at 0, w'' = (kr - omega^2 jr) w' + c w and w''' = -(kt - omega^2 mt) w - c w'; at 1 a tip mass
    mu: w'' = 0, -w''' = omega^2 mu w. Four independent power series (a_0 .. a_3 = unit)."""
    rows = []
    for start in range(4):
        a = np.zeros(80)
        a[start] = 1.0
        for k in range(len(a) - 4):
            a[k + 4] = omega2 * a[k] / ((k + 4) * (k + 3) * (k + 2) * (k + 1))
        n = np.arange(len(a))
        w, w2, w3 = a.sum(), (n * (n - 1) * a).sum(), (n * (n - 1) * (n - 2) * a).sum()
        rows.append([2 * a[2] - (kr - omega2 * jr) * a[1] - c * a[0],
                     6 * a[3] + (kt - omega2 * mt) * a[0] + c * a[1], w2, -w3 - omega2 * mu * w])
    return float(np.linalg.det(np.array(rows).T))


def scan_roots(f, start: float, stop: float, count: int, points: int = 3000) -> list[float]:
    """The first ``count`` sign changes of ``f`` on a grid, refined by Brent's method."""
    grid = np.linspace(start, stop, points)
    values = [f(x) for x in grid]
    return [brentq(f, grid[i], grid[i + 1], xtol=1e-13) for i in np.flatnonzero(np.diff(np.sign(values)))][:count]


def test_foundation_springs_and_masses_match_the_series_solution():
    kt, kr, c, mt, jr, mu = 40.0, 15.0, -8.0, 0.3, 0.02, 0.5
    stiffness = np.diag([kt, 1e3, 1e3, 1e3, kr, 1e3])      # surge, sway, heave, roll, pitch, yaw (OpenFAST)
    stiffness[0, 4] = stiffness[4, 0] = c                  # surge-pitch coupling, as of a monopile's soil
    mass = np.diag([mt, 0.0, 0.0, 0.0, jr, 0.0])
    tower = Tower(uniform_sections(1.0, 1.0, 1.0), top_mass=TopMass(mu), gravity=0.0,
                  supports=Supports(foundation=Foundation(stiffness, mass)))
    result = tower_modes(tower, 8, elements=60)
    fore_aft = [2 * np.pi * result.first("fore-aft", n).frequency_hz for n in (1, 2)]
    expected = scan_roots(lambda w: base_spring_determinant(w**2, kt, kr, c, mt, jr, mu), 0.05, 30.0, 2)
    # Hermite elements: omega converges as h^4; 60 elements give ~1e-9
    assert fore_aft == pytest.approx(expected, rel=1e-7)
    # the coupling's sign matters (surge-pitch in OpenFAST axes): the opposite sign gives other frequencies
    flipped = scan_roots(lambda w: base_spring_determinant(w**2, kt, kr, -c, mt, jr, mu), 0.05, 30.0, 1)
    assert abs(flipped[0] / expected[0] - 1) > 1e-3


def test_foundation_and_platform_exclude_each_other():
    platform = Platform(mass=1.0, centre_of_mass=[0, 0, 0], inertia=[1, 1, 1])
    with pytest.raises(InputError, match="not both"):
        Supports(foundation=Foundation(np.eye(6)), platform=platform)


def test_foundation_matrix_must_be_symmetric():
    K = np.eye(6)
    K[0, 1] = 1.0
    with pytest.raises(InputError, match="symmetric"):
        Foundation(K)


# -- wires ----------------------------------------------------------------------------------------------------

def test_evenly_spaced_wires_give_isotropic_lateral_stiffness():
    wires = Wires(count=3, stiffness=100.0, angle=np.radians(30.0), height=1.0, azimuth=0.3)
    K = wires.stiffness_matrix()
    lateral = 3 * 100.0 * np.sin(np.radians(30.0)) ** 2 / 2
    assert np.diag(K) == pytest.approx([3 * 100.0 * np.cos(np.radians(30.0)) ** 2, lateral, lateral])
    assert K[1, 2] == pytest.approx(0.0, abs=1e-12)


def test_wires_at_the_top_act_as_a_tip_spring():
    wires = Wires(count=4, stiffness=50.0, angle=np.radians(40.0), height=1.0)
    k = 4 * 50.0 * np.sin(np.radians(40.0)) ** 2 / 2
    tower = Tower(uniform_sections(1.0, 1.0, 1.0), top_mass=TopMass(0.5), gravity=0.0,
                  supports=Supports(wires=(wires,)))
    result = tower_modes(tower, 4, elements=60)

    def equation(b: float) -> float:        # tip mass equation with mu -> mu - k / b^4 (spring against inertia)
        mu = 0.5 - k / b**4
        c, s, ch, sh = np.cos(b), np.sin(b), np.cosh(b), np.sinh(b)
        return 1 + c * ch + mu * b * (c * sh - s * ch)

    grid = np.linspace(0.5, 6.0, 2000)
    values = [equation(b) for b in grid]
    expected = [brentq(equation, grid[i], grid[i + 1]) for i in np.flatnonzero(np.diff(np.sign(values)))][:2]
    for kind in ("fore-aft", "side-side"):
        found = [np.sqrt(2 * np.pi * result.first(kind, n).frequency_hz) for n in (1, 2)]
        assert found == pytest.approx(expected, rel=1e-7)


def transfer(lam: float, length: float) -> np.ndarray:
    """4x4 map of (w, w', w'', w''') across a segment of w'''' = lam w (power series about its start)."""
    T = np.zeros((4, 4))
    n = np.arange(80)
    falling = np.array([[math.perm(int(i), d) for d in range(4)] for i in n], dtype=float)
    powers = length ** np.maximum(n[:, None] - np.arange(4)[None, :], 0)
    for start in range(4):
        a = np.zeros(len(n))
        a[start] = 1.0 / math.factorial(start)        # unit value of the start-th derivative
        for k in range(len(a) - 4):
            a[k + 4] = lam * a[k] / ((k + 4) * (k + 3) * (k + 2) * (k + 1))
        T[:, start] = (a[:, None] * falling * powers).sum(axis=0)
    return T


def clamped_free_determinant(segments: list[np.ndarray]) -> float:
    """Clamped at 0 (start vectors w'' = 1 or w''' = 1), free at 1 (w'' = w''' = 0) through the given maps."""
    state = np.eye(4)[:, 2:]
    for T in segments:
        state = T @ state
    return float(np.linalg.det(state[2:]))


def test_wires_at_mid_height_match_the_transfer_solution():
    h, count, k_wire, angle = 0.6, 3, 30.0, np.radians(35.0)
    tower = Tower(uniform_sections(1.0, 1.0, 1.0), gravity=0.0,
                  supports=Supports(wires=(Wires(count=count, stiffness=k_wire, angle=angle, height=h),)))
    result = tower_modes(tower, 4, elements=60)
    k = count * k_wire * np.sin(angle) ** 2 / 2
    jump = np.eye(4)
    jump[3, 0] = -k                                   # EI [w'''] = -k w at the attachment point

    def f(omega: float) -> float:
        return clamped_free_determinant([transfer(omega**2, h), jump, transfer(omega**2, 1 - h)])

    expected = scan_roots(f, 0.5, 30.0, 2, 1500)
    found = [2 * np.pi * result.first("side-side", n).frequency_hz for n in (1, 2)]
    assert found == pytest.approx(expected, rel=1e-7)


# -- soil springs ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("rotary", [0.0, 0.2])
def test_winkler_springs_over_the_whole_length_shift_omega_squared(rotary):
    sections = uniform_sections(2.0, 3.0, 5.0, torsion_stiffness=7.0, axial_stiffness=11.0, flap_inertia=rotary,
                                edge_inertia=0.5 - rotary)
    bare = tower_modes(Tower(sections, gravity=0.0), 8, elements=40)
    soil = SoilSprings(height=[0.0, 1.0, 2.0], lateral=4.0, axial=6.0, torsional=0.5)
    held = tower_modes(Tower(sections, gravity=0.0, supports=Supports(soil=soil)), 8, elements=40)
    # springs proportional to a field's mass operator leave its mode shapes unchanged, so
    # omega^2 = omega_0^2 + k / (mass per length): exact for axial (m), torsion (polar inertia 0.5) and for
    # fore-aft bending only without section rotary inertia (rotary = 0); side-side always has rotary inertia
    shifts = {"axial": 6.0 / 3.0, "torsion": 0.5 / 0.5}
    if rotary == 0.0:
        shifts["fore-aft"] = 4.0 / 3.0
    for kind, shift in shifts.items():
        w0 = 2 * np.pi * bare.first(kind).frequency_hz
        w = 2 * np.pi * held.first(kind).frequency_hz
        # same mesh, same shapes: only rounding differs
        assert w**2 == pytest.approx(w0**2 + shift, rel=1e-9)


def test_soil_springs_along_part_of_the_length_match_the_transfer_solution():
    embedded, k = 0.4, 50.0
    soil = SoilSprings(height=[0.0, embedded], lateral=k)
    tower = Tower(uniform_sections(1.0, 1.0, 1.0), gravity=0.0, supports=Supports(soil=soil))
    result = tower_modes(tower, 4, elements=60)

    def f(omega: float) -> float:     # w'''' = (omega^2 - k) w in the soil, omega^2 w above it
        return clamped_free_determinant([transfer(omega**2 - k, embedded), transfer(omega**2, 1 - embedded)])

    expected = scan_roots(f, 0.5, 30.0, 2, 1500)
    found = [2 * np.pi * result.first("fore-aft", n).frequency_hz for n in (1, 2)]
    # the embedded length is a mesh node, so the element integrals stay exact: h^4 convergence, ~1e-9 here
    assert found == pytest.approx(expected, rel=1e-7)


def test_soil_points_must_lie_on_the_tower():
    with pytest.raises(InputError, match="above the tower top"):
        Tower(uniform_sections(1.0, 1.0, 1.0), supports=Supports(soil=SoilSprings([0.0, 2.0], 1.0)))
