"""Flutter of a rotating (or parked) blade: the damping and frequency of each blade mode along a sweep of rotor or
wind speed, with the unsteady section aerodynamics of :mod:`bladefem.models.flutter_aero` in a p-k iteration.

At each operating point (wind speed, rotor speed, pitch) the structure ``K0 + Omega^2 K2``, ``M`` and the Coriolis
matrix ``Omega G`` are reduced to the lowest ``basis`` undamped modes ``Phi`` at that rotor speed; the aerodynamic
section matrices (BEM operating point with its induction, frozen) are integrated on the blade's quadrature points
against the modes' motion there, the circulatory part point by point with Theodorsen's ``C(k)`` at the point's
own reduced frequency. Each of the lowest ``n_modes`` modes is then followed by the p-k iteration
(:func:`~bladefem.models.flutter_pk.pk_root`), starting from its root at the previous sweep point (MAC-tracked).

Why p-k with Theodorsen's function rather than indicial (Wagner/Jones) states: the reduced frequency
``omega b / W`` varies along a rotating blade, and the p-k root at zero damping is exactly Theodorsen's flutter
point at every section, whereas a two-pole Jones approximation of ``C(k)`` carries its own error (about 1 % in
``|C|``) into the flutter speed; the modal reduction keeps each p-k step a small dense eigenproblem. No structural
damping: the onset is where the aerodynamic damping of a mode turns negative.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from skfem import Basis

from ..aero.rotor import Rotor
from ..assembly import BladeMatrices, span_mesh
from ..assembly.blade import QUADRATURE_ORDER
from ..elements import beam_element, interpolated_motion
from ..modal.quadratic import complex_energy_fractions
from ..modal.solve import eigen_pairs
from .blade_aero import operating_point
from .flutter_aero import FlutterSections, flutter_sections, theodorsen
from .flutter_pk import mac, pk_root

#: undamped modes of the reduction basis per tracked mode (and at least BASIS_MIN)
BASIS_PER_MODE, BASIS_MIN = 3, 12
#: shares reported (kinetic-energy fractions of the fields)
SHARES = ("flap", "edge", "torsion")


@dataclass(frozen=True)
class OperatingCondition:
    """One point of the sweep: wind speed (m/s, along the shaft), rotor speed (rad/s) and blade pitch (rad)."""

    wind_speed: float
    rotor_speed: float
    pitch: float

    @property
    def rpm(self) -> float:
        return self.rotor_speed * 30.0 / math.pi


@dataclass(frozen=True)
class FlutterPoint:
    """The tracked modes at one operating condition: damped frequency (Hz), damping ratio (fraction of critical,
    negative: unstable), flap/edge/torsion kinetic-energy shares, whether the p-k iteration converged, and the
    complex shapes on the free DOFs (columns)."""

    condition: OperatingCondition
    frequency_hz: NDArray
    damping_ratio: NDArray
    shares: list[dict[str, float]]
    converged: NDArray
    shapes: NDArray = field(repr=False)

    def as_dict(self) -> dict:
        return {"rpm": self.condition.rpm, "wind_speed_m_s": self.condition.wind_speed,
                "pitch_deg": math.degrees(self.condition.pitch),
                "modes": [{"mode": j + 1, "frequency_hz": float(f), "damping_ratio": float(z), "shares": s,
                           "converged": bool(c)}
                          for j, (f, z, s, c) in enumerate(zip(self.frequency_hz, self.damping_ratio, self.shares,
                                                                self.converged))]}


@dataclass(frozen=True)
class FlutterOnset:
    """The first zero crossing of a mode's damping along the sweep, interpolated linearly between the two points:
    rotor speed (rpm), wind speed (m/s), frequency (Hz), mode (1-based tracked index), shares (at the first unstable
    point) and ``after``, the index of that point."""

    rpm: float
    wind_speed_m_s: float
    frequency_hz: float
    mode: int
    shares: dict[str, float]
    after: int

    def as_dict(self) -> dict:
        return {"rpm": self.rpm, "wind_speed_m_s": self.wind_speed_m_s, "frequency_hz": self.frequency_hz,
                "mode": self.mode, "shares": self.shares}


@dataclass(frozen=True)
class FlutterResult:
    """The sweep's points and the onset (None: every tracked mode stays damped)."""

    points: list[FlutterPoint]
    onset: FlutterOnset | None
    notes: tuple[str, ...] = ()

    def as_dict(self) -> dict:
        return {"onset": None if self.onset is None else self.onset.as_dict(),
                "sweep": [point.as_dict() for point in self.points], "notes": list(self.notes)}


class ReducedAero:
    """The section matrices of one operating point integrated against the modal basis ``Phi`` (free DOFs)."""

    def __init__(self, matrices: BladeMatrices, sections: FlutterSections, basis: NDArray):
        full = np.zeros((matrices.dofs.size, basis.shape[1]))
        full[matrices.free] = basis
        quadrature = matrices.quadrature
        motion = interpolated_motion(quadrature.functions, quadrature.element_dofs, full).kinematic
        phi = motion.reshape(6, basis.shape[1], -1)                          # (6, modes, points)
        weights = quadrature.weights.ravel()
        x = quadrature_points(matrices).ravel()
        at = self._interpolation(sections.span, x)

        def project(A: NDArray) -> NDArray:                                  # (points, modes, modes)
            return np.einsum("fmq,fgq,gkq,q->qmk", phi, at(A), phi, weights, optimize=True)

        self.constant_mass = project(sections.apparent_mass).sum(axis=0)
        self.constant_damping = project(sections.quasi_steady_damping + sections.apparent_damping).sum(axis=0)
        self.constant_stiffness = project(sections.quasi_steady_stiffness).sum(axis=0)
        self.lift_damping, self.lift_stiffness = project(sections.lift_damping), project(sections.lift_stiffness)
        inside = (x >= sections.span[0]) & (x <= sections.span[-1])
        speed = np.interp(x, sections.span, sections.speed)
        self.frequency_scale = np.divide(np.interp(x, sections.span, sections.semi_chord), speed,
                                         out=np.zeros_like(x), where=inside & (speed > 0))

    @staticmethod
    def _interpolation(span: NDArray, x: NDArray) -> Callable[[NDArray], NDArray]:
        """Linear interpolation of (6, 6, nodes) arrays to ``x``, zero outside the AeroDyn span."""
        right = np.clip(np.searchsorted(span, x, side="right"), 1, len(span) - 1)
        left = right - 1
        gap = span[right] - span[left]
        t = np.divide(x - span[left], gap, out=np.zeros_like(x), where=gap > 0)
        inside = (x >= span[0]) & (x <= span[-1])
        return lambda A: (A[:, :, left] * (1 - t) + A[:, :, right] * t) * inside

    def __call__(self, p: complex) -> tuple[NDArray, NDArray, NDArray]:
        c = theodorsen(abs(p.imag) * self.frequency_scale)
        return (self.constant_mass, self.constant_damping + np.einsum("q,qmk->mk", c, self.lift_damping),
                self.constant_stiffness + np.einsum("q,qmk->mk", c, self.lift_stiffness))


def quadrature_points(matrices: BladeMatrices) -> NDArray:
    """Span positions (m) of the blade mesh's quadrature points, (elements, points)."""
    basis = Basis(span_mesh(matrices.dofs.nodes), beam_element(matrices.dofs.fields), intorder=QUADRATURE_ORDER)
    return np.asarray(basis.global_coordinates())[0]


def flutter_point(matrices: BladeMatrices, rotor: Rotor, condition: OperatingCondition, n_modes: int,
                  previous: FlutterPoint | None, chordwise_centre: NDArray | float = 0.0) -> FlutterPoint:
    """The tracked modes at ``condition``: from the structure's lowest modes when ``previous`` is None, else
    continued from the roots of ``previous`` (module docstring)."""
    speed = condition.rotor_speed
    K, M = matrices.reduced(speed)
    values, basis = eigen_pairs(K, M, max(BASIS_MIN, BASIS_PER_MODE * n_modes))
    op = operating_point(rotor, condition.wind_speed, speed, condition.pitch)
    aero = ReducedAero(matrices, flutter_sections(op, chordwise_centre), basis)
    size = basis.shape[1]
    M_r, K_r = np.eye(size), np.diag(values)
    C_r = speed * (basis.T @ (matrices.free_gyroscopic @ basis))
    roots, shapes = [], []
    for j in range(n_modes):
        if previous is None:
            omega, start = math.sqrt(max(values[j], 0.0)), np.eye(size)[:, j].astype(complex)
        else:
            omega = 2 * math.pi * previous.frequency_hz[j]
            start = basis.T @ (M @ previous.shapes[:, j])
        root = pk_root(M_r, C_r, K_r, aero, max(omega, 1e-6), start, taken=tuple(r.p for r in roots))
        roots.append(root)
        shapes.append(basis @ root.shape)
    X = np.stack(shapes, axis=1)
    fractions = complex_energy_fractions(matrices, chord_frame(matrices, X, condition.pitch))
    return FlutterPoint(condition=condition, frequency_hz=np.array([r.frequency / (2 * math.pi) for r in roots]),
                        damping_ratio=np.array([r.damping_ratio for r in roots]),
                        shares=[{name: f[name] for name in SHARES} for f in fractions],
                        converged=np.array([r.converged for r in roots]), shapes=X)


def chord_frame(matrices: BladeMatrices, X: NDArray, pitch: float) -> NDArray:
    """Free-DOF shapes with the in-plane and out-of-plane fields (v, w) turned at each node into the section's chord
    frame by the structural twist plus ``pitch`` (rad): v along the chord (edge), w normal to it (flap), so that the
    kinetic-energy shares name flap and edge as the section sees them."""
    dofs = matrices.dofs
    if "v" not in dofs.fields or "w" not in dofs.fields:
        return X
    full = np.zeros((dofs.size, X.shape[1]), dtype=X.dtype)
    full[matrices.free] = X
    theta = (pitch + matrices.blade.sections.at(dofs.nodes, "twist"))[:, None]
    c, s = np.cos(theta), np.sin(theta)
    for kind in (dofs.value, dofs.slope):
        v, w = full[kind["v"]], full[kind["w"]]
        full[kind["v"]], full[kind["w"]] = c * v - s * w, s * v + c * w
    return full[matrices.free]


def onset(points: Sequence[FlutterPoint]) -> FlutterOnset | None:
    """The first sweep interval in which a converged mode's damping goes from >= 0 to < 0, interpolated linearly
    in the damping between its two points (rotor speed, wind speed and frequency alike); of several modes crossing
    in one interval, the earliest crossing."""
    for i in range(1, len(points)):
        before, after = points[i - 1], points[i]
        crossing = [(before.damping_ratio[j] / (before.damping_ratio[j] - after.damping_ratio[j]), j)
                    for j in range(len(after.damping_ratio))
                    if before.converged[j] and after.converged[j] and before.damping_ratio[j] >= 0
                    > after.damping_ratio[j]]
        if crossing:
            t, j = min(crossing)
            a, b = before.condition, after.condition
            return FlutterOnset(
                rpm=(a.rpm + t * (b.rpm - a.rpm)), wind_speed_m_s=a.wind_speed + t * (b.wind_speed - a.wind_speed),
                frequency_hz=float(before.frequency_hz[j] + t * (after.frequency_hz[j] - before.frequency_hz[j])),
                mode=j + 1, shares=after.shares[j], after=i)
    return None


def flutter_sweep(matrices: BladeMatrices, rotor: Rotor, conditions: Sequence[OperatingCondition],
                  n_modes: int = 6, chordwise_centre: NDArray | float = 0.0, notes: tuple[str, ...] = (),
                  progress: Callable[[Iterable], Iterable] = iter) -> FlutterResult:
    """Damping and frequency of the lowest ``n_modes`` blade modes at each of ``conditions`` (in sweep order),
    MAC-tracked from point to point, and the flutter onset (:func:`onset`). ``chordwise_centre``: the aerodynamic centre ahead of AeroDyn's reference line, m (per AeroDyn
    node or one value)."""
    points: list[FlutterPoint] = []
    for condition in progress(conditions):
        points.append(flutter_point(matrices, rotor, condition, n_modes, points[-1] if points else None,
                                    chordwise_centre))
    first = onset(points)
    unconverged = sum(int((~p.converged).sum()) for p in points)
    extra = (f"{unconverged} p-k roots did not converge (left out of the onset search)",) if unconverged else ()
    return FlutterResult(points=points, onset=first, notes=notes + extra)


def tracking_mac(a: FlutterPoint, b: FlutterPoint) -> NDArray:
    """MAC of each tracked mode of ``b`` against the same mode of ``a`` (a check of the tracking)."""
    return np.array([mac(a.shapes[:, j], b.shapes[:, [j]])[0] for j in range(a.shapes.shape[1])])
