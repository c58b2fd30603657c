"""BModes decks read as BModes means them: layouts, multipliers, el_loc, section conventions, tip mass, strict rows,
round trips and error reports. Towers and their supports: tests/test_io_bmodes_tower.py."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from bladefem.cli import main
from bladefem.errors import InputError
from bladefem.formats.bmodes import read_bmodes, read_bmodes_sections
from bladefem.builders.bmodes_model import blade_from_bmodes, bmodes_sections, file_columns
from bladefem.formats.bmodes_writer import write_bmodes
from bladefem.modal import modes
from bladefem.sections import extension_bending_stiffness, mass_moments

DATA = Path(__file__).parent / "data"
DECKS = ("bmodes_blade", "bmodes_tower_plain", "bmodes_tower_wires", "bmodes_tower_platform")


def copy_with(tmp_path: Path, name: str, old: str, new: str) -> Path:
    """Copies of the test decks and their section files in tmp_path, ``old`` replaced by ``new`` in ``name``."""
    for source in (path for path in DATA.glob("bmodes_*") if path.is_file()):
        text = source.read_text()
        if source.name == name:
            assert old in text, old
            text = text.replace(old, new, 1)
        (tmp_path / source.name).write_text(text)
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
    # the file's stations are the model's (BModes' el_loc mesh is not used); the mass is linear between them
    assert s.span.tolist() == pytest.approx([0.0, 3.0, 7.0, 10.0], rel=1e-15)
    assert s.flap_stiffness[0] == 2 * 4.0e5
    assert s.edge_stiffness[0] == pytest.approx(1.6e6 - 1.0e9 * (0.01 - 0.02) ** 2, rel=1e-14)
    assert s.at(np.array([4.5]), "mass")[0] == pytest.approx(16 + (12 - 16) * (0.45 - 0.3) / 0.4, rel=1e-14)
    assert s.cm_offset[0] == -0.05                           # BModes: toward the trailing edge
    assert s.tension_centre_offset[0] == pytest.approx(-(0.01 - 0.02), rel=1e-15)   # from the shear centre
    assert s.twist[0] == pytest.approx(math.radians(10), rel=1e-15)
    tip = blade.tip_mass
    assert tip.mass == 5.0 and tip.offset[0] == 0.2          # cm_axial is the axial offset
    assert np.linalg.norm(tip.offset[1:]) == pytest.approx(0.1, rel=1e-14)     # cm_loc along the chord
    # the tensor is turned by the tip angle: trace and eigenvalues kept, izz (torsion) stays about the span axis
    local = np.array([[0.3, 0.01, 0], [0.01, 0.4, 0], [0, 0, 0.5]])
    assert tip.inertia[0, 0] == 0.5
    assert np.allclose(np.linalg.eigvalsh(tip.inertia), np.linalg.eigvalsh(local), atol=1e-14)
    assert any("cm_axial" in note for note in blade.notes)
    assert blade.hub_radius == 2.0 and blade.pitch == pytest.approx(math.radians(1.0), rel=1e-15)


def test_tip_axes_and_products_are_bmodes_mass_matrix():
    # untwisted tip: BModes' mass matrix couples lag slope v' and flap slope w' by +ixy_tip (its internal
    # iyz_tp = -ixy_tip enters as -iyz_tp): ixy_tip is the tensor entry between the tip's x (flapwise) and y (toward
    # the trailing edge) axes. Unit slope rates v' = w' = 1 (Theta = (phi, -w', v')) give 1/2 (ixx + iyy) + ixy.
    deck = read_bmodes(DATA / "bmodes_blade.bmi")
    deck = replace(deck, pitch=0.0, sections=replace(deck.sections, columns={
        **deck.sections.columns, "str_tw": np.zeros(4), "tw_iner": np.zeros(4)}))
    tip = blade_from_bmodes(deck).tip_mass
    theta = np.array([0.0, -1.0, 1.0])                   # w' = 1, v' = 1
    assert 0.5 * theta @ tip.inertia @ theta == pytest.approx(
        0.5 * (0.3 + 0.4) + 0.01, rel=1e-14)
    assert tip.offset[1] == pytest.approx(-0.1, rel=1e-15)  # cm_loc toward the trailing edge: -y


def test_inertias_about_the_reference_axis_interpolated_per_mass():
    deck = read_bmodes(DATA / "bmodes_blade.bmi")
    c, sections = file_columns(deck), bmodes_sections(deck)
    x = c["sec_loc"] * deck.length
    moments = mass_moments(sections, x, 0.0)
    # BModes' torsional inertia is flp_iner + edge_iner (about the reference axis): J_yy + J_zz here
    assert np.allclose(moments.J[1, 1] + moments.J[2, 2], c["flp_iner"] + c["edge_iner"], rtol=1e-13)
    # between stations the inertia over the mass varies linearly (BModes' sq_km), not the inertia itself
    middle = 0.5 * (x[:-1] + x[1:])
    ratio = (c["flp_iner"] + c["edge_iner"]) / c["mass_den"]
    m = mass_moments(sections, middle, 0.0)
    assert np.allclose((m.J[1, 1] + m.J[2, 2]) / m.m, 0.5 * (ratio[:-1] + ratio[1:]), rtol=1e-13)


def test_stiffness_about_the_shear_centre():
    # BModes' section stiffness on (u', v'', w''): EA, -EA ea (cos, sin) with ea = tc_offst - sc_offst, and the
    # flap/edge stiffnesses turned by the twist with no parallel-axis term; bladefem's matrix is the same
    deck = read_bmodes(DATA / "bmodes_blade.bmi")
    c = file_columns(deck)
    x = c["sec_loc"] * deck.length
    D = extension_bending_stiffness(bmodes_sections(deck), x, 0.0)
    t, ea, EA = c["str_tw"], c["tc_offst"] - c["sc_offst"], c["axial_stff"]
    cos, sin = np.cos(t), np.sin(t)
    assert np.allclose(D[0, 1], -EA * ea * cos * -1, rtol=1e-13)          # bladefem's offsets point to the LE
    assert np.allclose(D[0, 2], -EA * ea * sin, rtol=1e-13)
    assert np.allclose(D[1, 1], c["edge_stff"] * cos**2 + c["flp_stff"] * sin**2, rtol=1e-13)
    assert np.allclose(D[2, 2], c["edge_stff"] * sin**2 + c["flp_stff"] * cos**2, rtol=1e-13)


def test_property_step_from_a_repeated_sec_loc(tmp_path):
    path = copy_with(tmp_path, "bmodes_blade_sec_props.dat", " 4         n_secs", " 5         n_secs")
    text = path.read_text().replace("0.3       6.0", "0.3       6.0     6.0      16.0      0.15      0.80       "
                                    "2.5e5      1.1e6       7.0e4      8.0e8       0.05      0.02     0.01\n"
                                    "0.3       6.0", 1)
    path.write_text(text.replace("0.3       6.0     6.0      16.0", "0.3       6.0     6.0      40.0", 1))
    deck = read_bmodes(tmp_path / "bmodes_blade.bmi")
    s = blade_from_bmodes(deck).sections
    assert np.count_nonzero(s.span == 3.0) == 2                       # the step is a pair of stations
    assert s.at(np.array([3.0 - 1e-9, 3.0 + 1e-9]), "mass") == pytest.approx([40.0, 16.0], rel=1e-6)
    result = modes(blade_from_bmodes(deck), 0.0, 3, elements=20)
    assert all(m.frequency_hz > 0 for m in result.modes)


@pytest.mark.parametrize(("hub_conn", "root"), [(1, "cantilever"), (2, "free"), (3, "axial-torsion"),
                                                (4, "hinged")])
def test_hub_conn_is_the_root_condition(hub_conn, root):
    deck = replace(read_bmodes(DATA / "bmodes_blade.bmi"), hub_conn=hub_conn)
    assert blade_from_bmodes(deck).root == root


def test_free_free_and_pinned_free_uniform_blades():
    # uniform beam without rotation: free-free lambda_1 = 4.73004074, pinned-free 3.92660231 (Blevins Table 8-1)
    deck = read_bmodes(DATA / "bmodes_tower_plain.bmi")
    # a little torsional inertia: without any, free-free leaves the rigid twist with neither mass nor stiffness (an
    # indeterminate frequency); the rotary inertia it adds, I / (m L^2) = 3e-11, is far below the tolerance
    inertia = {key: np.full_like(deck.sections.columns[key], 1e-3) for key in ("flp_iner", "edge_iner")}
    sections = replace(deck.sections, columns={**deck.sections.columns, **inertia})
    deck = replace(deck, beam_type=1, tip={key: 0.0 for key in deck.tip}, sections=sections)
    unit = 2 * math.pi * math.sqrt(5000.0 * 80.0**4 / 5.0e10)
    for hub_conn in (2, 3):          # free-free, and free in bending with axial motion and twist held
        free = modes(blade_from_bmodes(replace(deck, hub_conn=hub_conn)), 0.0, 8, elements=40)
        flexible = [m.frequency_hz for m in free.modes if m.frequency_hz * unit > 1.0]
        assert flexible[0] * unit == pytest.approx(4.73004074**2, rel=1e-6)  # converged below 1e-7 at 40 elements
    pinned = modes(blade_from_bmodes(replace(deck, hub_conn=4)), 0.0, 4, elements=40)
    flexible = [m.frequency_hz for m in pinned.modes if m.frequency_hz * unit > 1.0]
    assert flexible[0] * unit == pytest.approx(3.92660231**2, rel=1e-6)


@pytest.mark.parametrize("name", DECKS)
def test_round_trip(tmp_path, name):
    original = read_bmodes(DATA / f"{name}.bmi")
    write_bmodes(original, tmp_path / "deck.bmi")
    again = read_bmodes(tmp_path / "deck.bmi")
    assert again.sec_props_file == tmp_path / "deck_sec_props.dat"
    assert replace(again, sec_props_file=original.sec_props_file) == original


def test_round_trip_of_the_newer_fields(tmp_path):
    deck = read_bmodes(DATA / "bmodes_tower_platform.bmi")
    platform = replace(deck.platform, cm_pform_xy=(0.5, -0.25), ref_msl_xy=(0.0, 1.5))
    for changed in (replace(deck, hub_conn=4, platform=platform),
                    replace(deck, layout="offshore", tow_support=2, platform=platform)):
        write_bmodes(changed, tmp_path / "deck.bmi")
        assert replace(read_bmodes(tmp_path / "deck.bmi"), sec_props_file=deck.sec_props_file) == changed


@pytest.mark.parametrize(("name", "old", "new", "line", "field"), [
    ("bmodes_blade.bmi", "12.0      radius:", "1.0       radius:", 9, "radius"),
    ("bmodes_blade.bmi", "1         beam_type", "3         beam_type", 6, "beam_type"),
    ("bmodes_blade.bmi", "1         hub_conn", "5         hub_conn", 13, "hub_conn"),
    ("bmodes_blade.bmi", "1         id_mat", "2         id_mat", 30, "id_mat"),
    ("bmodes_blade.bmi", "0.75  0.9  1.0", "0.75  0.9", 49, "el_loc"),
    ("bmodes_blade.bmi", "0.75  0.9  1.0", "0.75  0.9  1.0  1.1", 49, "el_loc"),
    ("bmodes_blade.bmi", "2.0       flp_stff_mult", "two       flp_stff_mult", 37, "flp_stff_mult"),
    ("bmodes_blade.bmi", "2.0       flp_stff_mult", "2.0 1.0   flp_stff_mult", 37, "flp_stff_mult"),
    ("bmodes_blade.bmi", "'bmodes_blade_sec_props.dat'", "'nowhere.dat'", 31, "sec_props_file"),
    ("bmodes_blade_sec_props.dat", "0.3       6.0", "0.8       6.0", 8, "sec_loc"),
    ("bmodes_blade_sec_props.dat", "16.0      0.15", "-16.0     0.15", 7, "mass_den"),
    ("bmodes_blade_sec_props.dat", "2.5e5      1.1e6", "2.5e5", 7, "tc_offst"),
    # issue 16: an extra value would shift the columns (flp_stff read as edge_stff ...)
    ("bmodes_blade_sec_props.dat", "16.0      0.15", "16.0  400.6    0.15", 7, "table row"),
    ("bmodes_tower_wires.bmi", "6 9       node_attach", "6 19      node_attach", 54, "node_attach"),
    ("bmodes_tower_wires.bmi", "3 4       n_wires", "3 4 5     n_wires", 53, "n_wires"),
    ("bmodes_tower_wires.bmi", "30. 40.   th_wire", "30. 95.   th_wire", 56, "th_wire"),
    ("bmodes_tower_platform.bmi", "0.  0.  3.e6  0.  0.  0.", "0.  0.  3.e6  0.  0.  0.  7.", 70, "hydro_K"),
    ("bmodes_tower_platform.bmi", "5.0        cm_pform", "5.0 1.0    cm_pform", 53, "cm_pform"),
    ("bmodes_tower_platform.bmi", "0. 5. 10.  : z_distr_k", "0. 5.  : z_distr_k", 89, "z_distr_k"),
    ("bmodes_tower_platform.bmi", "1.e7 8.e6 5.e6", "1.e7 -8.e6 5.e6", 90, "distr_k"),
])
def test_malformed_decks(tmp_path, name, old, new, line, field):
    deck = name if name.endswith(".bmi") else "bmodes_blade.bmi"
    copy_with(tmp_path, name, old, new)
    with pytest.raises(InputError) as info:
        read_bmodes(tmp_path / deck)
    error = info.value
    assert (error.line, error.field) == (line, field)
    assert error.file.endswith(name if field != "sec_props_file" else deck) and "\n" not in str(error)


def test_section_file_alone():
    sections = read_bmodes_sections(DATA / "bmodes_tower_sec_props.dat")
    assert sections.columns["flp_stff"].tolist() == [5e10, 5e10]


def test_cli_takes_the_rotor_speed_and_mode_count_from_the_deck(capsys):
    assert main(["modes", str(DATA / "bmodes_blade.bmi"), "--elements", "20", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["rotor_speed_rpm"] == 30.0 and len(data["modes"]) == 20        # rot_rpm x rpm_mult, modepr
    assert main(["modes", str(DATA / "bmodes_blade.bmi"), "--elements", "20", "--rpm", "0", "--n-modes", "3",
                 "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["rotor_speed_rpm"] == 0.0 and len(data["modes"]) == 3


def test_export_takes_the_rotor_speed_from_the_deck(tmp_path):
    assert main(["export", str(DATA / "bmodes_blade.bmi"), "-o", str(tmp_path), "--elements", "20", "--n-modes", "2",
                 "--quiet"]) == 0
    sidecar = json.loads((tmp_path / "modes.json").read_text())
    assert [speed["rotor_speed_rpm"] for speed in sidecar["speeds"]] == [30.0]          # rot_rpm x rpm_mult


def test_bmodes_bugs_are_named_not_copied(capsys):
    # CertTest 02 (a rotating blade with a tip mass off the axis): bladefem keeps the tip mass's centrifugal tension
    # (BModes leaves it out: switched to BModes' way, the lowest four fall by 0.9-5.7 %) and reads cm_loc as the
    # transverse offset (BModes v3.00 reads the cm_axial line into cm_loc); the printed notes name both differences
    from bmodes_physics import frequencies
    path = DATA / "bmodes_certtest" / "Test02_blade_with_tip_mass.bmi"
    deck = read_bmodes(path)
    assert deck.rotor_speed_rpm > 0 and deck.tip["tip_mass"] > 0 and deck.tip["cm_loc"] != deck.tip["cm_axial"]
    ours, without_tension = frequencies(deck, 4, 80), frequencies(deck, 4, 80, ("tip mass",))
    assert np.all(ours > without_tension * (1 + 5e-3))
    blade = blade_from_bmodes(deck)
    assert np.linalg.norm(blade.tip_mass.offset[1:]) == pytest.approx(abs(deck.tip["cm_loc"]), rel=1e-14)
    assert blade.tip_mass.offset[0] == deck.tip["cm_axial"]
    assert main(["modes", str(path), "--n-modes", "4", "--elements", "40"]) == 0
    out = capsys.readouterr().out
    assert "the tip mass's own centrifugal force in the blade tension" in out
    assert "BModes v3.00 reads the cm_axial line into cm_loc" in out
