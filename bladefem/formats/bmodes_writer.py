"""Writing BModes decks (main file and section-property file) in either layout, for round trips and for handing a
bladefem model to BModes users."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from ..files import write_atomic
from ._fast_format import degrees_exact, format_number
from .bmodes import (
    MULTIPLIERS,
    SECTION_COLUMNS,
    TIP_KEYS,
    BModesInput,
    BModesPlatform,
    BModesSections,
    BModesWires,
)

RULE = "-" * 90


def _entry(value: object, key: str, description: str) -> str:
    text = format_number(value) if isinstance(value, float) else str(value)
    return f"{text:<24} {key}: {description}\n"


def bmodes_main_text(bmodes: BModesInput, sections_name: str) -> str:
    """The text of a BModes main file; ``sections_name`` is written as ``sec_props_file``."""
    b = bmodes
    flags = {key: ("true" if value else "false") for key, value in b.flags.items()}
    out = ["======================   BModes v3.00 Main Input File  ==================\n",
           f"{b.title[0]}\n", f"{b.title[1]}\n",
           f"--------- General parameters {RULE}\n"]
    if "Echo" in flags:
        out.append(f"{flags['Echo']:<24} Echo        Echo input file contents to *.echo file if true.\n")
    out += [_entry(b.beam_type, "beam_type", "1: blade, 2: tower (-)"),
            _entry(b.rot_rpm, "rot_rpm", "rotor speed, automatically set to zero for tower modal analysis (rpm)"),
            _entry(b.rpm_mult, "rpm_mult", "rotor speed multiplicative factor (-)"),
            _entry(b.radius, "radius", "rotor tip radius measured along coned blade axis OR tower height (m)"),
            _entry(b.hub_rad, "hub_rad", "hub radius along coned blade axis OR tower rigid-base height (m)"),
            _entry(degrees_exact(b.precone), "precone", "built-in precone angle (deg)"),
            _entry(degrees_exact(b.pitch), "bl_thp", "blade pitch setting (deg)"),
            _entry(b.hub_conn, "hub_conn", "hub-to-blade or tower-base boundary condition [1: cantilevered; "
                                           "2: free-free; 3: only axial and torsion constraints; 4: pinned-free] (-)"),
            _entry(b.modepr, "modepr", "number of modes to be printed (-)")]
    for key in ("TabDelim", "mid_node_tw"):
        if key in flags:
            out.append(f"{flags[key]:<24} {key}    (flag)\n")
    out.append(f"\n--------- Blade-tip or tower-top mass properties {RULE}\n")
    descriptions = {"tip_mass": "blade-tip or tower-top mass (kg)",
                    "cm_loc": "tip-mass c.m. offset from the axis along the tip section y reference axis (m)",
                    "cm_axial": "tip-mass c.m. offset along the beam (z) axis (m)",
                    "ixx_tip": "blade lag or tower s-s inertia about the tip-section x axis (kg-m^2)",
                    "iyy_tip": "blade flap or tower f-a inertia about the tip-section y axis (kg-m^2)",
                    "izz_tip": "torsion inertia about the tip-section z axis (kg-m^2)",
                    "ixy_tip": "cross product of inertia about x and y axes (kg-m^2)",
                    "izx_tip": "cross product of inertia about z and x axes (kg-m^2)",
                    "iyz_tip": "cross product of inertia about y and z axes (kg-m^2)"}
    out += [_entry(float(b.tip[key]), key, descriptions[key]) for key in TIP_KEYS]
    out += [f"\n--------- Distributed-property identifiers {RULE}\n",
            _entry(b.id_mat, "id_mat", "material_type [1: isotropic] (-)"),
            f"{chr(34) + sections_name + chr(34):<24} sec_props_file   name of beam section properties file (-)\n",
            "\nProperty scaling factors..............................\n"]
    out += [_entry(float(b.multipliers[key]), key, "multiplier (-)") for key in MULTIPLIERS]
    out += [f"\n--------- Finite element discretization {RULE}\n",
            _entry(len(b.el_loc) - 1, "nselt", "no of blade or tower elements (-)"),
            "Distance of element boundary nodes from blade or flexible-tower root (normalized), el_loc()\n",
            " ".join(format_number(v) for v in b.el_loc) + "\n"]
    if b.beam_type == 2:
        out += _support_lines(b)
    out.append("\nEND of Main Input File Data ***********************************************************\n")
    return "".join(out)


def _support_lines(b: BModesInput) -> list[str]:
    meaning = {"platform": "1: floating-platform or monopile with or without tension wires",
               "offshore": "1: tension wires; 2: floating platform or monopile"}.get(b.layout, "1: tension wires")
    out = [f"\n--------- Properties of tower support subsystem (read only if beam_type is 2) {RULE}\n",
           _entry(b.tow_support, "tow_support", f"additional tower support [0: none; {meaning}] (-)")]
    if b.layout in ("platform", "offshore") and b.tow_support > 0:
        out += _platform_lines(b.platform)
    if b.layout != "offshore":
        out += ["Tension wires data\n"] + _wire_lines(b.wires)
    return out


def _point(depth: float, offset: tuple[float, float], key: str, description: str) -> str:
    """``depth  key`` or, with a horizontal offset, ``depth x y  key`` (pybmodes' extension)."""
    if not any(offset):
        return _entry(float(depth), key, description)
    values = " ".join(format_number(float(v)) for v in (depth, *offset))
    return f"{values:<24} {key}: {description}, then the horizontal offset x y from the tower axis (m)\n"


def _matrix_lines(label: str, matrix: np.ndarray) -> list[str]:
    return [f"{label}:\n"] + [" ".join(format_number(v) for v in row) + "\n" for row in matrix]


def _platform_lines(platform: BModesPlatform | None) -> list[str]:
    p = platform or BModesPlatform(0.0, 0.0, 0.0, np.zeros((3, 3)), 0.0, np.zeros((6, 6)), np.zeros((6, 6)),
                                   np.zeros((6, 6)), np.zeros(0), np.zeros(0), np.zeros(0), np.zeros(0))
    out = [_entry(float(p.draft), "draft", "depth of tower base from the ground or the MSL (m)"),
           _point(p.cm_pform, p.cm_pform_xy, "cm_pform", "distance of platform c.m. below the MSL (m)"),
           _entry(float(p.mass_pform), "mass_pform", "platform mass (kg)")]
    out += _matrix_lines("Platform mass inertia 3X3 matrix (i_matrix_pform)", p.i_matrix_pform)
    out.append(_point(p.ref_msl, p.ref_msl_xy, "ref_msl", "distance of platform reference point below the MSL (m)"))
    out += _matrix_lines("Platform-reference-point-referred hydrodynamic 6X6 matrix (hydro_M)", p.hydro_M)
    out += _matrix_lines("Platform-reference-point-referred hydrodynamic 6X6 stiffness matrix (hydro_K)", p.hydro_K)
    out += _matrix_lines("Mooring-system 6X6 stiffness matrix (mooring_K)", p.mooring_K)

    def row(values: np.ndarray, key: str, description: str) -> str:
        numbers = " ".join(format_number(v) for v in values) if len(values) else "0."
        return f"{numbers}  : {key} {description}\n"

    out += ["\nDistributed (hydrodynamic) added-mass per unit length along the flexible tower:\n",
            _entry(len(p.added_mass), "n_secs_m_distr", "number of sections with added mass (-)"),
            row(p.added_mass_z, "z_distr_m", "section locations wrt the flexible tower base (m)"),
            row(p.added_mass, "distr_m", "added distributed masses per unit length (kg/m)"),
            "\nDistributed elastic stiffness per unit length along the flexible tower:\n",
            _entry(len(p.distributed_stiffness), "n_secs_k_distr", "number of points with stiffness (-)"),
            row(p.distributed_stiffness_z, "z_distr_k", "locations wrt the flexible tower base (m)"),
            row(p.distributed_stiffness, "distr_k", "distributed stiffness per unit length (N/m^2)"), "\n"]
    return out


def _wire_lines(wires: BModesWires | None) -> list[str]:
    if wires is None:        # the wire lines are still there: BModes reads them whatever n_attachments says
        return [_entry(0, "n_attachments", "no of wire-attachment locations on tower [0: no tension wires] (-)"),
                f"{'0':<24} n_wires: no of wires attached at each location (-)\n",
                f"{'0':<24} node_attach: node numbers of attachment locations (-)\n",
                f"{'0.':<24} wire_stfness: wire spring constant in each set (N/m)\n",
                f"{'0.':<24} th_wire: angle of the wires from the horizontal plane (deg)\n"]

    def row(values: tuple, key: str, description: str) -> str:
        return f"{' '.join(format_number(v) if isinstance(v, float) else str(v) for v in values):<24} {key}: " \
               f"{description}\n"

    return [_entry(len(wires.n_wires), "n_attachments", "no of wire-attachment locations on tower (-)"),
            row(wires.n_wires, "n_wires", "no of wires attached at each location (-)"),
            row(wires.node_attach, "node_attach", "node numbers of attachment locations (-)"),
            row(wires.stiffness, "wire_stfness", "wire spring constant in each set (N/m)"),
            row(tuple(degrees_exact(a) for a in wires.angle), "th_wire",
                "angle of the wires from the horizontal plane at each attachment (deg)")]


def bmodes_sections_text(sections: BModesSections) -> str:
    """The text of a BModes section-property file."""
    count = len(sections.columns["sec_loc"])
    out = [f"{sections.title}\n", f"{count:<10} n_secs:     number of sections at which properties are specified (-)\n",
           "\n", "".join(f"{name:>24}" for name in SECTION_COLUMNS) + "\n",
           "".join(f"{unit:>24}" for unit in ("(-)", "(deg)", "(deg)", "(kg/m)", "(kg-m)", "(kg-m)", "(Nm^2)",
                                                "(Nm^2)", "(Nm^2)", "(N)", "(m)", "(m)", "(m)")) + "\n"]
    for i in range(count):
        row = [sections.columns[name][i] for name in SECTION_COLUMNS]
        row[1], row[2] = degrees_exact(row[1]), degrees_exact(row[2])
        out.append("".join(f"{format_number(v):>24}" for v in row) + "\n")
    return "".join(out)


def write_bmodes(bmodes: BModesInput, path: str | os.PathLike, sections_path: str | os.PathLike | None = None) -> None:
    """Write the main file to ``path`` and the section properties to ``sections_path`` (default: beside it, named
    ``<stem>_sec_props.dat``), both atomically."""
    path = Path(path)
    sections_path = Path(sections_path) if sections_path else path.with_name(f"{path.stem}_sec_props.dat")
    write_atomic(sections_path, bmodes_sections_text(bmodes.sections))
    relative = Path(os.path.relpath(sections_path, path.parent)).as_posix()
    write_atomic(path, bmodes_main_text(bmodes, relative))
