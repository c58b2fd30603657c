"""Six-by-six beam formats (BeamDyn, HAWC2 st/htc, windIO 1.x and 2.x) on the IEA-15MW and IEA-22MW blades: files
read back after writing, axes settled by independent data, every format's first mode flapwise, formats from one
source agreeing, malformed files refused with file, line and field."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.beamdyn import beamdyn_sections, blade_from_beamdyn
from bladefem.builders.hawc2 import blade_from_hawc2, hawc2_sections
from bladefem.errors import InputError
from bladefem.formats.beamdyn import (
    read_beamdyn_blade,
    read_beamdyn_primary,
    write_beamdyn_blade,
    write_beamdyn_primary,
)
from bladefem.formats.hawc2_htc import read_hawc2_bodies, write_hawc2_bodies
from bladefem.formats.hawc2_st import read_hawc2_st, write_hawc2_st
from bladefem.builders.detect import read_model
from bladefem.formats.windio import read_windio
from bladefem.builders.windio_model import blade_from_windio, write_windio
from bladefem.modal import modes

DATA = Path(__file__).parent / "data"
IEA15 = DATA / "iea15"
BD15 = IEA15 / "beamdyn" / "IEA-15-240-RWT_BeamDyn.dat"
BD15_BLADE = IEA15 / "beamdyn" / "IEA-15-240-RWT_BeamDyn_blade.dat"
BD22 = DATA / "iea22" / "beamdyn" / "IEA-22-280-RWT_BeamDyn.dat"
ED15_BLADE = IEA15 / "beamdyn" / "IEA-15-240-RWT_ElastoDyn_blade.dat"
FPM = IEA15 / "hawc2" / "IEA_15MW_RWT_Blade_st_FPM.st"
NOFPM = IEA15 / "hawc2" / "IEA_15MW_RWT_Blade_st_noFPM.st"
HTC = IEA15 / "hawc2" / "IEA_15MW_RWT_WTG_bodies_noFPM.htc"
WINDIO2 = IEA15 / "windio" / "IEA-15-240-RWT_windio2_blade.yaml"
WINDIO1 = IEA15 / "windio" / "IEA-15-240-RWT_windio1.yaml"


def beamdyn(path: Path = BD15, sections: str = "full"):
    primary = read_beamdyn_primary(path)
    return blade_from_beamdyn(primary, read_beamdyn_blade(primary.blade_path()), sections=sections)


def hawc2(st: Path = FPM):
    return blade_from_hawc2(read_hawc2_st(st).subset(1, 1), read_hawc2_bodies(HTC).body("blade1"), str(st))


def elastodyn_table() -> np.ndarray:
    """BlFract, PitchAxis, StrcTwst, BMassDen, FlpStff, EdgStff of the ElastoDyn blade file (its rows of six
    numbers between the column header and the mode shapes)."""
    lines = ED15_BLADE.read_text().splitlines()
    start = next(i for i, line in enumerate(lines) if "BlFract" in line) + 2
    rows = []
    for line in lines[start:]:
        if len(line.split()) != 6:
            break
        rows.append([float(v) for v in line.split()])
    return np.array(rows)


# -- read -> write -> read -----------------------------------------------------------------------------------------

BD5 = DATA / "nrel5mw_beamdyn" / "bd_primary_nrel_5mw.inp"


@pytest.mark.parametrize("path", [BD15, BD22, BD5])
def test_beamdyn_files_read_back_after_writing(tmp_path, path):
    primary = read_beamdyn_primary(path)
    blade = read_beamdyn_blade(primary.blade_path())
    assert blade.stiffness.shape == (len(blade.eta), 6, 6) and len(primary.key_points) == sum(primary.members)
    write_beamdyn_primary(primary, tmp_path / "primary.dat")
    write_beamdyn_blade(blade, tmp_path / "blade.dat")
    assert read_beamdyn_primary(tmp_path / "primary.dat") == primary
    assert read_beamdyn_blade(tmp_path / "blade.dat") == blade


def test_hawc2_files_read_back_after_writing(tmp_path):
    for path in (FPM, NOFPM):
        st = read_hawc2_st(path)
        write_hawc2_st(st, tmp_path / "copy.st")
        assert read_hawc2_st(tmp_path / "copy.st") == st
    assert read_hawc2_st(FPM).subset(1, 1).fpm and not read_hawc2_st(NOFPM).subset(2, 1).fpm
    bodies = read_hawc2_bodies(HTC)
    write_hawc2_bodies(bodies, tmp_path / "bodies.htc")
    assert read_hawc2_bodies(tmp_path / "bodies.htc") == bodies
    assert bodies.body("blade1").c2_def.shape == (34, 4)


def test_beamdyn_v5_layout_with_modal_damping():
    blade = read_beamdyn_blade(read_beamdyn_primary(BD5).blade_path())
    assert blade.damping_type == 1 and blade.modal_zeta.tolist() == [0.01, 0.02, 0.03, 0.04]
    assert blade.mu.tolist() == [1e-3, 1e-3, 1e-3, 0.0014, 0.0022, 0.0022] and len(blade.eta) == 49


def test_nrel5mw_beamdyn_blade_against_the_elastodyn_blade():
    # OpenFAST's NREL 5MW BeamDyn example holds the 5MW blade's distributed properties without ElastoDyn's mass
    # factor AdjBlMs = 1.04536: its first flap and edge frequencies times sqrt(AdjBlMs) are bladefem's from the
    # ElastoDyn files within 0.2 % (the BeamDyn file adds section rotary inertia, about 0.1 % on the edge mode);
    # both Euler-Bernoulli (the BeamDyn sections' shear condensed: ElastoDyn has none)
    beamdyn5 = modes(beamdyn(BD5, "condensed"), 0.0, 2, elements=60)
    elastodyn = modes(read_model(DATA / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"), 0.0, 2, elements=60)
    assert beamdyn5.kinds == elastodyn.kinds == ["flap", "edge"]
    np.testing.assert_allclose(beamdyn5.frequencies_hz / math.sqrt(1.04536), elastodyn.frequencies_hz, rtol=2e-3)


def test_windio_1_file_reads_back_as_windio_2(tmp_path):
    # the writer writes windIO 2.x: the 1.x record comes back whole except the twist, which 1.x gives in radians
    # and 2.x in degrees (a radian value need not have a decimal-degree form that maps back to the same double:
    # within one ulp); the 2.x copy then reads back exactly
    turbine = read_windio(WINDIO1)
    write_windio(turbine, tmp_path / "copy.yaml")
    copy = read_windio(tmp_path / "copy.yaml")
    np.testing.assert_allclose(copy.blade.twist.values, turbine.blade.twist.values, rtol=0, atol=1e-16)
    assert copy.blade.stiffness.keys() == turbine.blade.stiffness.keys()
    assert all(np.array_equal(copy.blade.stiffness[k], turbine.blade.stiffness[k]) for k in copy.blade.stiffness)
    assert all(np.array_equal(copy.blade.inertia[k], turbine.blade.inertia[k]) for k in copy.blade.inertia)
    assert copy.cone_angle == turbine.cone_angle and copy.tower is None
    write_windio(copy, tmp_path / "again.yaml")
    assert read_windio(tmp_path / "again.yaml") == copy


# -- axes from independent data ----------------------------------------------------------------------------------

def test_beamdyn_and_windio_axes_against_elastodyn_stiffness():
    # OpenFAST's BeamDyn docs put EI_edge at K44 and EI_flap at K55; the ElastoDyn blade file of the same turbine
    # (an independent reduction by the turbine's authors) agrees with that order and not with the swapped one. At
    # every station from 10 to 95 % span the matched pair (K44 with EdgStff, K55 with FlpStff) is closer than the
    # swapped pair; from 30 to 75 % the matched ratios are within 15 % (the files differ by up to 12 % there, and
    # by up to 47 % outboard of 80 %: the ElastoDyn file comes from an earlier structural design) while the swapped
    # ones are a factor 2 or more away
    ed = elastodyn_table()
    blade = read_beamdyn_blade(BD15_BLADE)
    windio = read_windio(WINDIO2).blade
    for grid, k44, k55 in ((blade.eta, blade.stiffness[:, 3, 3], blade.stiffness[:, 4, 4]),
                           (windio.stiffness_grid, windio.stiffness["K44"], windio.stiffness["K55"])):
        span = (grid >= 0.1) & (grid <= 0.95)
        edge = np.interp(grid, ed[:, 0], ed[:, 5])
        flap = np.interp(grid, ed[:, 0], ed[:, 4])
        matched = np.abs(np.log(k44 / edge)) + np.abs(np.log(k55 / flap))
        swapped = np.abs(np.log(k44 / flap)) + np.abs(np.log(k55 / edge))
        assert np.all(matched[span] < swapped[span])
        mid = (grid >= 0.3) & (grid <= 0.75)
        assert np.all(np.abs(np.log(k44[mid] / edge[mid])) < math.log(1.15))
        assert np.all(np.abs(np.log(k55[mid] / flap[mid])) < math.log(1.15))
        assert np.all(k44[mid] / flap[mid] > 2.0) and np.all(k55[mid] / edge[mid] < 0.5)
    # and bladefem's blades carry them so: from 30 to 75 % span the reduced edgewise stiffness (about the tension
    # centre, K44 less the parallel-axis term K34^2 / K33) is at least twice the flapwise one
    for model in (beamdyn(), blade_from_windio(read_windio(WINDIO2))):
        fraction = model.sections.span / model.length
        mid = (fraction >= 0.3) & (fraction <= 0.75)
        assert np.all(model.sections.edge_stiffness[mid] > 2 * model.sections.flap_stiffness[mid])


def test_windio_entries_are_the_beamdyn_matrix_entries():
    # windIO 2.x's K, mass, cm_x, cm_y, i_edge, i_flap equal the BeamDyn blade file's 6x6 entries at the same grid
    # (K44, K55, m, M34/m, -M35/m, M44, M55): the same axes, the inertias about the reference axis
    blade = read_beamdyn_blade(BD15_BLADE)
    windio = read_windio(WINDIO2).blade
    np.testing.assert_array_equal(windio.stiffness_grid, blade.eta)
    np.testing.assert_allclose(windio.stiffness["K44"], blade.stiffness[:, 3, 3], rtol=1e-12)
    np.testing.assert_allclose(windio.stiffness["K34"], blade.stiffness[:, 2, 3], rtol=1e-12)
    m = blade.mass[:, 0, 0]
    np.testing.assert_allclose(windio.inertia["mass"], m, rtol=1e-12)
    np.testing.assert_allclose(windio.inertia["cm_y"], blade.mass[:, 2, 3] / m, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(windio.inertia["cm_x"], -blade.mass[:, 2, 4] / m, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(windio.inertia["i_edge"], blade.mass[:, 3, 3], rtol=1e-12)
    np.testing.assert_allclose(windio.inertia["i_flap"], blade.mass[:, 4, 4], rtol=1e-12)
    assert np.max(np.abs(windio.inertia["cm_y"])) > 0.8                  # chordwise: cm_y reaches 0.88 m


def test_windio_1_matrices_read_as_the_windio_team_converted_them():
    # the 1.x file's 6x6 mass entries, read by BeamDyn's mass-matrix form (cm_y = M34 / m, cm_x = -M35 / m,
    # i_edge = M44, i_flap = M55, i_cp = -M45, i_plr = M66), give exactly the 2.x file that windIO ships for the
    # same turbine (made by windIO's own v1-to-v2 converter), and the 21 stiffness entries its K11..K66
    one, two = read_windio(WINDIO1).blade, read_windio(WINDIO2).blade
    np.testing.assert_array_equal(one.stiffness_grid, two.stiffness_grid)
    assert one.stiffness.keys() == two.stiffness.keys() and one.inertia.keys() == two.inertia.keys()
    for name in one.stiffness:
        np.testing.assert_array_equal(one.stiffness[name], two.stiffness[name], err_msg=name)
    for name in one.inertia:
        np.testing.assert_array_equal(one.inertia[name], two.inertia[name], err_msg=name)


def test_hawc2_offsets_and_axes_match_beamdyn():
    # HAWC2's x_cg, x_e (half-chord frame, HAWC2's axes) and BeamDyn's M34, K34 (pitch-axis frame, BeamDyn's axes)
    # are independent descriptions of one blade: once mapped (x_BD = y_H2, y_BD = -x_H2) and moved from the half
    # chord to the pitch axis by c2_def's x, the centre of mass and tension centre agree within 2 cm from 10 % span
    # out (the st stations sit on c2_def's arc length, 0.03 % longer than the key points'), the stiffnesses and
    # the mass within 0.5 % up to 95 % span (the tip sections, a millionth of the root's stiffness, differ by 5 %
    # in the files themselves)
    bd, h2 = beamdyn().sections, hawc2().sections
    fraction = bd.span / bd.length
    outer = fraction >= 0.1
    for name, tolerance in (("cm_offset", 0.02), ("tension_centre_offset", 0.02)):
        other = np.interp(fraction, h2.span / h2.length, getattr(h2, name))
        assert np.max(np.abs(other - getattr(bd, name))[outer]) < tolerance, name
    for name in ("mass", "flap_stiffness", "edge_stiffness", "axial_stiffness", "torsion_stiffness"):
        np.testing.assert_allclose(getattr(h2, name)[:-1], getattr(bd, name)[:-1], rtol=5e-3, err_msg=name)
    # the format gives the radii of gyration about the elastic centre (the IEA-22MW file follows it, see below);
    # this IEA-15MW file holds them about the centre of gravity instead (openfast_toolbox's converters take them
    # so): from 30 to 95 % span m ri_y^2 is BeamDyn's edgewise inertia about the centre of mass within 0.1 %, and
    # bladefem, reading the file as the format says, has m ri_y^2 - m (x_cg - x_e)^2 within 0.2 % (the structural
    # pitch, which this ignores, is under 2 deg there: cos^2 within 0.1 %, plus the pitch-turned flapwise share)
    st = read_hawc2_st(FPM).subset(1, 1)
    m, ri_y, offset = st.column("m"), st.column("ri_y"), st.column("x_cg") - st.column("x_e")
    mid = (fraction >= 0.3) & (fraction <= 0.95)
    np.testing.assert_allclose((m * ri_y**2)[mid], bd.edge_inertia[mid], rtol=1e-3)
    np.testing.assert_allclose((m * ri_y**2 - m * offset**2)[mid], h2.edge_inertia[mid], rtol=2e-3)
    # the pitch axis found from c2_def (the half-chord point less its chordwise distance along the twisted chord)
    # follows BeamDyn's key points: prebend within 1 cm of BeamDyn's kp_xr (which reaches -4 m)
    primary = read_beamdyn_primary(BD15)
    bd6 = beamdyn_sections(primary, read_beamdyn_blade(primary.blade_path()))
    h6 = hawc2_sections(read_hawc2_st(FPM).subset(1, 1), read_hawc2_bodies(HTC).body("blade1"), str(FPM))
    prebend = np.interp(bd6.span / bd6.span[-1], h6.span / h6.span[-1], h6.axis[:, 0])
    assert np.max(np.abs(prebend - bd6.axis[:, 0])) < 0.01


# -- every format: first mode flapwise; one source, one answer ----------------------------------------------------

FORMATS = {
    "beamdyn": lambda: beamdyn(),
    "beamdyn blade file alone": lambda: read_model(BD15_BLADE),
    "hawc2 fpm": lambda: hawc2(FPM),
    "hawc2 isotropic": lambda: hawc2(NOFPM),
    "windio 2": lambda: blade_from_windio(read_windio(WINDIO2)),
    "windio 1": lambda: blade_from_windio(read_windio(WINDIO1)),
}


@pytest.fixture(scope="module")
def frequencies() -> dict[str, tuple[np.ndarray, list[str]]]:
    out = {}
    for name, build in FORMATS.items():
        result = modes(build(), 0.0, 4, elements=40)
        out[name] = (result.frequencies_hz, result.kinds)
    return out


@pytest.mark.parametrize("name", list(FORMATS))
def test_first_mode_is_flap(frequencies, name):
    # around OpenFAST/BeamDyn's 0.507 / 0.702 Hz on the straightened blade (tests/test_beamdyn_reference.py)
    hz, kinds = frequencies[name]
    assert kinds[:4] == ["flap", "edge", "flap", "edge"]
    assert 0.50 < hz[0] < 0.52 and 0.69 < hz[1] < 0.71


def test_formats_from_one_source_agree(frequencies):
    # BeamDyn and the HAWC2 FPM file hold the same 6x6 sections (the IEA-15 repository made one from the other):
    # their first four frequencies agree within 0.2 % (the HAWC2 stations sit on c2_def's arc length, 0.03 %
    # longer, about 0.05 % in frequency; the rest is the stations' interpolation). windIO 1.x and 2.x hold the
    # BeamDyn file's numbers on the same grid: within 0.05 % of it (arc length of the polyline through the windIO
    # reference axis, and the twist grid's extra stations)
    base = frequencies["beamdyn"][0]
    np.testing.assert_allclose(frequencies["hawc2 fpm"][0], base, rtol=2e-3)
    np.testing.assert_allclose(frequencies["beamdyn blade file alone"][0], base, rtol=1e-12)
    for name in ("windio 1", "windio 2"):
        np.testing.assert_allclose(frequencies[name][0], base, rtol=5e-4)
    np.testing.assert_allclose(frequencies["windio 1"][0], frequencies["windio 2"][0], rtol=1e-9)


IEA22 = DATA / "iea22"


def test_iea22_first_mode_is_flap_and_hawc2_agrees_with_windio():
    # the IEA-22MW HAWC2 st file holds windIO's rows (mass, K33 equal on all 102) at positions r that differ from
    # windIO's grid by up to 0.18 % of the length: the first seven frequencies (torsion included) agree within
    # 0.3 %. Its radii of gyration are about the elastic centre, as the format defines them: the edgewise rotary
    # inertia then equals windIO's about the centre of mass within 2.5 % from 30 to 95 % span (measured: 1.9 % at
    # 30-40 %, under 0.3 % from 50 %), where read about the centre of gravity it would be 8-12 % above it. The BeamDyn file holds 30 stations whose values differ from windIO's
    # there by up to 1.3 % (docs/formats.md tables it)
    st = read_hawc2_st(IEA22 / "hawc2" / "IEA-22MW_blade1_st.dat").subset(1, 1)
    windio = read_windio(IEA22 / "windio" / "IEA-22-280-RWT_windio2_blade.yaml")
    np.testing.assert_allclose(st.column("m"), windio.blade.inertia["mass"], rtol=1e-9)
    r = st.column("r")
    assert np.max(np.abs(r / r[-1] - windio.blade.stiffness_grid)) < 2e-3
    # the sections compared on the straightened axis: the HAWC2 pitch axis (c2_def moved along the chord) is not
    # windIO's reference axis near the root (0.24 m off at 10 % span), so the curved blades differ by 0.85 % on edge 2
    hawc2_blade = read_model(IEA22 / "hawc2" / "iea_22mw_rwt_steps_blade1.htc", axis="straight")
    windio_blade = blade_from_windio(windio, axis="straight")
    fraction = windio_blade.sections.span / windio_blade.length
    mid = (fraction >= 0.3) & (fraction <= 0.95)
    edge = np.interp(fraction, hawc2_blade.sections.span / hawc2_blade.length, hawc2_blade.sections.edge_inertia)
    np.testing.assert_allclose(edge[mid], windio_blade.sections.edge_inertia[mid], rtol=2.5e-2)
    results = {name: modes(build(), 0.0, 7, elements=60) for name, build in (
        ("beamdyn", lambda: beamdyn(BD22)),
        ("hawc2", lambda: hawc2_blade), ("windio", lambda: windio_blade))}
    for result in results.values():
        assert result.kinds[:4] == ["flap", "edge", "flap", "edge"] and 0.38 < result.frequencies_hz[0] < 0.40
    assert results["hawc2"].kinds == results["windio"].kinds
    np.testing.assert_allclose(results["hawc2"].frequencies_hz, results["windio"].frequencies_hz, rtol=3e-3)


# -- malformed files ---------------------------------------------------------------------------------------------

def edited(tmp_path: Path, source: Path, line: int, old: str, new: str) -> Path:
    lines = source.read_text().splitlines(keepends=True)
    assert old in lines[line - 1]
    lines[line - 1] = lines[line - 1].replace(old, new, 1)
    path = tmp_path / source.name
    path.write_text("".join(lines))
    return path


@pytest.mark.parametrize(("line", "old", "new", "field"), [
    (12, "6.7403759942007923e+09", "6.74O3e+09", "station 1 stiffness row 1[1]"),
    (26, "0.010000", "0.010000 0.2", "station 2 eta"),
    (4, "26", "27", "station_total"),
    (11, "0.000000", "0.500000", "eta"),
])
def test_malformed_beamdyn_blade_is_refused_with_line_and_field(tmp_path, line, old, new, field):
    path = edited(tmp_path, BD15_BLADE, line, old, new)
    with pytest.raises(InputError) as info:
        read_beamdyn_blade(path)
    assert (info.value.file, info.value.field) == (str(path), field)
    assert info.value.line is not None


def test_malformed_beamdyn_primary_and_hawc2_files_are_refused(tmp_path):
    path = edited(tmp_path, BD15, 26, "1.83726e-02", "x")
    with pytest.raises(InputError) as info:
        read_beamdyn_primary(path)
    assert (info.value.line, info.value.field) == (26, "kp_xr")
    path = edited(tmp_path, FPM, 6, "3.1265243837780e+03", "-3.1265243837780e+03")
    with pytest.raises(InputError) as info:
        read_hawc2_st(path)
    assert (info.value.line, info.value.field) == (6, "m")
    path = edited(tmp_path, HTC, 100, "nsec 34", "nsec 35")
    with pytest.raises(InputError) as info:
        read_hawc2_bodies(path)
    assert info.value.field == "nsec"


# -- command line ------------------------------------------------------------------------------------------------

def test_modes_command_on_each_format(tmp_path, capsys):
    from bladefem.cli import main
    for argv in ([str(BD15_BLADE)], [str(FPM), "--htc", str(HTC)], [str(WINDIO1)]):
        assert main(["modes", *argv, "--n-modes", "2", "--elements", "30"]) == 0
        out = capsys.readouterr().out
        assert out.splitlines()[-2].split()[2] == "flap", out
    bad = edited(tmp_path, BD15_BLADE, 12, "6.7403759942007923e+09", "abc")
    (tmp_path / BD15.name).write_text(BD15.read_text())
    assert main(["modes", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"{bad}:12: field 'station 1 stiffness row 1[1]'" in err
    assert main(["modes", str(FPM), "--htc", str(HTC), "--tip-radius", "120"]) == 2
    assert "--tip-radius" in capsys.readouterr().err


@pytest.mark.parametrize("source", [BD15, BD15_BLADE, FPM, NOFPM, HTC], ids=lambda p: p.name)
def test_truncated_and_corrupted_files_read_or_fail_with_one_located_error(tmp_path, source):
    # every truncation point (each 7th line) and a few corrupted tokens: a clean read or one InputError naming the
    # file, never another exception
    from bladefem.formats.hawc2_htc import read_hawc2_bodies as htc
    read = {".dat": read_beamdyn_primary if source == BD15 else read_beamdyn_blade, ".st": read_hawc2_st,
            ".htc": htc}[source.suffix]
    lines = source.read_text().splitlines(keepends=True)
    variants = [lines[:n] for n in range(0, len(lines), 7)]
    for n in range(3, len(lines), max(1, len(lines) // 12)):
        corrupted = list(lines)
        corrupted[n] = corrupted[n].replace("e", "x", 1).replace("0", "nan", 1)
        variants.append(corrupted)
    path = tmp_path / source.name
    for text in variants:
        path.write_text("".join(text))
        try:
            read(path)
        except InputError as error:
            assert error.file == str(path)
