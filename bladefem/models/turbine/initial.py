"""Free degrees of freedom and the initial state from ElastoDyn's switches and initial conditions.

ElastoDyn's DOF switches map onto the coordinates (``FlapDOF1`` -> every blade's ``flap1``, ``GenDOF`` ->
``generator_azimuth``, ...). Its initial conditions are physical: ``OoPDefl`` and ``IPDefl`` are blade-tip
deflections (m) out of the rotor plane (downwind) and in it (toward the trailing edge), turned into modal amplitudes
as ElastoDyn's ``InitBlDefl`` does (first flap and edge modes; the second flap mode when the first is off; a
least-squares fit with a note when the free modes cannot reach the deflection); ``TTDspFA``, ``TTDspSS`` are
tower-top displacements (m, downwind and to the left looking downwind) given to the first tower mode of each
direction (the second if the first is off); ``NacYaw``, ``Azimuth`` (blade 1 up at ``AzimB1Up``) in rad here and
``RotSpeed`` in rad/s.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from ...errors import InputError
from .kane import TurbineModel

#: ElastoDyn DOF switch -> the coordinates (or blade modes) it frees
ELASTODYN_DOFS = {"FlapDOF1": "flap1", "FlapDOF2": "flap2", "EdgeDOF": "edge1", "DrTrDOF": "drivetrain",
                  "GenDOF": "generator_azimuth", "YawDOF": "yaw", "TwFADOF1": "tower_fa1", "TwFADOF2": "tower_fa2",
                  "TwSSDOF1": "tower_ss1", "TwSSDOF2": "tower_ss2"}
#: ElastoDyn DOF switches of motions bladefem does not model (refused when on)
UNMODELLED_DOFS = ("PitchDOF", "TeetDOF", "PtfmSgDOF", "PtfmSwDOF", "PtfmHvDOF", "PtfmRDOF", "PtfmPDOF", "PtfmYDOF")


@dataclass(frozen=True)
class InitialConditions:
    """ElastoDyn's initial conditions (SI, angles in rad): OoPDefl, IPDefl (m), Azimuth of blade 1 from up
    (rad, AzimB1Up already removed), NacYaw (rad), RotSpeed (rad/s), TTDspFA, TTDspSS (m)."""

    oop_deflection: float = 0.0
    ip_deflection: float = 0.0
    azimuth: float = 0.0
    nacelle_yaw: float = 0.0
    rotor_speed: float = 0.0
    tower_top_fa: float = 0.0
    tower_top_ss: float = 0.0

    def with_(self, **changes: float) -> InitialConditions:
        return replace(self, **changes)


def free_from_switches(dofs: tuple[str, ...], switches: dict[str, bool]) -> NDArray[np.bool_]:
    """Mask of the free coordinates from ElastoDyn's DOF switches (missing switches count as on)."""
    blades = sum(dof.endswith("_flap1") for dof in dofs)
    for key in UNMODELLED_DOFS:
        if switches.get(key) and (key != "TeetDOF" or blades == 2):          # teeter exists for 2 blades only
            raise InputError(f"{key} is on, but bladefem's turbine model has no blade-pitch, teeter or platform motion; set it "
                             "to False", field=key)
    free = np.ones(len(dofs), dtype=bool)
    for key, coordinate in ELASTODYN_DOFS.items():
        if not switches.get(key, True):
            for i, dof in enumerate(dofs):
                if dof == coordinate or dof.endswith("_" + coordinate):
                    free[i] = False
    return free


def blade_amplitudes(tip_value: NDArray, free_modes: NDArray[np.bool_], oop: float, ip: float
                     ) -> tuple[NDArray, str | None]:
    """Modal amplitudes (3,) of flap 1, edge 1, flap 2 giving the tip deflection ``oop`` (downwind) and ``ip``
    (toward the trailing edge), m, as ElastoDyn's InitBlDefl: flap 1 and edge 1, flap 2 in place of flap 1 when
    flap 1 is off; ``tip_value`` (3, 2) in the blade frame (y toward the leading edge, z downwind). Returns the
    amplitudes and a note when the deflection can only be approximated."""
    amplitudes = np.zeros(3)
    if oop == 0.0 and ip == 0.0:
        return amplitudes, None
    flap = 0 if free_modes[0] else (2 if free_modes[2] else None)
    used = [i for i in (flap, 1 if free_modes[1] else None) if i is not None]
    target = np.array([oop, ip])
    if not used:
        return amplitudes, "no blade mode is free: the initial tip deflections OoPDefl, IPDefl are ignored"
    columns = np.array([[tip_value[i, 1], -tip_value[i, 0]] for i in used]).T       # rows: out-of-plane, in-plane
    solution, *_ = np.linalg.lstsq(columns, target, rcond=None)
    amplitudes[used] = solution
    residual = np.linalg.norm(columns @ solution - target)
    note = None if residual <= 1e-9 * np.linalg.norm(target) else (
        f"the free blade modes reach the initial tip deflection (OoPDefl, IPDefl) = ({oop:g}, {ip:g}) m only "
        f"approximately (residual {residual:.3g} m), as in ElastoDyn")
    return amplitudes, note


def initial_state(model: TurbineModel, free: NDArray[np.bool_], conditions: InitialConditions
                  ) -> tuple[NDArray, NDArray, tuple[str, ...]]:
    """Coordinates and rates (n,) of ElastoDyn's initial conditions with the free coordinates ``free``, and notes."""
    p, dofs = model.params, model.dofs
    q, u = np.zeros(model.n), np.zeros(model.n)
    notes: list[str] = []
    for columns in model.blade_columns:
        amplitudes, note = blade_amplitudes(p.blade.tip_value, free[columns], conditions.oop_deflection,
                                            conditions.ip_deflection)
        q[columns] = amplitudes
        if note and note not in notes:
            notes.append(note)
    for value, component, names in ((conditions.tower_top_fa, 0, ("tower_fa1", "tower_fa2")),
                                    (conditions.tower_top_ss, 1, ("tower_ss1", "tower_ss2"))):
        chosen = next((name for name in names if free[dofs.index(name)]), None)
        if value and chosen is None:
            notes.append(f"no tower mode of that direction is free: the initial tower-top displacement {value:g} m "
                         "is ignored")
        elif value:
            q[dofs.index(chosen)] = value / p.tower.tip_value[dofs.index(chosen), component]
    q[dofs.index("yaw")] = conditions.nacelle_yaw
    q[dofs.index("generator_azimuth")] = conditions.azimuth
    u[dofs.index("generator_azimuth")] = conditions.rotor_speed
    return q, u, tuple(notes)
