"""A-priori error of the FE frequencies on a given mesh, from the local wavenumber of each mode.

A cubic Hermite beam element of length ``h`` errs in omega^2 by ``(kappa h)^4 / 720`` relative (to leading order),
``kappa^4 = omega^2 m / EI`` being the bending wavenumber, so in the frequency by half that; quadratic rod elements
(torsion, extension) follow the same law with ``kappa^2 = omega^2 I_p / GJ`` or ``omega^2 m / EA``. Summed over
the elements with the mode's kinetic-energy share in each, this predicts the error of a whole mesh within a factor
of about two on the reference decks, which is enough to pick the refinement (the error scales as h^4: a factor
of two is 20 % in the element size); the Richardson check that follows confirms it.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..assembly import BladeMatrices
from ..elements import BENDING_FIELDS

#: leading coefficient of the relative frequency error of an element, (kappa h)^4 / HERMITE_FREQUENCY_ERROR
HERMITE_FREQUENCY_ERROR = 1440.0


def frequency_errors(matrices: BladeMatrices, values: NDArray, vectors: NDArray) -> NDArray:
    """Predicted relative error of each frequency (eigenpairs: omega^2 and free-DOF vectors) on the matrices'
    mesh. Uses the smaller bending stiffness of each element (conservative for the stiffer direction)."""
    sections, dofs = matrices.blade.sections, matrices.dofs
    h = np.diff(dofs.nodes)
    middle = 0.5 * (dofs.nodes[1:] + dofs.nodes[:-1])
    mass = sections.at(middle, "mass")
    bending = np.minimum(sections.at(middle, "flap_stiffness"), sections.at(middle, "edge_stiffness"))
    omega2 = np.abs(values)[None, :]
    kappa4 = omega2 * (mass / bending)[:, None]
    if sections.torsion_stiffness is not None:
        polar = sections.at(middle, "flap_inertia") + sections.at(middle, "edge_inertia")
        kappa4 = np.maximum(kappa4, (omega2 * (polar / sections.at(middle, "torsion_stiffness"))[:, None]) ** 2)
    if sections.axial_stiffness is not None:
        kappa4 = np.maximum(kappa4, (omega2 * (mass / sections.at(middle, "axial_stiffness"))[:, None]) ** 2)
    full = np.zeros((dofs.size, vectors.shape[1]))
    full[matrices.free] = vectors
    squared = sum(dofs.displacement(full, name) ** 2 for name in BENDING_FIELDS if name in dofs.value)
    share = (mass * h)[:, None] * 0.5 * (squared[1:] + squared[:-1])
    share = share / np.maximum(share.sum(axis=0), 1e-300)
    return np.sum(share * kappa4 * h[:, None] ** 4, axis=0) / HERMITE_FREQUENCY_ERROR
