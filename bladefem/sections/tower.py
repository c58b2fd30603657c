"""A tower: section table, the rigid body at its top, gravity and the supports at and along its base.

Tower frame (used everywhere inside bladefem for towers): ``x`` up the tower axis from the bottom of the flexible
beam, ``y`` side-side, ``z`` fore-aft (downwind); right-handed, so ``y`` points to the right when looking downwind.
The beam fields are ``v`` side-side and ``w`` fore-aft deflection, ``phi`` torsion, ``u`` axial. In the section
table ``flap_stiffness`` is the fore-aft EI (bending in the x-z plane), ``edge_stiffness`` the side-side EI,
``flap_inertia`` the rotary inertia per length resisting fore-aft section rotation, ``edge_inertia`` side-side.

Support matrices (foundation, platform) are given at the interface in the OpenFAST order
``(surge, sway, heave, roll, pitch, yaw)`` of the OpenFAST frame ``X`` downwind, ``Y`` lateral (to the left looking
downwind), ``Z`` up, and turned into the tower frame by :func:`openfast_to_tower`:
``x = Z``, ``y = -Y``, ``z = X``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from .blade import Blade, TipMass
from .table import SectionTable

#: standard gravity, m/s^2 (the value in the NREL 5MW ElastoDyn files)
STANDARD_GRAVITY = 9.80665
#: names of the six base coordinates in the tower frame's order (t_x, t_y, t_z, theta_x, theta_y, theta_z)
BASE_COORDINATES: tuple[str, ...] = ("heave", "sway", "surge", "yaw", "pitch", "roll")
#: tower-frame components (x, y, z) of the OpenFAST axes X (downwind), Y (lateral), Z (up)
OPENFAST_AXES = np.array([[0.0, 0.0, 1.0], [0.0, -1.0, 0.0], [1.0, 0.0, 0.0]]).T


def openfast_to_tower(matrix: NDArray) -> NDArray:
    """A 6x6 matrix on (surge, sway, heave, roll, pitch, yaw) turned into the tower frame's (t_x, t_y, t_z,
    theta_x, theta_y, theta_z): ``R M R^T`` with ``R = diag(A, A)``, ``A`` the OpenFAST axes in the tower frame."""
    R = np.zeros((6, 6))
    R[:3, :3] = R[3:, 3:] = OPENFAST_AXES
    return R @ np.asarray(matrix, dtype=float) @ R.T


def openfast_vector(vector: Sequence[float]) -> NDArray:
    """A position (X downwind, Y lateral, Z up) in the tower frame (x up, y side-side, z downwind)."""
    return OPENFAST_AXES @ np.asarray(vector, dtype=float)


def _matrix6(value: NDArray | None, name: str, symmetric_psd: bool = True) -> NDArray:
    matrix = np.zeros((6, 6)) if value is None else np.asarray(value, dtype=float)
    if matrix.shape != (6, 6) or not np.all(np.isfinite(matrix)):
        raise InputError(f"expected a finite 6x6 matrix, got shape {matrix.shape}", field=name)
    if not np.allclose(matrix, matrix.T, rtol=1e-9, atol=1e-12 * max(1.0, np.abs(matrix).max())):
        raise InputError("the 6x6 matrix must be symmetric", field=name)
    if symmetric_psd and np.linalg.eigvalsh(matrix).min() < -1e-9 * max(1.0, np.abs(matrix).max()):
        raise InputError("the 6x6 matrix must be positive semi-definite", field=name)
    return matrix


class TopMass(TipMass):
    """The tower-top rigid body (rotor-nacelle assembly), in the tower frame.

    mass : kg
    offset : centre of mass relative to the tower top, (vertical, side-side, fore-aft downwind), m
    inertia : 3x3 inertia tensor about the centre of mass in the tower frame, kg m^2
    """


@dataclass(frozen=True)
class RigidPart:
    """One rigid part of a compound body: mass (kg), centre of mass (m), inertia about its own centre of mass
    (kg m^2), all in one frame."""

    mass: float
    position: NDArray[np.float64]
    inertia: NDArray[np.float64] = field(default_factory=lambda: np.zeros((3, 3)))


def combine_parts(parts: Sequence[RigidPart]) -> TopMass:
    """One rigid body from its parts: total mass, centre of mass, and the inertia about it by the parallel-axis
    theorem ``I = sum (I_i + m_i (|d_i|^2 1 - d_i d_i^T))``, ``d_i`` from the common centre of mass."""
    mass = sum(part.mass for part in parts)
    if mass <= 0:
        return TopMass(0.0)
    centre = sum(part.mass * np.asarray(part.position, dtype=float) for part in parts) / mass
    inertia = np.zeros((3, 3))
    for part in parts:
        d = np.asarray(part.position, dtype=float) - centre
        inertia += np.asarray(part.inertia, dtype=float) + part.mass * (d @ d * np.eye(3) - np.outer(d, d))
    return TopMass(mass=mass, offset=centre, inertia=0.5 * (inertia + inertia.T))


@dataclass(frozen=True)
class Wires:
    """``count`` tension wires (guy cables) evenly spaced in azimuth, attached at one height (BModes style).

    count : number of wires (>= 1)
    stiffness : axial spring constant of each wire, N/m
    angle : angle between each wire and the tower axis, rad
    height : attachment height above the bottom of the beam, m (made a mesh node)
    azimuth : direction of the first wire's anchor from the downwind (z) axis toward y, rad
    """

    count: int
    stiffness: float
    angle: float
    height: float
    azimuth: float = 0.0

    def __post_init__(self) -> None:
        if int(self.count) != self.count or self.count < 1:
            raise InputError(f"wire count must be a positive integer, got {self.count}", field="count")
        for name in ("stiffness", "angle", "height", "azimuth"):
            if not np.isfinite(getattr(self, name)):
                raise InputError(f"must be a finite number, got {getattr(self, name)}", field=name)
        if self.stiffness < 0 or self.height <= 0:
            raise InputError("wire stiffness must not be negative and the height must be positive", field="wires")

    def directions(self) -> NDArray[np.float64]:
        """Unit vectors from the attachment point to each anchor (down and out), shape (count, 3)."""
        psi = self.azimuth + 2 * np.pi * np.arange(self.count) / self.count
        return np.stack([-np.cos(self.angle) * np.ones_like(psi), np.sin(self.angle) * np.sin(psi),
                         np.sin(self.angle) * np.cos(psi)], axis=1)

    def stiffness_matrix(self) -> NDArray[np.float64]:
        """3x3 translational stiffness at the attachment point, N/m: ``sum_i k e_i e_i^T`` (the wire pretension's
        geometric stiffness and the compression it adds to the tower are not modelled)."""
        e = self.directions()
        return self.stiffness * e.T @ e


@dataclass(frozen=True)
class Foundation:
    """Springs and masses at the tower base (e.g. monopile soil), OpenFAST order (surge .. yaw) about the base.

    stiffness : 6x6, N/m, N/rad, N m/rad
    mass : 6x6, kg, kg m, kg m^2
    """

    stiffness: NDArray[np.float64]
    mass: NDArray[np.float64] = field(default_factory=lambda: np.zeros((6, 6)))

    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", _matrix6(self.stiffness, "foundation.stiffness"))
        object.__setattr__(self, "mass", _matrix6(self.mass, "foundation.mass"))


@dataclass(frozen=True)
class Platform:
    """A floating platform: a rigid body carrying the tower base, with hydrodynamic and mooring matrices.

    mass : platform mass, kg
    centre_of_mass : platform CM relative to the reference point, OpenFAST (X downwind, Y lateral, Z up), m
    inertia : 3x3 inertia about the platform CM in OpenFAST axes (or the diagonal roll, pitch, yaw), kg m^2
    added_mass, hydrostatic, mooring : 6x6 about the reference point, OpenFAST order (surge .. yaw). The
        hydrostatic matrix holds the buoyancy (waterplane and centre-of-buoyancy) terms only: the weight of the
        platform, tower and top mass enters through gravity.
    base_height : height of the tower base above the platform reference point, m
    restoring_includes_weight : True when hydrostatic + mooring already hold the whole restoring of the rigid
        system, the weight terms included (BModes decks: BModes has no gravity, so its platform matrices must);
        gravity then acts only on the tower's deformation relative to the platform (see
        :func:`bladefem.assembly.supports.weight_in_restoring`)
    """

    mass: float
    centre_of_mass: NDArray[np.float64]
    inertia: NDArray[np.float64]
    added_mass: NDArray[np.float64] | None = None
    hydrostatic: NDArray[np.float64] | None = None
    mooring: NDArray[np.float64] | None = None
    base_height: float = 0.0
    restoring_includes_weight: bool = False

    def __post_init__(self) -> None:
        inertia = np.asarray(self.inertia, dtype=float)
        inertia = np.diag(inertia) if inertia.shape == (3,) else inertia.reshape(3, 3)
        object.__setattr__(self, "inertia", inertia)
        object.__setattr__(self, "centre_of_mass", np.asarray(self.centre_of_mass, dtype=float).reshape(3))
        object.__setattr__(self, "added_mass", _matrix6(self.added_mass, "platform.added_mass"))
        object.__setattr__(self, "hydrostatic", _matrix6(self.hydrostatic, "platform.hydrostatic", False))
        object.__setattr__(self, "mooring", _matrix6(self.mooring, "platform.mooring", False))
        if not np.isfinite(self.mass) or self.mass < 0 or not np.isfinite(self.base_height):
            raise InputError("platform mass must be a non-negative number", field="platform.mass")

    def body(self) -> TopMass:
        """The platform's own rigid body in the tower frame, relative to the reference point."""
        A = OPENFAST_AXES
        return TopMass(self.mass, openfast_vector(self.centre_of_mass), A @ self.inertia @ A.T)


@dataclass(frozen=True)
class SoilSprings:
    """Distributed springs along the embedded length of a pile, per unit length, linear between points and zero
    outside them.

    height : positions above the bottom of the beam, m (increasing, usually from 0; the last is the embedded length)
    lateral : lateral (p-y) stiffness acting on v and w, N/m per m
    axial : axial (t-z) stiffness on u, N/m per m, or None
    torsional : torsional stiffness on phi, N m/rad per m, or None
    """

    height: NDArray[np.float64]
    lateral: NDArray[np.float64]
    axial: NDArray[np.float64] | None = None
    torsional: NDArray[np.float64] | None = None

    def __post_init__(self) -> None:
        height = np.asarray(self.height, dtype=float)
        object.__setattr__(self, "height", height)
        for name in ("lateral", "axial", "torsional"):
            value = getattr(self, name)
            if value is not None:
                value = np.broadcast_to(np.asarray(value, dtype=float), height.shape).copy()
                object.__setattr__(self, name, value)
                if np.any(~np.isfinite(value)) or np.any(value < 0):
                    raise InputError("soil stiffness must be finite and not negative", field=f"soil.{name}")
        if (height.ndim != 1 or len(height) < 2 or not np.all(np.isfinite(height)) or height[0] < 0
                or np.any(np.diff(height) <= 0)):
            raise InputError("soil heights must not be negative and must increase (at least two points)",
                             field="soil.height")

    @property
    def embedded_length(self) -> float:
        return float(self.height[-1])

    def at(self, x: NDArray, name: str) -> NDArray:
        """Stiffness ``name`` at positions ``x``: linear between the given heights, zero outside them."""
        return along(self.height, getattr(self, name), x)


def along(height: NDArray, value: NDArray | None, x: NDArray) -> NDArray:
    """A distribution given at ``height`` (m) at positions ``x``: linear between the heights, zero outside."""
    if value is None:
        return np.zeros_like(x)
    tolerance = 1e-12 * max(abs(height[-1]), 1.0)
    inside = (x >= height[0] - tolerance) & (x <= height[-1] + tolerance)
    return np.where(inside, np.interp(x, height, value), 0.0)


@dataclass(frozen=True)
class LateralAddedMass:
    """Distributed added mass per unit length on the lateral translations v and w (e.g. the hydrodynamic added
    mass of a submerged tower or pile), linear between points and zero outside them. It adds inertia, not weight.

    height : positions above the bottom of the beam, m (increasing, at least two)
    mass : added mass per length at each height, kg/m (not negative)
    """

    height: NDArray[np.float64]
    mass: NDArray[np.float64]

    def __post_init__(self) -> None:
        height = np.asarray(self.height, dtype=float)
        mass = np.broadcast_to(np.asarray(self.mass, dtype=float), height.shape).copy()
        object.__setattr__(self, "height", height)
        object.__setattr__(self, "mass", mass)
        if (height.ndim != 1 or len(height) < 2 or not np.all(np.isfinite(height)) or height[0] < 0
                or np.any(np.diff(height) <= 0)):
            raise InputError("added-mass heights must not be negative and must increase (at least two points)",
                             field="added_mass.height")
        if not np.all(np.isfinite(mass)) or np.any(mass < 0):
            raise InputError("added mass per length must be finite and not negative", field="added_mass.mass")

    def at(self, x: NDArray) -> NDArray:
        """Added mass per length at positions ``x``, kg/m."""
        return along(self.height, self.mass, x)


@dataclass(frozen=True)
class Supports:
    """How the tower is held. Nothing given: clamped base. ``foundation`` and ``platform`` exclude each other;
    wires, soil springs and distributed added mass combine with any base. ``base_held``: base coordinates of a
    foundation or platform held fixed (e.g. ``("heave", "yaw")`` for a base free only to translate and rock
    laterally, ``("heave", "sway", "surge", "yaw")`` for a pinned base)."""

    wires: tuple[Wires, ...] = ()
    foundation: Foundation | None = None
    platform: Platform | None = None
    soil: SoilSprings | None = None
    added_mass: LateralAddedMass | None = None
    base_held: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "wires", tuple(self.wires))
        object.__setattr__(self, "base_held", tuple(self.base_held))
        if self.foundation is not None and self.platform is not None:
            raise InputError("give a foundation or a floating platform, not both", field="supports")
        unknown = [name for name in self.base_held if name not in BASE_COORDINATES]
        if unknown or (self.base_held and not self.moving_base):
            raise InputError(f"base_held names base coordinates ({', '.join(BASE_COORDINATES)}) of a foundation or "
                             f"platform, got {', '.join(self.base_held)}", field="supports.base_held")

    @property
    def free_base(self) -> tuple[int, ...]:
        """Indices of the base coordinates that move (none for a clamped base)."""
        if not self.moving_base:
            return ()
        return tuple(i for i, name in enumerate(BASE_COORDINATES) if name not in self.base_held)

    @property
    def moving_base(self) -> bool:
        """True when the base has its own six rigid-body coordinates (foundation or platform)."""
        return self.foundation is not None or self.platform is not None

    def mesh_points(self) -> NDArray[np.float64]:
        """Heights that must be mesh nodes: wire attachments, soil-spring and added-mass points."""
        points = [w.height for w in self.wires]
        if self.soil is not None:
            points += list(self.soil.height)
        if self.added_mass is not None:
            points += list(self.added_mass.height)
        return np.array(points, dtype=float)


@dataclass(frozen=True)
class Tower:
    """A tower for modal analysis.

    sections : span = height above the bottom of the flexible beam, m; flap = fore-aft, edge = side-side
    base_height : height of the beam's bottom above ground or mean sea level, m (reporting only)
    top_mass : the rotor-nacelle assembly as a rigid body at the top (:class:`TopMass`), or None
    supports : clamped base (default), foundation, floating platform, wires, soil springs
    gravity : gravitational acceleration, m/s^2 (0 switches gravity off)
    name : label for reports
    notes : modelling statements made while reading
    """

    sections: SectionTable
    base_height: float = 0.0
    top_mass: TipMass | None = None
    supports: Supports = field(default_factory=Supports)
    gravity: float = STANDARD_GRAVITY
    name: str = "tower"
    notes: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if not np.isfinite(self.gravity) or self.gravity < 0:
            raise InputError(f"gravity must be a non-negative number, got {self.gravity}", field="gravity")
        outside = self.supports.mesh_points()
        if outside.size and outside.max() > self.height * (1 + 1e-12):
            raise InputError(f"a wire or soil point at {outside.max():g} m lies above the tower top "
                             f"({self.height:g} m)", field="supports")

    @property
    def height(self) -> float:
        """Flexible length of the tower, m."""
        return self.sections.length

    def as_beam(self) -> Blade:
        """The tower as a non-rotating beam (a :class:`Blade` with no hub radius), e.g. for the ElastoDyn
        mode-shape fit: its ``flap`` is fore-aft and ``edge`` side-side."""
        return Blade(sections=self.sections, hub_radius=0.0, tip_mass=self.top_mass, name=self.name,
                     notes=self.notes)

    def with_(self, **changes: object) -> Tower:
        """A copy with some fields changed (e.g. ``tower.with_(gravity=0.0)``)."""
        return replace(self, **changes)


def as_tower(data: object) -> Tower:
    """A :class:`Tower` from any object with ``sections`` and optionally ``base_height``, ``top_mass``, ``name``,
    ``notes`` (e.g. the readers' :class:`bladefem.builders.tower.Tower`): clamped base, standard gravity."""
    if isinstance(data, Tower):
        return data
    return Tower(sections=data.sections, base_height=getattr(data, "base_height", 0.0),  # type: ignore[attr-defined]
                 top_mass=getattr(data, "top_mass", None), name=getattr(data, "name", "tower"),
                 notes=tuple(getattr(data, "notes", ())))
