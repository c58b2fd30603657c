"""BModes tower decks on the tower model: top-mass axes, hub_conn, wires, platform, soil springs, added mass,
checked against closed forms and BModes' own mass matrix."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from bladefem.elements import projected_inertia
from bladefem.errors import InputError
from bladefem.formats.bmodes import BModesWires, read_bmodes
from bladefem.builders.bmodes_tower import tower_from_bmodes
from bladefem.modal import modes
from bladefem.models.tower import tower_modes
from bladefem.sections.tower import Platform

DATA = Path(__file__).parent / "data"
#: the uniform test tower: 80 m, 5000 kg/m, EI 5e10 N m^2; omega L^2 sqrt(m / EI) of a frequency in Hz
UNIT = 2 * math.pi * math.sqrt(5000.0 * 80.0**4 / 5.0e10)


def bare(name: str = "bmodes_tower_plain.bmi", **changes):
    """A test tower deck without its top mass, with ``changes``."""
    deck = read_bmodes(DATA / name)
    return replace(deck, tip={key: 0.0 for key in deck.tip}, **changes)


def lateral(result, count: int) -> list[float]:
    """The lowest ``count`` frequencies of lateral modes, Hz (fore-aft, side-side and the base's surge, sway, pitch,
    roll: a mode is named after the coordinate with the largest share of its kinetic energy)."""
    kinds = ("fore-aft", "side-side", "surge", "sway", "pitch", "roll")
    return [m.frequency_hz for m in result.modes if m.kind in kinds][:count]


def test_tower_with_tip_mass_matches_the_closed_form():
    deck = read_bmodes(DATA / "bmodes_tower_plain.bmi")
    assert deck.layout == "v3.00" and deck.tow_support == 0 and deck.wires is None
    tower = tower_from_bmodes(deck)
    assert tower.top_mass.mass == 4.0e5 and tower.height == 80.0
    result = modes(tower.as_beam(), 0.0, 4, elements=40)
    # reference README item 3: tip mass equal to the beam mass (mu = 1), w1 = 1.557298; FE converged below 1e-6
    assert result.modes[0].frequency_hz * UNIT == pytest.approx(1.557298, rel=1e-6)


def test_top_mass_is_bmodes_tip_inertia_block():
    # BModes' tower top block on (u, v, v', w, w', phi) with v fore-aft (downwind), w side-side (lateral, OpenFAST
    # y): the BldVib tip-inertia terms with the tower's axis swap ixx_tp = izz, iyy_tp = ixx, izz_tp = iyy,
    # ixy_tp = izx, iyz_tp = ixy, izx_tp = iyz, cm_loc fore-aft and cm_axial along the axis
    tip = dict(tip_mass=3.0e5, cm_loc=-0.4, cm_axial=1.9, ixx_tip=4.4e7, iyy_tip=2.4e7, izz_tip=2.5e7,
               ixy_tip=3.0e5, izx_tip=1.2e6, iyz_tip=-2.0e5)
    m, d, c = tip["tip_mass"], tip["cm_loc"], tip["cm_axial"]
    gm = np.zeros((6, 6))
    gm[0, 0] = gm[1, 1] = gm[3, 3] = m
    gm[0, 2] = -m * d
    gm[1, 2] = gm[3, 4] = m * c
    gm[2, 2] = m * (d * d + c * c) + tip["iyy_tip"]
    gm[2, 4] = -tip["ixy_tip"]
    gm[2, 5] = tip["iyz_tip"]
    gm[3, 5] = m * d
    gm[4, 4] = tip["ixx_tip"] + m * c * c
    gm[4, 5] = -tip["izx_tip"] + m * d * c
    gm[5, 5] = tip["izz_tip"] + m * d * d
    gm = np.triu(gm) + np.triu(gm, 1).T
    top = tower_from_bmodes(replace(read_bmodes(DATA / "bmodes_tower_plain.bmi"), tip=tip)).top_mass
    G = projected_inertia(np.eye(3), np.float64(top.mass), top.mass * top.offset, top.second_moment)
    # bladefem's kinematic vector (u, v, w, phi, -w', v') in the tower frame (v side-side = -y_OpenFAST, w fore-aft)
    T = np.zeros((6, 6))                         # bladefem vector from BModes' (u, v, v', w, w', phi)
    T[0, 0] = 1.0                                # u
    T[1, 3] = -1.0                               # side-side v = -w_BModes
    T[2, 1] = 1.0                                # fore-aft w = v_BModes
    T[3, 5] = 1.0                                # twist about the axis (up)
    T[4, 2] = -1.0                               # -w' = -v'_BModes
    T[5, 4] = -1.0                               # v' = -w'_BModes
    assert np.allclose(T.T @ G @ T, gm, rtol=0, atol=1e-9 * np.abs(gm).max())


def test_tension_wires_are_springs_along_the_wires():
    deck = read_bmodes(DATA / "bmodes_tower_wires.bmi")
    assert deck.layout == "v3.00" and deck.tow_support == 1
    assert deck.wires.n_wires == (3, 4) and deck.wires.node_attach == (6, 9)
    tower = tower_from_bmodes(deck)
    first, second = tower.supports.wires
    # node_attach 6 and 9 of el_loc (0, 0.1, ..., 1) on the 80 m tower; th_wire from the horizontal plane
    assert (first.count, first.height, first.stiffness) == (3, pytest.approx(40.0, rel=1e-15), 2e6)
    assert (second.count, second.height) == (4, pytest.approx(64.0, rel=1e-15))
    K = first.stiffness_matrix()
    horizontal = math.cos(math.radians(30)) ** 2
    assert K[1, 1] == pytest.approx(3 * 2e6 * horizontal / 2, rel=1e-14)       # n k cos^2 / 2 each direction
    assert K[0, 0] == pytest.approx(3 * 2e6 * (1 - horizontal), rel=1e-14)      # n k sin^2 vertically
    assert any("BModes puts n k cos^2(th)" in note for note in tower.notes)


@pytest.mark.parametrize("stiffness", [1e11, 1e12])
def test_stiff_wires_at_the_top_pin_the_tower(stiffness):
    # three stiff wires at the top of a uniform tower without top mass or gravity approach a clamped-pinned beam,
    # lambda_1 = 3.92660231 (Blevins, Formulas for natural frequency, Table 8-1); the remaining error is the wires'
    # compliance, first order in EI / (k L^3): measured 1.9e-5 at k = 1e11 N/m and 1.8e-6 at 1e12 N/m
    deck = bare("bmodes_tower_wires.bmi", wires=BModesWires((3,), (11,), (stiffness,), (math.radians(45),)))
    tower = tower_from_bmodes(deck).with_(gravity=0.0)
    error = 1 - tower_modes(tower, 2, elements=40).modes[0].frequency_hz * UNIT / 3.92660231**2
    assert 0 < error < 2.5e-5 * (1e11 / stiffness)


def test_winkler_springs_along_the_tower_shift_omega_squared_by_k_over_m():
    # a uniform beam on a uniform elastic foundation k keeps its mode shapes, and omega^2 grows by k / m exactly;
    # hub_conn 3 frees lateral translation and rocking of the base (rigid modes at omega^2 = k / m), hub_conn 4
    # the rocking only; free-free lambda = 4.73004074, pinned-free 3.92660231, clamped-free 1.87510407 (Blevins)
    k = 2.0e4
    platform = read_bmodes(DATA / "bmodes_tower_platform.bmi").platform
    soil = replace(platform, distributed_stiffness_z=np.array([0.0, 80.0]), distributed_stiffness=np.array([k, k]),
                   added_mass=np.zeros(0), added_mass_z=np.zeros(0), hydro_M=np.zeros((6, 6)),
                   hydro_K=np.zeros((6, 6)), mooring_K=np.zeros((6, 6)), mass_pform=0.0,
                   i_matrix_pform=np.zeros((3, 3)), draft=0.0)
    shift = k * 80.0**4 / 5.0e10                       # k / m in the units of (omega L^2 sqrt(m / EI))^2
    for hub_conn, rigid, flexible in ((1, 0, 1.87510407), (3, 2, 4.73004074), (4, 1, 3.92660231)):
        deck = bare("bmodes_tower_platform.bmi", hub_conn=hub_conn, radius=80.0, hub_rad=0.0, platform=soil)
        tower = tower_from_bmodes(deck).with_(gravity=0.0)
        values = np.array(lateral(tower_modes(tower, 12, elements=40), 2 * rigid + 2)) * UNIT
        assert values[:2 * rigid] ** 2 == pytest.approx(shift, rel=1e-8)
        assert values[2 * rigid:] ** 2 == pytest.approx(flexible**4 + shift, rel=1e-6)


def test_distributed_added_mass_on_the_lateral_motion():
    # uniform added mass m_a over the whole tower: lateral frequencies scale by sqrt(m / (m + m_a)) exactly
    platform = read_bmodes(DATA / "bmodes_tower_platform.bmi").platform
    water = replace(platform, added_mass_z=np.array([0.0, 80.0]), added_mass=np.array([1250.0, 1250.0]),
                    distributed_stiffness=np.zeros(0), distributed_stiffness_z=np.zeros(0), draft=0.0)
    plain = bare("bmodes_tower_platform.bmi", hub_conn=1, radius=80.0, hub_rad=0.0,
                 platform=replace(water, added_mass=np.zeros(0), added_mass_z=np.zeros(0)))
    wet = replace(plain, platform=water)
    dry_modes = tower_modes(tower_from_bmodes(plain).with_(gravity=0.0), 6, elements=30)
    wet_modes = tower_modes(tower_from_bmodes(wet).with_(gravity=0.0), 6, elements=30)
    ratio = np.array(lateral(wet_modes, 4)) / np.array(lateral(dry_modes, 4))
    assert ratio == pytest.approx(math.sqrt(5000.0 / 6250.0), rel=1e-10)


def test_platform_block_on_the_tower_model():
    deck = read_bmodes(DATA / "bmodes_tower_platform.bmi")
    assert deck.layout == "platform" and deck.tow_support == 1 and deck.wires is None
    p = deck.platform
    assert (p.draft, p.cm_pform, p.mass_pform, p.ref_msl) == (20.0, 5.0, 1.5e6, 0.0)
    assert p.i_matrix_pform[2, 2] == 2e9 and p.hydro_M[3, 3] == 3e7 and p.mooring_K[5, 5] == 2e8
    assert p.added_mass.tolist() == [800, 600] and p.distributed_stiffness_z.tolist() == [0, 5, 10]
    assert deck.length == 100.0                              # radius 90 + draft 20 - a 10 m rigid base
    tower = tower_from_bmodes(deck)                          # hub_conn 2: free-free on the platform
    platform = tower.supports.platform
    assert isinstance(platform, Platform) and tower.supports.base_held == ()
    assert platform.base_height == pytest.approx(0.0 - 20.0 + 10.0, abs=1e-15)   # ref_msl - draft + hub_rad
    assert platform.centre_of_mass.tolist() == [0.0, 0.0, -5.0]                   # 5 m below the reference point
    assert platform.restoring_includes_weight and tower.gravity > 0
    assert tower.supports.added_mass.at(np.array([5.0]))[0] == pytest.approx(700.0, rel=1e-15)
    for hub_conn, held in ((3, ("heave", "yaw")), (4, ("heave", "sway", "surge", "yaw"))):
        supports = tower_from_bmodes(replace(deck, hub_conn=hub_conn)).supports
        assert supports.base_held == held and not supports.platform.restoring_includes_weight
    assert tower_from_bmodes(replace(deck, hub_conn=1)).supports.platform is None       # clamped: inert block


def test_weight_already_in_the_platform_restoring():
    # BModes platforms hold the weight terms in hydro_K + mooring_K; with gravity on, the rigid platform modes stay
    # where the deck puts them (the weight is not counted twice): gravity changes them only through the tower's
    # deformation, by an amount that falls as the tower's compliance (measured 3.3e-5 at 1e4 x the stiffness)
    deck = read_bmodes(DATA / "bmodes_tower_platform.bmi")
    changes = []
    for factor in (1e4, 1e6):
        stiff = replace(deck, multipliers={**deck.multipliers, "flp_stff_mult": factor, "edge_stff_mult": factor,
                                           "tor_stff_mult": factor, "axial_stff_mult": factor})
        tower = tower_from_bmodes(stiff)
        on = np.array([m.frequency_hz for m in tower_modes(tower, 6, elements=20).modes])
        off = np.array([m.frequency_hz for m in tower_modes(tower.with_(gravity=0.0), 6, elements=20).modes])
        changes.append(np.abs(on / off - 1).max())
    assert changes[0] < 1e-4 and changes[0] / changes[1] == pytest.approx(100, rel=0.01)


def test_free_free_tower_without_restoring_has_no_gravity():
    deck = bare("bmodes_tower_plain.bmi", hub_conn=2)
    deck = replace(deck, tip={**deck.tip, "izz_tip": 1e6})       # a yaw inertia: the test tower's sections have none
    tower = tower_from_bmodes(deck)
    assert tower.gravity == 0.0 and any("nothing carries its weight" in note for note in tower.notes)
    values = np.array(lateral(tower_modes(tower, 10, elements=40), 6)) * UNIT
    assert np.all(np.abs(values[:4]) < 1e-3) and values[4:] ** 0.5 == pytest.approx(4.73004074, rel=1e-6)


def test_tower_deck_columns_replaced_as_bmodes_does(tmp_path):
    text = (DATA / "bmodes_tower_sec_props.dat").read_text().replace("5.0e10     5.0e10", "5.0e10     7.0e10")
    (tmp_path / "bmodes_tower_sec_props.dat").write_text(text)
    (tmp_path / "bmodes_tower_plain.bmi").write_text((DATA / "bmodes_tower_plain.bmi").read_text())
    tower = tower_from_bmodes(read_bmodes(tmp_path / "bmodes_tower_plain.bmi"))
    assert np.all(tower.sections.edge_stiffness == 5.0e10)
    assert any("edge_stff replaced as BModes does" in note for note in tower.notes)


def test_free_yaw_without_inertia_is_a_clear_error():
    with pytest.raises(InputError) as info:
        tower_from_bmodes(bare("bmodes_tower_plain.bmi", hub_conn=2))
    assert info.value.field == "hub_conn" and info.value.line == 13



def test_a_rigid_segment_behind_a_property_step_is_read(tmp_path, capsys):
    # monopile decks make the tower above the pile axially rigid at a property step (EA 1e7 times higher, a station
    # given twice): a deliberate jump, read; the same jump between two distinct stations is refused as a unit slip
    from bladefem.cli import main
    header = (DATA / "bmodes_tower_sec_props.dat").read_text().splitlines()[:5]

    def row(x: float, axial: float) -> str:
        return f"{x} 0.0 0.0 5000.0 0.0 0.0 5.0e10 5.0e10 4.0e10 {axial} 0.0 0.0 0.0"

    def deck(upper: float) -> str:
        rows = [row(0.0, 1e12), row(0.5, 1e12), row(upper, 1e19), row(1.0, 1e19)]
        (tmp_path / "bmodes_tower_sec_props.dat").write_text("\n".join([header[0], "4 n_secs", *header[2:], *rows]))
        (tmp_path / "bmodes_tower_plain.bmi").write_text((DATA / "bmodes_tower_plain.bmi").read_text())
        return str(tmp_path / "bmodes_tower_plain.bmi")
    assert main(["modes", deck(0.5), "--n-modes", "2"]) == 0
    assert main(["modes", deck(0.6), "--n-modes", "2"]) == 2
    assert "unit slip" in capsys.readouterr().err


def test_a_step_written_as_two_close_stations_is_a_step(tmp_path):
    # a property step written as two stations 6e-6 of the height apart (as the IEA 15 MW monopile deck does) is one
    # node: the same frequencies as the exact step to the ramp's width (the sliver element it would otherwise make
    # scatters them by round-off)
    header = (DATA / "bmodes_tower_sec_props.dat").read_text().splitlines()[:5]

    def row(x: float, mass: float, stiffness: float) -> str:
        return f"{x} 0.0 0.0 {mass} 0.0 0.0 {stiffness} {stiffness} 4.0e10 1.0e12 0.0 0.0 0.0"

    def frequencies(upper: float) -> np.ndarray:
        rows = [row(0.0, 8000.0, 9e10), row(0.5, 8000.0, 9e10), row(upper, 4000.0, 3e10), row(1.0, 4000.0, 3e10)]
        (tmp_path / "bmodes_tower_sec_props.dat").write_text("\n".join([header[0], "4 n_secs", *header[2:], *rows]))
        (tmp_path / "bmodes_tower_plain.bmi").write_text((DATA / "bmodes_tower_plain.bmi").read_text())
        tower = tower_from_bmodes(read_bmodes(tmp_path / "bmodes_tower_plain.bmi")).with_(gravity=0.0)
        return np.array(lateral(tower_modes(tower, 8, elements=200), 6))
    assert frequencies(0.5 + 6e-6) == pytest.approx(frequencies(0.5), rel=1e-5)


@pytest.mark.filterwarnings("ignore:the gravity load is")
def test_a_floating_tower_chart_has_its_bending_modes():
    # the six rigid-platform modes come first on a free-free platform: the soft-stiff chart asks for them on top of
    # its modes, so its first bending mode is a tower bending mode, the same as the plain modal analysis finds
    from bladefem.models.tower_campbell import BENDING, tower_campbell
    tower = tower_from_bmodes(read_bmodes(DATA / "bmodes_tower_platform.bmi"))
    assert len(tower.supports.free_base) == 6
    chart = tower_campbell(tower, [0.0, 12.0], n_modes=2, elements=30)
    bending = [m.frequency_hz for m in tower_modes(tower, 12, elements=30).modes if m.kind in BENDING]
    assert chart.first_bending.frequency_hz == pytest.approx(bending[0], rel=1e-12)
    # and the ElastoDyn tower fit finds two fore-aft and two side-side modes past them
    from bladefem.models.tower_fit import tower_coefficients
    fitted = tower_coefficients(tower, n_modes=4, elements=30)
    assert all(fitted.fits[name].fe_frequency_hz > 0 for name in ("fa1", "fa2", "ss1", "ss2"))


@pytest.mark.filterwarnings("ignore:the gravity load is")
def test_an_arpack_failure_on_a_tower_falls_back_to_dense(monkeypatch):
    # ARPACK forced to fail (every error it raises) on a tapered tower with wires (CertTest 04) and a floating one:
    # the same frequencies from the dense solvers, no traceback (to 1e-8: the shifted solve of a free platform gives
    # its soft rigid-body modes to ~1e-8, solve_tower)
    import scipy.sparse.linalg as spla

    import bladefem.modal.solve as solve_module
    import bladefem.models.tower as tower_module
    towers = [tower_from_bmodes(read_bmodes(DATA / "bmodes_certtest" / "Test04_wires_supported_tower.bmi")),
              tower_from_bmodes(read_bmodes(DATA / "bmodes_tower_platform.bmi"))]
    expected = [tower_modes(tower, 8, elements=60).frequencies_hz for tower in towers]

    def failing(*args, **kwargs):
        raise spla.ArpackError(-9)

    monkeypatch.setattr(tower_module.spla, "eigsh", failing)
    monkeypatch.setattr(solve_module.spla, "eigsh", failing)
    for tower, frequencies in zip(towers, expected):
        result = tower_modes(tower, 8, elements=60)
        assert result.frequencies_hz == pytest.approx(frequencies, rel=1e-8)
        # the floating platform's yaw moves no tower DOF (exactly, in the dense solve): a zero shape, not 0 / 0
        assert all(np.isfinite(np.concatenate([mode.shape.flap, mode.shape.edge])).all() for mode in result.modes)


#: pybmodes 1.19.1 (PyPI) on the IEA-15MW BModes tower deck as it is (its own 61-element el_loc mesh, no gravity:
#: BModes leaves it out), Hz: ``pybmodes.models.Tower(deck).run(n_modes=8).frequencies``
PYBMODES_IEA15_TOWER = (0.14444, 0.14545, 0.87657, 0.91844, 0.93936, 2.13657, 2.18057, 4.55262)


def test_the_iea15_bmodes_tower_deck_reads_as_it_is():
    """Issue 25, item 6: the IEA-15MW repository's BModes tower deck (removed in e5fac6a; tests/data/bmodes_iea15)
    gives no placeholder rows for its zero distributed-stiffness sections; it reads, and without gravity its
    frequencies are pybmodes': the first pair within 0.05 % (measured 0.01 %), the rest within 0.5 % (measured
    0.3 %: pybmodes solves on the deck's coarser el_loc mesh, bladefem refines from the stations, and a coarser
    mesh is stiffer)."""
    deck = read_bmodes(DATA / "bmodes_iea15" / "IEA-15-240-RWT_BModes_tower.bmi")
    assert deck.platform is not None and deck.platform.distributed_stiffness.size == 0
    assert deck.platform.added_mass.size == 0 and deck.key_lines["n_secs_k_distr"] > 0
    frequencies = [m.frequency_hz for m in tower_modes(tower_from_bmodes(deck).with_(gravity=0.0), 8).modes]
    np.testing.assert_allclose(frequencies[:2], PYBMODES_IEA15_TOWER[:2], rtol=5e-4)
    np.testing.assert_allclose(frequencies, PYBMODES_IEA15_TOWER, rtol=5e-3)
