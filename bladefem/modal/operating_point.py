"""The blade's operating point under its centrifugal load (and its weight, when gravity is on): the static
deflection at a rotor speed, and the blade on its deflected reference axis (a prebent blade bends back toward the
rotor plane as it spins)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse.linalg as spla
from numpy.typing import NDArray
from scipy.interpolate import CubicHermiteSpline

from ..assembly import assemble_blade
from ..assembly.loads import centrifugal_load, gravity_load
from ..errors import InputError
from ..sections import Blade, ReferenceAxis
from .solve import rpm_to_rad_s

#: elements of the mesh the operating point is solved on (the deflection converges like a static solution)
ELEMENTS = 80


@dataclass(frozen=True)
class OperatingPoint:
    """The static deflection under the centrifugal load at ``rpm`` and the weight (gravity on).

    nodes : (n,) where the deflection is sampled along the axis (its knots, or the stations), m
    displacement : (3, n) the axis points' displacement in the blade frame, m
    twist : (n,) elastic twist, rad
    vector : the deflection over all DOFs
    """

    rpm: float
    nodes: NDArray
    displacement: NDArray
    twist: NDArray
    vector: NDArray


def operating_point(blade: Blade, rpm: float, elements: int = ELEMENTS) -> OperatingPoint:
    """Solve ``(K0 + Omega^2 K2) q = Omega^2 b + b_g`` for the centrifugal load ``b`` at ``rpm`` (rpm) and the
    weight ``b_g`` (zero without gravity; K0 then holds the weight's geometric stiffness) on a cantilever."""
    if blade.root != "cantilever":
        raise InputError(f"the operating point needs a clamped root (this blade's is {blade.root}): a static "
                         "deflection under load", field="root")
    matrices = assemble_blade(blade, elements)
    omega = rpm_to_rad_s(rpm)
    K, _ = matrices.reduced(omega)
    q = np.zeros(matrices.dofs.size)
    load = (omega**2 * centrifugal_load(matrices.quadrature, blade, matrices.dofs)
            + gravity_load(matrices.quadrature, blade, matrices.dofs))
    q[matrices.free] = spla.spsolve(K, load[matrices.free])
    dofs = matrices.dofs
    # where the deflected axis is sampled: the axis's own knots (or the stations), so that its modes are meshed
    # on the same nodes as the blade's
    at = blade.axis.span if blade.curved else np.unique(blade.sections.span)
    local = np.zeros((3, len(at)))
    if "u" in dofs.value:
        local[0] = np.interp(at, dofs.nodes, q[dofs.value["u"]])
    for k, name in ((1, "v"), (2, "w")):
        local[k] = CubicHermiteSpline(dofs.nodes, q[dofs.value[name]], q[dofs.slope[name]])(at)
        if f"{name}_s" in dofs.value:                 # a shear-flexible beam's axis moves by its shear part too
            local[k] += np.interp(at, dofs.nodes, q[dofs.value[f"{name}_s"]])
    frame = blade.axis_frame(at)
    displacement = local if frame is None else np.einsum("ij...,j...->i...", frame.rotation, local)
    twist = np.interp(at, dofs.nodes, q[dofs.value["phi"]]) if "phi" in dofs.value else np.zeros(len(at))
    return OperatingPoint(float(rpm), at, displacement, twist, q)


def deflected_blade(blade: Blade, rpm: float, elements: int = ELEMENTS) -> tuple[Blade, OperatingPoint]:
    """The blade on its reference axis deflected by the centrifugal load at ``rpm`` (rpm) and its weight (gravity
    on), and that deflection."""
    point = operating_point(blade, rpm, elements)
    axis = blade.axis or ReferenceAxis(blade.sections.span, np.zeros(len(blade.sections.span)),
                                       np.zeros(len(blade.sections.span)))
    moved = axis.displaced(point.nodes, point.displacement, blade.pitch)
    tip = point.displacement[:, -1]
    loads = "the centrifugal load" + (" and the weight" if blade.gravity is not None else "")
    note = (f"reference axis deflected by {loads} at {rpm:g} rpm (tip moved {tip[2]:+.3g} m "
            f"out of plane, {tip[1]:+.3g} m in plane)")
    return blade.with_(axis=moved, prestressed=True, notes=blade.notes + (note,)), point
