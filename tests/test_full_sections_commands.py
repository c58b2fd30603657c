"""Every command on a blade with full six-by-six sections (the IEA-15MW BeamDyn blade, the default path): modes,
Campbell with Coriolis, VTK export, report, check, the ElastoDyn fit (its documented reductions) and batch
scaling."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from bladefem.batch.cases import apply_inputs
from bladefem.builders.detect import read_model
from bladefem.errors import InputError
from bladefem.modal import modes
from bladefem.modal.elastodyn_fit import blade_coefficients
from bladefem.sections.principal import elastodyn_sections

DATA = Path(__file__).parent / "data"
FOLDER = DATA / "iea15" / "beamdyn"
BD15 = FOLDER / "IEA-15-240-RWT_BeamDyn.dat"
ED15 = FOLDER / "IEA-15-240-RWT_ElastoDyn_blade.dat"


def bladefem(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "bladefem", *args], capture_output=True, text=True, cwd=cwd)


@pytest.mark.parametrize("args", [
    ("modes", "--n-modes", "4"),
    ("campbell", "--coriolis", "--rpm", "0:8:3", "--n-modes", "4"),
])
def test_commands_print_on_full_sections(args):
    done = bladefem(args[0], str(BD15), *args[1:])
    assert done.returncode == 0, done.stderr
    assert "full six-by-six sections in the FE" in done.stdout


def test_export_and_report_write_their_files(tmp_path):
    done = bladefem("export", str(BD15), "--vtk", "-o", str(tmp_path / "vtk"), "--n-modes", "3")
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "vtk" / "modes.pvd").is_file()
    done = bladefem("report", str(BD15), "-o", str(tmp_path / "report"))
    assert done.returncode == 0, done.stderr
    text = (tmp_path / "report" / "report.md").read_text()
    assert "full six-by-six sections" in text


def test_check_on_full_sections(tmp_path):
    shutil.copy(BD15, tmp_path / BD15.name)
    shutil.copy(FOLDER / "IEA-15-240-RWT_BeamDyn_blade.dat", tmp_path)
    spec = tmp_path / "spec.yaml"
    spec.write_text(f"""models:
  blade: {{input: {BD15.name}, operating_rpm: [5.0, 7.56]}}
requirements:
  - {{name: flap 1 window, model: blade, window: {{mode: flap 1, hz: [0.50, 0.56]}}}}
""")
    done = bladefem("check", str(spec))
    assert done.returncode == 0, done.stdout + done.stderr
    spec.write_text(spec.read_text().replace("[0.50, 0.56]", "[0.60, 0.70]"))
    assert bladefem("check", str(spec)).returncode == 1
    # the spec chooses the section model like --sections; a value outside the two is a schema error (exit 2)
    reduced = spec.read_text().replace("operating_rpm", "sections: reduced, operating_rpm")
    spec.write_text(reduced.replace("[0.60, 0.70]", "[0.50, 0.56]"))
    assert bladefem("check", str(spec)).returncode == 0
    spec.write_text(reduced.replace("sections: reduced", "sections: diagonal"))
    done = bladefem("check", str(spec))
    assert done.returncode == 2 and "sections" in done.stderr


def test_elastodyn_reduction_of_full_sections():
    # ElastoDyn holds mass, principal flap and edge stiffnesses about the tension centre and the twist that turns
    # them: from the full sections that is exactly the diagonal reduction's principal columns (to round-off)
    full = read_model(BD15).sections
    reduced = read_model(BD15, sections="reduced").sections
    held = elastodyn_sections(full)
    assert held.full is None and held.torsion_stiffness is None and not np.any(held.cm_offset)
    for name in ("mass", "flap_stiffness", "edge_stiffness", "twist"):
        np.testing.assert_allclose(getattr(held, name), getattr(reduced, name), rtol=1e-9, atol=1e-12, err_msg=name)
    assert not np.any(elastodyn_sections(full, twisted=False).twist)


def test_elastodyn_fit_on_full_sections_and_its_reductions():
    # the fit's own ElastoDyn integrals take what the ElastoDyn file holds (the reduction above); on the untwisted
    # reduction (OpenFAST's guidance) ElastoDyn's frequencies equal the FE's: the polynomials can carry those modes
    # exactly (measured 0.00 %), held to 0.01 %
    blade = read_model(BD15, hub_radius=3.97, axis="straight")      # ElastoDyn's blade is straight
    untwisted = blade.with_(sections=elastodyn_sections(blade.sections, twisted=False))
    result = blade_coefficients(untwisted, 7.56)
    for fit in result.fits.values():
        assert abs(fit.elastodyn_frequency_hz / fit.fe_frequency_hz - 1) < 1e-4
    # what each keeps of the full model's frequencies at rated, the shear condensed in both (ElastoDyn's beam is
    # Euler-Bernoulli; measured: twisted reduction flap 1 +0.09 %, edge 1 +0.03 %, flap 2 +1.0 % (no torsion);
    # untwisted flap 1 -0.4 %, edge 1 +1.3 %)
    full = blade_coefficients(read_model(BD15, hub_radius=3.97, sections="condensed", axis="straight"), 7.56).fits
    twisted = blade_coefficients(blade.with_(sections=elastodyn_sections(blade.sections)), 7.56).fits
    for name, tolerance in (("flap1", 2e-3), ("edge1", 1e-3), ("flap2", 1.5e-2)):
        assert abs(twisted[name].fe_frequency_hz / full[name].fe_frequency_hz - 1) < tolerance, name


def test_elastodyn_command_options(tmp_path):
    done = bladefem("elastodyn", str(BD15), "--rpm", "7.56", "--elastodyn-compatible", "untwisted")
    assert done.returncode == 0, done.stderr
    assert "--elastodyn-compatible: FE modes of ElastoDyn's section model" in done.stdout
    # --write onto an ElastoDyn blade file, as a dry run (a copy with the labels spelled as this reader knows them)
    text = ED15.read_text()
    for old, new in (("BldFlDmp1 ", "BldFlDmp(1)"), ("BldFlDmp2 ", "BldFlDmp(2)"), ("BldEdDmp1 ", "BldEdDmp(1)"),
                     ("FlStTunr1 ", "FlStTunr(1)"), ("FlStTunr2 ", "FlStTunr(2)")):
        text = text.replace(old, new)
    target = tmp_path / "blade.dat"
    target.write_text(text)
    done = bladefem("elastodyn", str(BD15), "--rpm", "7.56", "--write", str(target), "--dry-run", "--force")
    assert done.returncode == 0, done.stderr
    assert "BldFl1Sh(2)" in done.stdout and target.read_text() == text


def test_batch_scales_full_sections():
    blade = read_model(BD15)
    base = modes(blade, 0.0, 4).frequencies_hz
    # the whole stiffness (or mass) times 1.21: every frequency times 1.1 (or divided by it), exactly
    stiffer = modes(apply_inputs(blade, {"stiffness_scale": 1.21}), 0.0, 4).frequencies_hz
    np.testing.assert_allclose(stiffer, 1.1 * base, rtol=1e-6)
    heavier = modes(apply_inputs(blade, {"mass_scale": 1.21}), 0.0, 4).frequencies_hz
    np.testing.assert_allclose(heavier, base / 1.1, rtol=1e-6)
    # one column: its diagonal entry times the factor, its couplings by the square root (coefficients kept)
    scaled = apply_inputs(blade, {"flap_stiffness_scale": 1.1}).sections.full
    K, K0 = scaled.stiffness, blade.sections.full.stiffness
    np.testing.assert_allclose(K[:, 4, 4], 1.1 * K0[:, 4, 4], rtol=1e-12)
    coefficient = K[:, 4, 5] / np.sqrt(K[:, 4, 4] * K[:, 5, 5])
    np.testing.assert_allclose(coefficient, K0[:, 4, 5] / np.sqrt(K0[:, 4, 4] * K0[:, 5, 5]), rtol=1e-12)
    flap = modes(blade.with_(sections=scaled.table()), 0.0, 4).frequencies_hz
    assert 1.0 < flap[0] / base[0] < np.sqrt(1.1)
    with pytest.raises(InputError, match="no 'flap_inertia' column"):
        apply_inputs(blade, {"flap_inertia_scale": 1.1})
