"""Collective blade pitch changed during a simulation, on the compiled kernels' arrays, in place.

A model is built at one pitch ``p0``: the blade's mode shapes are twisted by the structural twist plus ``p0``
(ElastoDyn's ``TwistedSF``, :func:`bladefem.modal.elastodyn_integrals.principal_directions`) and the aerodynamic
sections are set at twist plus ``p0``. Pitching to ``p`` turns every shape's across components (in-plane ``y``,
out-of-plane ``z``) by ``d = p - p0`` about the pitch axis, the same turn that building at ``p`` gives
(flapwise ``(sin t, cos t)`` and edgewise ``(cos t, -sin t)`` both go to ``(y cos d + z sin d, -y sin d + z cos d)``
at ``t + d``), and adds ``d`` to the sections' angle. What does not depend on the pitch is left alone: the modal
stiffness (ElastoDyn's from the untwisted polynomials; bladefem's FE shapes turn with their stiffness), masses on
the pitch axis, shortening integrals. The aerodynamic-centre offsets turn with the blade, as ``--pitch-deg``
builds them (AeroDyn places ``BlCrvAC`` and ``BlSwpAC`` in the pitched blade frame; their arms' motion along the
axis, -(offset . slope), follows), and the kernels cant the sections in the pitched blade by the pitch they are
given. The pitch rate's own inertial effect is left out, as in ElastoDyn without its pitch DOF, and so is the
offsets' velocity from the pitch rate (the pitch is held between the controller's calls).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ...aero.polar import turned
from ...numba_cache import cached_njit

njit = cached_njit()


def pitch_arrays(pitch, base, references, structure, aero):
    """Every blade pitched to ``pitch`` (rad) on the kernels' arrays (``structure``, ``aero``: the structural and
    aerodynamic tuples of :class:`~.compiled.CompiledEquations`): the shapes' across components, the sections' and
    their slopes turned by ``pitch - base`` from the ``references`` (shapes, sections, slopes, angles) built at
    ``base``, the aerodynamic-centre offsets turned alike, the offset nodes' motion along the axis set from the
    turned slopes, ``pitch - base`` added to the sections' angles and ``pitch`` set as the kernels' pitch; the
    blades' modal integrals (:mod:`.compiled_invariants`, built at ``base``) take the turn as theirs. Loops,
    so that numba compiles the same definition for the compiled controller loop."""
    blade, value, slope, theta, offset = references
    delta = pitch - base
    c, s = math.cos(delta), math.sin(delta)
    shapes, sections, offsets, slopes, angles = structure[5], aero[0], aero[3], aero[4], aero[8]
    for p in range(offset.shape[0]):
        y, z = offset[p, 1], offset[p, 2]
        offsets[p, 1], offsets[p, 2] = y * c + z * s, -y * s + z * c
    aero[26][0] = pitch
    turn = structure[24][9]
    turn[0], turn[1] = c, s
    for i in range(blade.shape[0]):
        for p in range(blade.shape[1]):
            y, z = blade[i, p, 1], blade[i, p, 2]
            shapes[i, p, 1], shapes[i, p, 2] = y * c + z * s, -y * s + z * c
        for p in range(value.shape[1]):
            y, z = value[i, p, 1], value[i, p, 2]
            sections[i, p, 1], sections[i, p, 2] = y * c + z * s, -y * s + z * c
        for p in range(slope.shape[1]):
            y, z = slope[i, p, 0], slope[i, p, 1]
            slopes[i, p, 0], slopes[i, p, 1] = y * c + z * s, -y * s + z * c
            # the offset node's motion along the axis follows the turned slopes (TurbineAero.along)
            sections[i, p, 0] = -(slopes[i, p, 0] * offsets[p, 1] + slopes[i, p, 1] * offsets[p, 2])
    for p in range(theta.shape[0]):
        angles[p] = theta[p] + delta


set_pitch = njit(cache=True)(pitch_arrays) if njit is not None else pitch_arrays


class CompiledPitch:
    """Sets the pitch (rad) of a :class:`~.compiled.CompiledEquations` built at ``model``'s pitch, in place."""

    def __init__(self, model, compiled) -> None:
        self.base = model.aero.pitch if model.aero is not None else model.params.pitch
        self.compiled = compiled
        self.pitch = self.base
        aero = compiled.aero
        slope = (np.asarray(model.aero.slope, dtype=float) if model.aero is not None
                 else np.zeros((0, 0, 2)))                  # (k, Na, 2): in-plane, out-of-plane
        #: the arrays at the base pitch: structural shapes (k, P, 3), sections (k, Na, 3), their slopes, angles,
        #: aerodynamic-centre offsets (Na, 3)
        self.references = tuple(np.ascontiguousarray(a, dtype=float).copy()
                                for a in (compiled.data[5], aero[0], slope, aero[8], aero[3]))
        self.tip = np.asarray(model.params.blade.tip_value, dtype=float).copy()      # (k, 2)

    def set(self, pitch: float) -> None:
        """Pitch every blade to ``pitch`` (rad)."""
        if pitch == self.pitch:
            return
        set_pitch(float(pitch), float(self.base), self.references, self.compiled.data, self.compiled.aero)
        self.pitch = pitch

    def tip_values(self, pitch: float) -> NDArray:
        """The blade's tip shapes (k, 2) at ``pitch`` (rad): in-plane, out-of-plane."""
        y, z = turned(self.tip[:, 0], self.tip[:, 1], pitch - self.base)
        return np.column_stack([y, z])
