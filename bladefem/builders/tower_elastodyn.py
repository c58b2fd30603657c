"""The rotor-nacelle assembly of an ElastoDyn turbine as the tower's rigid top body, and the tower of an ElastoDyn
main file (readers + tower model: this sits above both)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..sections.tower import (
    STANDARD_GRAVITY,
    RigidPart,
    TopMass,
    Tower,
    combine_parts,
    openfast_vector,
)
from .elastodyn_blade import blade_from_elastodyn, read_elastodyn_blade
from ..formats.elastodyn_main import ElastoDynMain, read_elastodyn_main
from .elastodyn_tower import read_elastodyn_tower, tower_from_elastodyn

# -- the tower-top body of an ElastoDyn turbine --------------------------------------------------------------

def shaft_axes(main: ElastoDynMain) -> tuple[NDArray, NDArray, NDArray]:
    """Unit vectors in the tower frame: along the shaft downwind (tilted by ShftTilt), perpendicular to it in the
    vertical plane (up), and side-side: ``c1 = cos(tilt) X + sin(tilt) Z``, ``c_up = -sin(tilt) X + cos(tilt) Z``,
    ``c1 x c_up = -Y = y``."""
    tilt = main.shaft_tilt
    c1 = openfast_vector([np.cos(tilt), 0.0, np.sin(tilt)])
    up = openfast_vector([-np.sin(tilt), 0.0, np.cos(tilt)])
    return c1, up, np.cross(c1, up)


def rotor_body(main: ElastoDynMain, azimuth: float, free_to_spin: bool) -> RigidPart:
    """Hub and rigid blades as one body in the tower frame relative to the tower top; blade 1 at ``azimuth`` (rad)
    from vertical up toward +y, the others evenly spaced, blade axes coned by PreCone toward the shaft direction.
    ``free_to_spin``: the rotor turns freely on its shaft (ElastoDyn's generator DOF), so its inertia about the
    shaft does not follow the tower top's rotation and is removed (the shaft is a principal axis of an evenly
    spaced rotor)."""
    c1, up, side = shaft_axes(main)
    apex = main.twr2shft * np.array([1.0, 0.0, 0.0]) + main.overhang * c1
    parts = [RigidPart(main.hub_mass, apex + main.hub_cm * c1, main.hub_inertia * np.outer(c1, c1))]
    for k in range(main.num_blades):
        sections = blade_from_elastodyn(read_elastodyn_blade(main.blade_files[k]), tip_radius=main.tip_radius,
                                        hub_radius=main.hub_radius).sections
        mass, first, second = sections.mass_moments(offset=main.hub_radius)      # about the apex along the axis
        tip = main.tip_mass[k]
        mass, first, second = mass + tip, first + tip * main.tip_radius, second + tip * main.tip_radius**2
        psi = azimuth + 2 * np.pi * k / main.num_blades
        axis = np.cos(main.precone[k]) * (np.cos(psi) * up + np.sin(psi) * side) + np.sin(main.precone[k]) * c1
        about_cm = second - first**2 / mass                                     # slender rigid rod
        parts.append(RigidPart(mass, apex + first / mass * axis, about_cm * (np.eye(3) - np.outer(axis, axis))))
    rotor = combine_parts(parts)
    inertia = rotor.inertia
    if free_to_spin:
        inertia = inertia - (c1 @ inertia @ c1) * np.outer(c1, c1)
    return RigidPart(rotor.mass, rotor.offset, inertia)


def elastodyn_top_mass(main: ElastoDynMain, azimuth: float = 0.0,
                       free_to_spin: bool | None = None) -> tuple[TopMass, tuple[str, ...]]:
    """The rotor-nacelle assembly of an ElastoDyn main file as one rigid body at the tower top, and the
    statement of its assumptions. Parts: yaw bearing (YawBrMass at the tower top), nacelle (NacMass at NacCM, with
    NacYIner about the yaw axis moved to its centre of mass), hub (HubMass at HubCM along the shaft, HubIner about
    the shaft) and the blades as rigid rods along their coned pitch axes (AdjBlMs applied, tip-brake masses at
    TipRad), rotor at ``azimuth`` (rad). ``free_to_spin`` (default: the main file's GenDOF, else True) drops the
    rotor's inertia about its shaft (:func:`rotor_body`)."""
    if free_to_spin is None:
        free_to_spin = main.dofs.get("GenDOF", True)
    nacelle = openfast_vector(main.nacelle_cm)
    yaw = main.nacelle_yaw_inertia - main.nacelle_mass * (nacelle[1] ** 2 + nacelle[2] ** 2)
    notes = []
    if yaw < 0:
        notes.append(f"NacYIner is smaller than NacMass times the squared CM offset: nacelle inertia about its "
                     f"centre of mass taken as 0 (would be {yaw:.4g} kg m^2)")
        yaw = 0.0
    parts = [RigidPart(main.yaw_bearing_mass, np.zeros(3)),
             RigidPart(main.nacelle_mass, nacelle, yaw * np.diag([1.0, 0.0, 0.0])),
             rotor_body(main, azimuth, free_to_spin)]
    top = combine_parts(parts)
    notes.append(
        f"tower-top rigid body from {Path(main.path).name}: {top.mass:.6g} kg, centre of mass "
        f"{top.offset[0]:.4g} m above the tower top and {top.offset[2]:.4g} m downwind; blades rigid, rotor at "
        f"azimuth {np.degrees(azimuth):.4g} deg, "
        + ("free to spin on its shaft (its inertia about the shaft left out)" if free_to_spin else
           "locked to the nacelle") + "; nacelle inertia only about the yaw axis (NacYIner), hub "
        "inertia only about the shaft (HubIner); the generator's own inertia and blade section inertias left out")
    return top, tuple(notes)


def elastodyn_tower(main_path: str | Path, azimuth: float = 0.0, gravity: float = STANDARD_GRAVITY,
                    point_mass: bool = False, free_to_spin: bool | None = None) -> Tower:
    """A clamped land tower from an ElastoDyn main file: the tower file's sections over TowerHt - TowerBsHt and the
    rotor-nacelle assembly as a rigid body (:func:`elastodyn_top_mass`), or, with ``point_mass``, as the point
    mass ElastoDyn's own tower mode-shape integrals use (its TwrTpMass)."""
    main = read_elastodyn_main(main_path)
    plain = tower_from_elastodyn(read_elastodyn_tower(main.tower_file),
                                 height=main.tower_height - main.tower_base_height,
                                 base_height=main.tower_base_height)
    top, notes = elastodyn_top_mass(main, azimuth, free_to_spin)
    if point_mass:
        top = TopMass(top.mass)
        notes = (f"tower-top point mass {top.mass:.6g} kg (ElastoDyn's TwrTpMass: no offset, no rotary inertia)",)
    return Tower(sections=plain.sections, base_height=plain.base_height, top_mass=top, gravity=gravity,
                 name=Path(main_path).stem, notes=plain.notes + notes)
