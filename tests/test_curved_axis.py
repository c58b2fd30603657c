"""The curved reference axis (prebend and sweep) against independent references: a circular-arc cantilever's tip
deflections by Castigliano's theorem (the curved beam's coupling of out-of-plane bending with torsion, and of
in-plane bending with extension), rigid motions of a free curved beam, a straight blade tilted out of the rotor
plane against the same blade preconed, and a blade with zero prebend against the straight model."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sl
import scipy.sparse.linalg as spla
from scipy.integrate import quad

from bladefem.assembly import assemble_blade
from bladefem.assembly.loads import centrifugal_load
from bladefem.errors import InputError
from bladefem.modal import modes
from bladefem.sections import Blade, ReferenceAxis, SectionTable, TipMass, uniform_sections

R, ALPHA = 10.0, 0.5                   # arc radius (m) and angle (rad): 5 m long, turning 29 deg
EI_FLAP, EI_EDGE, GJ, EA = 2.0e5, 6.0e5, 1.0e5, 4.0e6


def arc_blade(**changes) -> Blade:
    """A uniform cantilever on a circular arc curving downwind (out of the rotor plane): z0 = R (1 - cos(s / R))."""
    length = R * ALPHA
    s = np.linspace(0.0, length, 81)
    axis = ReferenceAxis(s, np.zeros_like(s), R * (1 - np.cos(s / R)))
    sections = uniform_sections(length, 10.0, EI_FLAP, EI_EDGE, GJ, EA)
    return Blade(sections, axis=axis, **changes)


def tip_displacement(blade: Blade, load_local: np.ndarray) -> np.ndarray:
    """Static (u, v, w) at the tip, local frame, under a tip force given in the tip's local frame (N)."""
    m = assemble_blade(blade, 120)
    b = np.zeros(m.dofs.size)
    for name, force in zip("uvw", load_local):
        b[m.dofs.value[name][-1]] += force
    q = np.zeros(m.dofs.size)
    q[m.free] = spla.spsolve(m.K0[m.free][:, m.free].tocsc(), b[m.free])
    return np.array([q[m.dofs.value[name][-1]] for name in "uvw"])


def test_arc_cantilever_out_of_plane_load_bends_and_twists_it():
    """A tip load P normal to the arc's plane: bending M = P R sin(psi) and torque T = P R (1 - cos(psi)) at the
    angle psi from the tip, so delta = P R^3 int_0^alpha sin^2 / EI + (1 - cos)^2 / GJ dpsi (Castigliano)."""
    P = 100.0
    expected = P * R**3 * quad(lambda p: np.sin(p) ** 2 / EI_EDGE + (1 - np.cos(p)) ** 2 / GJ, 0.0, ALPHA)[0]
    v = tip_displacement(arc_blade(), np.array([0.0, P, 0.0]))[1]
    assert v == pytest.approx(expected, rel=2e-5)
    straight = P * (R * ALPHA) ** 3 / (3 * EI_EDGE)
    assert v / straight - 1 > 0.05                       # the torsion the curve brings in is worth 5 % here


def test_arc_cantilever_in_plane_load_bends_and_stretches_it():
    """A tip load P along z (downwind) in the arc's plane, at the angle theta from the root: bending moment
    P R (sin(alpha) - sin(theta)), axial force P sin(theta); delta_z = P R int_0^alpha R^2 (sin alpha - sin theta)^2
    / EI + sin^2(theta) / EA dtheta."""
    P = 100.0
    expected = P * R * quad(lambda t: R**2 * (np.sin(ALPHA) - np.sin(t)) ** 2 / EI_FLAP + np.sin(t) ** 2 / EA,
                            0.0, ALPHA)[0]
    u, _, w = tip_displacement(arc_blade(), P * np.array([np.sin(ALPHA), 0.0, np.cos(ALPHA)]))
    assert u * np.sin(ALPHA) + w * np.cos(ALPHA) == pytest.approx(expected, rel=2e-5)


def test_a_free_curved_beam_moves_rigidly_without_strain():
    """Six rigid motions of a free beam curved in both planes (prebend and sweep) cost no strain energy: the
    curvature terms of every strain are complete and consistent."""
    s = np.linspace(0.0, 4.5, 61)
    axis = ReferenceAxis(s, 0.3 * R * (1 - np.cos(s / R)), -R * (1 - np.cos(s / R)))
    blade = Blade(uniform_sections(4.5, 10.0, EI_FLAP, EI_EDGE, GJ, EA, 0.1, 0.3), axis=axis, root="free")
    m = assemble_blade(blade, 60)
    values = sl.eigh(m.K0.toarray(), m.M.toarray(), eigvals_only=True)[:7]
    assert np.all(np.abs(values[:6]) < 1e-8 * values[6])


def offset_sections(length: float) -> SectionTable:
    """Uniform sections with a chordwise centre-of-mass offset, rotary inertias and a twist."""
    span = np.array([0.0, length])
    return SectionTable(span=span, mass=np.full(2, 12.0), flap_stiffness=np.full(2, 2e5),
                        edge_stiffness=np.full(2, 6e5), torsion_stiffness=np.full(2, 1e5),
                        axial_stiffness=np.full(2, 4e6), twist=np.array([0.3, 0.1]), flap_inertia=np.full(2, 0.1),
                        edge_inertia=np.full(2, 0.4), cm_offset=np.full(2, 0.2))


@pytest.mark.parametrize("rpm", [0.0, 40.0])
def test_a_tilted_straight_axis_is_precone(rpm):
    """A straight axis leaving the pitch axis downwind at the angle gamma, with the hub radius 0, is the same blade
    as one preconed by gamma more: every centrifugal, gyroscopic and tip-mass term on the curve (spin softening,
    the tension along the tangent, the position of each section, the Coriolis matrix, the centrifugal load) reproduces the preconed
    blade's, matrix by matrix."""
    gamma, precone, length = np.radians(12.0), np.radians(5.0), 10.0
    s = np.linspace(0.0, length, 11)
    tip = TipMass(3.0, offset=[0.1, 0.05, 0.02], inertia=[0.2, 0.1, 0.1])
    tilted = Blade(offset_sections(length), precone=precone, tip_mass=tip,
                   axis=ReferenceAxis(s, np.zeros_like(s), s * np.sin(gamma)))
    preconed = Blade(offset_sections(length), precone=precone + gamma, tip_mass=tip)
    np.testing.assert_allclose(modes(tilted, rpm, 8, elements=30).frequencies_hz,
                               modes(preconed, rpm, 8, elements=30).frequencies_hz, rtol=1e-10)
    a, b = assemble_blade(tilted, 30), assemble_blade(preconed, 30)
    for name in ("K0", "K2", "M", "G"):                      # the Coriolis matrix too
        difference = abs(getattr(a, name) - getattr(b, name)).max()
        assert difference <= 1e-10 * abs(getattr(b, name)).max(), name
    loads = [centrifugal_load(m.quadrature, blade, m.dofs) for m, blade in ((a, tilted), (b, preconed))]
    np.testing.assert_allclose(loads[0], loads[1], atol=1e-10 * np.max(np.abs(loads[1])))


def test_zero_prebend_reproduces_the_straight_blade():
    """A reference axis on the pitch axis (zero prebend and sweep) is today's straight blade, to 1e-10."""
    length = 10.0
    s = np.linspace(0.0, length, 6)
    kwargs = dict(hub_radius=1.5, precone=np.radians(-3.0), pitch=0.1, tip_mass=TipMass(2.0, offset=[0.1, 0.0, 0.0]))
    on_axis = Blade(offset_sections(length), axis=ReferenceAxis(s, np.zeros_like(s), np.zeros_like(s)), **kwargs)
    straight = Blade(offset_sections(length), **kwargs)
    for rpm in (0.0, 30.0):
        np.testing.assert_allclose(modes(on_axis, rpm, 8, elements=30).frequencies_hz,
                                   modes(straight, rpm, 8, elements=30).frequencies_hz, rtol=1e-10)


def test_prebend_lowers_edge_and_raises_torsion_frequencies_through_their_coupling():
    """On a uniform blade prebent like the IEA-15MW (4 % of the length upwind at the tip), the curve couples edgewise
    bending with torsion: edge modes fall, the torsion mode rises, flap barely moves."""
    length = 100.0
    s = np.linspace(0.0, length, 21)
    sections = uniform_sections(length, 600.0, 2e9, 6e9, 4e8, 2e10, 2.0, 20.0)
    curved = Blade(sections, axis=ReferenceAxis(s, np.zeros_like(s), -4.0 * (s / length) ** 2))
    a, b = modes(curved, 0.0, 6, elements=40), modes(Blade(sections), 0.0, 6, elements=40)
    change = a.frequencies_hz / b.frequencies_hz - 1
    kinds = b.kinds
    assert a.kinds == kinds
    assert all(change[i] < 0 for i, k in enumerate(kinds) if k == "edge")
    assert all(change[i] > 0 for i, k in enumerate(kinds) if k == "torsion")


def test_the_axis_is_checked():
    s = np.linspace(0.0, 10.0, 5)
    with pytest.raises(InputError, match="turns"):
        ReferenceAxis(s, np.zeros(5), s)                                 # 45 degrees off the pitch axis
    with pytest.raises(InputError, match="start on the pitch axis"):
        ReferenceAxis(s, np.zeros(5), np.ones(5))
    with pytest.raises(InputError, match="long"):
        Blade(uniform_sections(10.0, 1.0, 1.0, 1.0, 1.0, 1.0), axis=ReferenceAxis(s * 1.1, np.zeros(5), 0.01 * s))
    with pytest.raises(InputError, match="axial stiffness"):
        modes(Blade(uniform_sections(10.0, 1.0, 1.0, 1.0), axis=ReferenceAxis(s, np.zeros(5), 0.01 * s**2)), 0.0, 2)


def test_the_curved_blade_is_drawn_on_its_axis():
    """The drawing's axis points lie on the arc (x = R sin(s / R), z = R (1 - cos(s / R))), its chord turned with
    the local frame (perpendicular to the tangent)."""
    from bladefem.outputs.vtk_geometry import axis_positions, local_to_blade

    blade = arc_blade()
    s = np.array([0.0, 2.0, R * ALPHA])
    expected = np.stack([R * np.sin(s / R), np.zeros(3), R * (1 - np.cos(s / R))], axis=-1)
    np.testing.assert_allclose(axis_positions(blade, s), expected, atol=1e-7)
    normal = local_to_blade(blade, s, np.tile([0.0, 0.0, 1.0], (3, 1)))
    np.testing.assert_allclose(normal, np.stack([-np.sin(s / R), np.zeros(3), np.cos(s / R)], axis=-1), atol=1e-7)


def test_centrifugal_load_deflects_a_preconed_blade_as_the_beam_formulas():
    """The centrifugal load per Omega^2 on a uniform blade preconed by beta (hub radius 0): along the axis m cos^2(b)
    x, which stretches it by u(L) = m cos^2(b) L^3 / (3 EA); out of the rotor plane -m sin(b) cos(b) x, a load rising
    linearly to q0 = -m sin(b) cos(b) L, which bends it by 11 q0 L^4 / (120 EI) at the tip (K0 q = b)."""
    beta, length, m = np.radians(6.0), 10.0, 10.0
    blade = Blade(uniform_sections(length, m, EI_FLAP, EI_EDGE, GJ, EA), precone=beta)
    matrices = assemble_blade(blade, 40)
    b = centrifugal_load(matrices.quadrature, blade, matrices.dofs)
    q = np.zeros(matrices.dofs.size)
    free = matrices.free
    q[free] = spla.spsolve(matrices.K0[free][:, free].tocsc(), b[free])
    c, s = np.cos(beta), np.sin(beta)
    assert q[matrices.dofs.value["u"][-1]] == pytest.approx(m * c**2 * length**3 / (3 * EA), rel=1e-9)
    assert q[matrices.dofs.value["w"][-1]] == pytest.approx(-11 * m * s * c * length**5 / (120 * EI_FLAP), rel=1e-9)


def test_pitch_turns_the_curved_axis_about_the_pitch_axis():
    """Pitching a prebent blade turns its axis about the pitch axis with the sections: the same blade as one
    unpitched whose axis is the turned curve (offsets (z0 sin p, z0 cos p)) and whose twist is p more, matrix by
    matrix, at speed with precone."""
    from dataclasses import replace

    length, pitch = 10.0, 0.4
    s = np.linspace(0.0, length, 11)
    z0 = -0.015 * s**2
    sections = offset_sections(length)
    pitched = Blade(sections, precone=0.05, hub_radius=1.0, pitch=pitch,
                    axis=ReferenceAxis(s, np.zeros_like(s), z0))
    turned = Blade(replace(sections, twist=sections.twist + pitch), precone=0.05, hub_radius=1.0,
                   axis=ReferenceAxis(s, z0 * np.sin(pitch), z0 * np.cos(pitch)))
    a, b = assemble_blade(pitched, 20), assemble_blade(turned, 20)
    for name in ("K0", "K2", "M", "G"):
        assert abs(getattr(a, name) - getattr(b, name)).max() <= 1e-10 * abs(getattr(b, name)).max(), name


@pytest.mark.parametrize("load", ["in-plane", "out-of-plane"])
def test_shear_flexible_arc_cantilever_against_castigliano(load):
    """The curved Timoshenko beam (shear deflections on the curve, the extension taking the whole deflection): the
    arc cantilevers above with the shear forces' complementary energy added, ``int Q^2 / (k GA) ds``: in plane the
    shear force is ``P cos(theta)`` (across the chord, ``k GA`` normal), out of plane ``P`` (along the chord). Soft
    shear (``3 EI / (k GA L^2)`` 0.2 to 0.5) so that its share, 3 to 25 % of the deflection, is tested."""
    from bladefem.sections import FullSections, mass_matrix, stiffness_matrix

    ga_chord, ga_normal = 1.0e6, 1.5e5
    K = stiffness_matrix(EA, GJ, EI_FLAP, EI_EDGE, ga_chord, ga_normal)
    full = FullSections([0.0, R * ALPHA], [K, K], [mass_matrix(10.0)] * 2, shear_flexible=True)
    blade = arc_blade().with_(sections=full.table())
    m = assemble_blade(blade, 120)
    assert "w_s" in m.dofs.fields
    P, names = 100.0, {"u": ("u",), "v": ("v", "v_s"), "w": ("w", "w_s")}
    if load == "in-plane":
        force = P * np.array([np.sin(ALPHA), 0.0, np.cos(ALPHA)])
        shear = P * R * quad(lambda t: np.cos(t) ** 2 / ga_normal, 0.0, ALPHA)[0]
        expected = P * R * quad(lambda t: R**2 * (np.sin(ALPHA) - np.sin(t)) ** 2 / EI_FLAP + np.sin(t) ** 2 / EA,
                                0.0, ALPHA)[0] + shear
    else:
        force = np.array([0.0, P, 0.0])
        shear = P * R * ALPHA / ga_chord
        expected = P * R**3 * quad(lambda p: np.sin(p) ** 2 / EI_EDGE + (1 - np.cos(p)) ** 2 / GJ, 0.0, ALPHA)[0] + shear
    b = np.zeros(m.dofs.size)
    for name, f in zip("uvw", force):
        for field in names[name]:
            b[m.dofs.value[field][-1]] += f            # the force works on the whole deflection
    q = np.zeros(m.dofs.size)
    q[m.free] = spla.spsolve(m.K0[m.free][:, m.free].tocsc(), b[m.free])
    tip = np.array([m.dofs.displacement(q[:, None], name)[-1, 0] for name in "uvw"])
    assert tip @ force / P == pytest.approx(expected, rel=2e-5)
    assert shear / expected > 0.03
