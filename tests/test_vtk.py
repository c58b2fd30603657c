"""VTK export: files read back with meshio and pyvista give the solver's frequencies (field data in every VTU and
the sidecar) and displacements, the blade sits where the rotor-frame convention puts it, section points move as
rigid sections, the ribbon's area is the integral of the chord, and a Campbell sweep is one collection indexed by
rotor speed."""

from __future__ import annotations

import json
import math
import os
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.case import read_case
from bladefem.outputs.vtk import read_vtk, write_vtk
from bladefem.outputs.vtk_geometry import chord_edges, mode_displacement, surface_positions
from bladefem.modal import KINDS, campbell, modes
from bladefem.sections import Blade, uniform_sections

CASES = Path(__file__).resolve().parents[1] / "cases"
# float64 data are stored in binary VTU and read back bit for bit; JSON keeps the shortest exact float repr
EXACT = 0.0


def uniform_blade(precone_deg: float = 0.0, twist_deg: float = 0.0, chord: float | None = 2.0,
                  pitch_axis: float | None = 0.3, pitch_deg: float = 0.0) -> Blade:
    sections = uniform_sections(20.0, mass=50.0, flap_stiffness=2e7, edge_stiffness=6e7, torsion_stiffness=4e6,
                                flap_inertia=0.2, edge_inertia=2.0)
    sections = replace(sections, twist=math.radians(twist_deg), chord=chord, pitch_axis=pitch_axis)
    return Blade(sections, hub_radius=1.5, precone=math.radians(precone_deg), pitch=math.radians(pitch_deg),
                 name="uniform test blade")


@pytest.fixture(scope="module")
def coned(tmp_path_factory):
    blade = uniform_blade(precone_deg=-5.0, twist_deg=8.0)
    result = modes(blade, rpm=10.0, n_modes=5, elements=16)
    out = tmp_path_factory.mktemp("coned")
    return blade, result, write_vtk(blade, result, out, stem="coned")


def test_meshio_read_back_gives_the_solver_numbers(coned):
    blade, result, export = coned
    data = read_vtk(export.sidecar)
    (speed,) = data["speeds"]
    assert speed["rotor_speed_rpm"] == 10.0
    assert [m["frequency_hz"] for m in speed["modes"]] == pytest.approx(result.frequencies_hz, rel=EXACT, abs=0)
    assert [m["kind"] for m in speed["modes"]] == result.kinds
    axis = speed["meshes"]["axis"]
    # the files themselves keep the frequencies (field data added to meshio's VTU), exactly
    for mesh in speed["meshes"].values():
        np.testing.assert_array_equal(mesh.field_data["frequency_hz"], result.frequencies_hz)
        np.testing.assert_array_equal(mesh.field_data["rotor_speed_rpm"], [10.0])
        assert [KINDS[int(i)] for i in mesh.field_data["kind_index"]] == result.kinds
    beta = blade.precone
    for record, mode in zip(speed["modes"], result.modes):
        shape = mode.shape
        d = axis.point_data[f"{record['array']}_displacement"]
        # blade frame (u, v, w) turned by the precone about y (closed form of the rotor-frame convention)
        np.testing.assert_array_equal(d[:, 1], shape.edge)
        np.testing.assert_allclose(d[:, 0], shape.axial * math.cos(beta) - shape.flap * math.sin(beta),
                                   rtol=0, atol=1e-15)
        np.testing.assert_allclose(d[:, 2], shape.axial * math.sin(beta) + shape.flap * math.cos(beta),
                                   rtol=0, atol=1e-15)
        np.testing.assert_array_equal(axis.point_data[f"{record['array']}_twist_rad"], shape.twist)


def test_blade_sits_on_the_preconed_axis(coned):
    blade, result, export = coned
    points = read_vtk(export.sidecar)["speeds"][0]["meshes"]["axis"].points
    radius = blade.hub_radius + result.modes[0].shape.x
    beta = blade.precone
    np.testing.assert_allclose(points[:, 0], radius * math.cos(beta), atol=1e-12)
    np.testing.assert_allclose(points[:, 1], 0.0, atol=0)
    np.testing.assert_allclose(points[:, 2], radius * math.sin(beta), atol=1e-12)
    assert points[-1, 2] < 0            # negative precone: the tip is upwind


def test_pyvista_reads_the_same_arrays_and_the_collection(coned):
    pv = pytest.importorskip("pyvista")
    blade, result, export = coned
    reader = pv.get_reader(str(export.collection))
    assert reader.time_values == [10.0]
    blocks = reader.read()
    assert blocks.n_blocks == 2
    axis, surface = blocks[0], blocks[1]
    np.testing.assert_array_equal(surface.field_data["frequency_hz"], result.frequencies_hz)
    names = [m["array"] for m in json.loads(export.sidecar.read_text())["speeds"][0]["modes"]]
    for name, mode in zip(names, result.modes):
        flap_z = mode.shape.flap * math.cos(blade.precone) + mode.shape.axial * math.sin(blade.precone)
        np.testing.assert_allclose(axis.point_data[f"{name}_displacement"][:, 2], flap_z, rtol=0, atol=1e-15)
    expected = mode_displacement(blade, result.modes[0].shape, result.modes[0].shape.x).surface
    np.testing.assert_array_equal(surface.point_data[f"{names[0]}_displacement"],
                                  expected.transpose(1, 0, 2).reshape(-1, 3))
    assert surface.cell_data["chord_m"] == pytest.approx(2.0)


def test_section_cell_data_are_midpoint_values(coned):
    blade, result, export = coned
    axis = read_vtk(export.sidecar)["speeds"][0]["meshes"]["axis"]
    assert axis.cell_data["mass_kg_per_m"][0] == pytest.approx(50.0, rel=1e-15)
    assert axis.cell_data["torsion_stiffness_N_m2"][0] == pytest.approx(4e6, rel=1e-15)
    assert "axial_stiffness_N" not in axis.cell_data        # rigid axially: no column, no array


def test_section_points_move_as_rigid_sections():
    """A small modal displacement keeps the chord length to second order and turns the chord by -phi (positive
    twist phi turns the leading edge downwind, against the structural-twist sense)."""
    blade = uniform_blade(twist_deg=12.0, pitch_deg=3.0)
    result = modes(blade, rpm=0.0, n_modes=8, elements=12)
    torsion = result.first("torsion")
    x = torsion.shape.x
    edges = surface_positions(blade, x)
    moved = mode_displacement(blade, torsion.shape, x).surface
    chord = edges[:, 0] - edges[:, 1]
    for eps in (1e-3, 1e-4):
        turned = chord + eps * (moved[:, 0] - moved[:, 1])
        stretch = np.abs(np.linalg.norm(turned, axis=1) - 2.0)
        assert np.max(stretch) < 2.0 * eps**2                 # first-order rigid motion: O(eps^2) change
        angle = np.arctan2(-turned[:, 2], turned[:, 1])
        expected = math.radians(12.0 + 3.0) - eps * torsion.shape.twist
        assert np.max(np.abs(angle - expected)) < eps**2 * np.max(np.abs(torsion.shape.twist)) ** 2


def test_ribbon_area_is_the_integral_of_the_chord_untwisted(tmp_path):
    pv = pytest.importorskip("pyvista")
    sections = uniform_sections(20.0, mass=50.0, flap_stiffness=2e7, edge_stiffness=6e7)
    chord = np.array([1.0, 3.0])                      # linear taper: integral 40 m^2
    blade = Blade(replace(sections, chord=chord, pitch_axis=np.array([0.2, 0.4])), hub_radius=2.0)
    export = write_vtk(blade, modes(blade, 0.0, 2, elements=10), tmp_path)
    area = pv.read(tmp_path / "modes_000_surface.vtu").compute_cell_sizes().cell_data["Area"].sum()
    # untwisted: planar trapezoids, exact up to rounding
    assert area == pytest.approx(40.0, rel=1e-12)
    assert export.sidecar.exists()


def test_nrel5mw_ribbon_area_matches_the_chord_integral(tmp_path):
    pv = pytest.importorskip("pyvista")
    blade = read_case(CASES / "nrel5mw_blade.yaml")
    result = modes(blade, 12.1, 3, elements=60)
    write_vtk(blade, result, tmp_path, stem="nrel")
    x = result.modes[0].shape.x
    chord = blade.sections.at(x, "chord")
    integral = float(np.sum(np.diff(x) * (chord[1:] + chord[:-1]) / 2))      # exact: chord linear per cell
    # a twisted strip is a helicoid: its area exceeds int c dx by int int (sqrt(1 + (kappa eta)^2) - 1); bound it
    theta = blade.sections.at(x, "twist")
    kappa = np.abs(np.diff(theta) / np.diff(x))
    eta = np.abs(chord_edges(blade, x)).max(axis=1)[:-1]
    excess = float(np.sum(np.diff(x) * chord[:-1] * 0.5 * (kappa * eta) ** 2))
    area = pv.read(tmp_path / "nrel_000_surface.vtu").compute_cell_sizes().cell_data["Area"].sum()
    assert 0.0 <= area - integral <= excess + 1e-12 * integral
    assert excess / integral < 1e-4                  # so the ribbon's area is the chord integral to 0.01 %


def test_campbell_sweep_is_one_collection_indexed_by_rotor_speed(tmp_path):
    pv = pytest.importorskip("pyvista")
    blade = uniform_blade(chord=None)
    rpm = [0.0, 5.0, 10.0]
    result = campbell(blade, rpm, n_modes=3, elements=12)
    export = write_vtk(blade, result, tmp_path, stem="sweep")
    reader = pv.get_reader(str(export.collection))
    assert reader.time_values == rpm
    data = json.loads(export.sidecar.read_text())
    for k, speed in enumerate(data["speeds"]):
        frequencies = [m["frequency_hz"] for m in speed["modes"]]
        assert frequencies == [float(f.frequencies_hz[k]) for f in result.families]
        assert list(speed["files"]) == ["axis"]               # no chord: no surface
        reader.set_active_time_value(rpm[k])
        axis = reader.read()[0]
        for f, family in enumerate(result.families, 1):
            shape = result.results[k].modes[family.indices[k]].shape
            name = f"mode{f:02d}_{family.kind}"            # one name per family through the collection
            np.testing.assert_array_equal(axis.point_data[f"{name}_displacement"][:, 2], shape.flap)
        np.testing.assert_array_equal(axis.field_data["frequency_hz"], frequencies)
        np.testing.assert_array_equal(axis.field_data["rotor_speed_rpm"], [rpm[k]])
    assert data["campbell"]["rpm"] == rpm
    assert not any(name.startswith(".") for name in os.listdir(tmp_path))  # no temporary files left behind


def test_array_names_carry_mode_kind_and_frequency_and_files_state_the_normalisation(coned):
    blade, result, export = coned
    data = read_vtk(export.sidecar)
    speed = data["speeds"][0]
    names = [m["array"] for m in speed["modes"]]
    assert names == [f"mode{k:02d}_{m.kind}_{m.frequency_hz:.4g}Hz" for k, m in enumerate(result.modes, 1)]
    assert names[0].startswith("mode01_flap_") and names[0].endswith("Hz")
    assert set(f"{n}_displacement" for n in names) <= set(speed["meshes"]["axis"].point_data)
    for path in (*export.meshes, export.collection):
        head = path.read_text(errors="replace")[:4000]
        assert "largest displacement component" in head and "per unit modal amplitude" in head, path.name
    first = export.meshes[0].read_text(errors="replace")[:4000]
    assert f"{names[0]}: flap, {result.modes[0].frequency_hz:.6g} Hz" in first
    assert data["normalisation"].startswith("displacements in m per unit modal amplitude")


def test_a_tower_is_written_in_its_frame_with_tower_kinds(tmp_path):
    from bladefem.builders.tower_case import read_tower_case
    from bladefem.models.tower import TOWER_KINDS, tower_modes
    tower = read_tower_case(str(CASES / "uniform_tower.yaml"))           # a str path works too
    result = tower_modes(tower, 3, elements=16)
    export = write_vtk(tower, result, tmp_path)
    data = read_vtk(export.sidecar)
    assert data["structure"] == "tower" and data["kinds"] == list(TOWER_KINDS)
    axis = data["speeds"][0]["meshes"]["axis"]
    np.testing.assert_allclose(axis.points[:, 0], result.modes[0].shape.x)     # x up the tower axis
    assert [TOWER_KINDS[int(i)] for i in axis.field_data["kind_index"]] == result.kinds
    first = data["speeds"][0]["modes"][0]["array"]
    assert first.startswith("mode01_fore_aft_")
    np.testing.assert_array_equal(axis.point_data[f"{first}_displacement"][:, 2], result.modes[0].shape.flap)
