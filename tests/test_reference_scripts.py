"""The scripts that wrote the stored OpenFAST references (tests/data/openfast) still run: each imports, and those
built on the IEA-15MW decks write their decks (a refactor of the shared deck writer had left two of them calling
functions that no longer existed). OpenFAST itself is not needed: the runs were checked by hand to reproduce the
stored references (the rigid rotor's means to 7 digits, the blade's linearization frequencies to 4)."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

DATA = Path(__file__).resolve().parent / "data" / "openfast"
SCRIPTS = sorted(DATA.rglob("*.py"))


def load(path: Path):
    """The script as a module (its siblings' ``write_decks`` imported afresh: several folders have one)."""
    for folder in (DATA, path.parent):
        if str(folder) not in sys.path:
            sys.path.insert(0, str(folder))
    sys.modules.pop("write_decks", None)
    name = f"reference_{path.parent.name}_{path.stem}"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("path", SCRIPTS, ids=[str(p.relative_to(DATA)) for p in SCRIPTS])
def test_every_reference_script_imports(path):
    """Each script imports in a fresh interpreter, from the repository root (as their docstrings run them)."""
    code = f"import runpy; runpy.run_path({str(path)!r}, run_name='reference_script')"
    done = subprocess.run([sys.executable, "-c", code], cwd=DATA.parents[2], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]


def test_the_blade_linearization_writes_its_decks(tmp_path):
    """make_blade_aeroelastic_iea15.py: the straightened blade with aerodynamics (AeroDyn's offsets and cant 0) and
    without."""
    script = load(DATA / "make_blade_aeroelastic_iea15.py")
    for aero in (True, False):
        fst = script.write_case(tmp_path / f"aero{aero}", 13.5, aero)
        text = fst.read_text()
        assert fst.exists() and (fst.parent / "bd.dat").exists()
        assert any(line.split()[:2] == ["2" if aero else "0", "CompAero"] for line in text.splitlines())


def test_the_rigid_rotor_writes_its_decks(tmp_path):
    """iea15_rigid_rotor/write_decks.py: the held rotor at each stored case, and the flexible one."""
    script = load(DATA / "iea15_rigid_rotor" / "write_decks.py")
    for case in script.CASES:
        ed = script.write_case(tmp_path / script.name(case), case, "libdiscon.so").parent / script.rosco.ED
        assert any(line.split()[:2] == ["False", "FlapDOF1"] for line in ed.read_text().splitlines())
    assert script.write_flexible(tmp_path / "flexible", "libdiscon.so").exists()
