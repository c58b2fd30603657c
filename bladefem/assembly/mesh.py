"""Span meshes: every section station is a node; each station interval is subdivided.

Subdividing intervals (rather than merging station positions into a uniform grid) avoids sliver elements that ruin
the conditioning of the Hermite matrices. :func:`span_nodes` subdivides evenly to a target element count;
:func:`graded_nodes` also grades the elements toward the small end of a section property that changes by a large
factor within one interval (blade tips: EI falls a hundredfold to a thousandfold over the last interval of many
decks), so that the mesh meets the h^4 rate of its error from the start; :func:`subdivide` refines a mesh by
splitting every element evenly (nested meshes, for Richardson estimates).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray
from skfem import MeshLine


#: stations closer than this fraction of the length are one node (:func:`merge_near_steps`)
NEAR_STEP = 1e-4


def merge_near_steps(stations: NDArray) -> NDArray:
    """Increasing distinct stations without those closer than :data:`NEAR_STEP` times the length to the station
    kept before them (the last station stays, in place of its predecessor). Decks write a property step as two
    stations a millimetre apart (the IEA 15 MW monopile: 0.9 mm on 145 m); as two nodes they make a sliver element
    (EI / h^3 a hundred billion times its neighbours') whose round-off swamps the frequencies. As one node the step
    lies inside an element, within a millimetre of its end, where the quadrature samples it."""
    stations = np.unique(np.asarray(stations, dtype=float))
    gap = NEAR_STEP * (stations[-1] - stations[0])
    kept = [stations[0]]
    for x in stations[1:-1]:
        if x - kept[-1] >= gap:
            kept.append(x)
    if len(kept) > 1 and stations[-1] - kept[-1] < gap:
        kept.pop()
    return np.array(kept + [stations[-1]])


def span_nodes(stations: NDArray, elements: int) -> NDArray:
    """Node positions (m): each station interval split into ``ceil(interval / h)`` equal elements, with the target
    element size ``h = length / elements``; at least one element per interval (a station given twice, a property
    step, is one node, and so are stations closer than :data:`NEAR_STEP` of the length)."""
    stations = merge_near_steps(stations)
    h = (stations[-1] - stations[0]) / max(int(elements), 1)
    counts = np.maximum(np.ceil(np.diff(stations) / h - 1e-9).astype(int), 1)
    interval = np.repeat(np.arange(len(counts)), counts)
    fraction = (np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)) / counts[interval]
    left, right = stations[:-1][interval], stations[1:][interval]
    return np.concatenate([left + fraction * (right - left), stations[-1:]])


#: largest factor a section property changes by over one element of a graded mesh
PROPERTY_RATIO = 1.5
#: largest change of structural twist over one element of a graded mesh, rad
TWIST_STEP = 0.05
#: graded elements are not made shorter than this fraction of the length (a property step given as two close
#: stations stays one element; toward a free tip, where the bending moment vanishes, a finer grading gains
#: nothing and costs conditioning)
SHORTEST_ELEMENT = 2e-3
#: sample points of a station interval (fraction 0..1) for placing graded nodes, clustered geometrically toward
#: both ends so that a linear property falling a thousandfold changes by less than PROPERTY_RATIO between samples
_HALF = 0.5 * np.geomspace(1e-4, 1.0, 33)
_SAMPLES = np.concatenate([[0.0], _HALF[:-1], 1.0 - _HALF[::-1], [1.0]])


#: an interpolated station this much closer to one neighbour than to the other is left out of the mesh
SLIVER_RATIO = 0.1
#: a column is linear through a station when it deviates from its neighbours' line by less than this (relative to
#: the column's largest magnitude)
LINEAR_RTOL = 1e-9


def mesh_stations(span: NDArray, columns: Sequence[NDArray]) -> NDArray:
    """The stations a mesh keeps as nodes: all except interior stations where every column is linear through the
    station (an interpolated row, such as a BModes element node merged into the section table) and one of its two
    gaps is shorter than :data:`SLIVER_RATIO` times the other. Such a station changes nothing in the model, but as a
    node it would make a sliver element, whose stiffness (EI / h^3) ruins the conditioning: a 4 mm element on a
    150 m blade scatters the frequencies by 1e-2."""
    span = np.asarray(span, dtype=float)
    near = np.isin(span, merge_near_steps(span), invert=True)
    if np.any(near):
        span, columns = span[~near], [np.asarray(column, dtype=float)[~near] for column in columns]
    table = np.array([np.asarray(column, dtype=float) for column in columns]).reshape(len(columns), len(span))
    scale = np.maximum(np.max(np.abs(table), axis=1), 1e-300)
    keep, left = [0], 0
    for j in range(1, len(span) - 1):
        right = j + 1
        gaps = span[j] - span[left], span[right] - span[j]
        t = gaps[0] / (span[right] - span[left])
        line = table[:, left] + t * (table[:, right] - table[:, left])
        linear = np.all(np.abs(table[:, j] - line) <= LINEAR_RTOL * scale)
        if not (linear and min(gaps) < SLIVER_RATIO * max(gaps)):
            keep.append(j)
            left = j
    keep.append(len(span) - 1)
    return span[keep]


def graded_nodes(stations: NDArray, columns: Sequence[NDArray], twist: NDArray, elements: int) -> NDArray:
    """Node positions (m): every station a node; within each station interval the elements are no longer than
    ``length / elements``, each spans at most a factor :data:`PROPERTY_RATIO` of every (linear, positive) column
    of ``columns`` and at most :data:`TWIST_STEP` of ``twist`` (rad).

    Nodes equidistribute a density over each interval: the largest, over the columns, of the rate of
    ``log(p) / log(PROPERTY_RATIO)`` (exact per sample for a linear ``p``), the twist rate and ``elements /
    length``, at most ``1 / (SHORTEST_ELEMENT * length)``; an interval gets ``ceil`` of its integral in elements
    (at least one).
    """
    stations = np.asarray(stations, dtype=float)
    length = stations[-1] - stations[0]
    gaps = np.diff(stations)
    t = _SAMPLES
    steps = np.zeros((len(gaps), len(t) - 1))
    for column in columns:
        column = np.asarray(column, dtype=float)
        p = np.maximum(column, np.min(column[column > 0]))        # a zero (inertia) counts as the smallest value
        log_p = np.log(p[:-1, None] + (p[1:] - p[:-1])[:, None] * t)
        steps = np.maximum(steps, np.abs(np.diff(log_p, axis=1)) / np.log(PROPERTY_RATIO))
    rate = gaps * max(int(elements), 1) / length + np.abs(np.diff(twist)) / TWIST_STEP
    steps = np.maximum(steps, rate[:, None] * np.diff(t))
    steps = np.minimum(steps, (gaps / (SHORTEST_ELEMENT * length))[:, None] * np.diff(t))
    cumulative = np.concatenate([np.zeros((len(gaps), 1)), np.cumsum(steps, axis=1)], axis=1)
    total = cumulative[:, -1]
    counts = np.maximum(np.ceil(total - 1e-9).astype(int), 1)
    nodes = [stations[:1]]
    for i, count in enumerate(counts):
        targets = np.arange(1, count + 1) * total[i] / count
        nodes.append(stations[i] + gaps[i] * np.interp(targets, cumulative[i], t))
    out = np.concatenate(nodes)
    out[np.cumsum(np.concatenate([[0], counts]))] = stations        # stations exactly
    return out


def subdivide(nodes: NDArray, parts: int) -> NDArray:
    """The mesh with every element of ``nodes`` split into ``parts`` equal elements (a nested refinement)."""
    nodes = np.asarray(nodes, dtype=float)
    fraction = np.arange(parts) / parts
    inner = nodes[:-1, None] + np.diff(nodes)[:, None] * fraction
    return np.concatenate([inner.ravel(), nodes[-1:]])


def span_mesh(nodes: NDArray) -> MeshLine:
    """A scikit-fem line mesh on increasing ``nodes`` (root first)."""
    return MeshLine(np.asarray(nodes, dtype=float))
