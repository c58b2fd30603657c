"""windIO turbine files: blade and tower structure, closed-form checks, round trip, line-numbered errors."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from bladefem.errors import InputError
from bladefem.formats.windio import Distribution, arc_length, read_windio
from bladefem.builders.windio_model import blade_from_windio, tower_from_windio, write_windio
from bladefem.modal import modes

DATA = Path(__file__).parent / "data"
SMALL = DATA / "windio_small.yaml"


def test_small_turbine_values():
    turbine = read_windio(SMALL)
    assert turbine.number_of_blades == 3 and turbine.upwind
    assert turbine.hub_radius == 2.0
    assert turbine.precone == pytest.approx(-math.radians(4.0), rel=1e-15)   # upwind cone tilts blades upwind
    blade = blade_from_windio(turbine)
    # the union of the stiffness and inertia grids (0, 0.4, 0.6, 1) become stations, twist grid (0, 1) too
    assert blade.sections.span.tolist() == pytest.approx([0, 20, 30, 50], rel=1e-15)
    assert blade.sections.flap_stiffness[0] == 1e8 and blade.sections.edge_stiffness[0] == 4e8
    assert blade.sections.torsion_stiffness[0] == 1e7 and blade.sections.axial_stiffness[0] == 1e10
    assert blade.sections.flap_inertia[0] == 0.5 and blade.sections.edge_inertia[0] == 2.0


def rayleigh_rotary_correction(inertia: float, mass: float, length: float) -> float:
    """First-order relative change of omega^2 of a uniform cantilever's first mode from section rotary inertia:
    -(inertia int phi'^2) / (mass int phi^2), with the exact mode shape phi (Rayleigh's quotient)."""
    b = 1.87510407
    sigma = (math.cosh(b) + math.cos(b)) / (math.sinh(b) + math.sin(b))
    x = np.linspace(0, 1, 20001)
    phi = np.cosh(b * x) - np.cos(b * x) - sigma * (np.sinh(b * x) - np.sin(b * x))
    slope = b * (np.sinh(b * x) + np.sin(b * x) - sigma * (np.cosh(b * x) - np.cos(b * x))) / length
    return -inertia * np.trapezoid(slope**2, x) / (mass * np.trapezoid(phi**2, x))


def test_blade_frequency_matches_the_cantilever_closed_form():
    blade = blade_from_windio(read_windio(SMALL), sections="condensed")
    result = modes(blade, 0.0, 4, elements=40)
    # the Euler-Bernoulli beam (the shear condensed): uniform cantilever, reference README item 1: omega_1 =
    # 1.87510407^2 sqrt(EI / (m L^4)), lowered by the section rotary inertia (i_flap = 0.5, i_edge = 2 kg m) to first order (about 2e-5 and 7e-5); the neglected
    # second-order term is ~1e-9 and the FE is converged to 1e-6
    for kind, stiffness, inertia in (("flap", 1e8, 0.5), ("edge", 4e8, 2.0)):
        omega0 = 1.87510407**2 * math.sqrt(stiffness / (100 * 50.0**4))
        expected = omega0 * math.sqrt(1 + rayleigh_rotary_correction(inertia, 100.0, 50.0)) / (2 * math.pi)
        assert result.first(kind).frequency_hz == pytest.approx(expected, rel=2e-6)


def test_tower_with_rotor_nacelle_mass_matches_the_closed_form():
    tower = tower_from_windio(read_windio(SMALL))
    assert tower.base_height == 10.0 and tower.height == 80.0
    assert tower.top_mass.mass == pytest.approx(4.0e5, rel=1e-15)   # 3 x 5000 + 35000 + 300000 + 50000
    result = modes(tower.as_beam(), 0.0, 4, elements=40)
    # reference README item 3: tip mass equal to the beam mass, w1 = 1.557298
    w1 = result.modes[0].frequency_hz * 2 * math.pi * math.sqrt(5000.0 * 80.0**4 / 5.0e10)
    assert w1 == pytest.approx(1.557298, rel=1e-6)


def test_arc_length_of_a_curved_reference_axis():
    # a quarter circle of radius 10 sampled at 200 points: chord-polygon length within (pi/400)^2/24 of 5 pi
    t = np.linspace(0, 1, 200)
    axis = {"x": Distribution(t, 10 - 10 * np.cos(t * np.pi / 2)), "y": Distribution(np.array([0.0, 1.0]),
                                                                                   np.zeros(2)),
            "z": Distribution(t, 10 * np.sin(t * np.pi / 2))}
    assert arc_length(axis) == pytest.approx(5 * math.pi, rel=1e-5)


def test_round_trip(tmp_path):
    original = read_windio(SMALL)
    write_windio(original, tmp_path / "turbine.yaml")
    again = read_windio(tmp_path / "turbine.yaml")
    assert again == original


def replaced(tmp_path: Path, old: str, new: str) -> Path:
    text = SMALL.read_text()
    assert old in text
    path = tmp_path / "bad.yaml"
    path.write_text(text.replace(old, new, 1))
    return path


@pytest.mark.parametrize(("old", "new", "line", "field"), [
    ("K44: [4.0e8, 4.0e8, 4.0e8]", "K44: [4.0e8, -4.0e8, 4.0e8]", 33,
     "components.blade.structure.elastic_properties.stiffness_matrix.K44.1"),
    ("K55: [1.0e8, 1.0e8, 1.0e8]", "K55: [1.0e8, 1.0e8]", 35,
     "components.blade.structure.elastic_properties.stiffness_matrix.K55"),
    ("grid: [0.0, 0.6, 1.0]", "grid: [0.0, 0.6, 0.5]", 38,
     "components.blade.structure.elastic_properties.inertia_matrix.grid"),
    ("mass: [100.0, 100.0, 100.0]", "mass: [100.0, abc, 100.0]", 39,
     "components.blade.structure.elastic_properties.inertia_matrix.mass.1"),
    ("    diameter: 4.0", "    diameter: four", 11, "components.hub.diameter"),
    ("  rotor_orientation: upwind", "  rotor_orientation: sideways", 8, "assembly.rotor_orientation"),
    ("      twist: {grid: [0.0, 1.0], values: [0.0, 0.0]}", "      twist: {grid: [0.0, 1.0]}", 24,
     "components.blade.outer_shape.twist.values"),
])
def test_malformed_file(tmp_path, old, new, line, field):
    path = replaced(tmp_path, old, new)
    with pytest.raises(InputError) as info:
        read_windio(path)
    assert (info.value.line, info.value.field) == (line, field)
    assert info.value.file == str(path)


def test_windio_1_blade_without_six_x_six_is_refused(tmp_path):
    # windIO 1.x is read natively (tests/test_beam_formats.py reads the IEA-15MW's own WT_Ontology file); a 1.x
    # blade whose elastic_properties_mb lacks its six_x_six matrices is refused at that key's line
    path = replaced(tmp_path, "    structure:\n      elastic_properties:\n        stiffness_matrix:\n"
                              "          grid: [0.0, 0.4, 1.0]",
                    "    elastic_properties_mb: {}\n    structure:\n      elastic_properties:\n"
                    "        stiffness_matrix:\n          grid: [0.0, 0.4, 1.0]")
    with pytest.raises(InputError) as info:
        read_windio(path)
    assert "six_x_six" in info.value.message and info.value.line == 25


def test_a_tower_without_elastic_properties_fails_alone(tmp_path):
    # windIO's converter leaves a 1.x tower with its layup and no elastic_properties: the blade still reads, the
    # tower is refused when asked for, naming its key
    path = replaced(tmp_path, "  tower:\n    reference_axis:", "  tower:\n    layup_only: true\n    reference_axis:")
    text = path.read_text()
    start = text.index("  tower:")
    path.write_text(text[:start] + text[start:].replace("    structure:\n      elastic_properties:",
                                                        "    structure:\n      layers:", 1))
    turbine = read_windio(path)
    assert turbine.tower is None and blade_from_windio(turbine).sections.flap_stiffness[0] == 1e8
    with pytest.raises(InputError) as info:
        tower_from_windio(turbine)
    assert "elastic_properties" in info.value.message
    assert info.value.field == "components.tower.structure.elastic_properties"


def test_outer_shape_chord_gives_the_planform_and_round_trips(tmp_path):
    # windIO's outer_shape.chord (m) becomes the section table's chord (for the VTK ribbon and pictures), linear
    # between its grid points, and survives write -> read
    text = SMALL.read_text().replace(
        "      twist: {grid: [0.0, 1.0], values: [0.0, 0.0]}\n",
        "      twist: {grid: [0.0, 1.0], values: [0.0, 0.0]}\n"
        "      chord: {grid: [0.0, 0.25, 1.0], values: [3.0, 4.0, 1.5]}\n", 1)
    source = tmp_path / "with_chord.yaml"
    source.write_text(text)
    turbine = read_windio(source)
    blade = blade_from_windio(turbine)
    fraction = blade.sections.span / blade.length
    np.testing.assert_allclose(blade.sections.chord, np.interp(fraction, [0.0, 0.25, 1.0], [3.0, 4.0, 1.5]))
    copy = tmp_path / "copy.yaml"
    write_windio(turbine, copy)
    assert read_windio(copy) == turbine
    assert blade_from_windio(read_windio(SMALL)).sections.chord is None


def test_tower_fore_aft_is_k55_and_side_side_k44(tmp_path):
    # windIO's tower axes (turbine_schema.yaml, the tower's reference_axis): x downwind, y lateral, z up; bending
    # about y (K55) moves the tower along x: fore-aft. A tower with K44 != K55 keeps them apart
    text = SMALL.read_text()
    start = text.index("  tower:")
    tower = text[start:].replace("K44: [5.0e10, 5.0e10, 5.0e10]", "K44: [2.0e10, 2.0e10, 2.0e10]", 1)
    path = tmp_path / "tower.yaml"
    path.write_text(text[:start] + tower)
    sections = tower_from_windio(read_windio(path)).sections
    assert sections.flap_stiffness[0] == 5.0e10 and sections.edge_stiffness[0] == 2.0e10
