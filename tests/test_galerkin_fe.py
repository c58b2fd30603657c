"""The Galerkin model against the finite elements: two independent discretisations of the same energies."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from bladefem.builders.case import read_case
from bladefem.builders.elastodyn_blade import blade_from_elastodyn_main
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


def turned_blade(angle: float, split: float = 0.6) -> Blade:
    """Uniform blade whose sections are all turned by ``angle`` (rad, twist ``split * angle`` plus pitch), with
    section inertias and a centre-of-mass offset, rigid torsion: the only cross-section couplings are the turned
    principal axes of stiffness and of rotary inertia."""
    sections = SectionTable(span=np.array([0.0, L]), mass=5.0, flap_stiffness=2e4, edge_stiffness=6e4,
                            twist=split * angle, flap_inertia=0.05, edge_inertia=0.5, cm_offset=0.2)
    return Blade(sections, pitch=(1 - split) * angle)


#: both methods, each with one fixed discretisation (the FE on 40 elements, converged to 1e-8 on these uniform blades)
SOLVERS = {"fe": lambda blade, n, rpm=0.0: modes(blade, rpm, n, elements=40),
           "galerkin": lambda blade, n, rpm=0.0: galerkin_modes(blade, rpm, n, (14, 14, 8))}


@pytest.mark.parametrize("solver", SOLVERS)
def test_turning_every_section_turns_the_modes_rigidly(solver):
    """At rest a cantilever has no preferred direction in the y-z plane: turning every section by the same angle
    turns the whole problem. Frequencies stay those of the untwisted blade; a flap mode moves along the thickness
    axis (sin, cos), so edge / flap = tan(angle) everywhere, an edge mode along the chord (cos, -sin).

    This ties the stiffness coupling EI_yz and the inertia product J_yz to the same turned axes: with either sign
    flipped the stiffness and the rotary inertia act about mirrored axes (measured with each sign flipped in
    bladefem.sections.moments: FE frequencies move by 3.4 %, shapes by 1.1 (EI_yz) or 0.15 (J_yz) of the tip
    deflection)."""
    angle = 0.5
    turned = SOLVERS[solver](turned_blade(angle), 6)
    straight = SOLVERS[solver](turned_blade(0.0), 6)
    assert turned.kinds == straight.kinds == ["flap", "edge", "flap", "edge", "flap", "edge"]
    # the same discrete problem turned: only round-off may differ (measured 2e-10 in frequency, 1e-10 in shape)
    np.testing.assert_allclose(turned.frequencies_hz, straight.frequencies_hz, rtol=1e-8)
    x = np.linspace(0.5, L, 20)
    for mode in turned.modes:
        shape = mode.shape.at(x)
        if mode.kind == "flap":
            np.testing.assert_allclose(shape["edge"], np.tan(angle) * shape["flap"], atol=1e-8)
        else:
            np.testing.assert_allclose(shape["flap"], -np.tan(angle) * shape["edge"], atol=1e-8)


@pytest.mark.parametrize("solver", SOLVERS)
def test_propeller_moment_follows_the_pitched_section(solver):
    """Torsion of a uniform blade without offsets (docs/THEORY.md): the propeller moment adds
    1/2 Omega^2 (i_edge - i_flap) cos(2 theta) phi^2, theta = twist + pitch, to the potential while the polar inertia
    i_edge + i_flap stays; no term couples phi to bending here, so for every torsion mode
    omega^2 = omega_0^2 + Omega^2 (i_edge - i_flap) cos(2 theta) / (i_edge + i_flap)."""
    i_flap, i_edge, GJ, theta = 0.02, 0.3, 200.0, 0.6
    sections = SectionTable(span=np.array([0.0, L]), mass=5.0, flap_stiffness=2e4, edge_stiffness=6e4,
                            torsion_stiffness=GJ, twist=0.25, flap_inertia=i_flap, edge_inertia=i_edge)
    blade = Blade(sections, pitch=theta - 0.25)
    rpm = 60.0
    rest = SOLVERS[solver](blade, 12)
    spinning = SOLVERS[solver](blade, 12, rpm)
    omega = rpm * np.pi / 30
    for n in (1, 2):
        w0 = 2 * np.pi * rest.first("torsion", n).frequency_hz
        w = 2 * np.pi * spinning.first("torsion", n).frequency_hz
        expected = np.sqrt(w0**2 + omega**2 * (i_edge - i_flap) * np.cos(2 * theta) / (i_edge + i_flap))
        # the same discretisation at both speeds: round-off only (measured 1e-13); the shift is 35 % and 4 %
        assert w == pytest.approx(expected, rel=1e-8)
        assert w / w0 - 1 > 0.01


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
    # measured <= 5.3e-7 (the FE's own mesh tolerance is 1e-6): bending, torsion, their couplings and all the
    # centrifugal terms are the same in both models. The Galerkin model derives its section stiffness and inertia
    # itself (models/galerkin_sections.py), so this also checks the FE's bladefem.sections.moments: a flipped sign of
    # EI_yz there moves the difference to 0.8-1.5 %, of J_yz to 0.1-0.4 % (measured)
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
        # the 40-term Galerkin is converged to about 1e-4 on this blade (kinked properties; measured 7.7e-5 against
        # the FE, which is converged to 1e-6); the acceptance was 0.1 %
        np.testing.assert_allclose(g_family.frequencies_hz, fe_family.frequencies_hz, rtol=1.5e-4)
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
    # the section): the same properties and assumptions in both. Measured with 30 terms each: torsion 2.3e-5,
    # bending <= 1.7e-4 (the polynomial series converges algebraically on the kinked 5MW properties)
    blade = read_case(Path(__file__).resolve().parent.parent / "cases" / "nrel5mw_blade.yaml")
    s = blade.sections
    sections = replace(s, torsion_stiffness=0.3 * s.flap_stiffness, edge_inertia=s.mass * (0.25 * s.chord) ** 2,
                       flap_inertia=s.mass * (0.06 * s.chord) ** 2)
    blade = blade.with_(sections=sections)
    fe, galerkin = modes(blade, rpm, 8), galerkin_modes(blade, rpm, 8, terms=(30, 30, 30))
    for kind, number, bound in [("torsion", 1, 5e-5), ("flap", 1, 3e-4), ("edge", 1, 3e-4), ("flap", 2, 3e-4),
                                ("edge", 2, 3e-4)]:
        assert galerkin.first(kind, number).frequency_hz == pytest.approx(fe.first(kind, number).frequency_hz,
                                                                          rel=bound), (kind, number)
