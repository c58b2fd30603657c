"""What an installation carries: ``bladefem verify`` needs nothing outside the package (its NREL 5MW files are
package data), the metadata is complete with the version in one place, and public modules say what they export."""

from __future__ import annotations

import fnmatch
import importlib
import os
import shutil
import subprocess
import sys
import tomllib
import types
from pathlib import Path

import pytest

import bladefem

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())


def installed_copy(target: Path) -> Path:
    """The package as setuptools installs it: its Python modules and the package-data files pyproject names,
    nothing else of the repository."""
    patterns = PYPROJECT["tool"]["setuptools"]["package-data"]["bladefem"]
    source = ROOT / "bladefem"
    for path in source.rglob("*"):
        relative = path.relative_to(source).as_posix()
        if path.is_file() and (path.suffix == ".py" or any(fnmatch.fnmatch(relative, p) for p in patterns)):
            destination = target / "bladefem" / relative
            destination.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(path, destination)
    return target


def test_verify_data_are_package_data_identical_to_the_cases():
    from bladefem.verify import NREL5MW_MAIN
    assert (ROOT / "bladefem") in NREL5MW_MAIN.parents
    for name in ("NRELOffshrBsline5MW_Onshore_ElastoDyn.dat", "NRELOffshrBsline5MW_Blade.dat",
                 "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"):
        assert (NREL5MW_MAIN.parent / name).read_bytes() == (ROOT / "cases" / "nrel5mw" / name).read_bytes()


def test_verify_reads_its_nrel5mw_blade_from_an_installed_copy(tmp_path):
    site = installed_copy(tmp_path / "site")
    work = tmp_path / "elsewhere"                    # not the repository: no cases/ folder around
    work.mkdir()
    script = ("from bladefem.verify import NREL5MW_MAIN, nrel5mw_blade\n"
              "blade = nrel5mw_blade()\n"
              "print(NREL5MW_MAIN.is_relative_to(__import__('bladefem').__path__[0]), round(blade.length, 6))\n")
    env = dict(os.environ, PYTHONPATH=str(site))
    done = subprocess.run([sys.executable, "-c", script], cwd=work, env=env, capture_output=True, text=True,
                          timeout=600)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["True", "61.5"]


def test_metadata_and_one_version():
    project = PYPROJECT["project"]
    assert "version" not in project and project["dynamic"] == ["version"]
    assert PYPROJECT["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "bladefem.__version__"}
    assert project["authors"] and project["license"] == "MIT"
    classifiers = project["classifiers"]
    assert "Typing :: Typed" in classifiers and "Topic :: Scientific/Engineering" in classifiers
    assert any(c.startswith("Programming Language :: Python :: 3.11") for c in classifiers)
    assert (ROOT / "bladefem" / "py.typed").is_file()
    assert "py.typed" in PYPROJECT["tool"]["setuptools"]["package-data"]["bladefem"]



def test_the_command_reports_the_one_version(capsys):
    from bladefem.cli import main
    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"bladefem {bladefem.__version__}"


PUBLIC = ["bladefem", "bladefem.cli", "bladefem.errors", "bladefem.modal", "bladefem.sections", "bladefem.formats",
          "bladefem.builders", "bladefem.outputs",
          "bladefem.outputs.results", "bladefem.outputs.vtk", "bladefem.models", "bladefem.models.galerkin_converged",
          "bladefem.models.tower_campbell", "bladefem.plots", "bladefem.plots.campbell", "bladefem.plots.camera",
          "bladefem.plots.modes3d", "bladefem.plots.tower_campbell", "bladefem.plots.turbine_campbell",
          "bladefem.report", "bladefem.report_tower", "bladefem.verify"]


@pytest.mark.parametrize("name", PUBLIC)
def test_public_modules_declare_what_they_export(name):
    module = importlib.import_module(name)
    exported = module.__all__
    assert len(set(exported)) == len(exported)
    for symbol in exported:
        value = getattr(module, symbol)                          # every listed name exists
        assert not isinstance(value, types.ModuleType), symbol   # and is not an imported module such as np
    star: dict = {}
    exec(f"from {name} import *", star)
    assert not {"np", "Sequence", "replace", "annotations", "Path"} & set(star), name
