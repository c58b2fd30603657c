"""bladefem models from BModes decks: every field with the meaning BModes gives it (docs/formats.md has the table).

The section table is mapped so that bladefem's equations reproduce BModes' where BModes is right:

- frames: BModes' chordwise offsets (``cg_offst``, ``sc_offst``, ``tc_offst``, ``cm_loc``) point toward the trailing
  edge, bladefem's toward the leading edge (:data:`CHORDWISE_SIGN`); ``str_tw`` and ``bl_thp`` are positive toward
  feather in both.
- section inertias: BModes takes ``flp_iner`` and ``edge_iner`` about the reference axis (its torsional inertia is
  their sum) and interpolates their ratio to the mass along the span. bladefem's columns are about the centre of
  mass, so ``edge_inertia = edge_iner - m e^2`` (the chordwise offset ``e`` moves only the edgewise inertia), and the
  table interpolates the squared radii of gyration about the reference axis
  (:attr:`~bladefem.sections.SectionTable.inertia_per_mass`). Inertias given on axes at ``tw_iner`` are turned onto
  the structural axes at ``str_tw`` as BModes does (the product of inertia is dropped).
- stiffness: BModes couples extension and bending through ``ea = tc_offst - sc_offst`` (the tension centre measured
  from the shear centre) and takes ``edge_stff`` about its beam axis. bladefem's stiffness is about the tension
  centre, so the tension-centre offset is ``-ea`` and ``edge_stiffness = edge_stff - EA ea^2``: the 3x3 stiffness of
  (u', v'', w'') is then BModes' exactly.
- tip mass: a rigid body with its centre of mass ``cm_axial`` beyond the tip along the span and ``cm_loc`` along the
  tip section's chord (toward the trailing edge), inertias about its centre of mass in the tip section frame
  (x flapwise, y toward the trailing edge, z along the span), the products ``ixy_tip`` .. ``iyz_tip`` being
  inertia-tensor entries as BModes' mass matrix uses them. Towers: see :mod:`bladefem.builders.bmodes_tower`.
- ``el_loc``: BModes' own mesh is not used. bladefem meshes from the stations and refines until converged; BModes'
  element boundaries often lie within millimetres of a station (rounded fractions), and such sliver elements ruin
  the conditioning.

Where BModes' physics or code differs, bladefem keeps the right physics and the model's notes name the difference:
see :func:`blade_notes`.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..sections import Blade, SectionTable, TipMass
from ..formats.bmodes import BModesInput

#: BModes chordwise quantities are positive toward the trailing edge; bladefem's toward the leading edge.
CHORDWISE_SIGN = -1.0
#: BModes hub_conn -> bladefem root condition
ROOT_OF_HUB_CONN = {1: "cantilever", 2: "free", 3: "axial-torsion", 4: "hinged"}


def file_columns(bmodes: BModesInput) -> dict[str, NDArray]:
    """The section columns with the multipliers applied, as BModes uses them: a tower's twist and offsets are zero
    and its edgewise columns equal the flapwise ones (BModes overwrites them)."""
    out = scaled_columns(bmodes)
    if bmodes.beam_type == 2:
        zero = np.zeros_like(out["sec_loc"])
        out.update(str_tw=zero, tw_iner=zero, cg_offst=zero, sc_offst=zero, tc_offst=zero,
                   edge_iner=out["flp_iner"], edge_stff=out["flp_stff"])
    return out


def scaled_columns(bmodes: BModesInput) -> dict[str, NDArray]:
    """The section columns with the multipliers applied."""
    c, k = bmodes.sections.columns, bmodes.multipliers
    out = {"sec_loc": c["sec_loc"], "str_tw": c["str_tw"], "tw_iner": c["tw_iner"],
           "mass_den": c["mass_den"] * k["sec_mass_mult"],
           "flp_iner": c["flp_iner"] * k["flp_iner_mult"], "edge_iner": c["edge_iner"] * k["lag_iner_mult"],
           "flp_stff": c["flp_stff"] * k["flp_stff_mult"], "edge_stff": c["edge_stff"] * k["edge_stff_mult"],
           "tor_stff": c["tor_stff"] * k["tor_stff_mult"], "axial_stff": c["axial_stff"] * k["axial_stff_mult"],
           "cg_offst": c["cg_offst"] * k["cg_offst_mult"], "sc_offst": c["sc_offst"] * k["sc_offst_mult"],
           "tc_offst": c["tc_offst"] * k["tc_offst_mult"]}
    return out


def bmodes_sections(bmodes: BModesInput) -> SectionTable:
    """The section table (SI, bladefem's conventions) at the file's stations."""
    c = file_columns(bmodes)
    m, e = c["mass_den"], CHORDWISE_SIGN * c["cg_offst"]
    turn = c["str_tw"] - c["tw_iner"]                      # inertia axes onto the structural axes
    flap = c["flp_iner"] * np.cos(turn) ** 2 + c["edge_iner"] * np.sin(turn) ** 2
    edge = c["edge_iner"] * np.cos(turn) ** 2 + c["flp_iner"] * np.sin(turn) ** 2 - m * e**2
    ea = c["tc_offst"] - c["sc_offst"]                      # tension centre from the shear centre
    edge_stiffness = c["edge_stff"] - c["axial_stff"] * ea**2
    for name, values, what in (("edge_iner", edge, "edge_iner is less than m cg_offst^2, its part about the "
                                                   "reference axis that the centre-of-mass offset gives"),
                               ("edge_stff", edge_stiffness, "edge_stff is not above axial_stff (tc_offst - "
                                                             "sc_offst)^2: BModes' section stiffness is not "
                                                             "positive definite")):
        bad = np.flatnonzero(values < -1e-9 * np.abs(values).max() if name == "edge_iner" else values <= 0)
        if bad.size:
            raise InputError(what, file=bmodes.sections.path or None,
                             line=_line_of_station(bmodes, int(bad[0])), field=name)
    table = SectionTable(
        span=c["sec_loc"] * bmodes.length, mass=m, flap_stiffness=c["flp_stff"], edge_stiffness=edge_stiffness,
        torsion_stiffness=c["tor_stff"], axial_stiffness=c["axial_stff"], twist=c["str_tw"],
        flap_inertia=flap, edge_inertia=np.maximum(edge, 0.0), cm_offset=e,
        shear_centre_offset=CHORDWISE_SIGN * c["sc_offst"], tension_centre_offset=CHORDWISE_SIGN * ea,
        inertia_per_mass=True, source=bmodes.sections.path, lines=bmodes.sections.station_lines or None)
    return table


def _line_of_station(bmodes: BModesInput, index: int) -> int | None:
    lines = bmodes.sections.station_lines
    return lines[index] if index < len(lines) else None


def tip_frame(theta: float) -> NDArray:
    """Columns: BModes' tip-section axes x (flapwise), y (toward the trailing edge), z (span) in the blade frame,
    for a tip section turned by ``theta`` (tip twist plus pitch, rad)."""
    thickness = np.array([0.0, math.sin(theta), math.cos(theta)])
    chord = np.array([0.0, math.cos(theta), -math.sin(theta)])            # toward the leading edge
    return np.stack([thickness, CHORDWISE_SIGN * chord, np.array([1.0, 0.0, 0.0])], axis=1)


def tip_inertia(tip: dict[str, float]) -> NDArray:
    """The tip body's inertia tensor about its centre of mass in the deck's tip axes (products as tensor entries,
    which is how BModes' mass matrix uses ``ixy_tip``, ``izx_tip``, ``iyz_tip``)."""
    return np.array([[tip["ixx_tip"], tip["ixy_tip"], tip["izx_tip"]],
                     [tip["ixy_tip"], tip["iyy_tip"], tip["iyz_tip"]],
                     [tip["izx_tip"], tip["iyz_tip"], tip["izz_tip"]]])


def rigid_tip(bmodes: BModesInput, axes: NDArray, offset: NDArray, kind: type[TipMass] = TipMass) -> TipMass | None:
    """The tip mass with ``offset`` and the deck's inertias given in the deck's tip ``axes`` (columns in the model's
    frame); None when the deck has none."""
    t = bmodes.tip
    if not any(t.values()):
        return None
    try:
        return kind(mass=t["tip_mass"], offset=axes @ offset, inertia=axes @ tip_inertia(t) @ axes.T)
    except InputError as error:
        raise bmodes.error(error.message, "ixx_tip") from None


def blade_tip(bmodes: BModesInput, theta: float) -> TipMass | None:
    """The blade's tip mass in the blade frame; ``theta`` is the tip twist plus pitch, rad."""
    t = bmodes.tip
    return rigid_tip(bmodes, tip_frame(theta), np.array([0.0, t["cm_loc"], t["cm_axial"]]))


def common_notes(bmodes: BModesInput) -> list[str]:
    scaled = ", ".join(f"{k} = {v:g}" for k, v in bmodes.multipliers.items() if v != 1.0)
    notes = [f"BModes deck ({bmodes.layout} layout, hub_conn {bmodes.hub_conn}): multipliers applied: "
             f"{scaled or 'none other than 1'}; its el_loc mesh is not used (bladefem refines from the stations)"]
    t = bmodes.tip
    if t["tip_mass"] and (t["cm_axial"] or t["cm_loc"]):
        notes.append(f"tip mass: cm_axial is the offset along the beam axis and cm_loc the transverse one; BModes "
                     f"v3.00 reads the cm_axial line into cm_loc, so it uses cm_loc = {t['cm_axial']:g} m and no "
                     "axial offset")
    return notes


def blade_notes(bmodes: BModesInput, sections: SectionTable) -> tuple[str, ...]:
    """What bladefem does differently from BModes for this blade deck, and why."""
    c = bmodes.sections.columns
    notes = common_notes(bmodes)
    kept = ["the sections' rotary inertia in bending and the first-moment coupling of extension with the slopes",
            "the axial centrifugal softening"]
    if bmodes.precone:
        kept.append(f"the precone ({math.degrees(bmodes.precone):g} deg) in the centrifugal stiffness")
    if bmodes.tip["tip_mass"]:
        kept.append("the tip mass's own centrifugal force in the blade tension")
    notes.append("physics BModes leaves out and bladefem keeps: " + "; ".join(kept))
    if np.any(c["cg_offst"]) or np.any(c["sc_offst"]) or np.any(c["tc_offst"]):
        notes.append("offsets as BModes uses them: cg_offst from the reference axis (flp_iner, edge_iner about that "
                     "axis), the tension centre from the shear centre (tc_offst - sc_offst, edge_stff about the "
                     "shear centre)")
    if not np.allclose(c["tw_iner"], c["str_tw"]):
        notes.append("tw_iner differs from str_tw: the inertias are turned onto the structural axes as BModes does "
                     "(their product is dropped)")
    k = bmodes.multipliers
    if (k["sc_offst_mult"] != 1 or k["tc_offst_mult"] != 1) and (np.any(c["sc_offst"]) or np.any(c["tc_offst"])):
        notes.append("tc_offst_mult and sc_offst_mult scale tc_offst and sc_offst; BModes scales tc_offst - "
                     "sc_offst by their product")
    theta = float(sections.twist[-1]) + bmodes.pitch
    if bmodes.tip["tip_mass"] and theta and (bmodes.tip["cm_loc"] or any(bmodes.tip[key] for key in
                                                                         ("ixx_tip", "iyy_tip", "ixy_tip"))):
        notes.append(f"tip-mass offset and inertias are in the tip section's axes (turned {math.degrees(theta):.3g} "
                     "deg by tip twist and pitch); BModes' code applies them in the rotor-plane axes")
    return tuple(notes)


def blade_from_bmodes(bmodes: BModesInput) -> Blade:
    """A :class:`Blade` from a blade deck (``beam_type = 1``); its rotor speed is ``bmodes.rotor_speed_rpm`` (the
    CLI's default ``--rpm`` for the deck)."""
    if bmodes.beam_type != 1:
        raise bmodes.error("this is a tower deck (beam_type = 2), not a blade", "beam_type")
    sections = bmodes_sections(bmodes)
    theta = float(sections.twist[-1]) + bmodes.pitch
    return Blade(sections=sections, hub_radius=bmodes.hub_rad, precone=bmodes.precone, pitch=bmodes.pitch,
                 tip_mass=blade_tip(bmodes, theta), root=ROOT_OF_HUB_CONN[bmodes.hub_conn],  # type: ignore[arg-type]
                 name=bmodes.title[0].strip() or "BModes blade", notes=blade_notes(bmodes, sections))
