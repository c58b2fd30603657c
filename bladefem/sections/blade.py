"""A blade: its section table plus rotor geometry, tip mass and root condition.

Blade frame (used everywhere inside bladefem): ``x`` along the pitch axis from the blade root (the root sits at
``hub_radius`` from the rotor apex along the preconed axis), ``y`` in the rotor plane (edgewise, lead-lag, positive
toward the leading edge), ``z`` out of the rotor plane (flapwise, positive downwind). With precone ``beta`` the
shaft (rotation) axis in this frame is ``(sin beta, 0, cos beta)``.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from .axis import AxisFrame, ReferenceAxis
from .table import SectionTable

Root = Literal["cantilever", "hinged", "axial-torsion", "free"]
#: cantilever: all held; hinged: the four translations and twist held, the bending slopes free (pinned);
#: axial-torsion: only axial displacement and twist held; free: nothing held (BModes hub_conn 1, 4, 3, 2)
ROOTS: tuple[str, ...] = ("cantilever", "hinged", "axial-torsion", "free")
#: standard gravity, m/s^2
STANDARD_GRAVITY = 9.80665


@dataclass(frozen=True)
class Gravity:
    """The blade's weight, frozen at one rotor azimuth (a parked blade, or a rotating blade as it passes that
    azimuth: the load that turns with the rotor is taken as static there).

    Attributes
    ----------
    azimuth : rad, 0 with the blade pointing up, pi pointing down, increasing in the direction of rotation (the
        blade moves toward its leading edge, +y): at pi / 2 the blade is horizontal, its leading edge down
    acceleration : m/s^2

    The shaft is taken horizontal (its tilt is not modelled): gravity lies in the plane that holds the shaft axis
    and the vertical, the rotor plane turned by the precone.
    """

    azimuth: float = 0.0
    acceleration: float = STANDARD_GRAVITY

    def __post_init__(self) -> None:
        for name in ("azimuth", "acceleration"):
            if not np.isfinite(getattr(self, name)):
                raise InputError(f"must be a finite number, got {getattr(self, name)}", field=f"gravity.{name}")
        if self.acceleration < 0:
            raise InputError(f"must not be negative, got {self.acceleration}", field="gravity.acceleration")


@dataclass(frozen=True)
class TipMass:
    """A rigid body attached to the blade tip (or tower top).

    Attributes
    ----------
    mass : kg
    offset : position of its centre of mass relative to the tip of the reference axis, in the blade frame
        (x axial beyond the tip, y chordwise/in-plane, z out-of-plane), m. The chordwise offset is given along the
        chord of the tip section by :meth:`with_chordwise_offset`.
    inertia : 3x3 inertia tensor about its centre of mass in the blade frame, kg m^2
    """

    mass: float
    offset: NDArray[np.float64] = field(default_factory=lambda: np.zeros(3))
    inertia: NDArray[np.float64] = field(default_factory=lambda: np.zeros((3, 3)))

    def __post_init__(self) -> None:
        object.__setattr__(self, "offset", np.asarray(self.offset, dtype=float).reshape(3))
        inertia = np.asarray(self.inertia, dtype=float)
        if inertia.shape == (3,):
            inertia = np.diag(inertia)
        object.__setattr__(self, "inertia", inertia.reshape(3, 3))
        if not np.isfinite(self.mass) or self.mass < 0:
            raise InputError(f"tip mass must be a non-negative number, got {self.mass}", field="tip_mass")
        if not np.allclose(self.inertia, self.inertia.T) or np.any(np.linalg.eigvalsh(self.inertia) < -1e-12):
            raise InputError("tip inertia must be a symmetric positive semi-definite tensor", field="tip_inertia")

    @property
    def second_moment(self) -> NDArray[np.float64]:
        """int rho s s^T dV about the attachment point, kg m^2 (from the inertia tensor and the offset)."""
        about_cm = 0.5 * np.trace(self.inertia) * np.eye(3) - self.inertia
        return about_cm + self.mass * np.outer(self.offset, self.offset)


@dataclass(frozen=True)
class Blade:
    """A rotating blade.

    Attributes
    ----------
    sections : section properties along the flexible length
    hub_radius : distance from the rotor apex to the blade root along the preconed pitch axis, m
    precone : precone angle, rad (positive tilts the blade downwind, out of the rotor plane)
    pitch : blade pitch angle, rad (positive to feather); it adds to the structural twist
    tip_mass : optional rigid body at the tip
    root : ``"cantilever"`` (clamped), ``"hinged"`` (pinned in flap and edge, torsion and axial held),
        ``"axial-torsion"`` (only axial displacement and twist held) or ``"free"``
    name : a label for reports
    notes : statements about the modelling assumptions made while reading the input (printed by the CLI)
    axis : the reference axis's prebend and sweep (:class:`~bladefem.sections.axis.ReferenceAxis`, over the same
        arc length as the sections), or None for a straight blade along the pitch axis
    prestressed : the stiffness at speed holds the bending moments and torque of the centrifugal load (for a blade
        on its deflected axis, :func:`bladefem.modal.operating_point.deflected_blade`); otherwise only the tension
    gravity : the blade's weight at an azimuth (:class:`Gravity`), or None to leave gravity out
    """

    sections: SectionTable
    hub_radius: float = 0.0
    precone: float = 0.0
    pitch: float = 0.0
    tip_mass: TipMass | None = None
    root: Root = "cantilever"
    name: str = "blade"
    notes: tuple[str, ...] = ()
    axis: ReferenceAxis | None = None
    prestressed: bool = False
    gravity: Gravity | None = None

    def __post_init__(self) -> None:
        if self.axis is not None and abs(self.axis.length - self.length) > 1e-9 * self.length:
            raise InputError(f"the reference axis is {self.axis.length:.9g} m long, the sections "
                             f"{self.length:.9g} m", field="axis.span")
        if self.root not in ROOTS:
            raise InputError(f"unknown root condition '{self.root}' (choose from {', '.join(ROOTS)})", field="root")
        for name in ("hub_radius", "precone", "pitch"):
            if not np.isfinite(getattr(self, name)):
                raise InputError(f"must be a finite number, got {getattr(self, name)}", field=name)
        if self.hub_radius < 0:
            raise InputError(f"must not be negative, got {self.hub_radius}", field="hub_radius")

    @property
    def length(self) -> float:
        """Flexible length L = tip radius - hub radius, m."""
        return self.sections.length

    @property
    def tip_radius(self) -> float:
        """Distance from the apex to the blade tip along the pitch axis, m."""
        return self.hub_radius + self.length

    @property
    def shaft_axis(self) -> NDArray[np.float64]:
        """Unit rotation axis in the blade frame."""
        return np.array([np.sin(self.precone), 0.0, np.cos(self.precone)])

    @property
    def gravity_vector(self) -> NDArray[np.float64]:
        """The acceleration of gravity in the blade frame, m/s^2 (zeros without gravity): ``g (-cos psi r + sin psi
        e_y)`` with ``r = (cos beta, 0, -sin beta)`` the radial direction in the rotor plane under precone beta."""
        if self.gravity is None:
            return np.zeros(3)
        psi, beta = self.gravity.azimuth, self.precone
        radial = np.array([np.cos(beta), 0.0, -np.sin(beta)])
        return self.gravity.acceleration * (-np.cos(psi) * radial + np.sin(psi) * np.array([0.0, 1.0, 0.0]))

    @property
    def curved(self) -> bool:
        """Whether the reference axis leaves the pitch axis (prebend or sweep)."""
        return self.axis is not None and self.axis.curved

    def axis_frame(self, x: NDArray) -> AxisFrame | None:
        """The curved axis at arc lengths ``x`` (m), pitched with the blade; None for a straight blade."""
        return self.axis.frame(x, self.pitch) if self.curved else None

    def with_(self, **changes: object) -> Blade:
        """A copy with some fields changed (e.g. ``blade.with_(pitch=0.1)``)."""
        return replace(self, **changes)


def tip_mass_at_section(mass: float, theta: float, axial_offset: float = 0.0, chordwise_offset: float = 0.0,
                        flap_inertia: float = 0.0, edge_inertia: float = 0.0,
                        torsion_inertia: float = 0.0) -> TipMass:
    """A tip mass described in the tip section's frame, turned by the total angle ``theta`` (twist + pitch, rad).

    Offsets in m (axial beyond the tip, chordwise toward the leading edge); inertias about its centre of mass in
    kg m^2: ``flap_inertia`` about the chord axis, ``edge_inertia`` about the thickness axis, ``torsion_inertia``
    about the span axis.
    """
    chord = np.array([0.0, np.cos(theta), -np.sin(theta)])
    thickness = np.array([0.0, np.sin(theta), np.cos(theta)])
    span = np.array([1.0, 0.0, 0.0])
    inertia = (torsion_inertia * np.outer(span, span) + flap_inertia * np.outer(chord, chord)
               + edge_inertia * np.outer(thickness, thickness))
    return TipMass(mass=mass, offset=axial_offset * span + chordwise_offset * chord, inertia=inertia)
