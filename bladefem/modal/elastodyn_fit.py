"""ElastoDyn mode-shape coefficients: constrained polynomial fits of finite-element mode shapes, their quality, and
the frequencies ElastoDyn itself would derive from the polynomials.

ElastoDyn describes each blade and tower mode by ``phi(x) = sum_{i=2..6} c_i x^i`` on the normalised span
``x in [0, 1]``, normalised to 1 at the tip (``sum c_i = 1``). The fit minimises ``int_0^1 (phi - y)^2 dx`` where
``y`` is the finite-element shape divided by its tip value; the integral is evaluated by Gauss quadrature on every
finite element (the FE shape is a Hermite cubic there), so the result does not depend on where the nodes are. The
constraint is imposed exactly by eliminating ``c_6 = 1 - (c_2 + ... + c_5)``.

Flap modes are fitted to the out-of-plane displacement, edge modes to the in-plane displacement (for a tower:
fore-aft and side-side). For towers the rigid motion of the base (displacement and slope at the base) is
subtracted first, so that a flexible foundation does not enter the polynomial.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..sections import Blade, SectionTable
from .results import ModalResult, Mode

POWERS = np.arange(2, 7)
#: Gauss points per finite element: (sextic - cubic)^2 is a polynomial of degree 12, integrated exactly by 7.
GAUSS_POINTS = 7
#: Two frequencies closer than this (relative) form a degenerate pair (a tower with equal FA and SS stiffness).
DEGENERATE_RTOL = 1e-6
#: Default warning threshold on |tip displacement| / max |displacement| of the fitted component.
MIN_TIP_RATIO = 0.3

BLADE_MODES = {"flap1": ("flap", 1), "flap2": ("flap", 2), "edge1": ("edge", 1)}
TOWER_MODES = {"fa1": ("flap", 1), "fa2": ("flap", 2), "ss1": ("edge", 1), "ss2": ("edge", 2)}
LABELS = {"flap1": "blade flap 1", "flap2": "blade flap 2", "edge1": "blade edge 1", "fa1": "tower fore-aft 1",
          "fa2": "tower fore-aft 2", "ss1": "tower side-side 1", "ss2": "tower side-side 2"}


# -- the polynomial -----------------------------------------------------------------------------------------------

def polynomial(coefficients: NDArray, x: NDArray, derivative: int = 0) -> NDArray:
    """``d^k/dx^k sum_i c_i x^i`` (i = 2..6) at normalised positions ``x``."""
    x = np.asarray(x, dtype=float)
    total = np.zeros_like(x)
    for c, power in zip(coefficients, POWERS):
        if power >= derivative:
            total = total + c * math.perm(int(power), derivative) * x ** (power - derivative)
    return total


def composite_gauss(breakpoints: NDArray, order: int = GAUSS_POINTS) -> tuple[NDArray, NDArray]:
    """Points and weights of ``order``-point Gauss-Legendre rules on every interval between ``breakpoints``."""
    xi, wi = np.polynomial.legendre.leggauss(order)
    a, b = breakpoints[:-1, None], breakpoints[1:, None]
    points = (a + b) / 2 + (b - a) / 2 * xi[None, :]
    weights = (b - a) / 2 * wi[None, :]
    return points.ravel(), weights.ravel()


@dataclass(frozen=True)
class PolynomialFit:
    """A tip-normalised sextic and how well it reproduces a target shape.

    coefficients : c_2 .. c_6 (sum exactly 1 up to rounding)
    rms_error : sqrt(int_0^1 (phi - y)^2 dx), y the target normalised by its tip displacement
    tip_slope_error : phi'(1) - y'(1), slopes per unit normalised span (so relative to tip displacement / length)
    condition_number : 2-norm condition number of the weighted least-squares design matrix
    """

    coefficients: NDArray[np.float64]
    rms_error: float
    tip_slope_error: float
    condition_number: float


def fit_sextic(points: NDArray, weights: NDArray, target: NDArray, tip_slope: float) -> PolynomialFit:
    """Least-squares fit of ``sum c_i x^i`` with ``sum c_i = 1`` to ``target`` (tip-normalised) at quadrature
    ``points`` with ``weights`` over [0, 1]; ``tip_slope`` is the target's slope at x = 1."""
    basis = points[:, None] ** POWERS[None, :-1] - points[:, None] ** 6      # x^i - x^6, i = 2..5
    root_w = np.sqrt(weights)
    design = root_w[:, None] * basis
    free, *_ = np.linalg.lstsq(design, root_w * (target - points**6), rcond=None)
    coefficients = np.append(free, 1.0 - free.sum())
    return quality(coefficients, points, weights, target, tip_slope, float(np.linalg.cond(design)))


def quality(coefficients: NDArray, points: NDArray, weights: NDArray, target: NDArray, tip_slope: float,
            condition_number: float = float("nan")) -> PolynomialFit:
    """RMS and tip-slope errors of given coefficients against a tip-normalised target."""
    residual = polynomial(coefficients, points) - target
    rms = math.sqrt(float(np.sum(weights * residual**2)))
    slope_error = float(polynomial(coefficients, np.array([1.0]), 1)[0]) - tip_slope
    return PolynomialFit(np.asarray(coefficients, dtype=float), rms, slope_error, condition_number)


# -- from a finite-element mode -----------------------------------------------------------------------------------

@dataclass(frozen=True)
class Target:
    """A mode's displacement component prepared for fitting: tip-normalised values at quadrature points."""

    points: NDArray[np.float64]
    weights: NDArray[np.float64]
    values: NDArray[np.float64]
    tip_slope: float
    tip_ratio: float


def fitting_target(mode: Mode, component: str, length: float, remove_base_motion: bool = False) -> Target:
    """The ``component`` ('flap' or 'edge') of ``mode`` as a tip-normalised function of x / length.

    ``remove_base_motion`` subtracts the base displacement and slope (rigid motion of a tower on a flexible base).
    ``tip_ratio`` is |tip displacement| / max |displacement| of the elastic part.
    """
    shape = mode.shape
    points, weights = composite_gauss(shape.x / length)
    nodes = np.concatenate([points * length, shape.x, [length]])
    sampled = shape.at(nodes)
    value, slope = sampled[component], sampled[f"{component}_slope"]
    if remove_base_motion:
        value = value - value[len(points)] - slope[len(points)] * nodes   # base at shape.x[0] = 0
        slope = slope - slope[len(points)]
    tip_value, tip_slope = value[-1], slope[-1]
    peak = float(np.max(np.abs(value)))
    ratio = abs(tip_value) / peak if peak > 0 else 0.0
    scale = tip_value if tip_value != 0 else 1.0
    return Target(points, weights, value[:len(points)] / scale, float(tip_slope * length / scale), ratio)


def modes_of_kind(result: ModalResult, kind: str) -> list[Mode]:
    """Modes of one kind in frequency order. Degenerate clusters (equal frequencies, e.g. a tower with equal
    fore-aft and side-side stiffness, where the solver may return any mix of the two) hold as many modes of a kind
    as their energy shares add up to; the mode of the cluster with the largest share stands for them."""
    found: list[Mode] = []
    modes = result.modes
    i = 0
    while i < len(modes):
        j = i + 1
        while j < len(modes) and abs(modes[j].frequency_hz - modes[i].frequency_hz) <= DEGENERATE_RTOL * abs(
                modes[i].frequency_hz):
            j += 1
        cluster = modes[i:j]
        count = round(sum(mode.energy_fractions.get(kind, 0.0) for mode in cluster))
        best = max(cluster, key=lambda mode: mode.energy_fractions.get(kind, 0.0))
        found += [best] * count
        i = j
    return found


@dataclass(frozen=True)
class ModeFit:
    """The ElastoDyn polynomial of one mode, its quality and frequencies.

    name : 'flap1', 'flap2', 'edge1' (blade) or 'fa1', 'fa2', 'ss1', 'ss2' (tower)
    fit : coefficients and fit quality
    fe_frequency_hz : the finite-element frequency of the mode, Hz
    elastodyn_frequency_hz : the frequency ElastoDyn derives from the polynomial (its own node integrals), Hz
    tip_ratio : |tip displacement| / max |displacement| of the fitted component
    warnings : e.g. a tip displacement too small for a tip-normalised polynomial
    """

    name: str
    fit: PolynomialFit
    fe_frequency_hz: float
    elastodyn_frequency_hz: float
    tip_ratio: float
    warnings: tuple[str, ...] = ()

    @property
    def label(self) -> str:
        return LABELS.get(self.name, self.name)


# -- ElastoDyn's own generalized mass and stiffness ---------------------------------------------------------------

def elastodyn_nodes(length: float, count: int) -> tuple[NDArray, float]:
    """ElastoDyn's analysis nodes: midpoints of ``count`` equal elements over ``length``; (positions m, dr m)."""
    dr = length / count
    return (np.arange(count) + 0.5) * dr, dr


def centrifugal_load(sections: SectionTable, nodes: NDArray, dr: float, hub_radius: float, tip_mass: float,
                     omega: float, precone: float) -> NDArray:
    """Axial load N (N) at each node from the node masses outboard of it, lumped as ElastoDyn lumps them (the
    outer half of a node's own element sits at r + dr/4), plus the tip mass at the tip."""
    element = sections.at(nodes, "mass") * dr
    moments = element * (hub_radius + nodes)
    outboard = np.cumsum(moments[::-1])[::-1] - moments
    own = 0.5 * element * (hub_radius + nodes + dr / 4)
    tip = tip_mass * (hub_radius + sections.length)
    return omega**2 * math.cos(precone) ** 2 * (outboard + own + tip)


def gravity_load(sections: SectionTable, nodes: NDArray, dr: float, top_mass: float, gravity: float) -> NDArray:
    """Compressive axial load (N) at each tower node: the weight of the node masses above it (the upper half of
    its own element included) and of the top mass."""
    element = sections.at(nodes, "mass") * dr
    above = np.cumsum(element[::-1])[::-1] - element / 2
    return gravity * (above + top_mass)


def elastodyn_frequency(coefficients: NDArray, sections: SectionTable, stiffness: str, nodes: int, *,
                        tip_mass: float = 0.0, omega: float = 0.0, hub_radius: float = 0.0, precone: float = 0.0,
                        in_plane: bool = False, gravity: float = 0.0) -> float:
    """Frequency (Hz) ElastoDyn derives for a polynomial mode from its generalized mass and stiffness:
    ``M = sum m phi^2 dr + M_tip``, ``K = sum EI phi''^2 dr + sum N phi'^2 dr - sum P phi'^2 dr`` over its own
    ``nodes``, with ``stiffness`` the EI column ('flap_stiffness' or 'edge_stiffness'), the centrifugal tension
    ``N`` at rotor speed ``omega`` (rad/s), for an in-plane blade mode the spin softening ``- omega^2 M``, and for
    a tower the gravity load ``P`` (``gravity`` in m/s^2, 0 for none)."""
    length = sections.length
    r, dr = elastodyn_nodes(length, nodes)
    x = r / length
    phi, phi1, phi2 = (polynomial(coefficients, x, k) / length**k for k in (0, 1, 2))
    mass = float(np.sum(sections.at(r, "mass") * phi**2) * dr) + tip_mass
    elastic = float(np.sum(sections.at(r, stiffness) * phi2**2) * dr)
    load = centrifugal_load(sections, r, dr, hub_radius, tip_mass, omega, precone)
    load = load - gravity_load(sections, r, dr, tip_mass, gravity)
    geometric = float(np.sum(load * phi1**2) * dr)
    softening = omega**2 * mass if in_plane else 0.0
    return math.sqrt(max(elastic + geometric - softening, 0.0) / mass) / (2 * math.pi)


# -- whole blades and towers --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class BeamIntegrals:
    """What ElastoDyn's integrals need besides the polynomial: sections, the tip (or top) point mass, kg, the hub
    radius, m, the precone, rad, the rotor speed, rad/s, and gravity, m/s^2 (towers)."""

    sections: SectionTable
    tip_mass: float = 0.0
    hub_radius: float = 0.0
    precone: float = 0.0
    omega: float = 0.0
    gravity: float = 0.0
    tower: bool = False

    def frequency(self, coefficients: NDArray, kind: str, nodes: int) -> float:
        return elastodyn_frequency(coefficients, self.sections, f"{kind}_stiffness", nodes, tip_mass=self.tip_mass,
                                   omega=self.omega, hub_radius=self.hub_radius, precone=self.precone,
                                   in_plane=kind == "edge" and not self.tower, gravity=self.gravity)


def _tip_warning(name: str, target: Target, fit: PolynomialFit, min_tip_ratio: float) -> tuple[str, ...]:
    if target.tip_ratio >= min_tip_ratio:
        return ()
    return (f"{LABELS[name]}: tip displacement is only {target.tip_ratio:.3g} of the largest displacement; a "
            f"tip-normalised polynomial amplifies errors (coefficients up to {np.max(np.abs(fit.coefficients)):.3g})",)


def fit_modes(result: ModalResult, beam: BeamIntegrals, wanted: dict[str, tuple[str, int]], nodes: int,
              shipped: dict[str, NDArray] | None = None,
              min_tip_ratio: float = MIN_TIP_RATIO) -> tuple[dict[str, ModeFit], dict[str, ModeFit] | None]:
    """Fit the modes named in ``wanted`` (name -> (kind, number)) of ``result``; also evaluate the ``shipped``
    coefficients (e.g. those already in a file) against the same modes."""
    by_kind = {kind: modes_of_kind(result, kind) for kind in ("flap", "edge")}
    fits, compared = {}, {}
    for name, (kind, number) in wanted.items():
        if len(by_kind[kind]) < number:
            raise LookupError(f"{LABELS[name]}: only {len(by_kind[kind])} {kind} modes among the "
                              f"{len(result.modes)} computed; ask for more modes")
        mode = by_kind[kind][number - 1]
        target = fitting_target(mode, kind, beam.sections.length, remove_base_motion=beam.tower)
        fit = fit_sextic(target.points, target.weights, target.values, target.tip_slope)
        fits[name] = ModeFit(name, fit, mode.frequency_hz, beam.frequency(fit.coefficients, kind, nodes),
                             target.tip_ratio, _tip_warning(name, target, fit, min_tip_ratio))
        if shipped and name in shipped:
            old = quality(np.asarray(shipped[name], dtype=float), target.points, target.weights, target.values,
                          target.tip_slope)
            compared[name] = ModeFit(name, old, mode.frequency_hz, beam.frequency(old.coefficients, kind, nodes),
                                     target.tip_ratio)
    return fits, (compared or None)


@dataclass(frozen=True)
class ElastoDynCoefficients:
    """Fitted coefficients of a blade (flap1, flap2, edge1) or a tower (fa1, fa2, ss1, ss2).

    fits : name -> fit, FE and ElastoDyn-derived frequencies
    rpm : rotor speed of the modes, rpm (0 for a tower)
    nodes : ElastoDyn analysis nodes used for its generalized mass and stiffness
    tower : True for a tower
    shipped : quality of the coefficients given for comparison (e.g. those already in the file), or None
    notes : modelling statements from the model and the fit
    """

    fits: dict[str, ModeFit]
    rpm: float
    nodes: int
    tower: bool
    shipped: dict[str, ModeFit] | None = None
    notes: tuple[str, ...] = ()

    @property
    def warnings(self) -> tuple[str, ...]:
        return tuple(w for fit in self.fits.values() for w in fit.warnings)

    @property
    def coefficients(self) -> dict[str, NDArray[np.float64]]:
        return {name: fit.fit.coefficients for name, fit in self.fits.items()}


def blade_coefficients(blade: Blade, rpm: float, *, nodes: int = 17, n_modes: int = 12, elements: int | None = None,
                       shipped: dict[str, NDArray] | None = None,
                       min_tip_ratio: float = MIN_TIP_RATIO) -> ElastoDynCoefficients:
    """ElastoDyn blade coefficients (flap 1, flap 2, edge 1) from the FE modes at ``rpm`` (rpm); ``nodes`` is
    ElastoDyn's BldNodes; ``shipped`` coefficients, if given, are evaluated against the same modes."""
    from . import modes
    result = modes(blade, rpm, n_modes, elements)
    beam = BeamIntegrals(blade.sections, blade.tip_mass.mass if blade.tip_mass is not None else 0.0,
                         blade.hub_radius, blade.precone, rpm * math.pi / 30.0)
    fits, compared = fit_modes(result, beam, BLADE_MODES, nodes, shipped, min_tip_ratio)
    return ElastoDynCoefficients(fits, rpm, nodes, False, compared, result.notes)
