"""BModes input: the ``.bmi`` main file and its section-property file, for blades and towers.

Every field is read with the meaning BModes gives it (Bir, *User's Guide to BModes*, NREL/TP-500-39133, and the
BModes v3.00 source); docs/formats.md tables each field and what bladefem does with it. Three layouts of a tower
deck's support block are found in the wild, and all are read (:attr:`BModesInput.layout`):

- ``v3.00`` (BModes v3.00 as released with its CertTest): ``tow_support = 1`` means *tension wires*, followed by
  ``n_attachments``, ``n_wires``, ``node_attach``, ``wire_stfness``, ``th_wire``;
- ``platform`` (later BModes, e.g. its OC3 Hywind example, and pybmodes' decks): ``tow_support = 1`` is followed by a
  platform block (``draft``, ``cm_pform``, ``mass_pform``, the 3x3 ``i_matrix_pform``, ``ref_msl``, the 6x6
  ``hydro_M``, ``hydro_K``, ``mooring_K``, distributed added mass and stiffness) and then the tension-wire data;
- ``offshore`` (the offshore branch of the BModes v3 source): ``tow_support = 2`` is followed by the platform block
  alone.

The layout is found from the content (a number on the line after ``tow_support``). Blade decks (``beam_type = 1``)
have no support block (layout ``blade``). Entries are read by key (BModes writes ``value  key:  description``), arrays
and matrices from the lines after their labels; every table row and matrix row must hold exactly the values its
layout says (a stray value would shift the columns), optionally followed by a comment. Angles are stored in rad, the
rotor speed in rpm as in the file (``rot_rpm`` times ``rpm_mult`` is the speed BModes uses).

pybmodes' documented extensions are read too: ``hub_conn = 4`` (pinned-free), ``cm_pform`` and ``ref_msl`` lines
with a horizontal offset (``cm_pform x y`` or ``cm_pform_xyz``), and a ``sec_loc`` given twice (a property step).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ._fast_format import FastText, to_float

#: Property multipliers, in file order.
MULTIPLIERS = ("sec_mass_mult", "flp_iner_mult", "lag_iner_mult", "flp_stff_mult", "edge_stff_mult",
               "tor_stff_mult", "axial_stff_mult", "cg_offst_mult", "sc_offst_mult", "tc_offst_mult")
TIP_KEYS = ("tip_mass", "cm_loc", "cm_axial", "ixx_tip", "iyy_tip", "izz_tip", "ixy_tip", "izx_tip", "iyz_tip")
SECTION_COLUMNS = ("sec_loc", "str_tw", "tw_iner", "mass_den", "flp_iner", "edge_iner", "flp_stff", "edge_stff",
                   "tor_stff", "axial_stff", "cg_offst", "sc_offst", "tc_offst")
POSITIVE_COLUMNS = ("mass_den", "flp_stff", "edge_stff", "tor_stff", "axial_stff")
NON_NEGATIVE_COLUMNS = ("flp_iner", "edge_iner")
ANGLE_COLUMNS = ("str_tw", "tw_iner")
#: hub_conn: root (blade) or base (tower) condition; 4 is pybmodes' extension
HUB_CONN = {1: "cantilevered", 2: "free-free", 3: "axial and torsion held", 4: "pinned-free"}
#: the older key names of BModes' first decks (CertTest 02-04)
ALIASES = {"rot_rpm": "romg", "rpm_mult": "romg_mult"}


@dataclass(frozen=True)
class BModesSections:
    """A BModes section-property file; columns as in the file except angles (rad).

    columns : name -> values, for the 13 columns ``sec_loc`` .. ``tc_offst`` (``str_tw``, ``tw_iner`` in rad);
        ``sec_loc`` increases, an interior value given twice marking a property step
    """

    title: str
    columns: dict[str, NDArray[np.float64]]
    path: str = field(default="", compare=False)
    station_lines: tuple[int, ...] = field(default=(), compare=False)

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, BModesSections) and self.title == other.title
                and self.columns.keys() == other.columns.keys()
                and all(np.array_equal(self.columns[k], other.columns[k]) for k in self.columns))


@dataclass(frozen=True)
class BModesPlatform:
    """The platform (or monopile) block: SI as in the file, 6x6 matrices in OpenFAST order (surge .. yaw).

    draft : depth of the tower base below mean sea level, m (negative: above)
    cm_pform : depth of the platform's centre of mass below mean sea level, m
    cm_pform_xy : its horizontal offset from the tower axis (x downwind, y lateral), m (pybmodes' extension)
    mass_pform : platform mass, kg; i_matrix_pform : 3x3 inertia about its centre of mass, kg m^2
    ref_msl : depth of the reference point of hydro_M, hydro_K, mooring_K below mean sea level, m
    ref_msl_xy : its horizontal offset from the tower axis, m (pybmodes' extension)
    hydro_M : added mass; hydro_K : hydrostatic stiffness; mooring_K : mooring stiffness (about the reference point)
    added_mass_z, added_mass : distributed added mass per length (kg/m) at heights above the flexible base (m)
    distributed_stiffness_z, distributed_stiffness : distributed lateral stiffness per length (N/m^2), same heights
    """

    draft: float
    cm_pform: float
    mass_pform: float
    i_matrix_pform: NDArray[np.float64]
    ref_msl: float
    hydro_M: NDArray[np.float64]
    hydro_K: NDArray[np.float64]
    mooring_K: NDArray[np.float64]
    added_mass_z: NDArray[np.float64]
    added_mass: NDArray[np.float64]
    distributed_stiffness_z: NDArray[np.float64]
    distributed_stiffness: NDArray[np.float64]
    cm_pform_xy: tuple[float, float] = (0.0, 0.0)
    ref_msl_xy: tuple[float, float] = (0.0, 0.0)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, BModesPlatform) and all(
            np.array_equal(getattr(self, f), getattr(other, f)) for f in self.__dataclass_fields__)


@dataclass(frozen=True)
class BModesWires:
    """Tension wires: per attachment the number of wires, the node (1 = the flexible base), the spring constant
    ``wire_stfness`` (N/m) and the angle ``th_wire`` (rad, from the horizontal ground plane)."""

    n_wires: tuple[int, ...]
    node_attach: tuple[int, ...]
    stiffness: tuple[float, ...]
    angle: tuple[float, ...]


@dataclass(frozen=True)
class BModesInput:
    """A BModes main file with its section properties.

    layout : 'blade', 'v3.00', 'platform' or 'offshore' (see the module docstring)
    beam_type : 1 blade, 2 tower; rot_rpm, rpm_mult : rotor speed (rpm) and its multiplier
    radius : tip radius, or tower height above ground or mean sea level, m; hub_rad : hub radius, or height of the
        tower's rigid base, m
    precone, pitch : rad (bl_thp); hub_conn : 1 cantilevered, 2 free-free, 3 axial and torsion held, 4 pinned-free
    modepr : number of modes BModes prints
    tip : tip_mass (kg), cm_loc, cm_axial (m), ixx_tip .. iyz_tip (kg m^2) as in the file
    multipliers : the ten property multipliers
    el_loc : element boundaries, fraction of the flexible length (nselt + 1 values)
    tow_support : 0 none, 1 wires (v3.00) or platform (later layout), 2 platform; platform, wires : data or None
    """

    title: tuple[str, str]
    layout: str
    beam_type: int
    rot_rpm: float
    rpm_mult: float
    radius: float
    hub_rad: float
    precone: float
    pitch: float
    hub_conn: int
    modepr: int
    flags: dict[str, bool]
    tip: dict[str, float]
    id_mat: int
    sec_props_file: Path
    multipliers: dict[str, float]
    el_loc: NDArray[np.float64]
    sections: BModesSections
    tow_support: int = 0
    platform: BModesPlatform | None = None
    wires: BModesWires | None = None
    path: str = field(default="", compare=False)
    key_lines: dict[str, int] = field(default_factory=dict, compare=False)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, BModesInput):
            return NotImplemented
        names = [f for f in self.__dataclass_fields__ if f not in ("path", "key_lines", "el_loc")]
        return all(getattr(self, f) == getattr(other, f) for f in names) and np.array_equal(self.el_loc,
                                                                                          other.el_loc)

    @property
    def rotor_speed_rpm(self) -> float:
        """The rotor speed BModes uses, rpm: ``rot_rpm * rpm_mult`` for a blade, 0 for a tower."""
        return self.rot_rpm * self.rpm_mult if self.beam_type == 1 else 0.0

    @property
    def draft(self) -> float:
        """Depth of the tower base below mean sea level, m (0 without a platform block)."""
        return self.platform.draft if self.platform is not None else 0.0

    @property
    def length(self) -> float:
        """Flexible length, m: ``radius + draft - hub_rad``."""
        return self.radius + self.draft - self.hub_rad

    def error(self, message: str, key: str) -> InputError:
        """An :class:`InputError` at the line of ``key`` in this deck."""
        return InputError(message, file=self.path or None, line=self.key_lines.get(key), field=key)


# -- reading ------------------------------------------------------------------------------------------------------

def read_bmodes(path: str | os.PathLike) -> BModesInput:
    """Read a BModes main file and the section-property file it names (resolved against its folder)."""
    from .bmodes_support import read_support

    text = FastText.read(path)
    _one_value_each(text, ("beam_type", "radius", "hub_rad", "precone", "bl_thp", "hub_conn", "modepr", "id_mat",
                           "nselt", *TIP_KEYS, *MULTIPLIERS))
    beam_type = text.int("beam_type")
    if beam_type not in (1, 2):
        raise text.error(f"must be 1 (blade) or 2 (tower), got {beam_type}", text.line_of("beam_type"), "beam_type")
    speed_key, mult_key = (_key(text, name) for name in ("rot_rpm", "rpm_mult"))
    rot_rpm, rpm_mult = text.float(speed_key, non_negative=True), text.float(mult_key, non_negative=True)
    radius, hub_rad = text.float("radius", positive=True), text.float("hub_rad", non_negative=True)
    hub_conn = text.int("hub_conn")
    if hub_conn not in HUB_CONN:
        raise text.error(f"must be 1 (cantilevered), 2 (free-free), 3 (axial and torsion held) or 4 (pinned-free), "
                         f"got {hub_conn}", text.line_of("hub_conn"), "hub_conn")
    id_mat = text.int("id_mat")
    if id_mat != 1:
        raise text.error(f"must be 1 (isotropic; BModes has no other material type), got {id_mat}",
                         text.line_of("id_mat"), "id_mat")
    nselt = text.int("nselt", minimum=1)
    sections_file = Path(os.path.normpath(Path(text.path).parent / text.string("sec_props_file").strip()))
    support = read_support(text, nselt) if beam_type == 2 else None
    draft = support.platform.draft if support is not None and support.platform is not None else 0.0
    if not radius + draft > hub_rad:
        raise text.error(f"the flexible length radius + draft - hub_rad must be positive, got {radius} + {draft} - "
                         f"{hub_rad}", text.line_of("radius"), "radius")
    keys = ["beam_type", speed_key, mult_key, "radius", "hub_rad", "precone", "bl_thp", "hub_conn", "modepr",
            "id_mat", "sec_props_file", "nselt", *TIP_KEYS, *MULTIPLIERS]
    key_lines = {key: text.line_of(key) for key in keys if text.has(key)}
    key_lines.update({"rot_rpm": text.line_of(speed_key), "rpm_mult": text.line_of(mult_key)})
    if support is not None:
        key_lines.update(support.key_lines)
    return BModesInput(
        title=(_line(text, 2), _line(text, 3)),
        layout="blade" if support is None else support.layout,
        beam_type=beam_type,
        rot_rpm=rot_rpm,
        rpm_mult=rpm_mult,
        radius=radius,
        hub_rad=hub_rad,
        precone=math.radians(text.float("precone")),
        pitch=math.radians(text.float("bl_thp")),
        hub_conn=hub_conn,
        modepr=text.int("modepr", minimum=1),
        flags={key: text.bool(key) for key in ("Echo", "TabDelim", "mid_node_tw") if text.has(key)},
        tip={key: text.float(key, non_negative=key in ("tip_mass", "ixx_tip", "iyy_tip", "izz_tip"))
             for key in TIP_KEYS},
        id_mat=id_mat,
        sec_props_file=sections_file,
        multipliers={key: text.float(key, non_negative=True) for key in MULTIPLIERS},
        el_loc=_el_loc(text, nselt),
        sections=read_bmodes_sections(sections_file, source=text, key="sec_props_file"),
        tow_support=0 if support is None else support.tow_support,
        platform=None if support is None else support.platform,
        wires=None if support is None else support.wires,
        path=text.path,
        key_lines=key_lines,
    )


def _one_value_each(text: FastText, keys: tuple[str, ...]) -> None:
    """A key written after several values (``60.0 99  rot_rpm``) is an error at its line, not a missing key."""
    for key in keys:
        if text.has(key):
            continue
        for number, line in enumerate(text.lines, start=1):
            words = [word.rstrip(":") for word in line.split()]
            if key in words[1:] and all(is_number(word) for word in words[:words.index(key)]):
                raise text.error(f"expected one value before the key, found {words.index(key)}", number, key)


def _key(text: FastText, name: str) -> str:
    """``name``, or its older alias where the deck uses that (``romg`` for ``rot_rpm``)."""
    return ALIASES[name] if not text.has(name) and text.has(ALIASES[name]) else name


def _line(text: FastText, number: int) -> str:
    return text.lines[number - 1].rstrip("\r\n") if number <= len(text.lines) else ""


def label_line(text: FastText, label: str, after: int = 0) -> int:
    """1-based number of the first line after ``after`` containing ``label`` (case-insensitive)."""
    for number in range(after + 1, len(text.lines) + 1):
        if label.lower() in text.lines[number - 1].lower():
            return number
    raise text.error(f"'{label}' not found", len(text.lines) or None, label)


def is_number(word: str) -> bool:
    try:
        value = float(word.replace("D", "E").replace("d", "e"))
    except ValueError:
        return False
    return math.isfinite(value) or word.lower().lstrip("+-") in ("nan", "inf", "infinity")


def leading_numbers(text: FastText, number: int, name: str) -> list[float]:
    """The numbers at the start of line ``number`` (up to the first word that is not a number)."""
    values = []
    for word in text.lines[number - 1].split():
        if not is_number(word):
            break
        values.append(to_float(word, text.error, number, name))
    return values


def row(text: FastText, number: int, names: tuple[str, ...] | int, name: str = "") -> NDArray[np.float64]:
    """Exactly one number per column of ``names`` (or ``names`` numbers, the field called ``name``) at the start of
    line ``number``; a comment may follow. Too few values name the first missing column; too many are an error (a
    stray value would shift the columns)."""
    count = names if isinstance(names, int) else len(names)
    if number > len(text.lines):
        raise text.error(f"expected a row of {count} values, found the end of the file", number - 1,
                         name or names[0])
    values = leading_numbers(text, number, name or "table row")
    if len(values) != count:
        missing = not isinstance(names, int) and len(values) < count
        raise text.error(f"expected {count} values on this line, found {len(values)}"
                         + ("" if len(values) < count else " (a stray value shifts the columns)"), number,
                         names[len(values)] if missing else (name or "table row"))
    return np.array(values)


def _el_loc(text: FastText, nselt: int) -> NDArray:
    """``nselt + 1`` element boundaries from the lines after the ``el_loc`` label (one line or several)."""
    label = label_line(text, "el_loc", after=text.line_of("nselt"))
    values: list[float] = []
    number = last = label
    while len(values) < nselt + 1 and number < len(text.lines):
        number += 1
        found = leading_numbers(text, number, "el_loc")
        if not found:
            break
        values, last = values + found, number
    if len(values) != nselt + 1:
        raise text.error(f"expected nselt + 1 = {nselt + 1} values, found {len(values)}", max(last, label + 1),
                         "el_loc")
    el_loc = np.array(values)
    if el_loc[0] != 0.0 or el_loc[-1] != 1.0 or np.any(np.diff(el_loc) <= 0):
        raise text.error("el_loc must increase strictly from 0 to 1", label + 1, "el_loc")
    return el_loc


def read_bmodes_sections(path: str | os.PathLike, source: FastText | None = None,
                         key: str = "") -> BModesSections:
    """Read a BModes section-property file. A missing file is reported at the main file's ``key`` line."""
    try:
        text = FastText.read(path)
    except InputError as error:
        if source is None:
            raise
        raise source.error(f"section-property file: {error.message}", source.line_of(key), key) from None
    count = text.int("n_secs", minimum=2)
    header = text.header_line("sec_loc", after=text.line_of("n_secs"))
    names = tuple(text.lines[header - 1].split())
    if set(SECTION_COLUMNS) <= set(names) and names[:len(SECTION_COLUMNS)] != SECTION_COLUMNS:
        raise text.error(f"columns out of order: BModes reads them by position as {' '.join(SECTION_COLUMNS)}",
                         header, "sec_loc")
    first = header + 1
    if first <= len(text.lines) and text.lines[first - 1].lstrip().startswith("("):
        first += 1
    table = np.array([row(text, number, SECTION_COLUMNS) for number in range(first, first + count)])
    lines = tuple(range(first, first + count))            # each read: a count beyond the file failed above
    columns = {name: table[:, i].copy() for i, name in enumerate(SECTION_COLUMNS)}
    _check_sections(text, columns, lines)
    for name in ANGLE_COLUMNS:
        columns[name] = np.array([math.radians(v) for v in columns[name]])
    return BModesSections(title=_line(text, 1), columns=columns, path=text.path, station_lines=lines)


def _check_sections(text: FastText, columns: dict[str, NDArray], lines: tuple[int, ...]) -> None:
    x = columns["sec_loc"]
    if x[0] != 0.0 or x[-1] != 1.0:
        bad = 0 if x[0] != 0.0 else len(x) - 1
        raise text.error(f"sec_loc must run from 0 to 1, got {x[bad]}", lines[bad], "sec_loc")
    gaps = np.diff(x)
    bad = gaps < 0
    bad[0] |= gaps[0] == 0
    bad[-1] |= gaps[-1] == 0
    bad[1:] |= (gaps[1:] == 0) & (gaps[:-1] == 0)
    if np.any(bad):
        raise text.error("sec_loc must increase (an interior value may be given twice for a property step)",
                         lines[int(np.flatnonzero(bad)[0]) + 1], "sec_loc")
    for name in POSITIVE_COLUMNS:
        bad_value = np.flatnonzero(columns[name] <= 0)
        if bad_value.size:
            raise text.error(f"must be positive, got {columns[name][bad_value[0]]}", lines[int(bad_value[0])], name)
    for name in NON_NEGATIVE_COLUMNS:
        bad_value = np.flatnonzero(columns[name] < 0)
        if bad_value.size:
            raise text.error(f"must not be negative, got {columns[name][bad_value[0]]}", lines[int(bad_value[0])],
                             name)
