"""Results of a modal solve: frequencies, mode shapes, kinds, residuals; and of a Campbell sweep."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

KINDS: tuple[str, ...] = ("flap", "edge", "torsion", "axial")


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

    ``flap`` is the out-of-plane deflection w (m per unit modal amplitude), ``edge`` the in-plane deflection v,
    their slopes (rad), ``twist`` the elastic twist phi (rad) and ``axial`` the axial displacement u (m); fields
    that are rigid in the model are zero. The shape is scaled so that its largest displacement component
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
