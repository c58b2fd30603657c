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
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from ..sections import Blade, SectionTable
from ..sections.principal import elastodyn_sections
from .elastodyn_integrals import (  # noqa: F401 - re-exported
    BLADE_DOFS,
    elastodyn_coupled_frequencies,
    centrifugal_load,
    elastodyn_forms,
    elastodyn_frequency,
    elastodyn_nodes,
    gravity_load,
)
from .results import ModalResult, Mode
from .sextic import (  # noqa: F401 - the polynomial's tools, re-exported for the users of this module
    GAUSS_POINTS,
    POWERS,
    PolynomialFit,
    composite_gauss,
    fit_sextic,
    fit_sextic_at_frequency,
    monomials,
    polynomial,
    quality,
)

#: Two frequencies closer than this (relative) form a degenerate pair (a tower with equal FA and SS stiffness).
DEGENERATE_RTOL = 1e-6
#: Default warning threshold on |tip displacement| / max |displacement| of the fitted component.
MIN_TIP_RATIO = 0.3

BLADE_MODES = {"flap1": ("flap", 1), "flap2": ("flap", 2), "edge1": ("edge", 1)}
TOWER_MODES = {"fa1": ("flap", 1), "fa2": ("flap", 2), "ss1": ("edge", 1), "ss2": ("edge", 2)}
LABELS = {"flap1": "blade flap 1", "flap2": "blade flap 2", "edge1": "blade edge 1", "fa1": "tower fore-aft 1",
          "fa2": "tower fore-aft 2", "ss1": "tower side-side 1", "ss2": "tower side-side 2"}


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
    elastodyn_frequency_hz : the frequency of the polynomial mode alone in ElastoDyn's equations of motion (its own
        node integrals; blades: the shapes twisted as in its equations, so slightly below the untwisted estimate
        ElastoDyn prints as FreqBF), Hz
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


# -- whole blades and towers --------------------------------------------------------------------------------------

@dataclass(frozen=True)
class BeamIntegrals:
    """What ElastoDyn's integrals need besides the polynomial: sections, the tip (or top) point mass, kg, the hub
    radius, m, the precone, rad, the rotor speed, rad/s, gravity, m/s^2 (towers), and for blades the pitch, rad
    (blade shapes are twisted by the structural twist plus pitch, as in ElastoDyn's equations of motion)."""

    sections: SectionTable
    tip_mass: float = 0.0
    hub_radius: float = 0.0
    precone: float = 0.0
    omega: float = 0.0
    gravity: float = 0.0
    tower: bool = False
    pitch: float = 0.0

    def forms(self, kind: str, nodes: int) -> tuple[NDArray, NDArray]:
        """ElastoDyn's stiffness and mass quadratic forms of a ``kind`` ('flap', 'edge') mode (see
        :func:`elastodyn_forms`)."""
        return elastodyn_forms(self.sections, f"{kind}_stiffness", nodes, tip_mass=self.tip_mass, omega=self.omega,
                               hub_radius=self.hub_radius, precone=self.precone,
                               in_plane=kind == "edge" and not self.tower, gravity=self.gravity,
                               twist_pitch=None if self.tower else self.pitch)

    def frequency(self, coefficients: NDArray, kind: str, nodes: int) -> float:
        K, M = self.forms(kind, nodes)
        c = np.asarray(coefficients, dtype=float)
        return math.sqrt(max(float(c @ K @ c), 0.0) / float(c @ M @ c)) / (2 * math.pi)


def _tip_warning(name: str, target: Target, fit: PolynomialFit, min_tip_ratio: float) -> tuple[str, ...]:
    if target.tip_ratio >= min_tip_ratio:
        return ()
    return (f"{LABELS[name]}: tip displacement is only {target.tip_ratio:.3g} of the largest displacement; a "
            f"tip-normalised polynomial amplifies errors (coefficients up to {np.max(np.abs(fit.coefficients)):.3g})",)


def fit_modes(result: ModalResult, beam: BeamIntegrals, wanted: dict[str, tuple[str, int]], nodes: int,
              shipped: dict[str, NDArray] | None = None, min_tip_ratio: float = MIN_TIP_RATIO,
              preserve_frequency: bool = True) -> tuple[dict[str, ModeFit], dict[str, ModeFit] | None]:
    """Fit the modes named in ``wanted`` (name -> (kind, number)) of ``result``; also evaluate the ``shipped``
    coefficients (e.g. those already in a file) against the same modes.

    ``preserve_frequency``: constrain each fit so that ElastoDyn's own integrals of the polynomial (``beam`` on
    ``nodes``) give the finite-element frequency (:func:`fit_sextic_at_frequency`; when no sextic reaches it, the
    displacement fit, with a warning). A warning also when ElastoDyn's frequency of the fit is farther from the
    finite element's than that of the ``shipped`` coefficients."""
    by_kind = {kind: modes_of_kind(result, kind) for kind in ("flap", "edge")}
    fits, compared = {}, {}
    for name, (kind, number) in wanted.items():
        if len(by_kind[kind]) < number:
            raise LookupError(f"{LABELS[name]}: only {len(by_kind[kind])} {kind} modes among the "
                              f"{len(result.modes)} computed; ask for more modes")
        mode = by_kind[kind][number - 1]
        target = fitting_target(mode, kind, beam.sections.length, remove_base_motion=beam.tower)
        fit = fit_sextic(target.points, target.weights, target.values, target.tip_slope)
        warnings = _tip_warning(name, target, fit, min_tip_ratio)
        if preserve_frequency:
            fit, note = _frequency_preserving(fit, target, beam, kind, nodes, mode.frequency_hz)
            warnings += (f"{LABELS[name]}: {note}",) if note else ()
        fits[name] = ModeFit(name, fit, mode.frequency_hz, beam.frequency(fit.coefficients, kind, nodes),
                             target.tip_ratio, warnings)
        if shipped and name in shipped:
            old = quality(np.asarray(shipped[name], dtype=float), target.points, target.weights, target.values,
                          target.tip_slope)
            compared[name] = ModeFit(name, old, mode.frequency_hz, beam.frequency(old.coefficients, kind, nodes),
                                     target.tip_ratio)
            fits[name] = _compare_with_shipped(fits[name], compared[name])
    return fits, (compared or None)


#: a frequency-preserving fit is kept while its RMS error stays within this factor of the displacement fit's (or
#: below 1e-2 of the tip deflection)
DISTORTION_FACTOR = 10.0
#: an unreachable FE frequency is reported when the displacement fit is farther from it than this (relative)
UNREACHED_TOLERANCE = 1e-3


def _frequency_preserving(plain: PolynomialFit, target: Target, beam: BeamIntegrals, kind: str, nodes: int,
                          frequency_hz: float) -> tuple[PolynomialFit, str | None]:
    """The fit constrained to the FE frequency in ElastoDyn's integrals, or the displacement fit with a note when
    no sextic reaches that frequency, or when reaching it would distort the shape (the mode holds what ElastoDyn's
    integrals cannot see, e.g. a tower top's rotary inertia)."""
    K, M = beam.forms(kind, nodes)
    constrained = fit_sextic_at_frequency(target.points, target.weights, target.values, target.tip_slope, K, M,
                                          2 * math.pi * frequency_hz)
    reached = beam.frequency(plain.coefficients, kind, nodes)
    if not constrained.frequency_preserved:
        if abs(reached / frequency_hz - 1) <= UNREACHED_TOLERANCE:
            return plain, None
        return plain, (f"no sextic has the finite-element frequency {frequency_hz:.5g} Hz with ElastoDyn's "
                       f"integrals on {nodes} nodes; the displacement fit gives {reached:.5g} Hz")
    if constrained.rms_error > max(DISTORTION_FACTOR * plain.rms_error, 1e-2):
        return plain, (f"holding the finite-element frequency {frequency_hz:.5g} Hz would distort the shape (RMS "
                       f"{constrained.rms_error:.2g} against {plain.rms_error:.2g}): ElastoDyn's integrals do not "
                       f"hold what sets it; the displacement fit ({reached:.5g} Hz) is kept")
    return constrained, None


def _compare_with_shipped(fresh: ModeFit, shipped: ModeFit) -> ModeFit:
    """The fresh fit with a warning when ElastoDyn's frequency of it is farther from the finite element's than that
    of the shipped coefficients (by more than 1e-4, relative)."""
    def frequency_error(fit: ModeFit) -> float:
        return abs(fit.elastodyn_frequency_hz / fit.fe_frequency_hz - 1)

    if frequency_error(fresh) <= frequency_error(shipped) + 1e-4:
        return fresh
    note = (f"{fresh.label}: ElastoDyn's frequency of the fit is {100 * frequency_error(fresh):.2f} % from the "
            f"finite element's, that of the file's coefficients {100 * frequency_error(shipped):.2f} %",)
    return replace(fresh, warnings=fresh.warnings + note)


@dataclass(frozen=True)
class ElastoDynCoefficients:
    """Fitted coefficients of a blade (flap1, flap2, edge1) or a tower (fa1, fa2, ss1, ss2).

    fits : name -> fit, FE and ElastoDyn-derived frequencies
    rpm : rotor speed of the modes, rpm (0 for a tower)
    nodes : ElastoDyn analysis nodes used for its generalized mass and stiffness
    tower : True for a tower
    shipped : quality of the coefficients given for comparison (e.g. those already in the file), or None
    notes : modelling statements from the model and the fit
    coupled_hz : blades: the frequencies (Hz) of the three fitted modes together in ElastoDyn's equations, as its
        linearization finds them (:func:`~bladefem.modal.elastodyn_integrals.elastodyn_coupled_frequencies`)
    shipped_coupled_hz : the same for the ``shipped`` coefficients
    """

    fits: dict[str, ModeFit]
    rpm: float
    nodes: int
    tower: bool
    shipped: dict[str, ModeFit] | None = None
    notes: tuple[str, ...] = ()
    coupled_hz: dict[str, float] | None = None
    shipped_coupled_hz: dict[str, float] | None = None

    @property
    def warnings(self) -> tuple[str, ...]:
        return tuple(w for fit in self.fits.values() for w in fit.warnings)

    @property
    def coefficients(self) -> dict[str, NDArray[np.float64]]:
        return {name: fit.fit.coefficients for name, fit in self.fits.items()}


def blade_coefficients(blade: Blade, rpm: float, *, nodes: int = 17, n_modes: int = 12, elements: int | None = None,
                       shipped: dict[str, NDArray] | None = None, min_tip_ratio: float = MIN_TIP_RATIO,
                       preserve_frequency: bool = True) -> ElastoDynCoefficients:
    """ElastoDyn blade coefficients (flap 1, flap 2, edge 1) from the FE modes at ``rpm`` (rpm); ``nodes`` is
    ElastoDyn's BldNodes; ``shipped`` coefficients, if given, are evaluated against the same modes;
    ``preserve_frequency`` constrains each fit to the FE frequency (see :func:`fit_modes`). ElastoDyn's own
    integrals take what its blade file holds (:func:`bladefem.sections.principal.elastodyn_sections`: for
    six-by-six sections the principal stiffnesses about the tension centre, the principal angle in the twist)."""
    from . import modes
    result = modes(blade, rpm, n_modes, elements)
    beam = BeamIntegrals(elastodyn_sections(blade.sections), blade.tip_mass.mass if blade.tip_mass is not None else 0.0,
                         blade.hub_radius, blade.precone, rpm * math.pi / 30.0, pitch=blade.pitch)
    fits, compared = fit_modes(result, beam, BLADE_MODES, nodes, shipped, min_tip_ratio, preserve_frequency)

    def coupled(coefficients: dict[str, NDArray] | None) -> dict[str, float] | None:
        if not coefficients or any(name not in coefficients for name, _ in BLADE_DOFS):
            return None
        return elastodyn_coupled_frequencies(coefficients, beam.sections, nodes, tip_mass=beam.tip_mass,
                                             omega=beam.omega, hub_radius=beam.hub_radius, precone=beam.precone,
                                             twist_pitch=beam.pitch)

    return ElastoDynCoefficients(fits, rpm, nodes, False, compared, result.notes,
                                 coupled({name: fit.fit.coefficients for name, fit in fits.items()}), coupled(shipped))
