"""BModes decks: both layouts, multipliers, el_loc, tip mass, round trips, error reports, a closed-form check."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from bladefem.errors import InputError
from bladefem.io.bmodes import BModesWires, read_bmodes, read_bmodes_sections
from bladefem.io.bmodes_model import (
    blade_from_bmodes,
    tower_from_bmodes,
    tower_model_from_bmodes,
)
from bladefem.io.bmodes_writer import write_bmodes
from bladefem.modal import modes
from bladefem.models.tower import tower_modes

DATA = Path(__file__).parent / "data"
DECKS = ("bmodes_blade", "bmodes_tower_plain", "bmodes_tower_wires", "bmodes_tower_platform")


def copy_with(tmp_path: Path, name: str, old: str, new: str) -> Path:
    """Copies of a deck and its section files in tmp_path, with ``old`` replaced by ``new`` in ``name``."""
    for source in DATA.glob("bmodes_*"):
        text = source.read_text()
        (tmp_path / source.name).write_text(text.replace(old, new, 1) if source.name == name else text)
    return tmp_path / name


def test_blade_deck_values():
    deck = read_bmodes(DATA / "bmodes_blade.bmi")
    assert deck.layout == "blade" and deck.beam_type == 1
    assert deck.rotor_speed_rpm == 30.0                       # rot_rpm 60 times rpm_mult 0.5
    assert deck.length == 10.0 and deck.precone == pytest.approx(math.radians(2.5), rel=1e-15)
    assert deck.tip["cm_axial"] == 0.2 and deck.tip["cm_loc"] == 0.1
    assert deck.multipliers["flp_stff_mult"] == 2.0
    assert deck.el_loc.tolist() == [0, 0.1, 0.2, 0.3, 0.45, 0.6, 0.75, 0.9, 1.0]
    assert deck.sections.station_lines == (6, 7, 8, 9)


def test_blade_from_deck_applies_multipliers_mesh_and_tip_mass():
    deck = read_bmodes(DATA / "bmodes_blade.bmi")
    blade = blade_from_bmodes(deck)
    s = blade.sections
    # every el_loc node and every station is a station of the model; properties stay linear between file stations
    assert set(np.round(deck.el_loc * 10, 12)) <= set(np.round(s.span, 12))
    assert s.flap_stiffness[0] == 2 * 4.0e5 and s.edge_stiffness[0] == 1.6e6
    assert s.at(np.array([4.5]), "mass")[0] == pytest.approx(16 + (12 - 16) * (0.45 - 0.3) / 0.4, rel=1e-14)
    assert s.cm_offset[0] == -0.05                           # BModes: toward the trailing edge
    assert s.twist[0] == pytest.approx(math.radians(10), rel=1e-15)
    tip = blade.tip_mass
    assert tip.mass == 5.0
    assert tip.offset[0] == 0.2                              # cm_axial is the axial offset
    assert np.linalg.norm(tip.offset[1:]) == pytest.approx(0.1, rel=1e-14)     # cm_loc along the chord
    # a rotation keeps the trace and the eigenvalues of the inertia tensor; izz (torsion) stays about x
    assert np.trace(tip.inertia) == pytest.approx(1.2, rel=1e-14)
    assert tip.inertia[0, 0] == 0.5
    local = np.array([[0.3, -0.01, 0], [-0.01, 0.4, 0], [0, 0, 0.5]])
    assert np.allclose(np.linalg.eigvalsh(tip.inertia), np.linalg.eigvalsh(local), atol=1e-14)
    assert any("cm_axial" in note for note in blade.notes)
    assert blade.hub_radius == 2.0 and blade.pitch == pytest.approx(math.radians(1.0), rel=1e-15)


def test_tower_with_tip_mass_matches_the_closed_form():
    deck = read_bmodes(DATA / "bmodes_tower_plain.bmi")
    assert deck.layout == "v3.00" and deck.tow_support == 0 and deck.wires is None
    tower = tower_from_bmodes(deck)
    assert tower.top_mass.mass == 4.0e5 and tower.height == 80.0
    result = modes(tower.as_beam(), 0.0, 4, elements=40)
    # reference README item 3: tip mass equal to the beam mass (mu = 1), w1 = 1.557298; FE converged below 1e-6
    w1 = result.modes[0].frequency_hz * 2 * math.pi * math.sqrt(5000.0 * 80.0**4 / 5.0e10)
    assert w1 == pytest.approx(1.557298, rel=1e-6)


def test_v300_tension_wires_are_read_and_reported():
    deck = read_bmodes(DATA / "bmodes_tower_wires.bmi")
    assert deck.layout == "v3.00" and deck.tow_support == 1
    assert deck.wires.n_wires == (3, 4) and deck.wires.node_attach == (6, 9)
    assert deck.wires.stiffness == (2e6, 1e6)
    assert deck.wires.angle == pytest.approx((math.radians(30), math.radians(40)), rel=1e-15)
    with pytest.raises(InputError) as info:
        tower_from_bmodes(deck)
    assert info.value.field == "tow_support" and info.value.line == 51


def test_tension_wires_become_tower_model_supports():
    deck = read_bmodes(DATA / "bmodes_tower_wires.bmi")
    tower = tower_model_from_bmodes(deck)
    first, second = tower.supports.wires
    # node_attach 6 and 9 of el_loc (0, 0.1, ..., 1) on the 80 m flexible length; v3.00 angles from the tower axis
    assert (first.count, first.height, first.stiffness) == (3, pytest.approx(40.0, rel=1e-15), 2e6)
    assert (second.count, second.height, second.stiffness) == (4, pytest.approx(64.0, rel=1e-15), 1e6)
    assert first.angle == pytest.approx(math.radians(30), rel=1e-15)


@pytest.mark.parametrize("stiffness", [1e11, 1e12])
def test_stiff_wires_at_the_top_pin_the_tower(stiffness):
    # three stiff wires at the top of a uniform tower without top mass or gravity approach a clamped-pinned beam,
    # lambda_1 = 3.92660231 (Blevins, Formulas for natural frequency, Table 8-1); the remaining error is the wires'
    # compliance, first order in EI / (k L^3): measured 1.9e-5 at k = 1e11 N/m and 1.8e-6 at 1e12 N/m
    deck = read_bmodes(DATA / "bmodes_tower_wires.bmi")
    deck = replace(deck, tip={key: 0.0 for key in deck.tip},
                   wires=BModesWires((3,), (11,), (stiffness,), (math.radians(45),)))
    tower = replace(tower_model_from_bmodes(deck), gravity=0.0)
    w1 = tower_modes(tower, 2, elements=40).modes[0].frequency_hz * 2 * math.pi * math.sqrt(5000 * 80.0**4 / 5e10)
    error = 1 - w1 / 3.92660231**2
    assert 0 < error < 2.5e-5 * (1e11 / stiffness)


def test_platform_layout_is_detected():
    deck = read_bmodes(DATA / "bmodes_tower_platform.bmi")
    assert deck.layout == "platform" and deck.tow_support == 1 and deck.wires is None
    p = deck.platform
    assert (p.draft, p.cm_pform, p.mass_pform, p.ref_msl) == (20.0, 5.0, 1.5e6, 0.0)
    assert p.i_matrix_pform[2, 2] == 2e9 and p.hydro_M[3, 3] == 3e7 and p.mooring_K[5, 5] == 2e8
    assert p.hydro_K[2, 2] == 3e6
    assert p.added_mass.tolist() == [800, 600] and p.distributed_stiffness_z.tolist() == [0, 5, 10]
    assert deck.length == 80.0                               # radius 90 minus a 10 m rigid base
    with pytest.raises(InputError) as info:
        tower_from_bmodes(deck)
    assert info.value.field == "hub_conn" and info.value.line == 13


@pytest.mark.parametrize("name", DECKS)
def test_round_trip(tmp_path, name):
    original = read_bmodes(DATA / f"{name}.bmi")
    write_bmodes(original, tmp_path / "deck.bmi")
    again = read_bmodes(tmp_path / "deck.bmi")
    assert again.sec_props_file == tmp_path / "deck_sec_props.dat"
    assert replace(again, sec_props_file=original.sec_props_file) == original


@pytest.mark.parametrize(("name", "old", "new", "line", "field"), [
    ("bmodes_blade.bmi", "12.0      radius:", "1.0       radius:", 9, "radius"),
    ("bmodes_blade.bmi", "1         beam_type", "3         beam_type", 6, "beam_type"),
    ("bmodes_blade.bmi", "0.75  0.9  1.0", "0.75  0.9", 49, "el_loc"),
    ("bmodes_blade.bmi", "2.0       flp_stff_mult", "two       flp_stff_mult", 37, "flp_stff_mult"),
    ("bmodes_blade.bmi", "'bmodes_blade_sec_props.dat'", "'nowhere.dat'", 31, "sec_props_file"),
    ("bmodes_blade_sec_props.dat", "0.3       6.0", "0.8       6.0", 8, "sec_loc"),
    ("bmodes_blade_sec_props.dat", "16.0      0.15", "-16.0     0.15", 7, "mass_den"),
    ("bmodes_blade_sec_props.dat", "2.5e5      1.1e6", "2.5e5", 7, "tc_offst"),
    ("bmodes_tower_wires.bmi", "6 9       node_attach", "6 19      node_attach", 54, "node_attach"),
])
def test_malformed_decks(tmp_path, name, old, new, line, field):
    deck = "bmodes_blade.bmi" if name.startswith("bmodes_blade") else name
    path = copy_with(tmp_path, name, old, new)
    assert (tmp_path / name).read_text() != (DATA / name).read_text()
    with pytest.raises(InputError) as info:
        read_bmodes(tmp_path / deck)
    error = info.value
    assert (error.line, error.field) == (line, field)
    assert error.file.endswith(name if field != "sec_props_file" else deck) and "\n" not in str(error)
    del path


def test_section_file_alone():
    sections = read_bmodes_sections(DATA / "bmodes_tower_sec_props.dat")
    assert sections.columns["flp_stff"].tolist() == [5e10, 5e10]
