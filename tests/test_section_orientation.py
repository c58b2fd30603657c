"""The bent blade section's orientation (``bladefem.aero.polar``): the least rotation of the span axis onto the
deflected one (against scipy's rotation vectors), and AeroDyn's Euler angles of a section (against the matrix that
the NWTC library's ``EulerConstruct`` builds, NWTC_Num.f90: M = R(theta_z) R(theta_y) R(theta_x), change of basis)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from bladefem.aero.polar import bent_axes, euler_angles, euler_frame, section_angle, section_inflow


@pytest.mark.parametrize("v, w", [(0.0, 0.0), (0.0, 0.15), (0.02, 0.0), (0.015, 0.17), (-0.3, 0.5), (0.8, -0.6)])
def test_bent_axes_are_the_least_rotation_onto_the_deflected_axis(v, w):
    """Components along (i3, e_t, i1) = (x, y, z) of the turned normal, tangent and span axis equal scipy's
    rotation by the angle between i3 and s = (1, v, w) / L about i3 x s (a rotation axis normal to i3: no twist
    about the span), to 1e-15; with v = 0 the normal is (i1 - w i3) / sqrt(1 + w^2)."""
    n3, nt, n1, t3, tt, t1, s3, st, s1 = bent_axes(v, w)
    span = np.array([1.0, v, w]) / math.sqrt(1 + v * v + w * w)
    axis = np.cross([1.0, 0.0, 0.0], span)
    size = np.linalg.norm(axis)
    rotation = Rotation.from_rotvec(axis / size * math.atan2(size, span[0]) if size > 0 else np.zeros(3))
    expected = rotation.apply(np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]))
    np.testing.assert_allclose([[n3, nt, n1], [t3, tt, t1], [s3, st, s1]], expected, rtol=0, atol=1e-15)
    if v == 0.0:
        np.testing.assert_allclose([n3, nt, n1], np.array([-w, 0.0, 1.0]) / math.sqrt(1 + w * w), atol=1e-16)


def euler_construct(toe: float, cant: float, twist: float) -> np.ndarray:
    """NWTC's M = R(theta_z) R(theta_y) R(theta_x) with theta_x = toe, theta_y = cant, theta_z = -twist."""
    cx, sx, cy, sy = math.cos(toe), math.sin(toe), math.cos(cant), math.sin(cant)
    cz, sz = math.cos(-twist), math.sin(-twist)
    return np.array([[cy * cz, cx * sz + sx * sy * cz, sx * sz - cx * sy * cz],
                     [-cy * sz, cx * cz - sx * sy * sz, sx * cz + cx * sy * sz],
                     [sy, -sx * cy, cx * cy]])


@pytest.mark.parametrize("toe, cant, twist", [(0.0, 0.0, 0.0), (0.01, 0.17, 0.001), (-0.3, 0.5, 1.2),
                                              (2.0, -1.0, -2.5), (0.4, math.pi / 2, 0.0)])
def test_euler_angles_invert_the_nwtc_construction(toe, cant, twist):
    """The angles of the constructed matrix come back to 1e-12 (at cant = 90 deg, gimbal lock, as the NWTC
    library: the twist taken 0 and the toe from the second row)."""
    M = euler_construct(toe, cant, twist)
    angles = euler_angles(M[0, 0], M[0, 1], M[0, 2], M[1, 0], M[1, 1], M[1, 2], M[2, 0])
    np.testing.assert_allclose(angles, (toe, cant, twist), rtol=0, atol=1e-12)


@pytest.mark.parametrize("toe, cant, twist", [(0.0, 0.0, 0.0), (0.01, 0.17, 0.001), (-0.3, 0.5, 1.2),
                                              (2.0, -1.0, -2.5), (0.4, math.pi / 2, 0.0)])
def test_euler_frame_gives_the_cosines_and_sines_without_trigonometry(toe, cant, twist):
    """euler_frame's twist is euler_angles', and its cosines and sines of the twist, the cant and the toe (from the
    matrix entries) equal cos and sin of euler_angles' angles to 1e-15, gimbal lock included."""
    M = euler_construct(toe, cant, twist)
    entries = (M[0, 0], M[0, 1], M[0, 2], M[1, 0], M[1, 1], M[1, 2], M[2, 0])
    frame = euler_frame(*entries)
    toe_angle, cant_angle, twist_angle = euler_angles(*entries)
    assert frame[0] == twist_angle
    expected = [f(angle) for angle in (twist_angle, cant_angle, toe_angle) for f in (math.cos, math.sin)]
    np.testing.assert_allclose(frame[1:], expected, rtol=0, atol=1e-15)


def test_section_inflow_is_the_section_angle_with_its_sine_and_cosine():
    """section_inflow(phi, x, y) for phi = atan2(x, y) is section_angle's angle, and its sine and
    cosine (the atan2's arguments scaled to unit length) are those of that angle, to 1e-15, for plane and for
    canted and toed sections, the polar frame's inflow of either sign; both components zero give (phi, 0, 1)."""
    rng = np.random.default_rng(5)
    for _ in range(200):
        x, y = rng.normal(size=2) * rng.uniform(0.1, 80.0)
        cant, toe = (0.0, 0.0) if rng.uniform() < 0.3 else tuple(rng.uniform(-0.4, 0.4, size=2))
        phi = math.atan2(x, y)
        angle, sine, cosine = section_inflow(phi, x, y, math.cos(cant), math.sin(cant), math.cos(toe), math.sin(toe))
        assert abs(angle - section_angle(phi, cant, toe)) <= 1e-15 * max(1.0, abs(angle))
        np.testing.assert_allclose((sine, cosine), (math.sin(angle), math.cos(angle)), rtol=0, atol=1e-15)
    assert section_inflow(0.3, 0.0, 0.0, math.cos(0.1), math.sin(0.1), math.cos(0.2), math.sin(0.2)) == (0.3, 0.0, 1.0)
