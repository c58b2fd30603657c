"""Span meshes: every section station is a node; each station interval is subdivided evenly.

Subdividing intervals (rather than merging station positions into a uniform grid) avoids sliver elements that ruin
the conditioning of the Hermite matrices.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from skfem import MeshLine


def span_nodes(stations: NDArray, elements: int) -> NDArray:
    """Node positions (m): each station interval split into ``ceil(interval / h)`` equal elements, with the target
    element size ``h = length / elements``; at least one element per interval (a station given twice, a property
    step, is one node)."""
    stations = np.unique(np.asarray(stations, dtype=float))
    h = (stations[-1] - stations[0]) / max(int(elements), 1)
    counts = np.maximum(np.ceil(np.diff(stations) / h - 1e-9).astype(int), 1)
    pieces = [np.linspace(a, b, n, endpoint=False) for a, b, n in zip(stations[:-1], stations[1:], counts)]
    return np.concatenate(pieces + [stations[-1:]])


def span_mesh(nodes: NDArray) -> MeshLine:
    """A scikit-fem line mesh on increasing ``nodes`` with boundaries named ``root`` and ``tip``."""
    root, tip = nodes[0], nodes[-1]
    tol = 1e-9 * (tip - root)
    return MeshLine(np.asarray(nodes, dtype=float)).with_boundaries({
        "root": lambda x: np.abs(x[0] - root) < tol,
        "tip": lambda x: np.abs(x[0] - tip) < tol,
    })
