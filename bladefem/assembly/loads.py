"""The centrifugal load on the blade as a load vector, per Omega^2: what deflects a blade at its operating point
(a prebent blade's centrifugal load bends it back toward the rotor plane; an offset centre of mass twists it);
and the blade's weight at an azimuth."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..elements.rigid_slice import EPS
from ..sections import Blade, mass_moments
from .dofs import DofMap
from .forms import Quadrature
from .parameters import axis_position, plane_of_rotation


def centrifugal_load_density(blade: Blade, x: NDArray) -> NDArray:
    """Generalized centrifugal force per length per Omega^2 on the section kinematic vector ``(u, v, w, phi, -w',
    v')`` in each section's frame, shape (6, ...): the force ``Q (m r + S)`` and the moment ``S x Q r + int rho s x
    Q s`` about the axis point, ``Q`` the plane-of-rotation projection and ``r`` the point from the apex."""
    moments = mass_moments(blade.sections, x, blade.pitch)
    frame = blade.axis_frame(np.asarray(x, dtype=float))
    Q = plane_of_rotation(blade)
    r = np.zeros((3,) + np.shape(x))
    r[0] = blade.hub_radius + x
    if frame is not None:
        Q, r = frame.tensor_to_local(Q), frame.to_local(axis_position(blade, frame))
    Q = np.broadcast_to(Q.reshape(Q.shape + (1,) * (Q.ndim == 2) * np.ndim(x)), (3, 3) + np.shape(x))
    Qr = np.einsum("ij...,j...->i...", Q, r)
    force = moments.m * Qr + np.einsum("ij...,j...->i...", Q, moments.S)
    moment = (np.einsum("abc,b...,c...->a...", EPS, moments.S, Qr)
              + np.einsum("abc,cd...,bd...->a...", EPS, Q, moments.J))
    return np.concatenate([force, moment])


def load_vector(quadrature: Quadrature, density: NDArray) -> NDArray:
    """``b_i = int phi_i . g dx`` for a density ``g`` on the kinematic vector (6, elements, points), over all DOFs."""
    local = np.einsum("fieq,feq,eq->ie", quadrature.functions.kinematic, density, quadrature.weights)
    return np.bincount(quadrature.element_dofs.ravel(), weights=local.ravel(), minlength=quadrature.size)


def tip_geometry(blade: Blade) -> tuple[NDArray, NDArray]:
    """The plane-of-rotation projection and the tip's position from the apex in the tip node's frame: the blade
    frame, or the local frame at the tip of a curved axis (where the tip mass's offset and inertia are given)."""
    P = plane_of_rotation(blade)
    frame = blade.axis_frame(np.array(blade.length))
    if frame is None:
        return P, np.array([blade.tip_radius, 0.0, 0.0])
    return frame.tensor_to_local(P), frame.to_local(axis_position(blade, frame))


def centrifugal_load(quadrature: Quadrature, blade: Blade, dofs: DofMap) -> NDArray:
    """The centrifugal load vector per Omega^2 over all DOFs, N s^2 (sections and tip mass)."""
    b = load_vector(quadrature, centrifugal_load_density(blade, quadrature.points))
    tip = blade.tip_mass
    if tip is not None and tip.mass > 0:
        Q, r = tip_geometry(blade)
        S = tip.mass * tip.offset
        moment = np.cross(S, Q @ r) + np.einsum("abc,cd,bd->a", EPS, Q, tip.second_moment)
        T = dofs.kinematic_selector(len(dofs.nodes) - 1)
        b = b + T.T @ np.concatenate([Q @ (tip.mass * r + S), moment])
    return b


def gravity_load_density(blade: Blade, x: NDArray) -> NDArray:
    """The weight per length on the section kinematic vector ``(u, v, w, phi, -w', v')`` in each section's frame,
    N/m and N, shape (6, ...): the force ``m g`` and its moment ``S x g`` about the axis point."""
    moments = mass_moments(blade.sections, x, blade.pitch)
    g = np.broadcast_to(blade.gravity_vector.reshape((3,) + (1,) * np.ndim(x)), (3,) + np.shape(x))
    frame = blade.axis_frame(np.asarray(x, dtype=float))
    if frame is not None:
        g = frame.to_local(g)
    return np.concatenate([moments.m * g, np.einsum("abc,b...,c...->a...", EPS, moments.S, g)])


def gravity_load(quadrature: Quadrature, blade: Blade, dofs: DofMap) -> NDArray:
    """The weight's load vector over all DOFs, N (sections and tip mass; zeros without gravity)."""
    if blade.gravity is None:
        return np.zeros(dofs.size)
    b = load_vector(quadrature, gravity_load_density(blade, quadrature.points))
    tip = blade.tip_mass
    if tip is not None and tip.mass > 0:
        frame = blade.axis_frame(np.array(blade.length))
        g = blade.gravity_vector if frame is None else frame.to_local(blade.gravity_vector)
        T = dofs.kinematic_selector(len(dofs.nodes) - 1)
        b = b + T.T @ np.concatenate([tip.mass * g, np.cross(tip.mass * tip.offset, g)])
    return b
