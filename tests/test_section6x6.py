"""The reduction of a six-by-six section (BeamDyn's axes) to bladefem's diagonal beam, term by term against closed
forms: the parallel-axis theorem for the tension centre and the centre of mass, the condensed shear, and the
principal-axis turn checked on a uniform cantilever's first mode (its frequency and its direction)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bladefem.builders.section6x6 import reduce, section_table
from bladefem.modal import modes
from bladefem.sections import Blade


def diagonal(EA=1e10, EI_x=4e8, EI_y=1e8, GJ=1e7, GA=1e9, m=100.0, i_x=0.0, i_y=0.0):
    K = np.diag([GA, GA, EA, EI_x, EI_y, GJ])[None].astype(float)
    M = np.diag([m, m, m, i_x, i_y, i_x + i_y])[None].astype(float)
    return K, M


def test_tension_centre_by_the_parallel_axis_theorem():
    # EA at y_C = 0.3 m toward the trailing edge, x_C = 0.05 m toward the suction side: about the reference axis
    # K34 = EA y_C, K35 = -EA x_C, K44 = EI_x + EA y_C^2, K55 = EI_y + EA x_C^2, K45 = -EA x_C y_C
    K, M = diagonal()
    EA, y, x = 1e10, 0.3, 0.05
    K[0, 2, 3] = K[0, 3, 2] = EA * y
    K[0, 2, 4] = K[0, 4, 2] = -EA * x
    K[0, 3, 3] += EA * y**2
    K[0, 4, 4] += EA * x**2
    K[0, 3, 4] = K[0, 4, 3] = -EA * x * y
    r = reduce(K, M)
    assert r.edge_stiffness[0] == pytest.approx(4e8, rel=1e-9)
    assert r.flap_stiffness[0] == pytest.approx(1e8, rel=1e-9)
    assert r.principal_angle[0] == pytest.approx(0.0, abs=1e-12)
    assert r.tension_centre_offset[0] == pytest.approx(-0.3, rel=1e-12)        # bladefem: toward the leading edge
    assert r.dropped["thickness-wise tension-centre offset (m)"][0] == pytest.approx(0.05, rel=1e-12)


def test_centre_of_mass_and_inertias_by_the_parallel_axis_theorem():
    # BeamDyn's mass matrix about the reference axis (input_files.rst) for a centre of mass at y_G = 0.7 m
    # (toward the trailing edge): M34 = m y_G, M16 = -m y_G, M44 = i_G + m y_G^2
    K, M = diagonal(i_x=50.0, i_y=5.0)
    m, y = 100.0, 0.7
    M[0, 2, 3] = M[0, 3, 2] = m * y
    M[0, 0, 5] = M[0, 5, 0] = -m * y
    M[0, 3, 3] += m * y**2
    M[0, 5, 5] += m * y**2
    r = reduce(K, M)
    assert r.cm_offset[0] == pytest.approx(-0.7, rel=1e-12)
    assert r.edge_inertia[0] == pytest.approx(50.0, rel=1e-12) and r.flap_inertia[0] == pytest.approx(5.0, rel=1e-12)


def test_shear_torsion_coupling_is_condensed():
    # with the shear forces free (slender beam) a shear-torsion coupling K16 lowers the torsional stiffness to
    # K66 - K16^2 / K11 (the Schur complement); the coupling is named with its size
    K, M = diagonal()
    K[0, 0, 5] = K[0, 5, 0] = 0.4 * math.sqrt(1e9 * 1e7)
    r = reduce(K, M)
    assert r.torsion_stiffness[0] == pytest.approx(1e7 - 0.16 * 1e9 * 1e7 / 1e9, rel=1e-12)
    assert r.dropped["shear-torsion coupling K16"][0] == pytest.approx(0.4, rel=1e-12)


@pytest.mark.parametrize("angle_deg", [20.0, -35.0])
def test_principal_axes_turn_the_first_mode(angle_deg):
    # a uniform 50 m cantilever whose principal bending axes are turned by phi about +z (BeamDyn's axes) from the
    # chord: EI = 4e8 about x' = (cos phi, sin phi), 1e8 about y' = (-sin phi, cos phi). Its first mode bends about
    # y', the deflection along x'; in bladefem's axes (flap z = x, edge y = -y) edge / flap = -tan(phi). Its
    # frequency is the cantilever's, 1.87510407^2 sqrt(EI / (m L^4)) with EI = 1e8 (no rotary inertia)
    phi = math.radians(angle_deg)
    c, s = math.cos(phi), math.sin(phi)
    e1, e2 = np.array([c, s]), np.array([-s, c])
    K, M = diagonal()
    K[0, 3:5, 3:5] = 4e8 * np.outer(e1, e1) + 1e8 * np.outer(e2, e2)
    span = np.array([0.0, 50.0])
    table, notes = section_table(span, np.repeat(K, 2, axis=0), np.repeat(M, 2, axis=0), np.zeros(2))
    assert table.flap_stiffness[0] == pytest.approx(1e8, rel=1e-12)
    result = modes(Blade(sections=table), 0.0, 2, elements=40)
    first = result.modes[0]
    expected = 1.87510407**2 * math.sqrt(1e8 / (100 * 50.0**4)) / (2 * math.pi)
    assert first.frequency_hz == pytest.approx(expected, rel=2e-6)
    assert first.shape.edge[-1] / first.shape.flap[-1] == pytest.approx(-math.tan(phi), rel=1e-6)
    assert any("principal axes" in note for note in notes)
