"""Inputs of the Kane turbine model: bodies, geometry, springs and the assumed-mode beams (SI, angles in rad).

Frames (ElastoDyn's): earth ``x`` downwind, ``y`` lateral (to the left looking downwind), ``z`` up, origin at the
tower base. The tower deflects fore-aft along ``x`` and side-side along ``y``. The rotor turns positively about
the downwind shaft axis. The blade frame is bladefem's (``x`` along the pitch axis, ``y`` in-plane toward the
leading edge, ``z`` out-of-plane downwind); blade 1 points up at zero azimuth.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from ...errors import InputError
from .shapes import ModalBeam

#: degrees of freedom of the nacelle, drivetrain and tower, in the order of the generalized coordinates
PLATFORM_DOFS = ("tower_fa1", "tower_fa2", "tower_ss1", "tower_ss2", "yaw", "generator_azimuth", "drivetrain")
#: degrees of freedom of each blade
BLADE_DOFS = ("flap1", "edge1", "flap2")
#: readable names, for tables
DOF_LABELS = {"tower_fa1": "tower fore-aft 1", "tower_fa2": "tower fore-aft 2", "tower_ss1": "tower side-side 1",
              "tower_ss2": "tower side-side 2", "yaw": "nacelle yaw", "generator_azimuth": "generator azimuth",
              "drivetrain": "drivetrain torsion", "flap1": "flap 1", "edge1": "edge 1", "flap2": "flap 2"}
STANDARD_GRAVITY = 9.80665
#: structural damping conventions (see :attr:`TurbineParameters.damping`)
DAMPING_CONVENTIONS = ("elastodyn", "rna")


def coordinate_label(dof: str) -> str:
    """Readable name of a generalized coordinate: 'tower_fa1' -> 'tower fore-aft 1', 'blade2_edge1' -> 'blade 2
    edge 1'."""
    if dof.startswith("blade") and "_" in dof:
        blade, mode = dof.split("_", 1)
        return f"blade {blade[5:]} {DOF_LABELS[mode]}"
    return DOF_LABELS.get(dof, dof)


def dof_names(n_blades: int) -> tuple[str, ...]:
    """Names of the generalized coordinates: tower, yaw, generator azimuth, drivetrain, then each blade's modes."""
    return PLATFORM_DOFS + tuple(f"blade{k + 1}_{dof}" for k in range(n_blades) for dof in BLADE_DOFS)


@dataclass(frozen=True)
class TurbineParameters:
    """A horizontal-axis turbine as rigid bodies and assumed-mode beams (ElastoDyn's structural model).

    tower : modes (fore-aft 1, fore-aft 2, side-side 1, side-side 2) with components (x, y), from the tower base
    blade : modes (flap 1, edge 1, flap 2) with components (y in-plane, z out-of-plane), from the blade root
    n_blades : number of blades (1 to 3)
    tower_base_height : height of the tower base above the ground, m (the tower top is at base + tower length)
    twr2shft : vertical distance from the tower top to the shaft, m
    overhang : distance along the shaft from the yaw axis to the rotor apex, m (negative upwind)
    shaft_tilt : rad, positive raises the downwind end of the shaft (upwind rotors have a negative tilt)
    precone : rad, positive tilts the blades downwind
    hub_radius : distance from the apex to the blade root along the pitch axis, m
    hub_cm : distance from the apex to the hub centre of mass along the shaft, m (positive downwind)
    hub_mass : kg; hub_inertia : about the shaft, kg m^2
    generator_inertia : about the high-speed shaft, kg m^2; gearbox_ratio : high-speed / low-speed shaft speed
    nacelle_mass : kg; nacelle_yaw_inertia : about the yaw axis, kg m^2; nacelle_cm : (downwind, lateral, up) from
        the tower top, m
    yaw_bearing_mass : point mass at the tower top, kg
    drivetrain_stiffness : N m/rad and drivetrain_damping : N m s/rad, low-speed-shaft equivalent
    yaw_stiffness : N m/rad and yaw_damping : N m s/rad (ServoDyn's YawSpr and YawDamp)
    blade_tip_mass : point mass on the pitch axis at each blade tip, kg
    pitch : blade pitch, rad (already in the blade shapes and stiffness; kept for reports)
    damping : how the beams' modal damping ratios become damping forces: 'elastodyn' (ElastoDyn's CBF, CBE, CTFA,
        CTSS: each mode's frequency of the beam alone, without tip or tower-top mass) or 'rna' (modal mass with the
        blade tip mass and, for the tower, the rotor-nacelle assembly at the top)
    gravity : m/s^2
    name : a label
    """

    tower: ModalBeam
    blade: ModalBeam
    n_blades: int = 3
    tower_base_height: float = 0.0
    twr2shft: float = 0.0
    overhang: float = 0.0
    shaft_tilt: float = 0.0
    precone: float = 0.0
    hub_radius: float = 0.0
    hub_cm: float = 0.0
    hub_mass: float = 0.0
    hub_inertia: float = 0.0
    generator_inertia: float = 0.0
    gearbox_ratio: float = 1.0
    nacelle_mass: float = 0.0
    nacelle_yaw_inertia: float = 0.0
    nacelle_cm: NDArray = field(default_factory=lambda: np.zeros(3))
    yaw_bearing_mass: float = 0.0
    drivetrain_stiffness: float = 0.0
    drivetrain_damping: float = 0.0
    yaw_stiffness: float = 0.0
    yaw_damping: float = 0.0
    blade_tip_mass: float = 0.0
    pitch: float = 0.0
    damping: str = "elastodyn"
    gravity: float = STANDARD_GRAVITY
    name: str = "turbine"
    notes: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "nacelle_cm", np.asarray(self.nacelle_cm, dtype=float).reshape(3))
        if self.n_blades not in (1, 2, 3):
            raise InputError(f"1 to 3 blades are supported, got {self.n_blades}", field="n_blades")
        if self.tower.n_modes != 4 or self.blade.n_modes != 3:
            raise InputError("the tower needs 4 modes (FA1, FA2, SS1, SS2) and the blade 3 (flap 1, edge 1, flap 2)",
                             field="modes")
        if self.damping not in DAMPING_CONVENTIONS:
            raise InputError(f"damping convention must be one of {', '.join(DAMPING_CONVENTIONS)}, got "
                             f"'{self.damping}'", field="damping")
        if self.nacelle_yaw_inertia < self.nacelle_mass * (self.nacelle_cm[0] ** 2 + self.nacelle_cm[1] ** 2):
            raise InputError("nacelle yaw inertia about the yaw axis is smaller than its centre of mass's own share",
                             field="NacYIner")
        for name in ("hub_mass", "hub_inertia", "generator_inertia", "nacelle_mass", "yaw_bearing_mass",
                     "drivetrain_stiffness", "drivetrain_damping", "yaw_stiffness", "yaw_damping",
                     "blade_tip_mass", "gravity"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value >= 0):
                raise InputError(f"must be a non-negative number, got {value}", field=name)

    @property
    def dofs(self) -> tuple[str, ...]:
        return dof_names(self.n_blades)

    @property
    def tower_height(self) -> float:
        """Height of the tower top above the ground, m."""
        return self.tower_base_height + self.tower.length

    @property
    def rotor_nacelle_mass(self) -> float:
        """Hub, nacelle, yaw bearing and blades (with tip masses), kg."""
        blade = float(np.sum(self.blade.point_mass)) + self.blade_tip_mass
        return self.hub_mass + self.nacelle_mass + self.yaw_bearing_mass + self.n_blades * blade

    def with_(self, **changes: object) -> TurbineParameters:
        """A copy with some fields changed (e.g. ``params.with_(gravity=0.0)``)."""
        return replace(self, **changes)

    def damping_matrices(self) -> tuple[NDArray, NDArray]:
        """Modal damping of the blade (3, 3) and the tower (4, 4), N s/m, in the chosen convention."""
        if self.damping == "elastodyn":
            return self.blade.damping_matrix("elastodyn"), self.tower.damping_matrix("elastodyn")
        return (self.blade.damping_matrix("end-mass", self.blade_tip_mass),
                self.tower.damping_matrix("end-mass", self.rotor_nacelle_mass))

    def without_damping(self) -> TurbineParameters:
        """The same turbine with structural, drivetrain and yaw damping off."""
        return replace(self, tower=self.tower.with_damping(0.0), blade=self.blade.with_damping(0.0),
                       drivetrain_damping=0.0, yaw_damping=0.0)
