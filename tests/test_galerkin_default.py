"""The Galerkin model's default is converged: terms are added until the requested frequencies settle to the finite
elements' tolerance, and the terms used are reported; ``--terms 5,5,3`` keeps the paper's truncation."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from bladefem.cli import main
from bladefem.modal import MESH_RTOL
from bladefem.models.galerkin import galerkin_modes
from bladefem.models.galerkin_converged import MAX_TERMS, converged_galerkin_modes, grown
from bladefem.verify import rigid_section_uniform_blade

#: uniform cantilever at rest (m = EI = L = 1): omega_n = b_n^2, b_n the roots of 1 + cos b cosh b = 0
FLAP = [1.87510407**2, 4.69409113**2, 7.85475744**2]


def flap_omegas(result) -> list[float]:
    return [2 * math.pi * mode.frequency_hz for mode in result.modes if mode.kind == "flap"][:3]


def test_paper_truncation_is_stiff_and_the_default_is_converged():
    blade = rigid_section_uniform_blade()
    paper = flap_omegas(galerkin_modes(blade, 0.0, 6, (5, 5, 3)))
    assert paper[2] / FLAP[2] - 1 > 0.02                     # measured +2.5 % on the third flap frequency
    result = converged_galerkin_modes(blade, 0.0, 6)
    # settled to the FE's 1e-6 between the last two term counts; the references have 9 digits
    np.testing.assert_allclose(flap_omegas(result), FLAP, rtol=MESH_RTOL)
    assert any("N_w, N_v, N_phi = 18, 18" in note for note in result.notes)     # 5 -> 8 -> 12 -> 18 terms
    assert any("changed by less than 1e-06" in note for note in result.notes)


def test_terms_grow_by_half_and_the_growth_stops_at_its_cap():
    assert grown((5, 5, 3)) == (8, 8, 5) and grown((1, 1, 0)) == (2, 2, 0)
    blade = rigid_section_uniform_blade()
    result = converged_galerkin_modes(blade, 0.0, 3, rtol=1e-30, max_terms=8)     # cannot settle to 1e-30
    assert any("stopped at 8, 8" in note for note in result.notes)
    assert MAX_TERMS >= 40


def test_cli_default_and_fixed_terms(capsys):
    case = "cases/uniform_blade.yaml"
    assert main(["modes", case, "--method", "galerkin", "--n-modes", "6", "--json"]) == 0
    converged = json.loads(capsys.readouterr().out)
    assert any("grown until" in note for note in converged["notes"])
    assert main(["modes", case, "--method", "galerkin", "--n-modes", "6", "--json", "--terms", "5,5,3"]) == 0
    paper = json.loads(capsys.readouterr().out)
    assert any("N_w, N_v, N_phi = 5, 5, 3" in note for note in paper["notes"])
    assert not any("grown until" in note for note in paper["notes"])
    assert main(["modes", case, "--n-modes", "6", "--json"]) == 0
    fe = json.loads(capsys.readouterr().out)
    # the converged Galerkin model and the FE agree to the FE's tolerance (both converged, 2e-6 for their sum);
    # the paper's truncation does not
    np.testing.assert_allclose(converged["frequencies_hz"], fe["frequencies_hz"], rtol=2 * MESH_RTOL)
    assert max(abs(np.array(paper["frequencies_hz"]) / fe["frequencies_hz"] - 1)) > 1e-5


def test_terms_without_galerkin_is_a_user_error(capsys):
    assert main(["modes", "cases/uniform_blade.yaml", "--terms", "5,5,3"]) == 2
    assert "field '--terms'" in capsys.readouterr().err


@pytest.mark.parametrize("terms", ["5,5", "0,5,3", "a,b,c"])
def test_bad_terms_are_one_line_errors(terms, capsys):
    assert main(["modes", "cases/uniform_blade.yaml", "--method", "galerkin", "--terms", terms]) == 2
    assert "field '--terms'" in capsys.readouterr().err
