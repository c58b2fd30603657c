"""Every example script runs (examples are also tests); the seed comparison in docs/ is what its script writes."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"


def run(script: str, *arguments: str) -> str:
    completed = subprocess.run([sys.executable, str(EXAMPLES / script), *arguments], capture_output=True, text=True,
                               cwd=ROOT, timeout=600)
    assert completed.returncode == 0, completed.stderr
    return completed.stdout


def test_quickstart(tmp_path):
    output = run("quickstart.py", str(tmp_path))
    assert "flap" in output and (tmp_path / "campbell.png").stat().st_size > 20_000


def test_rotating_uniform_beam_prints_the_table():
    rows = [line.split() for line in run("rotating_uniform_beam.py").splitlines()[1:]]
    values = np.array(rows, dtype=float)
    # FE column against the published column (6 digits) and the in-plane relation, as the printout claims
    np.testing.assert_allclose(values[:, 1], values[:, 2], rtol=1e-4)
    np.testing.assert_allclose(values[:, 3], values[:, 4], rtol=1e-8)


def test_elastodyn_coefficients_example():
    output = run("elastodyn_coefficients.py")
    assert all(name in output for name in ("flap1", "flap2", "edge1", "fa1", "ss2"))


def test_seed_comparison_document_is_current(tmp_path):
    # docs/seed-comparison.md must be exactly what the example writes now (regenerate it after model changes)
    written = tmp_path / "seed-comparison.md"
    run("seed_comparison.py", "--output", str(written))
    assert written.read_text() == (ROOT / "docs" / "seed-comparison.md").read_text()
