"""A BModes tower deck as bladefem's tower model (:class:`bladefem.sections.tower.Tower`) with its supports.

BModes' tower frame is OpenFAST's: ``x`` downwind (fore-aft, BModes' ``v``), ``y`` lateral (side-side, ``w``), ``z``
up. So ``cm_loc`` is the top mass's fore-aft offset (positive downwind), ``cm_axial`` its height above the tower top,
``ixx_tip`` its side-side (roll) inertia, ``iyy_tip`` fore-aft (pitch), ``izz_tip`` yaw, the products being
inertia-tensor entries. The support block maps onto the tower model as follows:

- ``hub_conn`` 1 (cantilevered) clamps the base; a platform block is then inert, as in BModes (its matrices act on
  held coordinates). ``hub_conn`` 2 (free-free) lets the base move in all six coordinates, 3 holds heave and yaw
  (BModes: "only axial and torsion constraints"), 4 (pybmodes' pinned-free) holds the translations and yaw.
- The platform block becomes a :class:`~bladefem.sections.tower.Platform` whose reference point is BModes'
  (``ref_msl`` below mean sea level, on the tower axis; an off-axis ``ref_msl x y`` moves the matrices to the axis by
  the rigid-arm transform): the platform body at ``cm_pform`` (and ``x y``), ``hydro_M`` as added mass, ``hydro_K`` and
  ``mooring_K`` as restoring, the beam's bottom ``ref_msl - draft + hub_rad`` above the reference point. Matrices are
  made symmetric (bladefem's eigensolver is symmetric; a note gives the size of the antisymmetric part, which
  moves frequencies only at second order).
- Gravity: BModes has none, so a floating deck's (``hub_conn = 2``) restoring already holds the weight terms of the
  rigid system; bladefem keeps gravity for the tower's deformation (axial load, top-mass pendulum) and takes the
  rigid-system terms from the deck (:attr:`~bladefem.sections.tower.Platform.restoring_includes_weight`). For
  ``hub_conn`` 1, 3 and 4 the base matrices are foundation springs and gravity acts in full. A free-free tower with
  no restoring at all has nothing to carry its weight, and is solved without gravity.
- ``distr_k`` becomes :class:`~bladefem.sections.tower.SoilSprings` (lateral) and ``distr_m``
  :class:`~bladefem.sections.tower.LateralAddedMass`, both at heights above the flexible base, zero outside.
- Tension wires: each of the ``n_wires`` wires of a set is an axial spring ``wire_stfness`` at ``th_wire`` from the
  horizontal plane, evenly spaced in azimuth; together they give ``n k cos^2(th)/2`` laterally in every direction
  and ``n k sin^2(th)`` vertically. BModes adds ``n k cos^2(th)`` to each lateral axis and nothing vertically (twice
  the wires' lateral stiffness); a note says so.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..sections.tower import (
    OPENFAST_AXES,
    STANDARD_GRAVITY,
    Foundation,
    LateralAddedMass,
    Platform,
    SoilSprings,
    Supports,
    TopMass,
    Tower,
    Wires,
)
from ..formats.bmodes import BModesInput, BModesPlatform
from .bmodes_model import bmodes_sections, common_notes, file_columns, rigid_tip, scaled_columns

#: base coordinates held fixed for each hub_conn that lets the base move
HELD_BASE = {2: (), 3: ("heave", "yaw"), 4: ("heave", "sway", "surge", "yaw")}
#: the deck key of each Platform field (for error messages)
PLATFORM_KEYS = {"platform.added_mass": "hydro_M", "platform.hydrostatic": "hydro_K", "platform.mooring": "mooring_K",
                 "platform.mass": "mass_pform"}
#: relative antisymmetric part of a platform matrix worth a note
ASYMMETRY_NOTE = 1e-9


def top_mass(bmodes: BModesInput) -> TopMass | None:
    """The tower-top body in the tower frame (OpenFAST axes: cm_loc downwind, cm_axial up)."""
    t = bmodes.tip
    return rigid_tip(bmodes, OPENFAST_AXES, np.array([t["cm_loc"], 0.0, t["cm_axial"]]), TopMass)  # type: ignore


def shifted(matrix: NDArray, arm: NDArray) -> NDArray:
    """A 6x6 matrix about point P (OpenFAST order) referred to point O, ``arm = P - O``: ``T^T A T`` with
    ``T = [[1, -[arm]x], [0, 1]]`` (the motion of P when O moves rigidly)."""
    skew = np.array([[0.0, -arm[2], arm[1]], [arm[2], 0.0, -arm[0]], [-arm[1], arm[0], 0.0]])
    T = np.eye(6)
    T[:3, 3:] = -skew
    return T.T @ matrix @ T


def symmetric(matrix: NDArray) -> tuple[NDArray, float]:
    """(the symmetric part, the antisymmetric part's largest entry relative to the matrix's largest)."""
    scale = float(np.abs(matrix).max()) or 1.0
    return 0.5 * (matrix + matrix.T), float(np.abs(matrix - matrix.T).max()) / (2 * scale)


def platform_model(bmodes: BModesInput, p: BModesPlatform) -> tuple[Platform, list[str]]:
    """The platform block as bladefem's :class:`Platform`, with notes."""
    arm = np.array([p.ref_msl_xy[0], p.ref_msl_xy[1], 0.0])        # reference point from the tower axis
    notes = []
    matrices = {}
    for name in ("hydro_M", "hydro_K", "mooring_K"):
        value, asymmetry = symmetric(shifted(getattr(p, name), arm) if arm.any() else getattr(p, name))
        matrices[name] = value
        if asymmetry > ASYMMETRY_NOTE:
            notes.append(f"{name} made symmetric (its antisymmetric part is {asymmetry:.1e} of its largest entry)")
    if arm.any():
        notes.append("the off-axis reference point (ref_msl x y) moved to the tower axis by the rigid-arm transform")
    centre = np.array([p.cm_pform_xy[0], p.cm_pform_xy[1], p.ref_msl - p.cm_pform])
    try:
        platform = Platform(mass=p.mass_pform, centre_of_mass=centre, inertia=p.i_matrix_pform,
                            added_mass=matrices["hydro_M"], hydrostatic=matrices["hydro_K"],
                            mooring=matrices["mooring_K"], base_height=p.ref_msl - p.draft + bmodes.hub_rad,
                            restoring_includes_weight=bmodes.hub_conn == 2)
    except InputError as error:
        raise bmodes.error(error.message, PLATFORM_KEYS.get(error.field or "", "i_matrix_pform")) from None
    return platform, notes


def _inside(bmodes: BModesInput, heights: NDArray, key: str) -> None:
    if heights.size and (heights[0] < 0 or heights[-1] > bmodes.length * (1 + 1e-9)):
        raise bmodes.error(f"heights must lie on the flexible tower, 0..{bmodes.length:g} m above its base", key)


def supports(bmodes: BModesInput) -> tuple[Supports, float, list[str]]:
    """The supports, the gravity to use (m/s^2) and notes."""
    p, notes = bmodes.platform, []
    base: dict[str, object] = {}
    gravity = STANDARD_GRAVITY
    restoring = p is not None and bool(np.any(p.hydro_K) or np.any(p.mooring_K))
    inert = p is not None and (restoring or np.any(p.hydro_M) or p.mass_pform)
    if bmodes.hub_conn == 1:
        if inert:
            notes.append("hub_conn = 1 clamps the base: the platform block's matrices act on held coordinates and "
                         "have no effect (as in BModes)")
    elif p is not None:
        base["platform"], platform_notes = platform_model(bmodes, p)
        notes += platform_notes
        if bmodes.hub_conn == 2:
            notes.append("the platform's restoring (hydro_K + mooring_K) is taken as complete, weight terms included "
                         "(BModes has no gravity); gravity acts on the tower's deformation relative to the platform")
    else:
        base["foundation"] = Foundation(stiffness=np.zeros((6, 6)))
    if bmodes.hub_conn == 2 and not _yaw_inertia(bmodes):
        raise bmodes.error("a free-free tower (hub_conn = 2) needs inertia about its axis (flp_iner, edge_iner, "
                           "izz_tip or the platform's): its yaw would be undetermined", "hub_conn")
    if bmodes.hub_conn == 2 and not restoring:
        gravity = 0.0
        notes.append("free-free tower without restoring: nothing carries its weight, so gravity is left out")
    held = HELD_BASE.get(bmodes.hub_conn, ())
    soil = added = None
    if p is not None and p.distributed_stiffness.size:
        _inside(bmodes, p.distributed_stiffness_z, "z_distr_k")
        soil = SoilSprings(height=p.distributed_stiffness_z, lateral=p.distributed_stiffness)
    if p is not None and p.added_mass.size:
        _inside(bmodes, p.added_mass_z, "z_distr_m")
        added = LateralAddedMass(height=p.added_mass_z, mass=p.added_mass)
    wires = ()
    if bmodes.wires is not None:
        w = bmodes.wires
        wires = tuple(Wires(count=n, stiffness=k, angle=math.pi / 2 - angle,
                            height=float(bmodes.el_loc[node - 1]) * bmodes.length)
                      for n, node, k, angle in zip(w.n_wires, w.node_attach, w.stiffness, w.angle))
        notes.append(f"{len(wires)} tension-wire sets: each wire an axial spring of wire_stfness at th_wire from the "
                     "horizontal (lateral stiffness n k cos^2(th)/2 in every direction, n k sin^2(th) vertically); "
                     "BModes puts n k cos^2(th) on each lateral axis")
    return Supports(wires=wires, soil=soil, added_mass=added, base_held=held, **base), gravity, notes  # type: ignore


def _yaw_inertia(bmodes: BModesInput) -> bool:
    """True when something has inertia about the tower axis (sections, top mass, platform)."""
    c, p = file_columns(bmodes), bmodes.platform
    platform = p is not None and (p.i_matrix_pform[2, 2] > 0 or p.hydro_M[5, 5] > 0)
    return bool(np.any(c["flp_iner"] + c["edge_iner"] > 0) or bmodes.tip["izz_tip"] > 0 or platform)


def tower_notes(bmodes: BModesInput) -> list[str]:
    given, used = scaled_columns(bmodes), file_columns(bmodes)
    notes = common_notes(bmodes)
    overwritten = [name for name in used if not np.array_equal(used[name], given[name])]
    if overwritten:
        notes.append(f"tower deck: {', '.join(overwritten)} replaced as BModes does (twist and offsets zero, the "
                     "side-side columns equal to the fore-aft ones)")
    notes.append("physics BModes leaves out and bladefem keeps: gravity (axial load and top-mass pendulum; "
                 "--no-gravity to compare) and the sections' rotary inertia in bending")
    return notes


def tower_from_bmodes(bmodes: BModesInput) -> Tower:
    """The tower model of a tower deck (``beam_type = 2``): sections over the flexible length ``radius + draft -
    hub_rad``, the top body, and the supports of ``hub_conn`` and the support block."""
    if bmodes.beam_type != 2:
        raise bmodes.error("this is a blade deck (beam_type = 1), not a tower", "beam_type")
    held, gravity, notes = supports(bmodes)
    try:
        return Tower(sections=bmodes_sections(bmodes), base_height=bmodes.hub_rad - bmodes.draft,
                     top_mass=top_mass(bmodes), supports=held, gravity=gravity,
                     name=bmodes.title[0].strip() or "BModes tower", notes=tuple(tower_notes(bmodes) + notes))
    except InputError as error:                  # e.g. a support point above the tower top
        raise bmodes.error(error.message, "tow_support") from None
