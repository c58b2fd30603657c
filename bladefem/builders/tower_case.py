"""bladefem's tower case file (YAML, ``kind: tower``): sections, top mass, gravity and supports.

Example (every unit is in the key name; 6x6 matrices are SI in the OpenFAST order surge, sway, heave, roll, pitch,
yaw, see docs/tower.md)::

    kind: tower
    name: NREL 5MW land tower
    height_m: 87.6                 # flexible length; needed when the table gives height_fraction
    base_height_m: 0.0
    gravity_m_s2: 9.80665          # 0 switches gravity off
    top_mass:
      mass_kg: 349606.5
      cm_offset_m: [1.966, 0.0, -0.408]       # up, side-side, downwind from the tower top
      inertia_kg_m2: [2.49e7, 2.34e7, 1.8e5]  # about the CM: [Ixx, Iyy, Izz] (x up, y side-side, z downwind)
                                             # or a 3x3 list
    sections:
      columns: [height_fraction, mass_kg_per_m, fore_aft_stiffness_N_m2, side_side_stiffness_N_m2]
      rows:
        - [0.0, 5590.87, 6.14343e11, 6.14343e11]
        - ...
    supports:                      # all optional; none: clamped base
      wires: [{count: 3, stiffness_N_per_m: 1.0e6, angle_deg: 40, height_m: 60, azimuth_deg: 0}]
      foundation: {stiffness_SI: [[...6x6...]], mass_SI: [[...6x6...]]}
      platform: {mass_kg: ..., cm_m: [X, Y, Z], inertia_kg_m2: [roll, pitch, yaw], added_mass_SI: ...,
                 hydrostatic_SI: ..., mooring_SI: ..., base_height_m: ...}
      soil: {columns: [height_m, lateral_N_per_m2, axial_N_per_m2, torsional_N_m_per_m], rows: [...]}
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError, shown
from ..limits import MAX_MAGNITUDE
from ..sections import SectionTable
from ..sections.tower import (
    STANDARD_GRAVITY,
    Foundation,
    Platform,
    SoilSprings,
    Supports,
    TopMass,
    Tower,
    Wires,
)
from .case import CaseFile
from ..sections.checks import body_problem, check_section_values
from ..formats.yamlnodes import Key, load_yaml

#: case-file column -> SectionTable field
COLUMNS: dict[str, str] = {
    "height_m": "span",
    "height_fraction": "span",
    "mass_kg_per_m": "mass",
    "fore_aft_stiffness_N_m2": "flap_stiffness",
    "side_side_stiffness_N_m2": "edge_stiffness",
    "torsion_stiffness_N_m2": "torsion_stiffness",
    "axial_stiffness_N": "axial_stiffness",
    "fore_aft_inertia_kg_m": "flap_inertia",
    "side_side_inertia_kg_m": "edge_inertia",
}
REQUIRED = ("mass_kg_per_m", "fore_aft_stiffness_N_m2", "side_side_stiffness_N_m2")
TOP_KEYS = {"kind", "name", "source", "height_m", "base_height_m", "gravity_m_s2", "top_mass", "sections",
            "supports", "notes"}
TOP_MASS_KEYS = {"mass_kg", "cm_offset_m", "inertia_kg_m2"}
SUPPORT_KEYS = {"wires", "foundation", "platform", "soil"}
WIRE_KEYS = {"count": "count", "stiffness_N_per_m": "stiffness", "angle_deg": "angle", "height_m": "height",
             "azimuth_deg": "azimuth"}
PLATFORM_KEYS = {"mass_kg", "cm_m", "inertia_kg_m2", "added_mass_SI", "hydrostatic_SI", "mooring_SI",
                 "base_height_m"}
#: Largest gravity accepted, m/s^2 (about 100 g: beyond it is a typing slip, not a study)
MAX_GRAVITY = 1000.0
SOIL_COLUMNS = {"height_m": "height", "lateral_N_per_m2": "lateral", "axial_N_per_m2": "axial",
                "torsional_N_m_per_m": "torsional"}


def _keys(case: CaseFile, key: Key, known: set[str] | dict[str, str]) -> dict:
    value = case.get(key)
    if not isinstance(value, dict):
        raise case.error("expected a mapping", key)
    for name in value:
        if name not in known:
            raise case.error(f"unknown key (known: {', '.join(sorted(known))})", key + (name,),
                             shown(name, quoted=False))
    return value


def _array(case: CaseFile, key: Key, shapes: tuple[tuple[int, ...], ...]) -> np.ndarray:
    """A list (of lists) of numbers with one of the given shapes."""
    value = case.get(key)
    try:
        if isinstance(value, bool) or value is None:
            raise ValueError
        array = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise case.error(f"expected a list of numbers of shape {' or '.join(map(str, shapes))}", key) from None
    if array.shape not in shapes or not np.all(np.isfinite(array)):
        raise case.error(f"expected finite numbers of shape {' or '.join(map(str, shapes))}, got shape "
                         f"{array.shape}", key)
    if np.any(np.abs(array) > MAX_MAGNITUDE):
        raise case.error(f"{np.max(np.abs(array)):g} is beyond any real tower (|value| up to {MAX_MAGNITUDE:g})",
                         key)
    return array


def _sections(case: CaseFile) -> SectionTable:
    key: Key = ("sections",)
    table = case.table(key, COLUMNS, REQUIRED)
    columns = list(table.pop("_columns"))
    if ("height_m" in columns) == ("height_fraction" in columns):
        raise case.error("give exactly one of height_m or height_fraction", key + ("columns",))
    height = None
    if "height_fraction" in columns or case.get(("height_m",)) is not None:
        height = case.number(("height_m",), field="height_m")
        if height <= 0:
            raise case.error(f"must be positive, got {height:g}", ("height_m",))
    if "height_fraction" in columns:
        last = key + ("rows", len(table["span"]) - 1, columns.index("height_fraction"))
        if table["span"][-1] != 1.0:
            raise case.error(f"the last height_fraction must be 1 (the top), got {table['span'][-1]}", last,
                             "height_fraction")
        table["span"] = table["span"] * height
    lines = tuple(case.lines.get(key + ("rows", i), 0) for i in range(len(table["span"])))
    sections = SectionTable(**table, source=str(case.path), lines=lines)
    check_section_values(sections)
    if height is not None and abs(sections.length - height) > 1e-9 * height:
        raise case.error(f"height_m {height:g} contradicts the table's last height_m {sections.length:.12g}: give one "
                         "or make them agree", ("height_m",))
    return sections


def _top_mass(case: CaseFile, sections: SectionTable) -> TopMass | None:
    key: Key = ("top_mass",)
    if case.get(key) is None:
        return None
    data = _keys(case, key, TOP_MASS_KEYS)
    mass = case.number(key + ("mass_kg",), field="mass_kg")
    if mass < 0:
        raise case.error("must not be negative", key + ("mass_kg",))
    offset = _array(case, key + ("cm_offset_m",), ((3,),)) if "cm_offset_m" in data else np.zeros(3)
    inertia = (_array(case, key + ("inertia_kg_m2",), ((3,), (3, 3))) if "inertia_kg_m2" in data
               else np.zeros(3))
    top = _located(case, key + ("inertia_kg_m2",), lambda: TopMass(mass, offset, inertia))
    problem = body_problem(top.mass, top.offset, top.inertia, sections.length)
    if problem:
        raise case.error(problem, key + ("cm_offset_m",))
    return top


def _located(case: CaseFile, key: Key, build: Any) -> Any:
    """Run a constructor; an InputError it raises is given this key's file and line."""
    try:
        return build()
    except InputError as error:
        raise case.error(error.message, key, error.field) from None


def _supports(case: CaseFile) -> Supports:
    key: Key = ("supports",)
    if case.get(key) is None:
        return Supports()
    data = _keys(case, key, SUPPORT_KEYS)
    wires = []
    listed = data.get("wires") or []
    if not isinstance(listed, list):
        raise case.error("expected a list of wire sets", key + ("wires",))
    for i, _ in enumerate(listed):
        item = key + ("wires", i)
        _keys(case, item, WIRE_KEYS)
        values = {WIRE_KEYS[k]: case.number(item + (k,), 0.0 if k == "azimuth_deg" else None, k) for k in WIRE_KEYS}
        values["angle"], values["azimuth"] = math.radians(values["angle"]), math.radians(values["azimuth"])
        values["count"] = int(values["count"]) if float(values["count"]).is_integer() else values["count"]
        wires.append(_located(case, item, lambda v=values: Wires(**v)))
    foundation = None
    if data.get("foundation") is not None:
        item = key + ("foundation",)
        f = _keys(case, item, {"stiffness_SI", "mass_SI"})
        stiffness = _array(case, item + ("stiffness_SI",), ((6, 6),))
        mass = _array(case, item + ("mass_SI",), ((6, 6),)) if "mass_SI" in f else np.zeros((6, 6))
        foundation = _located(case, item, lambda: Foundation(stiffness, mass))
    platform = None
    if data.get("platform") is not None:
        item = key + ("platform",)
        p = _keys(case, item, PLATFORM_KEYS)
        matrices = {name: _array(case, item + (name + "_SI",), ((6, 6),)) if name + "_SI" in p else None
                    for name in ("added_mass", "hydrostatic", "mooring")}
        platform = _located(case, item, lambda: Platform(
            mass=case.number(item + ("mass_kg",), field="mass_kg"),
            centre_of_mass=_array(case, item + ("cm_m",), ((3,),)),
            inertia=_array(case, item + ("inertia_kg_m2",), ((3,), (3, 3))),
            base_height=case.number(item + ("base_height_m",), 0.0), **matrices))
    soil = None
    if data.get("soil") is not None:
        item = key + ("soil",)
        table = case.table(item, SOIL_COLUMNS, ("height_m", "lateral_N_per_m2"))
        table.pop("_columns")
        soil = _located(case, item, lambda: SoilSprings(**table))
    return _located(case, key, lambda: Supports(wires=tuple(wires), foundation=foundation, platform=platform,
                                                soil=soil))


def is_tower_case(path: str | Path) -> bool:
    """True if ``path`` is a YAML file whose top level says ``kind: tower`` (false for unreadable files)."""
    try:
        data, _ = load_yaml(path)
    except InputError:       # any reading problem is reported by the reader that is chosen instead
        return False
    return isinstance(data, dict) and data.get("kind") == "tower"


def read_tower_case(path: str | Path) -> Tower:
    """Read a bladefem YAML tower case into a :class:`~bladefem.sections.tower.Tower`."""
    case = CaseFile.open(path, "tower", TOP_KEYS)
    data = case.data
    gravity = case.number(("gravity_m_s2",), STANDARD_GRAVITY)
    if not 0 <= gravity <= MAX_GRAVITY:
        raise case.error(f"must lie between 0 (gravity off) and {MAX_GRAVITY:g} m/s^2, got {gravity:g}",
                         ("gravity_m_s2",))
    sections = _sections(case)
    notes = [str(note) for note in data.get("notes", []) or []]
    if sections.torsion_stiffness is None:
        notes.append("no torsion_stiffness column: torsion is rigid (the tower twists only with its base)")
    if sections.axial_stiffness is None:
        notes.append("no axial_stiffness column: the tower is inextensible (it moves axially only with its base)")
    top, supports = _top_mass(case, sections), _supports(case)
    return _located(case, ("supports",), lambda: Tower(
        sections=sections, base_height=case.number(("base_height_m",), 0.0), top_mass=top, supports=supports,
        gravity=gravity, name=str(data.get("name", case.path.stem)), notes=tuple(notes)))
