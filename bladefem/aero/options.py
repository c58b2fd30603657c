"""Switches of the blade-element momentum solution, named and defaulted like AeroDyn's input flags.

The defaults are AeroDyn's documented defaults and the values of the OpenFAST NREL 5MW decks: BEM on
(Wake_Mod 1), Prandtl tip and hub loss, tangential induction, drag in neither induction equation, the Glauert/Pitt-
Peters skewed-wake redistribution with factor 15 pi / 32 (Skew_Mod 1, SkewRedistr_Mod 1; the legacy SkewMod 2),
residual tolerance 5e-10 (double precision), at most 100 iterations, pitching moment used.

``formulation`` is AeroDyn's BEM_Mod: it chooses the projection of the velocities (legacy or polar,
:func:`bladefem.aero.polar.projection`) and what changes the induction: 1 (legacy, AeroDyn's default when BEM_Mod
is absent):
Buhl's high-induction thrust curve above a = 0.4, the propeller-brake branch for phi < 0, loss factors at any
inflow angle, the skew redistribution without F; 2 (polar, OpenFAST 4's recommended setting): the quadratic
empirical thrust C_T(a) continuing momentum theory C1-smoothly from a_c = min(0.35 / cos chi0, 0.5) to C_T(1) = 2,
the tangential induction scaled by H = 4 a (1 - a) F / C_T(a) above a_c, the momentum branch chosen by the sign
of vx, loss factors only for phi > 0, the skew redistribution weighted by F.

``high_induction`` (the empirical thrust above a_c) is always on in AeroDyn; it is a switch here only so that the
pure momentum relation can be checked against its closed form.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..limits import MAX_BEM_ITERATIONS

#: Indices of the option vector the kernels read (see :meth:`BEMOptions.vector`).
(INDUCTION, TIP_LOSS, HUB_LOSS, TAN_IND, AI_DRAG, TI_DRAG, HIGH_INDUCTION, USE_CM, SKEW_REDISTRIBUTION,
 FORMULATION, SKEW_FACTOR, TOLERANCE, MAX_ITER) = range(13)
OPTION_COUNT = 13

#: AeroDyn's default Pitt/Peters constant (SkewModFactor / SkewRedistrFactor).
PITT_PETERS_FACTOR = 15.0 * math.pi / 32.0


@dataclass(frozen=True)
class BEMOptions:
    """BEM switches (AeroDyn's names in brackets).

    induction : solve for the induced velocities [Wake_Mod 1]; False gives the geometric inflow [Wake_Mod 0]
    tip_loss, hub_loss : Prandtl tip and hub loss factors [TipLoss, HubLoss]
    tangential_induction : angular-momentum balance for a' [TanInd]
    axial_drag, tangential_drag : drag in the axial and tangential induction equations [AIDrag, TIDrag]
    high_induction : Buhl's thrust correction for a > 0.4 (always on in AeroDyn)
    pitching_moment : use the Cm column [UseBlCm]
    skew_redistribution : Glauert/Pitt-Peters azimuthal redistribution of the axial induction in a skewed wake
        (yaw, shaft tilt) [Skew_Mod 1 with SkewRedistr_Mod 1; legacy SkewMod 2]
    skew_factor : the redistribution constant [SkewRedistrFactor, legacy SkewModFactor], default 15 pi / 32
    formulation : 1 legacy or 2 polar [BEM_Mod], see above
    tolerance : residual tolerance of the inflow-angle equation [IndToler]
    max_iterations : most Brent iterations per solve [MaxIter]
    """

    induction: bool = True
    tip_loss: bool = True
    hub_loss: bool = True
    tangential_induction: bool = True
    axial_drag: bool = False
    tangential_drag: bool = False
    high_induction: bool = True
    pitching_moment: bool = True
    skew_redistribution: bool = True
    skew_factor: float = PITT_PETERS_FACTOR
    formulation: int = 1
    tolerance: float = 5e-10
    max_iterations: int = 100

    def __post_init__(self) -> None:
        if not self.tolerance > 0:
            raise ValueError(f"tolerance must be positive, got {self.tolerance}")
        if self.formulation not in (1, 2):
            raise ValueError(f"formulation must be 1 or 2 (AeroDyn BEM_Mod), got {self.formulation}")
        if not 1 <= self.max_iterations <= MAX_BEM_ITERATIONS:
            raise ValueError(f"max_iterations must lie between 1 and {MAX_BEM_ITERATIONS}, got {self.max_iterations}")

    def vector(self) -> NDArray[np.float64]:
        """The options as the float vector the compiled kernels read (indices above)."""
        v = np.zeros(OPTION_COUNT)
        v[INDUCTION] = self.induction
        v[TIP_LOSS] = self.tip_loss
        v[HUB_LOSS] = self.hub_loss
        v[TAN_IND] = self.tangential_induction
        v[AI_DRAG] = self.axial_drag
        v[TI_DRAG] = self.tangential_drag
        v[HIGH_INDUCTION] = self.high_induction
        v[USE_CM] = self.pitching_moment
        v[SKEW_REDISTRIBUTION] = self.skew_redistribution
        v[FORMULATION] = self.formulation
        v[SKEW_FACTOR] = self.skew_factor
        v[TOLERANCE] = self.tolerance
        v[MAX_ITER] = self.max_iterations
        return v
