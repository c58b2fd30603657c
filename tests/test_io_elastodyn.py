"""ElastoDyn main and blade files: reading the NREL 5MW files, error reports, round trips, in-place updates."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from bladefem.errors import InputError
from bladefem.builders.elastodyn_blade import (
    blade_from_elastodyn,
    blade_from_elastodyn_main,
    blade_with_mode_shapes,
    read_elastodyn_blade,
    write_elastodyn_blade,
)
from bladefem.formats.elastodyn_main import read_elastodyn_main, write_elastodyn_main

DATA = Path(__file__).parent / "data"
BLADE = DATA / "NRELOffshrBsline5MW_Blade.dat"
MAIN = DATA / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"


def edited(tmp_path: Path, source: Path, line: int, new: str | None, name: str | None = None) -> Path:
    """A copy of ``source`` with 1-based ``line`` replaced by ``new`` (or removed when None)."""
    lines = source.read_text().splitlines(keepends=True)
    if new is None:
        del lines[line - 1]
    else:
        lines[line - 1] = new + "\n"
    path = tmp_path / (name or source.name)
    path.write_text("".join(lines))
    return path


# -- reading the published files ---------------------------------------------------------------------------------

def test_blade_file_matches_the_published_table():
    blade = read_elastodyn_blade(BLADE)
    # NREL/TP-500-38060 Table 2-1 and the file itself: 49 stations, AdjBlMs = 1.04536
    assert blade.stations == 49
    assert blade.adj_mass == 1.04536
    assert blade.fraction[0] == 0.0 and blade.fraction[-1] == 1.0
    assert blade.mass[0] == 678.935 and blade.flap_stiffness[0] == 1.811e10 and blade.edge_stiffness[-1] == 5.01e6
    assert blade.twist[0] == pytest.approx(math.radians(13.308), rel=1e-15)
    assert blade.pitch_axis is not None and blade.pitch_axis[13] == 0.375
    assert blade.flap_damping_percent == (0.477465, 0.477465)
    assert blade.modes["flap1"].tolist() == [0.0622, 1.7254, -3.2452, 4.7131, -2.2555]
    assert blade.station_lines[0] == 17 and blade.station_lines[-1] == 65
    assert blade.key_lines["BldEdgSh(6)"] == 81


def test_blade_mass_properties_match_the_nrel_report():
    blade = blade_from_elastodyn_main(MAIN)
    assert blade.hub_radius == 1.5 and blade.length == pytest.approx(61.5, rel=1e-15)
    assert blade.precone == pytest.approx(math.radians(-2.5), rel=1e-15)
    assert blade.sections.torsion_stiffness is None and blade.sections.axial_stiffness is None
    mass, first, second = blade.sections.mass_moments()
    # NREL/TP-500-38060 Table 2-1: 17,740 kg, first moment 363,231 kg m, second 11,776,047 kg m^2 about the root.
    # The report integrates over ElastoDyn's 17 midpoint nodes, we integrate the linear distribution exactly: the
    # two quadratures differ by < 1 % on this table (the root and tip steps are where they differ most).
    assert mass == pytest.approx(17740, rel=0.01)
    assert first == pytest.approx(363231, rel=0.01)
    assert second == pytest.approx(11776047, rel=0.01)
    assert any("AdjBlMs = 1.04536" in note for note in blade.notes)
    assert any("rigid" in note for note in blade.notes)
    assert blade.sections.lines[0] == 17 and blade.sections.source.endswith(BLADE.name)


def test_adjustment_factors_scale_mass_and_stiffness(tmp_path):
    text = BLADE.read_text().replace("          1   AdjFlSt", "          2   AdjFlSt").replace(
        "          1   AdjEdSt", "          3   AdjEdSt")
    path = tmp_path / "adjusted.dat"
    path.write_text(text)
    plain = blade_from_elastodyn(read_elastodyn_blade(BLADE), tip_radius=63, hub_radius=1.5)
    adjusted = blade_from_elastodyn(read_elastodyn_blade(path), tip_radius=63, hub_radius=1.5)
    assert np.array_equal(adjusted.sections.flap_stiffness, 2 * plain.sections.flap_stiffness)
    assert np.array_equal(adjusted.sections.edge_stiffness, 3 * plain.sections.edge_stiffness)
    raw = read_elastodyn_blade(BLADE)
    assert np.array_equal(plain.sections.mass, raw.mass * 1.04536)


def test_blade_file_without_pitch_axis_column(tmp_path):
    lines = BLADE.read_text().splitlines(keepends=True)
    for i in range(14, 65):                      # header, units and the 49 rows: drop the second column
        words = lines[i].split()
        lines[i] = "  ".join(words[:1] + words[2:]) + "\n"
    path = tmp_path / "no_pitch_axis.dat"
    path.write_text("".join(lines))
    without, with_ = read_elastodyn_blade(path), read_elastodyn_blade(BLADE)
    assert without.pitch_axis is None
    for name in ("fraction", "twist", "mass", "flap_stiffness", "edge_stiffness"):
        assert np.array_equal(getattr(without, name), getattr(with_, name))


def test_main_file_matches_the_published_values():
    main = read_elastodyn_main(MAIN)
    # values quoted in the reference README (NREL/TP-500-38060 Table 6-1 / the OpenFAST model)
    assert (main.num_blades, main.tip_radius, main.hub_radius) == (3, 63.0, 1.5)
    assert main.overhang == -5.0191 and main.tower_height == 87.6 and main.twr2shft == 1.96256
    assert main.shaft_tilt == pytest.approx(math.radians(-5), rel=1e-15)
    assert (main.hub_mass, main.hub_inertia, main.nacelle_mass, main.nacelle_yaw_inertia) == (
        56780, 115926, 240000, 2607890)
    assert main.nacelle_cm == (1.9, 0.0, 1.75)
    assert (main.generator_inertia, main.gearbox_ratio, main.drivetrain_spring, main.drivetrain_damper) == (
        534.116, 97, 8.67637e8, 6.215e6)
    assert main.rotor_speed == pytest.approx(12.1 * 2 * math.pi / 60, rel=1e-15)
    assert main.rotor_speed_rpm == pytest.approx(12.1, rel=1e-14)
    assert main.dofs["FlapDOF1"] and not main.dofs["TeetDOF"]
    assert main.blade_files[0] == DATA / BLADE.name
    assert main.tower_file.name == "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"


def test_relative_paths_resolve_against_the_main_file(tmp_path):
    sub = tmp_path / "model" / "elastodyn"
    sub.mkdir(parents=True)
    (tmp_path / "model" / "blades").mkdir()
    shutil.copy(BLADE, tmp_path / "model" / "blades" / BLADE.name)
    text = MAIN.read_text().replace('"NRELOffshrBsline5MW_Blade.dat"      ', f'"../blades/{BLADE.name}"')
    (sub / "main.dat").write_text(text)
    main = read_elastodyn_main(sub / "main.dat")
    assert main.blade_files[0] == tmp_path / "model" / "blades" / BLADE.name
    assert blade_from_elastodyn_main(sub / "main.dat").length == pytest.approx(61.5, rel=1e-15)


# -- round trips and in-place updates ----------------------------------------------------------------------------

def test_blade_round_trip(tmp_path):
    original = read_elastodyn_blade(BLADE)
    write_elastodyn_blade(original, tmp_path / "blade.dat")
    again = read_elastodyn_blade(tmp_path / "blade.dat")
    assert again.title == original.title
    for name in ("fraction", "pitch_axis", "twist", "mass", "flap_stiffness", "edge_stiffness"):
        assert np.array_equal(getattr(again, name), getattr(original, name)), name
    for name in ("adj_mass", "adj_flap_stiffness", "adj_edge_stiffness", "flap_tuners", "flap_damping_percent",
                 "edge_damping_percent"):
        assert getattr(again, name) == getattr(original, name), name
    for mode in original.modes:
        assert np.array_equal(again.modes[mode], original.modes[mode])


def test_main_round_trip(tmp_path):
    original = read_elastodyn_main(MAIN)
    write_elastodyn_main(original, tmp_path / "main.dat")
    again = read_elastodyn_main(tmp_path / "main.dat")
    assert again == original       # dataclass equality: every value, angles and rotor speed bit for bit
    unchanged = MAIN.read_text().splitlines()
    written = (tmp_path / "main.dat").read_text().splitlines()
    assert len(unchanged) == len(written)
    assert unchanged[130:] == written[130:]     # the OutList and everything else untouched


def test_in_place_update_changes_only_coefficient_lines():
    new = np.array([0.5, 0.25, 0.125, 0.0625, 0.0625])
    old_text, new_text = blade_with_mode_shapes(BLADE, {"flap2": new})
    old_lines, new_lines = old_text.splitlines(keepends=True), new_text.splitlines(keepends=True)
    changed = [i + 1 for i, (a, b) in enumerate(zip(old_lines, new_lines)) if a != b]
    assert changed == [72, 73, 74, 75, 76]
    for number, value in zip(changed, new):
        assert float(new_lines[number - 1].split()[0]) == value
        # the key stays in its column and the description byte for byte
        assert new_lines[number - 1][14:] == old_lines[number - 1][14:]


def test_written_coefficients_add_up_to_one_in_decimal():
    from decimal import Decimal

    from bladefem.formats._modeshape_blocks import decimal_texts
    coefficients = np.array([-70.53191234567, -63.7623456789, 289.7371111111, -176.5130987654, 0.0])
    coefficients[-1] = 1 - coefficients[:-1].sum()
    texts = decimal_texts(coefficients)
    assert sum(Decimal(t) for t in texts) == 1
    assert np.allclose([float(t) for t in texts], coefficients, rtol=0, atol=1e-10)


# -- errors: one InputError naming file, line and field ----------------------------------------------------------

@pytest.mark.parametrize(("line", "new", "err_line", "field"), [
    (4, None, None, "NBlInpSt"),                                                    # missing key
    (11, "    one   AdjBlMs     - Factor", 11, "AdjBlMs"),                          # non-numeric
    (11, "    nan   AdjBlMs     - Factor", 11, "AdjBlMs"),                          # NaN
    (20, "3.5770000E-02  2.5490000E-01  1.3308000E+01  7.4055000E+02", 20, "FlpStff"),   # column count
    (20, "1.0000000E-02  2.5490000E-01  1.3308000E+01  7.4055000E+02  1.7E+10  1.9E+10", 20, "BlFract"),
    (20, "3.5770000E-02  2.5490000E-01  1.3308000E+01  0.0  1.7E+10  1.9E+10", 20, "BMassDen"),
    (20, "3.5770000E-02  2.5490000E-01  1.3308000E+01  7.4E+02  -1.7E+10  1.9E+10", 20, "FlpStff"),
    (20, "3.5770000E-02  2.5490000E-01  NaN  7.4E+02  1.7E+10  1.9E+10", 20, "StrcTwst"),
    (20, "3.5770000E-02  2.5490000E-01  1.3308000E+01  x  1.7E+10  1.9E+10", 20, "BMassDen"),
    (71, "    -3.2555   BldFl1Sh(6) -", 71, "BldFl1Sh"),                             # coefficients do not add to 1
])
def test_malformed_blade_file(tmp_path, line, new, err_line, field):
    path = edited(tmp_path, BLADE, line, new)
    with pytest.raises(InputError) as info:
        read_elastodyn_blade(path)
    error = info.value
    assert error.file == str(path) and error.field == field
    if err_line is not None:
        assert error.line == err_line
    else:
        assert error.line is not None
    assert "\n" not in str(error) and str(path) in str(error)


def test_truncated_table_is_reported(tmp_path):
    lines = BLADE.read_text().splitlines(keepends=True)[:40]
    path = tmp_path / "short.dat"
    path.write_text("".join(lines))
    with pytest.raises(InputError) as info:
        read_elastodyn_blade(path)
    assert info.value.line == 40 and info.value.field is not None


def test_missing_file_is_an_input_error(tmp_path):
    with pytest.raises(InputError) as info:
        read_elastodyn_blade(tmp_path / "absent.dat")
    assert "absent.dat" in str(info.value)


@pytest.mark.parametrize(("line", "new", "field"), [
    (45, "        abc   TipRad      - The distance", "TipRad"),
    (45, "        1.0   TipRad      - The distance", "TipRad"),                    # below HubRad
    (33, "       12.1   RotSpd      - typo in the key", "RotSpeed"),
    (8, "Maybe         FlapDOF1    - First flapwise blade mode DOF (flag)", "FlapDOF1"),
    (86, '""    BldFile(1)  - Name', "BldFile(1)"),
])
def test_malformed_main_file(tmp_path, line, new, field):
    path = edited(tmp_path, MAIN, line, new)
    with pytest.raises(InputError) as info:
        read_elastodyn_main(path)
    assert info.value.field == field and info.value.file == str(path) and info.value.line is not None


def test_missing_blade_file_names_the_main_file_key(tmp_path):
    path = edited(tmp_path, MAIN, 86, '"nowhere.dat"    BldFile(1)  - Name')
    with pytest.raises(InputError) as info:
        blade_from_elastodyn_main(path)
    assert "nowhere.dat" in str(info.value)


# -- tower file --------------------------------------------------------------------------------------------------

TOWER = DATA / "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"


def test_tower_file_matches_the_published_table():
    from bladefem.builders.elastodyn_tower import read_elastodyn_tower, tower_from_elastodyn
    tower_file = read_elastodyn_tower(TOWER)
    assert tower_file.stations == 11 and tower_file.station_lines == tuple(range(20, 31))
    assert tower_file.mass[0] == 5590.87 and tower_file.fa_stiffness[-1] == 1.1582e11
    assert tower_file.modes["fa2"].tolist() == [-70.5319, -63.7623, 289.737, -176.513, 22.0706]
    tower = tower_from_elastodyn(tower_file, height=87.6, top_mass=350000.0)
    # NREL/TP-500-38060 Table 6-1: tower mass 347,460 kg (the report integrates the same linear distribution)
    assert tower.sections.mass_moments()[0] == pytest.approx(347460, rel=1e-5)
    assert tower.as_beam().tip_mass.mass == 350000.0


def test_tower_round_trip_and_in_place_update(tmp_path):
    from bladefem.builders.elastodyn_tower import (
        read_elastodyn_tower,
        tower_with_mode_shapes,
        write_elastodyn_tower,
    )
    original = read_elastodyn_tower(TOWER)
    write_elastodyn_tower(original, tmp_path / "tower.dat")
    again = read_elastodyn_tower(tmp_path / "tower.dat")
    for name in ("fraction", "mass", "fa_stiffness", "ss_stiffness"):
        assert np.array_equal(getattr(again, name), getattr(original, name)), name
    for name in ("adj_mass", "adj_fa_stiffness", "adj_ss_stiffness", "fa_tuners", "ss_tuners", "fa_damping_percent",
                 "ss_damping_percent", "title"):
        assert getattr(again, name) == getattr(original, name), name
    assert all(np.array_equal(again.modes[k], original.modes[k]) for k in original.modes)
    old, new = tower_with_mode_shapes(TOWER, {"ss1": np.array([1.0, 0.0, 0.0, 0.0, 0.0])})
    changed = [i + 1 for i, (a, b) in enumerate(zip(old.splitlines(), new.splitlines())) if a != b]
    assert changed == [43, 44, 45, 46, 47] and len(old) - len(new) < 40


@pytest.mark.parametrize(("line", "new", "field"), [
    (22, "2.0000000E-01  4.8857600E+03  4.6326700E+11", "TwSSStif"),
    (22, "2.0000000E-01  -4.8857600E+03  4.6326700E+11  4.6326700E+11", "TMassDen"),
    (22, "0.05  4.8857600E+03  4.6326700E+11  4.6326700E+11", "HtFract"),
    (14, "        abc   AdjTwMa     - Factor", "AdjTwMa"),
    (18, "  HtFract       TMassDen         TwFAStif", "TwSSStif"),
])
def test_malformed_tower_file(tmp_path, line, new, field):
    from bladefem.builders.elastodyn_tower import read_elastodyn_tower
    path = edited(tmp_path, TOWER, line, new)
    with pytest.raises(InputError) as info:
        read_elastodyn_tower(path)
    assert info.value.field == field and info.value.line == line and info.value.file == str(path)
