"""Property-based invariants of the FE model (hypothesis)."""

from __future__ import annotations

import numpy as np
import scipy.linalg as la
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bladefem.assembly import assemble_blade
from bladefem.modal import converged_matrices, solve_modes
from bladefem.sections import Blade, SectionTable, TipMass

SETTINGS = settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@st.composite
def blades(draw) -> Blade:
    """Random twisted, tapered blades with offsets, inertias, optional torsion, hub radius, precone and tip mass."""
    n = draw(st.integers(3, 7))
    length = draw(st.floats(5.0, 80.0))
    interior = draw(st.lists(st.integers(1, 19), min_size=n - 2, max_size=n - 2, unique=True))
    span = np.concatenate([[0.0], np.sort(interior) / 20.0, [1.0]]) * length
    positive = st.floats(0.3, 3.0)
    # realistic taper: neighbouring stations differ by at most 1.5x (a factor of 30 within one interval leaves the
    # mesh pre-asymptotic until round-off takes over; bladefem then says so in the notes)
    steps = np.array([draw(st.floats(1 / 1.5, 1.5)) for _ in range(n - 1)])
    scale = draw(positive) * np.concatenate([[1.0], np.cumprod(steps)])
    sections = SectionTable(
        span=span, mass=300.0 * scale, flap_stiffness=1e9 * scale**2 * draw(positive),
        edge_stiffness=3e9 * scale**2 * draw(positive),
        torsion_stiffness=(5e8 * scale**2 if draw(st.booleans()) else None),
        twist=np.radians(np.linspace(draw(st.floats(0, 20)), 0.0, n)),
        flap_inertia=2.0 * scale, edge_inertia=20.0 * scale,
        cm_offset=0.1 * np.array([draw(st.floats(-1, 1)) for _ in range(n)]))
    tip = TipMass(draw(st.floats(0, 50)), offset=[draw(st.floats(0, 0.5)), 0, 0]) if draw(st.booleans()) else None
    return Blade(sections, hub_radius=draw(st.floats(0, 5)), precone=np.radians(draw(st.floats(-5, 5))),
                 pitch=np.radians(draw(st.floats(-10, 10))), tip_mass=tip)


def frequencies(blade: Blade, rpm: float = 0.0, n: int = 5, elements: int = 24) -> np.ndarray:
    return solve_modes(assemble_blade(blade, elements), rpm, n).frequencies_hz


def scaled_mass(blade: Blade, k: float) -> Blade:
    tip = blade.tip_mass
    return blade.with_(sections=blade.sections.scaled(mass=k),
                       tip_mass=None if tip is None else TipMass(tip.mass * k, tip.offset, tip.inertia * k))


@SETTINGS
@given(blades(), st.floats(0.2, 5.0))
def test_mass_scaling_divides_frequencies_by_sqrt_k(blade, k):
    # at rest M -> k M with K unchanged (section and tip masses and inertias all scaled): omega / sqrt(k)
    np.testing.assert_allclose(frequencies(scaled_mass(blade, k)), frequencies(blade) / np.sqrt(k), rtol=1e-7)


@SETTINGS
@given(blades(), st.floats(0.2, 5.0))
def test_mass_scaling_with_rotation_leaves_centrifugal_share_unchanged(blade, k):
    # rotating: K2 scales with the mass too, so K0/k + Omega^2 K2 against M: scaling mass by k equals scaling the
    # elastic stiffness by 1/k (a second, independent route through the code)
    lighter_stiffness = blade.with_(sections=blade.sections.scaled(stiffness=1 / k))
    np.testing.assert_allclose(frequencies(scaled_mass(blade, k), 10.0), frequencies(lighter_stiffness, 10.0),
                               rtol=1e-7)


@SETTINGS
@given(blades(), st.floats(0.2, 5.0))
def test_stiffness_scaling_multiplies_frequencies_by_sqrt_k(blade, k):
    stiffer = blade.with_(sections=blade.sections.scaled(stiffness=k))
    np.testing.assert_allclose(frequencies(stiffer), frequencies(blade) * np.sqrt(k), rtol=1e-7)


@SETTINGS
@given(blades())
def test_flap_frequencies_rise_with_rotor_speed(blade):
    blade = blade.with_(precone=0.0)
    speeds = [0.0, 5.0, 10.0, 15.0]
    first_flap = [solve_modes(assemble_blade(blade, 16), rpm, 6).first("flap").frequency_hz for rpm in speeds]
    assert np.all(np.diff(first_flap) > 0)


@SETTINGS
@given(blades())
def test_matrices_symmetric_and_mass_positive_definite(blade):
    matrices = assemble_blade(blade, 12)
    for name in ("K0", "K2", "M"):
        A = getattr(matrices, name)
        assert abs(A - A.T).max() <= 1e-12 * abs(A).max(), name
    M = matrices.M[matrices.free][:, matrices.free].toarray()
    assert la.eigvalsh(M)[0] > 0


@SETTINGS
@given(blades())
def test_memory_layout_of_inputs_does_not_matter(blade):
    # the same stations handed over as reversed-and-reversed (negative-stride) views and Fortran-ordered copies
    s = blade.sections
    def strided(a):
        return None if a is None else np.asfortranarray(a[::-1].copy()[::-1])
    other = SectionTable(span=strided(s.span), mass=strided(s.mass), flap_stiffness=strided(s.flap_stiffness),
                         edge_stiffness=strided(s.edge_stiffness), torsion_stiffness=strided(s.torsion_stiffness),
                         twist=strided(s.twist), flap_inertia=strided(s.flap_inertia),
                         edge_inertia=strided(s.edge_inertia), cm_offset=strided(s.cm_offset))
    np.testing.assert_array_equal(frequencies(blade.with_(sections=other), 7.0), frequencies(blade, 7.0))


@settings(max_examples=5, deadline=None)
@given(blades())
def test_refining_a_converged_mesh_changes_nothing(blade):
    # beyond convergence the mesh does not matter: the automatic mesh (error < 1e-6 claimed) and one twice as fine
    # agree within 1e-6. (Four times as fine is no better reference: on short stiff blades such meshes already sit
    # on the round-off floor, which grows as h^-4: a 5 m blade at 770 elements is off by 3e-6.)
    automatic = converged_matrices(blade, 4, rpm=12.0)
    assert not automatic.notes
    finer = assemble_blade(blade, 2 * (len(automatic.dofs.nodes) - 1))
    np.testing.assert_allclose(solve_modes(automatic, 12.0, 4).frequencies_hz,
                               solve_modes(finer, 12.0, 4).frequencies_hz, rtol=1e-6)
