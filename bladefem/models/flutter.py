"""Flutter of a rotating (or parked) blade: the damping and frequency of each blade mode along a sweep of rotor or
wind speed, with the unsteady section aerodynamics of :mod:`bladefem.models.flutter_aero` in a p-k iteration.

The structure ``K0 + Omega^2 K2``, ``M`` and the Coriolis matrix ``Omega G`` are reduced once for the sweep to the
undamped modes at its lowest and highest rotor speeds (:class:`~bladefem.models.flutter_basis.SweepBasis`); at each
operating point (wind speed, rotor speed, pitch) the aerodynamic section matrices (BEM operating point with its
induction, frozen) are integrated on the blade's quadrature points against the basis's motion there, the
circulatory part point by point with Theodorsen's ``C(k)`` at the point's own reduced frequency. Each of the lowest ``n_modes`` modes is then followed by the p-k iteration
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
import scipy.linalg as la

from ..aero.rotor import Rotor
from ..assembly import BladeMatrices
from ..modal.quadratic import complex_energy_fractions
from .blade_aero import operating_point
from .flutter_aero import flutter_sections
from .flutter_basis import ReducedAero, SweepBasis
from .flutter_pk import PkRoot, mac, pk_root

#: undamped modes per end of the sweep in the reduction basis, per tracked mode (and at least BASIS_MIN)
BASIS_PER_MODE, BASIS_MIN = 2, 10
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
    reduced: NDArray = field(repr=False, default_factory=lambda: np.zeros((0, 0)))

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


def flutter_point(matrices: BladeMatrices, basis: SweepBasis, rotor: Rotor, condition: OperatingCondition,
                  n_modes: int, previous: FlutterPoint | None, chordwise_centre: NDArray | float = 0.0
                  ) -> FlutterPoint:
    """The tracked modes at ``condition``: from the structure's lowest modes when ``previous`` is None, else
    continued from the roots of ``previous`` (module docstring)."""
    speed = condition.rotor_speed
    op = operating_point(rotor, condition.wind_speed, speed, condition.pitch, matrices.blade)
    aero = ReducedAero(basis, flutter_sections(op, chordwise_centre))
    M_r, K_r, C_r = np.eye(basis.size), basis.stiffness(speed), speed * basis.G
    if previous is None:
        values, vectors = la.eigh(K_r)
        starts = [(math.sqrt(max(values[j], 0.0)), vectors[:, j].astype(complex)) for j in range(n_modes)]
    else:
        starts = [(2 * math.pi * previous.frequency_hz[j], previous.reduced[:, j]) for j in range(n_modes)]
    roots: list[PkRoot] = []
    for omega, start in starts:
        roots.append(pk_root(M_r, C_r, K_r, aero, max(omega, 1e-6), start, taken=tuple(r.p for r in roots)))
    reduced = np.stack([r.shape for r in roots], axis=1)
    X = basis.vectors @ reduced
    fractions = complex_energy_fractions(matrices, chord_frame(matrices, X, condition.pitch))
    return FlutterPoint(condition=condition, frequency_hz=np.array([r.frequency / (2 * math.pi) for r in roots]),
                        damping_ratio=np.array([r.damping_ratio for r in roots]),
                        shares=[{name: f[name] for name in SHARES} for f in fractions],
                        converged=np.array([r.converged for r in roots]), shapes=X, reduced=reduced)


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
    basis = SweepBasis(matrices, [c.rotor_speed for c in conditions], max(BASIS_MIN, BASIS_PER_MODE * n_modes))
    points: list[FlutterPoint] = []
    for condition in progress(conditions):
        points.append(flutter_point(matrices, basis, rotor, condition, n_modes, points[-1] if points else None,
                                    chordwise_centre))
    first = onset(points)
    unconverged = sum(int((~p.converged).sum()) for p in points)
    extra = (f"{unconverged} p-k roots did not converge (left out of the onset search)",) if unconverged else ()
    return FlutterResult(points=points, onset=first, notes=notes + extra)


def tracking_mac(a: FlutterPoint, b: FlutterPoint) -> NDArray:
    """MAC of each tracked mode of ``b`` against the same mode of ``a`` (a check of the tracking)."""
    return np.array([mac(a.shapes[:, j], b.shapes[:, [j]])[0] for j in range(a.shapes.shape[1])])
