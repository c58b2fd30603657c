"""Automatic mesh choice: nested refinements of a starting mesh, their error estimated from the h^4 rate.

Level ``s`` of a starting mesh splits each of its elements into ``s`` equal elements. The FE frequencies
(Hermite cubic bending, quadratic torsion and axial fields, exactly integrated section properties) converge from
above as ``h^4``: the relative error of level ``s`` is ``e(s) = C s^-4``. Two solved levels give ``C``
(Richardson), and with it the coarsest level whose error is below half the tolerance: one more assembly, checked
once more against the previous level. A third level also measures the rate; a mesh still short of the h^4 regime
(the rate below 4) is then estimated with its observed rate. Round-off grows as ``s^4`` (the Hermite stiffness
is ill-conditioned like ``h^-4``): where the sum of both estimates cannot reach the tolerance, the level that
minimises it is chosen and a note says so, instead of refining into noise.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Generic, TypeVar

import numpy as np
from numpy.typing import NDArray

Matrices = TypeVar("Matrices")

#: frequencies below this fraction of the highest one count as zero (rigid-body modes) and are left out of the
#: comparison of meshes: their computed values are round-off, which grows with refinement like the square root of
#: the eigenvalue noise (1e-5 of the highest frequency at 3000 elements)
ZERO_FREQUENCY = 1e-4
#: the chosen mesh's estimated error is held below this fraction of the tolerance (the doubling rule before it
#: accepted a mesh whose change to the next finer was below half the tolerance: the same margin)
SAFETY = 0.5
#: asymptotic convergence rate of the frequencies (Hermite cubic and quadratic Lagrange elements)
RATE = 4.0
#: at most this many levels are solved (the starting mesh, its first refinement and the checks that follow)
MAX_SOLVES = 6


@dataclass(frozen=True)
class Solved:
    """What the mesh choice needs from one solve: the frequencies (Hz), an estimate of each one's relative
    round-off error, and the solve's own result (handed back for re-use)."""

    frequencies: NDArray[np.float64]
    roundoff: NDArray[np.float64]
    result: object = None


@dataclass(frozen=True)
class MeshChoice(Generic[Matrices]):
    """The chosen level, its matrices and solve, its estimated relative frequency error (discretisation plus
    round-off, largest over the modes), and a note when the tolerance could not be reached."""

    matrices: Matrices
    level: int
    solved: Solved
    error: float
    note: str | None = None


def relative_change(coarse: NDArray, fine: NDArray) -> NDArray:
    """|coarse - fine| / |fine| per mode; zero for zero-frequency modes (below ZERO_FREQUENCY of the highest)."""
    zero = np.abs(fine) < ZERO_FREQUENCY * np.max(np.abs(fine))
    return np.where(zero, 0.0, np.abs(coarse - fine) / np.where(zero, 1.0, np.abs(fine)))


def observed_rate(levels: tuple[int, int, int], changes: tuple[NDArray, NDArray]) -> NDArray:
    """Per-mode rate p with ``e(s) = C s^-p`` that explains the changes between three levels (bisection on p in
    [1, RATE]; RATE where the changes are too small to tell or the rate is above it)."""
    s0, s1, s2 = levels
    ratio = changes[0] / np.maximum(changes[1], 1e-300)

    def model(p: NDArray) -> NDArray:
        return (s0**-p - s1**-p) / (s1**-p - s2**-p)

    low, high = np.ones_like(ratio), np.full_like(ratio, RATE)
    for _ in range(40):
        middle = 0.5 * (low + high)
        below = model(middle) < ratio
        low, high = np.where(below, middle, low), np.where(below, high, middle)
    return np.where(ratio >= model(np.full_like(ratio, RATE)), RATE, 0.5 * (low + high))


def choose_mesh(assemble: Callable[[int], Matrices], solve: Callable[[Matrices], Solved], rtol: float,
                max_level: int, predict: Callable[[Matrices, Solved], NDArray] | None = None) -> MeshChoice[Matrices]:
    """The coarsest level (at most ``max_level``) whose estimated frequency error is below ``SAFETY * rtol``
    (relative), from the Richardson estimate of the last two solved levels.

    Level 1 is solved first. With ``predict`` (an a-priori estimate of each frequency's relative error on a mesh,
    from its solve) the second level solved is the one the prediction says is enough (at least 2): when the
    prediction holds, the Richardson check of that pair accepts it at once; without, it is level 2."""
    solved: dict[int, tuple[Matrices, Solved]] = {}

    def run(level: int) -> None:
        matrices = assemble(level)
        solved[level] = (matrices, solve(matrices))

    target = SAFETY * rtol
    run(1)
    second = 2
    if predict is not None:
        predicted = float(np.max(predict(*solved[1])))
        second = min(max(2, int(np.ceil((predicted / target) ** (1 / RATE) - 1e-9))), max(2, max_level))
    run(second)
    while True:
        levels = sorted(solved)
        s1, s2 = levels[-2:]
        f1, f2 = solved[s1][1].frequencies, solved[s2][1].frequencies
        change = relative_change(f1, f2)
        rate = np.full_like(change, RATE)
        if len(levels) >= 3:
            s0 = levels[-3]
            earlier = relative_change(solved[s0][1].frequencies, f1)
            noise = solved[s2][1].roundoff
            rate = np.where(change > 10 * noise, observed_rate((s0, s1, s2), (earlier, change)), RATE)
        constant = change / (float(s1) ** -rate - float(s2) ** -rate)
        noise_constant = solved[s2][1].roundoff / float(s2) ** 4

        def error(level: int) -> float:
            return float(np.max(constant * float(level) ** -rate + noise_constant * float(level) ** 4))

        ready = [level for level in levels if error(level) <= target]
        if ready:
            return _choice(solved, ready[0], error(ready[0]))
        optimum = min(range(1, max_level + 1), key=error)
        if len(solved) < MAX_SOLVES:
            meeting = [level for level in range(s2 + 1, max_level + 1) if error(level) <= target]
            following = meeting[0] if meeting else optimum
            if following not in solved:
                run(following)
                continue
        best = min(solved, key=error)
        if error(best) <= rtol:                         # within the tolerance, if not within the margin
            return _choice(solved, best, error(best))
        reason = ("the element limit" if best == max_level else
                  "round-off, which grows as the mesh is refined" if best == optimum else
                  "a convergence slower than predicted")
        note = (f"mesh refinement stopped short of the tolerance {rtol:g} by {reason}: the frequencies' estimated "
                f"relative error is {error(best):.1e} (rough or extreme section properties; check with --elements)")
        return _choice(solved, best, error(best), note)


def _choice(solved: dict, level: int, error: float, note: str | None = None) -> MeshChoice:
    matrices, solution = solved[level]
    return MeshChoice(matrices=matrices, level=level, solved=solution, error=error, note=note)


def refine_until_converged(assemble: Callable[[int], Matrices], frequencies: Callable[[Matrices], NDArray],
                           start: int, rtol: float, max_elements: int,
                           finer: bool = False) -> tuple[Matrices, float | None]:
    """The mesh choice for callers that assemble by element count: level ``s`` is ``start * s`` elements, and
    no round-off estimate is made. Returns the matrices and None, or the estimated error when ``rtol`` was not
    reached. ``finer`` holds the error below ``rtol / 30`` instead of ``rtol / 2`` (what the finer mesh of a doubled
    pair whose change is below ``rtol / 2`` has), for closed-form checks to 1e-7."""
    def solve(matrices: Matrices) -> Solved:
        values = frequencies(matrices)
        return Solved(values, np.zeros_like(values))

    choice = choose_mesh(lambda level: assemble(start * level), solve, rtol / 15 if finer else rtol,
                         max(2, max_elements // start))
    return choice.matrices, (None if choice.note is None else choice.error)
