"""The IEA-15MW blade frequencies published in 2020 (Gaertner et al., NREL/TP-5000-75698, Table 2.1: 0.555 Hz flap,
0.642 Hz edge, isolated blade) are those of the v1.0 blade's ElastoDyn file (tests/data/iea15/v1.0/), clamped and
parked, as an Euler-Bernoulli beam; the repository's current files describe the 2021 redesign, whose frequencies
differ (docs/iea-blades.md)."""

from __future__ import annotations

from pathlib import Path

import pytest

from bladefem.builders.detect import Geometry, read_model
from bladefem.modal import modes

DATA = Path(__file__).parent / "data" / "iea15"
#: published to three decimals, computed by another beam solver from the same distributed properties: one unit of
#: the last published digit (measured: 0.5555 and 0.6414 Hz, 0.5 and 0.6 of a unit)
LAST_DIGIT = 0.001


def first_flap_and_edge(path: Path) -> tuple[float, float]:
    blade = read_model(str(path), "blade", Geometry(tip_radius=120.97, hub_radius=3.97))
    result = modes(blade, 0.0, 6)
    flap = next(m.frequency_hz for m in result.modes if m.kind == "flap")
    edge = next(m.frequency_hz for m in result.modes if m.kind == "edge")
    return flap, edge


def test_the_2020_blade_gives_the_published_frequencies():
    flap, edge = first_flap_and_edge(DATA / "v1.0" / "IEA-15-240-RWT_ElastoDyn_blade.dat")
    assert flap == pytest.approx(0.555, abs=LAST_DIGIT)
    assert edge == pytest.approx(0.642, abs=LAST_DIGIT)


def test_the_redesigned_blade_does_not():
    flap, edge = first_flap_and_edge(DATA / "IEA-15-240-RWT" / "IEA-15-240-RWT_ElastoDyn_blade.dat")
    assert abs(flap - 0.555) > 0.01 and abs(edge - 0.642) > 0.05


def test_a_quoted_blade_file_name_with_blanks_reads(tmp_path):
    """OpenFAST reads a quoted file name holding blanks (the 2020 IEA-15MW BeamDyn primary names its blade file
    "IEA 15MW Offshore Reference Turbine, with taped chord tip design_BeamDyn_Blade.dat"); so does bladefem."""
    source = DATA / "beamdyn"
    name = "IEA 15MW blade, with blanks_BeamDyn_Blade.dat"
    (tmp_path / name).write_bytes((source / "IEA-15-240-RWT_BeamDyn_blade.dat").read_bytes())
    primary = (source / "IEA-15-240-RWT_BeamDyn.dat").read_text()
    lines = [f'"{name}"    BldFile - blade file' if line.split()[1:2] == ["BldFile"] else line
             for line in primary.splitlines()]
    (tmp_path / "primary.dat").write_text("\n".join(lines) + "\n")
    blade = read_model(str(tmp_path / "primary.dat"), "blade", Geometry())
    reference = read_model(str(source / "IEA-15-240-RWT_BeamDyn.dat"), "blade", Geometry())
    assert blade.sections.length == reference.sections.length
    assert modes(blade, 0.0, 2).modes[0].frequency_hz == modes(reference, 0.0, 2).modes[0].frequency_hz
