"""BeamDyn's six-by-six axes onto bladefem's section frame (bladefem.builders.section_axes)."""

from __future__ import annotations

import numpy as np
import pytest

from bladefem.builders.section_axes import beamdyn_permutation, full_sections_from_beamdyn

#: the NREL 5MW BeamDyn blade's root station: OpenFAST docs/source/user/beamdyn/examples/nrel_5mw_blade.inp
#: (commit 2895884d2be01862173c88d70f86b358d2f1a50a, Apache-2.0): K11, K22 shear, K33 EA, K44 EI_edge, K55 EI_flap,
#: K66 GJ; the mass m, i_edge, i_flap, i_plr
ROOT_K = np.diag([9.729480e08, 9.729480e08, 9.729480e09, 1.811360e10, 1.811000e10, 5.564400e09])
ROOT_M = np.diag([6.789350e02, 6.789350e02, 6.789350e02, 9.730400e02, 9.728600e02, 1.945900e03])


def test_permutation_is_a_proper_rotation():
    P = beamdyn_permutation()
    assert np.allclose(P @ P.T, np.eye(6))
    assert np.linalg.det(P[:3, :3]) == pytest.approx(1.0)
    assert np.array_equal(P[:3, :3], P[3:, 3:])


def test_nrel5mw_root_station_lands_on_the_named_stiffnesses():
    sections = full_sections_from_beamdyn([0.0, 61.5], [ROOT_K, ROOT_K], [ROOT_M, ROOT_M], [0.2323, 0.0])
    summary = sections.summary()
    assert summary["axial_stiffness"][0] == pytest.approx(9.729480e09)
    assert summary["edge_stiffness"][0] == pytest.approx(1.811360e10)     # BeamDyn K44, about X (= zeta)
    assert summary["flap_stiffness"][0] == pytest.approx(1.811000e10)     # BeamDyn K55, about Y (= -eta)
    assert summary["torsion_stiffness"][0] == pytest.approx(5.564400e09)
    # BeamDyn's i_Edg (M44, about X) is the spread along the chord: bladefem's edge inertia
    assert summary["edge_inertia"][0] == pytest.approx(9.730400e02)
    assert summary["flap_inertia"][0] == pytest.approx(9.728600e02)


def test_offsets_follow_the_axes():
    """BeamDyn's mass matrix (input_files.rst, 0-based: M[2, 3] = m Y_cm, M[2, 4] = -m X_cm) and the stiffness
    offsets alike (K[2, 3] = EA Y_t, K[2, 4] = -EA X_t, the fibre strain eps + kappa_X Y - kappa_Y X): bladefem's
    eta = -Y, zeta = X."""
    m, X_cm, Y_cm, EA, X_t, Y_t = 500.0, 0.12, -0.4, 1e10, 0.05, 0.3
    K = np.diag([1e9, 1e9, EA, 2e10, 1e10, 5e9])
    K[2, 3] = K[3, 2] = EA * Y_t
    K[2, 4] = K[4, 2] = -EA * X_t
    K[3, 3] += EA * Y_t**2
    K[4, 4] += EA * X_t**2
    K[3, 4] = K[4, 3] = -EA * X_t * Y_t
    M = np.diag([m, m, m, 900.0, 300.0, 1200.0])
    M[0, 5] = M[5, 0] = -m * Y_cm
    M[1, 5] = M[5, 1] = m * X_cm
    M[2, 3] = M[3, 2] = m * Y_cm
    M[2, 4] = M[4, 2] = -m * X_cm
    sections = full_sections_from_beamdyn([0.0, 50.0], [K, K], [M, M], [0.0, 0.0])
    classical = sections.classical(np.array(1.0))
    assert -classical[0, 3] / classical[0, 0] == pytest.approx(-Y_t)      # eta of the tension centre
    assert classical[0, 2] / classical[0, 0] == pytest.approx(X_t)        # zeta of the tension centre
    moments = sections.mass_moments(np.array([1.0]))
    assert moments.S[:, 0] == pytest.approx([0.0, -m * Y_cm, m * X_cm])   # zeta = z at zero twist
