"""Named views of the global DOFs: field values and slopes at each mesh node, root conditions."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray
from skfem import CellBasis

from ..elements import BENDING_FIELDS, SHEAR_FIELDS


@dataclass(frozen=True)
class DofMap:
    """Global DOF numbers by name.

    nodes : node positions along the span, m (increasing)
    value : field -> DOF of the field's value at each node
    slope : field -> DOF of the field's span derivative at each node (Hermite fields only)
    field_dofs : field -> every DOF of the field (including element-interior ones)
    size : total number of DOFs
    """

    fields: tuple[str, ...]
    nodes: NDArray[np.float64]
    value: dict[str, NDArray[np.int64]]
    slope: dict[str, NDArray[np.int64]]
    field_dofs: dict[str, NDArray[np.int64]]
    size: int

    @classmethod
    def from_basis(cls, basis: CellBasis, fields: tuple[str, ...]) -> DofMap:
        order = np.argsort(basis.mesh.p[0])
        value, slope, row = {}, {}, 0
        for name in fields:
            value[name] = basis.nodal_dofs[row][order]
            row += 1
            if name in BENDING_FIELDS:
                slope[name] = basis.nodal_dofs[row][order]
                row += 1
        field_dofs = dict(zip(fields, basis.split_indices()))
        return cls(fields, basis.mesh.p[0][order], value, slope, field_dofs, basis.N)

    def root_dofs(self, root: str) -> NDArray[np.int64]:
        """DOFs held at the root: all for a cantilever; values only (slopes free) for a hinge; axial displacement and
        twist only for ``axial-torsion``; none for ``free``. The shear deflections' root values are held in every
        case: a constant moves between ``v`` and ``v_s`` without changing the beam's motion (a zero-energy,
        massless split), and ``v_s(0) = 0`` fixes it."""
        fields = () if root == "free" else ("u", "phi") if root == "axial-torsion" else self.fields
        held = [self.value[name][0] for name in dict.fromkeys(fields + SHEAR_FIELDS) if name in self.value]
        if root == "cantilever":
            held += [self.slope[name][0] for name in self.slope]
        return np.array(sorted(held), dtype=np.int64)

    def displacement(self, vectors: NDArray, name: str) -> NDArray:
        """Nodal values (nodes, vectors) of the deflection ``name`` (``v`` or ``w``, with its shear part when the
        beam has one), or of the field ``name``, from vectors over all DOFs (columns)."""
        values = vectors[self.value[name]]
        shear = dict(zip(BENDING_FIELDS, SHEAR_FIELDS)).get(name)
        return values + vectors[self.value[shear]] if shear in self.value else values

    def kinematic_selector(self, node: int) -> sp.csr_matrix:
        """6 x size matrix T with T x = (u, v + v_s, w + w_s, phi, -w', v') at ``node`` (zeros for absent fields)."""
        entries = [("u", self.value, 0, 1.0), ("v", self.value, 1, 1.0), ("w", self.value, 2, 1.0),
                   ("phi", self.value, 3, 1.0), ("w", self.slope, 4, -1.0), ("v", self.slope, 5, 1.0),
                   ("v_s", self.value, 1, 1.0), ("w_s", self.value, 2, 1.0)]
        rows, cols, signs = [], [], []
        for name, table, row, sign in entries:
            if name in table:
                rows.append(row)
                cols.append(table[name][node])
                signs.append(sign)
        return sp.csr_matrix((signs, (rows, cols)), shape=(6, self.size))
