"""bladefem's own case file (YAML): a blade's geometry, root, tip mass and section table.

Example (every unit is in the key name; see the README for all keys)::

    kind: blade
    name: NREL 5MW blade
    hub_radius_m: 1.5
    tip_radius_m: 63.0          # needed when the table gives span_fraction
    precone_deg: -2.5
    pitch_deg: 0.0
    root: cantilever            # or hinged
    tip_mass: {mass_kg: 0, axial_offset_m: 0, chordwise_offset_m: 0,
               flap_inertia_kg_m2: 0, edge_inertia_kg_m2: 0, torsion_inertia_kg_m2: 0}
    sections:
      columns: [span_fraction, twist_deg, mass_kg_per_m, flap_stiffness_N_m2, edge_stiffness_N_m2]
      rows:
        - [0.0, 13.308, 678.935, 1.811e10, 1.811e10]
        - ...
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError, shown
from ..limits import MAX_MAGNITUDE
from ..sections import ROOTS, Blade, SectionTable, tip_mass_at_section
from ..sections.checks import body_problem, check_section_values, length_problem, precone_problem
from ..formats.yamlnodes import Key, load_yaml

#: case-file column -> (SectionTable field, factor to SI)
COLUMNS: dict[str, tuple[str, float]] = {
    "span_m": ("span", 1.0),
    "span_fraction": ("span", 1.0),
    "mass_kg_per_m": ("mass", 1.0),
    "flap_stiffness_N_m2": ("flap_stiffness", 1.0),
    "edge_stiffness_N_m2": ("edge_stiffness", 1.0),
    "torsion_stiffness_N_m2": ("torsion_stiffness", 1.0),
    "axial_stiffness_N": ("axial_stiffness", 1.0),
    "twist_deg": ("twist", math.pi / 180),
    "flap_inertia_kg_m": ("flap_inertia", 1.0),
    "edge_inertia_kg_m": ("edge_inertia", 1.0),
    "cm_offset_m": ("cm_offset", 1.0),
    "shear_centre_offset_m": ("shear_centre_offset", 1.0),
    "tension_centre_offset_m": ("tension_centre_offset", 1.0),
    "chord_m": ("chord", 1.0),
    "pitch_axis_fraction": ("pitch_axis", 1.0),
}
REQUIRED_COLUMNS = ("mass_kg_per_m", "flap_stiffness_N_m2", "edge_stiffness_N_m2")
TOP_KEYS = {"kind", "name", "source", "hub_radius_m", "tip_radius_m", "precone_deg", "pitch_deg", "root",
            "tip_mass", "sections", "notes"}
TIP_KEYS = {"mass_kg": "mass", "axial_offset_m": "axial_offset", "chordwise_offset_m": "chordwise_offset",
            "flap_inertia_kg_m2": "flap_inertia", "edge_inertia_kg_m2": "edge_inertia",
            "torsion_inertia_kg_m2": "torsion_inertia"}


class CaseFile:
    """Reads values out of the parsed YAML with errors that name file, line and field."""

    def __init__(self, path: Path, data: Any, lines: dict[Key, int]) -> None:
        self.path, self.data, self.lines = path, data, lines

    def error(self, message: str, key: Key, field: str | None = None) -> InputError:
        line = None
        for n in range(len(key), -1, -1):
            if key[:n] in self.lines:
                line = self.lines[key[:n]]
                break
        return InputError(message, file=str(self.path), line=line, field=field or ".".join(map(str, key)))

    def get(self, key: Key) -> Any:
        """The value at a key path (mapping keys and list indices), or None where there is none."""
        value = self.data
        for part in key:
            if isinstance(value, dict) and part in value:
                value = value[part]
            elif isinstance(value, list) and isinstance(part, int) and 0 <= part < len(value):
                value = value[part]
            else:
                return None
        return value

    @classmethod
    def open(cls, path: str | Path, kind: str, known_keys: set[str]) -> CaseFile:
        """Parse a case file and check its top level: a mapping of known keys with ``kind: <kind>`` (a blade case
        may leave ``kind`` out)."""
        path = Path(path)
        data, lines = load_yaml(path)
        case = cls(path, data, lines)
        if not isinstance(data, dict):
            raise case.error("expected a mapping of keys at the top level", ())
        for name in data:
            if name not in known_keys:
                raise case.error(f"unknown key (known: {', '.join(sorted(known_keys))})", (name,),
                                 shown(name, quoted=False))
        found = data.get("kind", "blade")
        if found != kind:
            raise case.error(f"expected 'kind: {kind}', got {shown(found)}", ("kind",))
        return case

    def number(self, key: Key, default: float | None = None, field: str | None = None) -> float:
        value = self.get(key)
        if value is None:
            if default is None:
                raise self.error("missing value", key, field)
            return default
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise self.error(f"expected a finite number, got {shown(value)}", key, field)
        if abs(value) > MAX_MAGNITUDE:
            raise self.error(f"{value:g} is beyond any real blade or tower (|value| up to {MAX_MAGNITUDE:g})", key,
                             field)
        return float(value)

    def table(self, key: Key, columns_map: dict[str, str], required: Sequence[str]) -> dict[str, np.ndarray]:
        """A ``columns``/``rows`` table at ``key`` as arrays by the mapped names (plus ``_columns``, the names as
        given); every error names the line of the offending row or column list."""
        data = self.get(key)
        if not isinstance(data, dict):
            raise self.error("expected a mapping with 'columns' and 'rows'", key)
        for name in data:
            if name not in ("columns", "rows"):
                raise self.error("unknown key (known: columns, rows)", key + (name,),
                                 shown(name, quoted=False))
        columns, rows = data.get("columns"), data.get("rows")
        if not isinstance(columns, list) or not columns:
            raise self.error("expected a list of column names", key + ("columns",))
        for i, name in enumerate(columns):
            if not isinstance(name, str) or name not in columns_map:
                raise self.error(f"unknown column {shown(name)} (known: {', '.join(columns_map)})",
                                 key + ("columns", i), shown(name, quoted=False))
        targets = [columns_map[name] for name in columns]
        if len(set(targets)) != len(targets):
            raise self.error("a quantity is given twice", key + ("columns",))
        for name in required:
            if name not in columns:
                raise self.error(f"required column '{name}' is missing", key + ("columns",))
        if not isinstance(rows, list) or len(rows) < 2:
            raise self.error("expected at least two rows", key + ("rows",))
        values = np.empty((len(rows), len(columns)))
        for i, row in enumerate(rows):
            if not isinstance(row, list) or len(row) != len(columns):
                count = len(row) if isinstance(row, list) else 1
                raise self.error(f"row has {count} values, expected {len(columns)} ({', '.join(columns)})",
                                 key + ("rows", i), "rows")
            for j, value in enumerate(row):
                if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                    raise self.error(f"expected a finite number, got {shown(value)}", key + ("rows", i, j),
                                     columns[j])
                if abs(value) > MAX_MAGNITUDE:
                    raise self.error(f"{value:g} is beyond any real blade or tower (|value| up to "
                                     f"{MAX_MAGNITUDE:g})", key + ("rows", i, j), columns[j])
                values[i, j] = value
        return {target: values[:, j] for j, target in enumerate(targets)} | {"_columns": np.array(columns)}


def _section_table(case: CaseFile, hub_radius: float, tip_radius: float | None, option: str | None) -> SectionTable:
    """The section table; span fractions scaled by ``tip_radius - hub_radius`` (the file's tip_radius_m when
    ``tip_radius`` is None). ``option``: the command-line option that changed the geometry, if any (errors name
    it instead of a line of the file)."""
    key: Key = ("sections",)
    given = case.table(key, {name: field for name, (field, _) in COLUMNS.items()}, REQUIRED_COLUMNS)
    columns = [str(name) for name in given.pop("_columns")]
    if "span" not in given:
        raise case.error("give one of span_m or span_fraction", key + ("columns",))
    table = {COLUMNS[name][0]: given[COLUMNS[name][0]] * COLUMNS[name][1] for name in columns}
    name = "span_fraction" if "span_fraction" in columns else "span_m"
    span, last = table["span"], key + ("rows", len(table["span"]) - 1, columns.index(name))
    if name == "span_fraction":
        if span[-1] != 1.0:
            raise case.error(f"the last span_fraction must be 1 (the tip), got {span[-1]}", last, name)
        tip = case.number(("tip_radius_m",), field="tip_radius_m") if tip_radius is None else tip_radius
        where = ("tip_radius_m",)
    else:
        if tip_radius is not None:
            raise InputError("the case's table gives span_m, which fixes the blade length: --tip-radius applies to "
                             "span_fraction tables (--hub-radius moves the root)", file=str(case.path),
                             field="--tip-radius")
        tip, where = hub_radius + float(span[-1]), last
        if case.get(("tip_radius_m",)) is not None and option is None:
            given = case.number(("tip_radius_m",))
            if abs(given - tip) > 1e-9 * max(tip, 1.0):
                raise case.error(f"tip_radius_m {given:g} contradicts hub_radius_m + the last span_m = {tip:.12g}: "
                                 "give one or make them agree", ("tip_radius_m",))
    problem = length_problem(hub_radius, tip)
    if name == "span_fraction":
        _raise(case, problem, where, option)
        table["span"] = span * (tip - hub_radius)
    lines = tuple(case.lines.get(key + ("rows", i), 0) for i in range(len(table["span"])))
    sections = SectionTable(**table, source=str(case.path), lines=lines)
    _raise(case, problem, where, option)
    return sections


def _raise(case: CaseFile, problem: str | None, key: Key, option: str | None) -> None:
    """Raise ``problem`` (if any) at ``key``, or naming the command-line ``option`` that caused it."""
    if problem and option:
        raise InputError(problem, file=str(case.path), field=option)
    if problem:
        raise case.error(problem, key)


def read_case(path: str | Path, tip_radius: float | None = None, hub_radius: float | None = None) -> Blade:
    """Read a bladefem YAML case file into a :class:`~bladefem.sections.Blade`. ``tip_radius`` and ``hub_radius``
    (m) replace the file's values (a span_m table fixes the length: the tip radius cannot then be changed)."""
    case = CaseFile.open(path, "blade", TOP_KEYS)
    path, data = case.path, case.data
    file_hub = case.number(("hub_radius_m",), 0.0)
    if file_hub < 0:
        raise case.error("must not be negative", ("hub_radius_m",))
    if hub_radius is not None and not (math.isfinite(hub_radius) and hub_radius >= 0):
        raise InputError(f"must be a non-negative number, got {hub_radius}", file=str(path), field="--hub-radius")
    hub_override = hub_radius is not None
    hub_radius = file_hub if hub_radius is None else hub_radius
    precone = math.radians(case.number(("precone_deg",), 0.0))
    problem = precone_problem(precone)
    if problem:
        raise case.error(problem, ("precone_deg",))
    pitch = math.radians(case.number(("pitch_deg",), 0.0))
    root = data.get("root", "cantilever")
    if root not in ROOTS:
        raise case.error(f"unknown root condition '{root}' (choose from {', '.join(ROOTS)})", ("root",))
    option = "--tip-radius" if tip_radius is not None else "--hub-radius" if hub_override else None
    sections = _section_table(case, hub_radius, tip_radius, option)
    tip_mass = None
    if data.get("tip_mass") is not None:
        tip = data["tip_mass"]
        if not isinstance(tip, dict):
            raise case.error("expected a mapping", ("tip_mass",))
        for key in tip:
            if key not in TIP_KEYS:
                raise case.error(f"unknown key (known: {', '.join(TIP_KEYS)})", ("tip_mass", key),
                                 shown(key, quoted=False))
        values = {TIP_KEYS[k]: case.number(("tip_mass", k), 0.0) for k in TIP_KEYS}
        for name, value in values.items():
            if value < 0 and "offset" not in name:
                raise case.error("must not be negative", ("tip_mass", next(k for k, v in TIP_KEYS.items()
                                                                              if v == name)))
        theta = float(sections.twist[-1]) + pitch
        tip_mass = tip_mass_at_section(theta=theta, **values)
        problem = body_problem(tip_mass.mass, tip_mass.offset, tip_mass.inertia, sections.length)
        if problem:
            raise case.error(problem, ("tip_mass",))
    notes = [str(note) for note in data.get("notes", []) or []]
    if sections.torsion_stiffness is None:
        notes.append("no torsion_stiffness column: torsion is rigid (the twist DOF is removed)")
    if sections.axial_stiffness is None:
        notes.append("no axial_stiffness column: the blade is inextensible (the axial DOF is removed)")
    check_section_values(sections)
    return Blade(sections=sections, hub_radius=hub_radius, precone=precone, pitch=pitch, tip_mass=tip_mass,
                 root=root, name=str(data.get("name", path.stem)),
                 notes=tuple(notes))
