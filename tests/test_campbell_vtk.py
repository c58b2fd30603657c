"""``bladefem campbell --vtk DIR``: the diagram's mode shapes as VTK, the same families and frequencies as the
table, for blades and towers; a folder that is a file is a one-line error."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from bladefem.cli import main
from bladefem.outputs.vtk import read_vtk

CASES = Path(__file__).resolve().parent.parent / "cases"


def test_blade_campbell_writes_every_family_at_every_speed(tmp_path, capsys):
    assert main(["campbell", str(CASES / "nrel5mw_blade.yaml"), "--rpm", "0:15:4", "--n-modes", "4", "--json",
                 "--vtk", str(tmp_path / "vtk")]) == 0
    table = json.loads(capsys.readouterr().out)
    export = read_vtk(tmp_path / "vtk" / "campbell.json")
    assert [speed["rotor_speed_rpm"] for speed in export["speeds"]] == pytest.approx([0, 5, 10, 15])
    written = np.array([[mode["frequency_hz"] for mode in speed["modes"]] for speed in export["speeds"]])
    families = np.array([family["frequencies_hz"] for family in table["families"]]).T
    np.testing.assert_allclose(written, families, rtol=1e-12)
    axis = export["speeds"][-1]["meshes"]["axis"]
    assert {f"mode{k:02d}_{family['kind']}_displacement" for k, family in enumerate(table["families"], 1)} <= set(
        axis.point_data)


def test_tower_campbell_writes_the_tower_modes(tmp_path, capsys):
    assert main(["campbell", str(CASES / "nrel5mw_tower.yaml"), "--rpm", "6.9:12.1:3", "--n-modes", "4", "--json",
                 "--vtk", str(tmp_path / "vtk")]) == 0
    chart = json.loads(capsys.readouterr().out)
    export = read_vtk(tmp_path / "vtk" / "campbell.json")
    assert export["structure"] == "tower" and len(export["speeds"]) == 1
    written = [mode["frequency_hz"] for mode in export["speeds"][0]["modes"]]
    np.testing.assert_allclose(written, [mode["frequency_hz"] for mode in chart["modes"]], rtol=1e-12)


def test_a_file_in_place_of_the_folder_is_refused_before_solving(tmp_path, capsys):
    taken = tmp_path / "taken"
    taken.write_text("keep")
    assert main(["campbell", str(CASES / "nrel5mw_blade.yaml"), "--rpm", "0:15:4", "--vtk", str(taken)]) == 2
    error = capsys.readouterr().err.strip().splitlines()
    assert len(error) == 1 and "--vtk" in error[0] and taken.read_text() == "keep"
