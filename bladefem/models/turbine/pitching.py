"""Collective blade pitch changed during a simulation, on the compiled kernels' arrays, in place.

A model is built at one pitch ``p0``: the blade's mode shapes are twisted by the structural twist plus ``p0``
(ElastoDyn's ``TwistedSF``, :func:`bladefem.modal.elastodyn_integrals.principal_directions`) and the aerodynamic
sections are set at twist plus ``p0``. Pitching to ``p`` turns every shape's across components (in-plane ``y``,
out-of-plane ``z``) by ``d = p - p0`` about the pitch axis, the same turn that building at ``p`` gives
(flapwise ``(sin t, cos t)`` and edgewise ``(cos t, -sin t)`` both go to ``(y cos d + z sin d, -y sin d + z cos d)``
at ``t + d``), and adds ``d`` to the sections' angle. What does not depend on the pitch is left alone: the modal
stiffness (ElastoDyn's from the untwisted polynomials; bladefem's FE shapes turn with their stiffness), masses on
the pitch axis, shortening integrals, the aerodynamic-centre offsets (as ``--pitch-deg`` builds them; their
arms' motion along the axis, -(offset . slope), follows the turned slopes). The pitch
rate's own inertial effect is left out, as in ElastoDyn without its pitch DOF.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray


def turn(y: NDArray, z: NDArray, angle: float) -> tuple[NDArray, NDArray]:
    """Across components (in-plane, out-of-plane) turned by ``angle`` (rad) of pitch."""
    c, s = math.cos(angle), math.sin(angle)
    return y * c + z * s, -y * s + z * c


class CompiledPitch:
    """Sets the pitch (rad) of a :class:`~.compiled.CompiledEquations` built at ``model``'s pitch, in place."""

    def __init__(self, model, compiled) -> None:
        self.base = model.aero.pitch if model.aero is not None else model.params.pitch
        self.compiled = compiled
        self.pitch = self.base
        self.blade = compiled.data[5].copy()                 # (k, P, 3) structural shapes
        aero = compiled.aero
        self.aero_value = aero[0].copy()                     # (k, Na, 3)
        self.aero_slope = (np.asarray(model.aero.slope, dtype=float).copy() if model.aero is not None
                           else np.zeros((0, 0, 2)))         # (k, Na, 2): in-plane, out-of-plane
        self.theta = aero[8].copy()
        self.tip = np.asarray(model.params.blade.tip_value, dtype=float).copy()      # (k, 2)

    def set(self, pitch: float) -> None:
        """Pitch every blade to ``pitch`` (rad)."""
        if pitch == self.pitch:
            return
        delta = pitch - self.base
        data, aero = self.compiled.data, self.compiled.aero
        data[5][..., 1], data[5][..., 2] = turn(self.blade[..., 1], self.blade[..., 2], delta)
        aero[0][..., 1], aero[0][..., 2] = turn(self.aero_value[..., 1], self.aero_value[..., 2], delta)
        if self.aero_slope.size:
            aero[4][..., 0], aero[4][..., 1] = turn(self.aero_slope[..., 0], self.aero_slope[..., 1], delta)
            # the offset nodes' motion along the axis follows the turned slopes (TurbineAero.along)
            aero[0][..., 0] = -(aero[4][..., 0] * aero[3][:, 1] + aero[4][..., 1] * aero[3][:, 2])
        aero[8][...] = self.theta + delta
        self.pitch = pitch

    def tip_values(self, pitch: float) -> NDArray:
        """The blade's tip shapes (k, 2) at ``pitch`` (rad): in-plane, out-of-plane."""
        y, z = turn(self.tip[:, 0], self.tip[:, 1], pitch - self.base)
        return np.column_stack([y, z])
