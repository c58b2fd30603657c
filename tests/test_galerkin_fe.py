"""The Galerkin model against the finite elements: two independent discretisations of the same energies."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from bladefem.io.case import read_case
from bladefem.io.elastodyn_blade import blade_from_elastodyn_main
from bladefem.modal import campbell, modes
from bladefem.models.galerkin import galerkin_campbell, galerkin_modes
from bladefem.sections import Blade, SectionTable, TipMass

MAIN_FILE = Path(__file__).parents[1] / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
L = 10.0


def coupled_uniform_sections() -> SectionTable:
    """Uniform properties with everything that couples: twist, torsion, section inertias, cm offset."""
    return SectionTable(span=np.array([0.0, L]), mass=5.0, flap_stiffness=2e4, edge_stiffness=6e4,
                        torsion_stiffness=4e3, twist=np.array([0.3, 0.0]), flap_inertia=0.02, edge_inertia=0.25,
                        cm_offset=0.08)


def relative_difference(galerkin, fe) -> float:
    assert galerkin.kinds == fe.kinds
    return float(np.max(np.abs(galerkin.frequencies_hz / fe.frequencies_hz - 1)))


@pytest.mark.parametrize("lam", [0.0, 6.0, 12.0])
def test_uniform_rotating_blade_agrees_with_fe(lam):
    blade = Blade(SectionTable(span=np.array([0.0, 1.0]), mass=1.0, flap_stiffness=1.0, edge_stiffness=4.0))
    rpm = lam * 30 / np.pi                                     # m = EI = L = 1: lambda = Omega
    difference = relative_difference(galerkin_modes(blade, rpm, 6, (14, 14, 0)), modes(blade, rpm, 6))
    # acceptance 1e-5; the FE mesh is refined to 1e-6, the 14-term Galerkin is converged to 1e-9
    assert difference < 1e-5


@pytest.mark.parametrize("geometry", [dict(), dict(hub_radius=1.5, precone=np.radians(-4), pitch=0.1)],
                         ids=["plain", "hub-precone-pitch"])
@pytest.mark.parametrize("rpm", [0.0, 40.0])
def test_coupled_uniform_blade_agrees_with_fe(geometry, rpm):
    blade = Blade(coupled_uniform_sections(), **geometry)
    difference = relative_difference(galerkin_modes(blade, rpm, 8, (14, 14, 10)), modes(blade, rpm, 8))
    # measured <= 2.5e-7 (the FE's own mesh tolerance is 1e-6): bending, torsion, their couplings and all the
    # centrifugal terms are the same in both models
    assert difference < 1e-5


def test_tip_mass_with_offsets_and_inertia_agrees_with_fe():
    tip = TipMass(3.0, offset=[0.1, 0.05, 0.02], inertia=[0.05, 0.02, 0.03])
    blade = Blade(coupled_uniform_sections(), hub_radius=1.5, precone=np.radians(-4), pitch=0.1, tip_mass=tip)
    difference = relative_difference(galerkin_modes(blade, 40.0, 8, (16, 16, 30)), modes(blade, 40.0, 8))
    # the torsion sines all have phi'(L) = 0 while a tip body loads the tip in torsion: the torsion series converges
    # only algebraically (measured 3.1e-4, 1.8e-4, 6e-5 with 6, 10, 30 sines); bound 1e-4 for 30 sines
    assert difference < 1e-4


def test_nrel5mw_agrees_with_fe_from_0_to_15_rpm():
    blade = blade_from_elastodyn_main(MAIN_FILE)
    rpm = [0.0, 3.0, 6.0, 9.0, 12.0, 15.0]
    fe = campbell(blade, rpm, n_modes=4)
    galerkin = galerkin_campbell(blade, rpm, n_modes=4, terms=(40, 40, 0))
    for fe_family, g_family in zip(fe.families, galerkin.families):
        assert fe_family.kind == g_family.kind
        # acceptance 0.1%: the 40-term Galerkin is converged to about 1e-4 on this blade (kinked properties)
        np.testing.assert_allclose(g_family.frequencies_hz, fe_family.frequencies_hz, rtol=1e-3)
    assert [family.kind for family in fe.families] == ["flap", "edge", "flap", "edge"]


def stacked_shape(mode, x) -> np.ndarray:
    shape = mode.shape.at(x)
    return np.concatenate([shape["flap"], shape["edge"], shape["twist"] * 10.0])   # twist times ~ a chord, m


def test_mode_shapes_agree_with_fe():
    blade = Blade(coupled_uniform_sections(), hub_radius=1.5)
    x = blade.sections.span
    fe = modes(blade, 20.0, 4)
    galerkin = galerkin_modes(blade, 20.0, 4, (16, 16, 24))
    for g_mode, fe_mode in zip(galerkin.modes, fe.modes):
        g, f = stacked_shape(g_mode, x), stacked_shape(fe_mode, x)
        g = g * (f @ g) / (g @ g)              # the two methods may scale a mode differently
        # the torsion sines converge algebraically in shape when twist couples to bending (measured 3e-6 relative
        # with 24 sines); the FE shape is converged to about 1e-6
        np.testing.assert_allclose(g, f, atol=2e-5 * np.abs(f).max())


@pytest.mark.parametrize("rpm", [0.0, 7.5, 15.0])
def test_nrel5mw_first_torsion_mode_with_assumed_torsion_properties(rpm):
    # the ElastoDyn data carry no GJ or section mass inertias, so this compares the two methods on the 5MW with an
    # ASSUMED torsion distribution (GJ = 0.3 EI_flap; mass radii of gyration 0.25 chord along and 0.06 chord through
    # the section): the same properties and assumptions in both. First torsion and the first four bending modes
    # within 0.1 % (measured: torsion 2.3e-5, bending <= 1.6e-4 with 30 terms each)
    blade = read_case(Path(__file__).resolve().parent.parent / "cases" / "nrel5mw_blade.yaml")
    s = blade.sections
    sections = replace(s, torsion_stiffness=0.3 * s.flap_stiffness, edge_inertia=s.mass * (0.25 * s.chord) ** 2,
                       flap_inertia=s.mass * (0.06 * s.chord) ** 2)
    blade = blade.with_(sections=sections)
    fe, galerkin = modes(blade, rpm, 8), galerkin_modes(blade, rpm, 8, terms=(30, 30, 30))
    for kind, number in [("torsion", 1), ("flap", 1), ("edge", 1), ("flap", 2), ("edge", 2)]:
        assert galerkin.first(kind, number).frequency_hz == pytest.approx(fe.first(kind, number).frequency_hz,
                                                                          rel=1e-3), (kind, number)
