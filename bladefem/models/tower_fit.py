"""ElastoDyn tower mode-shape coefficients fitted to the tower model's modes."""

from __future__ import annotations

from numpy.typing import NDArray

from ..modal import modes
from ..modal.elastodyn_fit import (
    MIN_TIP_RATIO,
    TOWER_MODES,
    BeamIntegrals,
    ElastoDynCoefficients,
    fit_modes,
)
from ..sections import Blade
from ..sections.tower import as_tower
from .tower import tower_modes, with_blade_kinds


def tower_coefficients(tower: object, *, nodes: int = 20, n_modes: int = 12, elements: int | None = None,
                       shipped: dict[str, NDArray] | None = None,
                       min_tip_ratio: float = MIN_TIP_RATIO) -> ElastoDynCoefficients:
    """ElastoDyn tower coefficients (fore-aft 1 and 2, side-side 1 and 2); ``nodes`` is TwrNodes.

    ``tower``: a :class:`bladefem.sections.tower.Tower` (or reader output with sections and a top mass), solved by
    the tower model (gravity, supports; the ElastoDyn integrals then include ElastoDyn's gravity term), or a
    non-rotating :class:`Blade` (``Tower.as_beam()``: flap = fore-aft, edge = side-side, no gravity). ElastoDyn's
    integrals see the top body as a point mass (its TwrTpMass), whatever its offsets and inertia in the FE model.
    """
    notes: tuple[str, ...] = ()
    if isinstance(tower, Blade):
        result = modes(tower, 0.0, n_modes, elements)
        sections, top, gravity = tower.sections, tower.tip_mass, 0.0
    else:
        model = as_tower(tower)         # the rigid-base modes of a moving base come on top of the n_modes
        result = with_blade_kinds(tower_modes(model, n_modes + len(model.supports.free_base), elements))
        sections, top, gravity = model.sections, model.top_mass, model.gravity
        if model.supports.wires or model.supports.moving_base or model.supports.soil is not None:
            notes += ("ElastoDyn's tower integrals have no wires, foundation, platform or soil springs: its "
                      "frequencies below are those of the fitted shapes on a clamped base",)
    beam = BeamIntegrals(sections, top.mass if top is not None else 0.0, gravity=gravity, tower=True)
    fits, compared = fit_modes(result, beam, TOWER_MODES, nodes, shipped, min_tip_ratio)
    return ElastoDynCoefficients(fits, 0.0, nodes, True, compared, result.notes + notes)
