"""bladefem models (:class:`Blade`, :class:`Tower`) from BModes input, with BModes' conventions made explicit.

Conventions assumed from the BModes user's guide (the guide is not shipped with bladefem; these are stated here so
a user can check them against their deck):

- section frame: BModes ``x`` is the flapwise (thickness) direction, ``y`` the chordwise direction, ``z`` the beam
  axis. ``flp_iner`` and ``edge_iner`` are mass moments of inertia per length about the section's centre of mass
  (flap: about the chord axis; edge: about the thickness axis).
- chordwise offsets ``cg_offst``, ``sc_offst``, ``tc_offst`` and the tip mass's ``cm_loc`` are measured along
  ``y`` positive toward the trailing edge; bladefem measures them toward the leading edge, so they change sign.
- ``str_tw`` is the structural twist (positive toward feather, as in bladefem); ``tw_iner``, the orientation of the
  inertia principal axes, is taken equal to it (a note says so when the file differs).
- tip inertias ``ixx_tip`` (lag / tower side-side, about ``x``), ``iyy_tip`` (flap / tower fore-aft, about ``y``),
  ``izz_tip`` (torsion) and the products ``ixy_tip``, ``izx_tip``, ``iyz_tip`` (``int x y dm`` etc.) are about the
  tip mass's centre of mass, in the tip section frame (turned by the tip twist plus pitch).
- towers: ``flp_stff`` is fore-aft and ``edge_stff`` side-side bending stiffness; ``radius`` is the tower height and
  ``hub_rad`` the height of the rigid base, so the flexible length is their difference.
- ``hub_conn = 1`` is a clamped root. bladefem has no free-free or platform-supported beams yet: decks with
  ``hub_conn = 2 or 3``, tension wires or a platform are read (for round trips and inspection) but building a model
  from them is an :class:`InputError`.
- ``el_loc``: every element boundary becomes a station (properties interpolated linearly, which leaves the property
  distribution unchanged), so the FE mesh contains BModes' nodes; bladefem refines between them until converged.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..sections import Blade, SectionTable, TipMass
from .bmodes import BModesInput
from .tower import Tower

#: BModes chordwise quantities are positive toward the trailing edge; bladefem's toward the leading edge.
CHORDWISE_SIGN = -1.0


def bmodes_sections(bmodes: BModesInput) -> SectionTable:
    """The section table with the property multipliers applied and the ``el_loc`` nodes inserted as stations."""
    c = bmodes.sections.columns
    k = bmodes.multipliers
    fraction = c["sec_loc"]
    nodes = np.union1d(fraction, bmodes.el_loc)
    at = {name: np.interp(nodes, fraction, values) for name, values in c.items()}
    lines = _station_lines(bmodes.sections.station_lines, fraction, nodes)
    return SectionTable(
        span=nodes * bmodes.length,
        mass=at["mass_den"] * k["sec_mass_mult"],
        flap_stiffness=at["flp_stff"] * k["flp_stff_mult"],
        edge_stiffness=at["edge_stff"] * k["edge_stff_mult"],
        torsion_stiffness=at["tor_stff"] * k["tor_stff_mult"],
        axial_stiffness=at["axial_stff"] * k["axial_stff_mult"],
        twist=at["str_tw"],
        flap_inertia=at["flp_iner"] * k["flp_iner_mult"],
        edge_inertia=at["edge_iner"] * k["lag_iner_mult"],
        cm_offset=CHORDWISE_SIGN * at["cg_offst"] * k["cg_offst_mult"],
        shear_centre_offset=CHORDWISE_SIGN * at["sc_offst"] * k["sc_offst_mult"],
        tension_centre_offset=CHORDWISE_SIGN * at["tc_offst"] * k["tc_offst_mult"],
        source=bmodes.sections.path,
        lines=lines,
    )


def _station_lines(lines: tuple[int, ...], fraction: NDArray, nodes: NDArray) -> tuple[int, ...] | None:
    """File line of each station (an inserted node gets the line of the station below it)."""
    if not lines:
        return None
    index = np.clip(np.searchsorted(fraction, nodes, side="right") - 1, 0, len(lines) - 1)
    return tuple(int(lines[i]) for i in index)


def tip_body(bmodes: BModesInput, theta: float) -> TipMass | None:
    """The tip mass as a rigid body in the blade frame; ``theta`` is the tip twist plus pitch, rad."""
    t = bmodes.tip
    if t["tip_mass"] == 0 and not any(t[key] for key in t):
        return None
    thickness = np.array([0.0, math.sin(theta), math.cos(theta)])     # BModes x
    chord = np.array([0.0, math.cos(theta), -math.sin(theta)])        # toward the leading edge
    span = np.array([1.0, 0.0, 0.0])                                  # BModes z
    y = CHORDWISE_SIGN * chord                                        # BModes y (toward the trailing edge)
    axes = (thickness, y, span)
    local = np.array([[t["ixx_tip"], -t["ixy_tip"], -t["izx_tip"]],
                      [-t["ixy_tip"], t["iyy_tip"], -t["iyz_tip"]],
                      [-t["izx_tip"], -t["iyz_tip"], t["izz_tip"]]])
    rotation = np.stack(axes, axis=1)                                 # columns: BModes axes in the blade frame
    inertia = rotation @ local @ rotation.T
    offset = t["cm_axial"] * span + t["cm_loc"] * y
    try:
        return TipMass(mass=t["tip_mass"], offset=offset, inertia=inertia)
    except InputError as error:
        raise InputError(error.message, file=bmodes.path or None, line=bmodes.key_lines.get("ixx_tip"),
                         field="ixx_tip") from None


def _check_supported(bmodes: BModesInput) -> None:
    if bmodes.hub_conn != 1:
        raise InputError(f"hub_conn = {bmodes.hub_conn} (not cantilevered) is read but not modelled by bladefem "
                         "yet; only hub_conn = 1", file=bmodes.path or None, line=bmodes.key_lines.get("hub_conn"),
                         field="hub_conn")
    if bmodes.platform is not None or bmodes.wires is not None:
        what = "a platform/monopile" if bmodes.platform is not None else "tension wires"
        raise InputError(f"the tower support ({what}) is read but not modelled by bladefem yet",
                         file=bmodes.path or None, line=bmodes.key_lines.get("tow_support"), field="tow_support")


def _notes(bmodes: BModesInput) -> tuple[str, ...]:
    scaled = ", ".join(f"{k} = {v:g}" for k, v in bmodes.multipliers.items() if v != 1.0)
    notes = [f"BModes deck ({bmodes.layout} layout), property multipliers applied: {scaled or 'none other than 1'}",
             f"el_loc: {len(bmodes.el_loc) - 1} BModes elements, their nodes are stations of the FE mesh"]
    c = bmodes.sections.columns
    if not np.allclose(c["tw_iner"], c["str_tw"]):
        notes.append("tw_iner differs from str_tw; the inertia axes are taken along the structural axes")
    if bmodes.tip["cm_axial"] or bmodes.tip["cm_loc"]:
        notes.append("cm_axial read as the axial tip-mass offset and cm_loc as the chordwise one (BModes v3.00 "
                     "reads the cm_axial line into cm_loc)")
    return tuple(notes)


def blade_from_bmodes(bmodes: BModesInput) -> Blade:
    """A :class:`Blade` from a blade deck (``beam_type = 1``); the rotor speed is ``bmodes.rotor_speed_rpm``."""
    if bmodes.beam_type != 1:
        raise InputError("this is a tower deck (beam_type = 2), not a blade", file=bmodes.path or None,
                         line=bmodes.key_lines.get("beam_type"), field="beam_type")
    _check_supported(bmodes)
    sections = bmodes_sections(bmodes)
    theta = float(sections.twist[-1]) + bmodes.pitch
    return Blade(sections=sections, hub_radius=bmodes.hub_rad, precone=bmodes.precone, pitch=bmodes.pitch,
                 tip_mass=tip_body(bmodes, theta), name=bmodes.title[0].strip() or "BModes blade",
                 notes=_notes(bmodes))


def tower_from_bmodes(bmodes: BModesInput) -> Tower:
    """A :class:`Tower` from a tower deck (``beam_type = 2``): clamped at the top of the rigid base."""
    if bmodes.beam_type != 2:
        raise InputError("this is a blade deck (beam_type = 1), not a tower", file=bmodes.path or None,
                         line=bmodes.key_lines.get("beam_type"), field="beam_type")
    _check_supported(bmodes)
    sections = bmodes_sections(bmodes)
    return Tower(sections=sections, base_height=bmodes.hub_rad, top_mass=tip_body(bmodes, 0.0),
                 name=bmodes.title[0].strip() or "BModes tower", notes=_notes(bmodes))


def wire_angle_to_axis(bmodes: BModesInput, angle: float) -> float:
    """``th_wire`` as the angle between a wire and the tower axis, rad: v3.00 decks give it from the tower axis,
    the later layout (its description) from the horizontal ground plane."""
    return angle if bmodes.layout == "v3.00" else math.pi / 2 - angle


def tower_model_from_bmodes(bmodes: BModesInput):
    """The tower deck as a :class:`bladefem.sections.tower.Tower` for the tower model, with its tension wires as
    supports (each wire of a set with the set's ``wire_stfness`` as its own axial stiffness, attached at BModes node
    ``node_attach`` = ``el_loc[node - 1]`` of the flexible length). A platform block is not mapped yet."""
    from ..sections.tower import Supports, Wires
    from ..sections.tower import Tower as ModelTower
    if bmodes.beam_type != 2:
        raise InputError("this is a blade deck (beam_type = 1), not a tower", file=bmodes.path or None,
                         line=bmodes.key_lines.get("beam_type"), field="beam_type")
    if bmodes.platform is not None or bmodes.hub_conn != 1:
        _check_supported(bmodes)
    plain = tower_from_bmodes(replace(bmodes, wires=None))
    wires = ()
    if bmodes.wires is not None:
        w = bmodes.wires
        wires = tuple(Wires(count=n, stiffness=k, angle=wire_angle_to_axis(bmodes, a),
                            height=float(bmodes.el_loc[node - 1]) * bmodes.length)
                      for n, node, k, a in zip(w.n_wires, w.node_attach, w.stiffness, w.angle))
    notes = plain.notes + ((f"{len(wires)} tension-wire sets from the deck (each wire with wire_stfness as its "
                            "axial stiffness; th_wire measured from the tower axis in v3.00 decks, from the "
                            "ground plane in the later layout)",) if wires else ())
    return ModelTower(sections=plain.sections, base_height=plain.base_height, top_mass=plain.top_mass,
                      supports=Supports(wires=wires), name=plain.name, notes=notes)
