"""Start-up stays light: ``bladefem --help`` and argument errors import no numerical library, and a blade ``modes``
run imports neither matplotlib nor scipy.optimize (the time is measured in bench/bench_startup.py; here the imports
that cost it are checked, each in a fresh interpreter)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("numpy", "scipy", "scipy.optimize", "matplotlib", "skfem", "meshio", "pyvista", "yaml", "rich")


def imported_after(argv: list[str]) -> tuple[int, set[str]]:
    """Exit code of ``bladefem ARGV`` run in a fresh interpreter, and the heavy modules it imported."""
    script = (
        "import json, sys\n"
        "from bladefem.cli import main\n"
        f"code = main({argv!r})\n"
        f"print(json.dumps([code, [m for m in {list(HEAVY)!r} if m in sys.modules]]), file=sys.stderr)\n")
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""), MPLBACKEND="Agg")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env, cwd=ROOT,
                          timeout=600)
    code, modules = json.loads(done.stderr.strip().splitlines()[-1])
    return code, set(modules)


@pytest.mark.parametrize("argv", [["--help"], ["--version"], ["modes", "--help"], ["campbell", "--help"],
                                  ["export", "--help"], ["report", "--help"], ["elastodyn", "--help"],
                                  ["verify", "--help"], ["turbine", "--help"], ["check", "--help"], ["batch", "--help"],
                                  ["modes", "cases/uniform_blade.yaml", "--rpm", "fast"], ["bogus"]])
def test_help_and_argument_errors_import_no_numerical_library(argv):
    code, modules = imported_after(argv)
    assert code in (0, 2)
    assert modules == set(), modules


def test_a_blade_modes_run_imports_neither_matplotlib_nor_scipy_optimize():
    code, modules = imported_after(["modes", "cases/nrel5mw_blade.yaml", "--n-modes", "2"])
    assert code == 0 and "numpy" in modules                        # it did solve
    assert not {"matplotlib", "scipy.optimize", "pyvista", "rich"} & modules, modules


def test_importing_bladefem_is_light():
    code = ("import sys, bladefem\n"
            f"print(sorted(m for m in {list(HEAVY)!r} if m in sys.modules))")
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=600)
    assert done.stdout.strip() == "[]"
