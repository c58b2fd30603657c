"""The paths that use a blade keep working with six-by-six sections, the shear condensed or kept (a Timoshenko
beam): Campbell with its mode tracking, the Coriolis (quadratic) eigenproblem, the ElastoDyn fit and the VTK
drawing, on a twisted, tapered blade with every coupling."""

from __future__ import annotations

import numpy as np
import pytest
from test_galerkin_full_sections import coupled_sections

from bladefem.outputs.vtk import write_vtk
from bladefem.modal import blade_matrices, campbell, modes
from bladefem.modal.elastodyn_fit import blade_coefficients
from bladefem.modal.quadratic import solve_quadratic_modes
from bladefem.sections import Blade


def blade(shear: bool = False) -> Blade:
    return Blade(coupled_sections((0.1, -0.04), [0.3, 0.0]).with_shear(shear).table(), hub_radius=1.5,
                 precone=np.radians(-3), pitch=0.05)


@pytest.mark.parametrize("shear", [False, True], ids=["condensed", "shear-flexible"])
def test_campbell_coriolis_elastodyn_and_vtk_run_on_six_by_six_sections(tmp_path, shear):
    b = blade(shear)
    chart = campbell(b, [0.0, 20.0, 40.0, 60.0], n_modes=6)
    assert [family.kind for family in chart.families][:3] == ["flap", "edge", "flap"]
    assert np.all(np.diff(chart.families[0].frequencies_hz) > 0)         # the first flap stiffens with speed
    at_rest = modes(b, 0.0, 6).frequencies_hz
    np.testing.assert_allclose([family.frequencies_hz[0] for family in chart.families], at_rest, rtol=1e-8)
    # without rotation the quadratic problem is the plain one
    quadratic = solve_quadratic_modes(blade_matrices(b, n_modes=6), 0.0, 6)
    np.testing.assert_allclose(quadratic.frequencies_hz, at_rest, rtol=1e-8)
    coefficients = blade_coefficients(b, 0.0)
    assert coefficients.fits
    write_vtk(b, chart, tmp_path)
    assert len(list(tmp_path.iterdir())) == 6
