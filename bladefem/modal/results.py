"""Results of a modal solve: frequencies, mode shapes, kinds, residuals; and of a Campbell sweep."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ..errors import SolveError

KINDS: tuple[str, ...] = ("flap", "edge", "torsion", "axial")
#: Largest relative eigen-residual ||K x - omega^2 M x|| / ||K x|| of a mode that is a result. On fine meshes the
#: residual measures the round-off of K x, not the frequency (taken from the Rayleigh quotient): NREL 5MW blade on
#: 1600 elements 6e-4, with a 1e4 stiffness spike 0.4, all frequencies within 1e-5. It reaches 1 when round-off
#: swamps a mode: a 1e6 spike on 1600 elements gives 1.0 with the first frequency 5e-3 off. Values that far out
#: (unit slips, 1e308) are refused by the readers; this catches what gets past them.
MAX_RESIDUAL = 0.5
#: Frequencies below this, or below RIGID_FRACTION of the highest one computed, are rigid-body motions at round-off
#: (no blade, tower or platform mode is that slow; a floating platform's surge is near 0.008 Hz): their relative
#: residual has no meaning, K x being itself round-off. The eigen-solver puts them near sqrt(eps) times its mesh's
#: highest frequency: a hinged uniform blade at rest has its rigid flap and edge modes at 1e-3 and 1e-2 Hz, 1.3e-2
#: of its first elastic (torsion) mode. With a single mode asked for there is no scale to judge it by.
RIGID_HZ = 1e-3
RIGID_FRACTION = 0.05


def hermite_interpolate(nodes: NDArray, values: NDArray, slopes: NDArray, x: NDArray) -> tuple[NDArray, NDArray]:
    """Cubic Hermite interpolation of nodal values and slopes at points ``x``; returns (value, slope)."""
    x = np.asarray(x, dtype=float)
    i = np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, len(nodes) - 2)
    h = nodes[i + 1] - nodes[i]
    t = (x - nodes[i]) / h
    h00, h10, h01, h11 = 2 * t**3 - 3 * t**2 + 1, t**3 - 2 * t**2 + t, -2 * t**3 + 3 * t**2, t**3 - t**2
    d00, d10, d01, d11 = 6 * t**2 - 6 * t, 3 * t**2 - 4 * t + 1, -6 * t**2 + 6 * t, 3 * t**2 - 2 * t
    value = h00 * values[i] + h10 * h * slopes[i] + h01 * values[i + 1] + h11 * h * slopes[i + 1]
    slope = (d00 * values[i] + d01 * values[i + 1]) / h + d10 * slopes[i] + d11 * slopes[i + 1]
    return value, slope


@dataclass(frozen=True)
class ModeShape:
    """A mode shape at the mesh nodes (every section station is a node), blade frame.

    ``flap`` is the out-of-plane deflection w (m per unit modal amplitude), ``edge`` the in-plane deflection v (a
    shear-flexible beam: bending plus shear deflection), their slopes (rad: the section's rotation, which a
    shear-flexible beam's deflection slope exceeds by the shear strain), ``twist`` the elastic twist phi (rad) and
    ``axial`` the axial displacement u (m); fields that are rigid in the model are zero. The shape is scaled so that its largest displacement component
    (flap, edge or axial, or twist if torsion dominates) is 1 with positive sign.
    """

    x: NDArray[np.float64]
    flap: NDArray[np.float64]
    flap_slope: NDArray[np.float64]
    edge: NDArray[np.float64]
    edge_slope: NDArray[np.float64]
    twist: NDArray[np.float64]
    axial: NDArray[np.float64]

    def at(self, x: NDArray) -> dict[str, NDArray]:
        """The shape at any span positions ``x`` (m), interpolated with the element's own shape functions
        (Hermite cubic for flap and edge, piecewise linear between nodes for twist and axial)."""
        flap, flap_slope = hermite_interpolate(self.x, self.flap, self.flap_slope, x)
        edge, edge_slope = hermite_interpolate(self.x, self.edge, self.edge_slope, x)
        return {"x": np.asarray(x, dtype=float), "flap": flap, "flap_slope": flap_slope, "edge": edge,
                "edge_slope": edge_slope, "twist": np.interp(x, self.x, self.twist),
                "axial": np.interp(x, self.x, self.axial)}


def signed_frequency_hz(eigenvalue: float) -> float:
    """Natural frequency (Hz) from omega^2 (rad^2/s^2); negative for a negative eigenvalue (statically unstable)."""
    return float(np.sign(eigenvalue) * np.sqrt(abs(eigenvalue)) / (2 * np.pi))


def dominant_kind(fractions: dict[str, float]) -> str:
    """The kind with the largest kinetic-energy share."""
    return max(fractions, key=fractions.get)  # type: ignore[arg-type]


@dataclass(frozen=True)
class Mode:
    """One natural mode.

    frequency_hz : natural frequency, Hz
    kind : 'flap', 'edge', 'torsion' or 'axial', the field with the largest share of kinetic energy
    energy_fractions : kinetic-energy share of each field (sums to 1)
    residual : ||K x - omega^2 M x|| / ||K x||, the relative eigen-residual (quadratic problem:
        ||(lambda^2 M + lambda C + K) x|| / ||K x||)
    shape : the mode shape at the mesh nodes (quadratic problem: the real part of the complex shape turned so that
        its largest component is real)
    damping_ratio : -Re(lambda) / |lambda| of the quadratic eigenproblem (with Coriolis or damping), else None;
        frequency_hz is then the undamped natural frequency |lambda| / 2 pi
    damped_frequency_hz : Im(lambda) / 2 pi of the quadratic eigenproblem, else None
    """

    frequency_hz: float
    kind: str
    energy_fractions: dict[str, float]
    residual: float
    shape: ModeShape
    damping_ratio: float | None = None
    damped_frequency_hz: float | None = None


def check_modes(modes: list[Mode], rpm: float) -> None:
    """A :class:`~bladefem.errors.SolveError` for the first mode that is not a result: a frequency that is not finite
    or a residual above :data:`MAX_RESIDUAL` (it would print as a plausible frequency that is not one)."""
    highest = max((abs(mode.frequency_hz) for mode in modes if math.isfinite(mode.frequency_hz)), default=0.0)
    for number, mode in enumerate(modes, 1):
        rigid = abs(mode.frequency_hz) < max(RIGID_HZ, RIGID_FRACTION * highest)
        if not (math.isfinite(mode.frequency_hz) and (rigid or mode.residual <= MAX_RESIDUAL)):
            raise SolveError(f"mode {number} at {rpm:g} rpm is not a result: frequency {mode.frequency_hz:.6g} Hz with "
                             f"eigen-residual {mode.residual:.2g} (a result needs at most {MAX_RESIDUAL:g}); the "
                             "section properties are too extreme for double precision (check for a value many "
                             "decades off, e.g. a stiffness typed in the wrong unit)")


@dataclass(frozen=True)
class ModalResult:
    """Natural modes at one rotor speed.

    rotor_speed_rpm : rotor speed, rpm
    modes : modes sorted by frequency
    stations : span positions of the section stations, m
    vectors : mass-normalised eigenvectors over the free DOFs (columns), for MAC tracking and post-processing
    n_dofs : number of free DOFs in the model
    notes : modelling statements (e.g. rigid torsion because the input had no GJ)
    """

    rotor_speed_rpm: float
    modes: list[Mode]
    stations: NDArray[np.float64]
    vectors: NDArray[np.float64] = field(repr=False)
    n_dofs: int = 0
    notes: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        check_modes(self.modes, self.rotor_speed_rpm)

    @property
    def frequencies_hz(self) -> NDArray[np.float64]:
        return np.array([mode.frequency_hz for mode in self.modes])

    @property
    def kinds(self) -> list[str]:
        return [mode.kind for mode in self.modes]

    def first(self, kind: str, number: int = 1) -> Mode:
        """The ``number``-th mode of a kind (e.g. ``first('flap', 2)`` is the second flap mode)."""
        found = [mode for mode in self.modes if mode.kind == kind]
        if len(found) < number:
            raise LookupError(f"only {len(found)} {kind} modes among the {len(self.modes)} computed")
        return found[number - 1]


@dataclass(frozen=True)
class ModeFamily:
    """One mode followed over rotor speed by MAC between neighbouring speeds.

    kind : the family's kind at the first speed
    frequencies_hz : frequency at each speed, Hz
    indices : position of the family's mode in each speed's sorted mode list
    mac : MAC between the family's mode at each speed and at the previous speed (1 at the first speed)
    damping_ratios : damping ratio at each speed (quadratic eigenproblem only, else None)
    """

    kind: str
    frequencies_hz: NDArray[np.float64]
    indices: NDArray[np.int64]
    mac: NDArray[np.float64]
    damping_ratios: NDArray[np.float64] | None = None


@dataclass(frozen=True)
class CampbellResult:
    """Modes over a sweep of rotor speeds, grouped into families."""

    rpm: NDArray[np.float64]
    families: list[ModeFamily]
    results: list[ModalResult] = field(repr=False)
    notes: tuple[str, ...] = ()
