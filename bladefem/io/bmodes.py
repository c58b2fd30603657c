"""BModes input: the ``.bmi`` main file and its section-property file, for blades and towers.

Two layouts of the main file are found in the wild, and both are read:

- ``v3.00`` (BModes v3.00, 2007): for a tower, ``tow_support = 1`` means *tension wires*, followed directly by the
  wire data (``n_attachments``, ``n_wires``, ``node_attach``, ``wire_stfness``, ``th_wire``);
- ``platform`` (later BModes): ``tow_support = 1`` means a *floating platform or monopile*, followed by a platform
  block (``draft``, ``cm_pform``, ``mass_pform``, the 3x3 ``i_matrix_pform``, ``ref_msl``, the 6x6 ``hydro_M``,
  ``hydro_K`` and ``mooring_K``, distributed added mass and stiffness) and then the tension-wire data.

The layout is detected from the content (a ``draft`` entry after ``tow_support``) and reported in
:attr:`BModesInput.layout`. Blade decks (``beam_type = 1``) have no support block (layout ``blade``).

Entries are read by key (BModes writes ``value  key:  description``); arrays and matrices by their labels. Angles
are stored in rad, the rotor speed in rpm as in the file (``rot_rpm`` times ``rpm_mult`` is the speed used).

``cm_axial`` is read as what its name and description say: the axial offset of the tip mass's centre of mass along
the beam axis. BModes v3.00 itself reads that line into its ``cm_loc`` variable (so the chordwise offset it uses is
the axial value and the axial offset is never used); bladefem reads ``cm_loc`` as the chordwise offset and
``cm_axial`` as the axial offset, so results differ from BModes' whenever either is non-zero.
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

#: Property multipliers: key -> meaning.
MULTIPLIERS = ("sec_mass_mult", "flp_iner_mult", "lag_iner_mult", "flp_stff_mult", "edge_stff_mult",
               "tor_stff_mult", "axial_stff_mult", "cg_offst_mult", "sc_offst_mult", "tc_offst_mult")
TIP_KEYS = ("tip_mass", "cm_loc", "cm_axial", "ixx_tip", "iyy_tip", "izz_tip", "ixy_tip", "izx_tip", "iyz_tip")
SECTION_COLUMNS = ("sec_loc", "str_tw", "tw_iner", "mass_den", "flp_iner", "edge_iner", "flp_stff", "edge_stff",
                   "tor_stff", "axial_stff", "cg_offst", "sc_offst", "tc_offst")
POSITIVE_COLUMNS = ("mass_den", "flp_stff", "edge_stff", "tor_stff", "axial_stff")
NON_NEGATIVE_COLUMNS = ("flp_iner", "edge_iner")
ANGLE_COLUMNS = ("str_tw", "tw_iner")


@dataclass(frozen=True)
class BModesSections:
    """A BModes section-property file; columns as in the file except angles (rad).

    columns : name -> values, for the 13 columns ``sec_loc`` .. ``tc_offst`` (``str_tw``, ``tw_iner`` in rad)
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
    """The platform/monopile block of the later layout (SI as in the file)."""

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

    def __eq__(self, other: object) -> bool:
        return isinstance(other, BModesPlatform) and all(
            np.array_equal(getattr(self, f), getattr(other, f)) for f in self.__dataclass_fields__)


@dataclass(frozen=True)
class BModesWires:
    """Tension wires: per attachment the number of wires, the node, the spring constant (N/m), the angle (rad)."""

    n_wires: tuple[int, ...]
    node_attach: tuple[int, ...]
    stiffness: tuple[float, ...]
    angle: tuple[float, ...]


@dataclass(frozen=True)
class BModesInput:
    """A BModes main file with its section properties.

    layout : 'blade', 'v3.00' (tow_support = 1 means tension wires) or 'platform' (the later layout)
    beam_type : 1 blade, 2 tower; rot_rpm, rpm_mult : rotor speed (rpm) and its multiplier
    radius : tip radius or tower height, m; hub_rad : hub radius or rigid tower-base height, m
    precone, pitch : rad (bl_thp); hub_conn : 1 cantilevered, 2 free-free, 3 axial and torsion held
    tip : tip_mass (kg), cm_loc, cm_axial (m), ixx_tip .. iyz_tip (kg m^2) as named in the file
    multipliers : the ten property multipliers
    el_loc : element boundaries, fraction of the flexible length (nselt + 1 values)
    tow_support : 0 none, 1 wires (v3.00) or platform (later layout); platform, wires : their data or None
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
        return self.rot_rpm * self.rpm_mult

    @property
    def length(self) -> float:
        """Flexible length, m."""
        return self.radius - self.hub_rad


# -- reading ------------------------------------------------------------------------------------------------------

def read_bmodes(path: str | os.PathLike) -> BModesInput:
    """Read a BModes main file and the section-property file it names (resolved against its folder)."""
    text = FastText.read(path)
    beam_type = text.int("beam_type")
    if beam_type not in (1, 2):
        raise text.error(f"must be 1 (blade) or 2 (tower), got {beam_type}", text.line_of("beam_type"), "beam_type")
    speed_key = "rot_rpm" if text.has("rot_rpm") or not text.has("romg") else "romg"
    mult_key = "rpm_mult" if text.has("rpm_mult") or not text.has("romg_mult") else "romg_mult"
    radius, hub_rad = text.float("radius"), text.float("hub_rad", non_negative=True)
    if not radius > hub_rad:
        raise text.error(f"must exceed hub_rad ({hub_rad}), got {radius}", text.line_of("radius"), "radius")
    hub_conn = text.int("hub_conn")
    if hub_conn not in (1, 2, 3):
        raise text.error(f"must be 1, 2 or 3, got {hub_conn}", text.line_of("hub_conn"), "hub_conn")
    nselt = text.int("nselt", minimum=1)
    sections_file = Path(os.path.normpath(Path(text.path).parent / text.string("sec_props_file").strip()))
    layout, tow_support, platform, wires = "blade", 0, None, None
    if beam_type == 2:
        layout, tow_support, platform, wires = _support(text, nselt)
    keys = ["beam_type", speed_key, mult_key, "radius", "hub_rad", "precone", "bl_thp", "hub_conn", "modepr",
            "id_mat", "sec_props_file", "nselt", "tow_support", "n_attachments", *TIP_KEYS, *MULTIPLIERS]
    return BModesInput(
        title=(_line(text, 2), _line(text, 3)),
        layout=layout,
        beam_type=beam_type,
        rot_rpm=text.float(speed_key, non_negative=True),
        rpm_mult=text.float(mult_key, non_negative=True),
        radius=radius,
        hub_rad=hub_rad,
        precone=math.radians(text.float("precone")),
        pitch=math.radians(text.float("bl_thp")),
        hub_conn=hub_conn,
        modepr=text.int("modepr", minimum=0),
        flags={key: text.bool(key) for key in ("Echo", "TabDelim", "mid_node_tw") if text.has(key)},
        tip={key: text.float(key, non_negative=key in ("tip_mass", "ixx_tip", "iyy_tip", "izz_tip"))
             for key in TIP_KEYS},
        id_mat=text.int("id_mat"),
        sec_props_file=sections_file,
        multipliers={key: text.float(key, non_negative=True) for key in MULTIPLIERS},
        el_loc=_el_loc(text, nselt),
        sections=read_bmodes_sections(sections_file, source=text, key="sec_props_file"),
        tow_support=tow_support,
        platform=platform,
        wires=wires,
        path=text.path,
        key_lines={key: text.line_of(key) for key in keys if text.has(key)},
    )


def _line(text: FastText, number: int) -> str:
    return text.lines[number - 1].rstrip("\r\n") if number <= len(text.lines) else ""


def _label_line(text: FastText, label: str, after: int = 0) -> int:
    """1-based number of the first line after ``after`` containing ``label`` (case-insensitive)."""
    for number in range(after + 1, len(text.lines) + 1):
        if label.lower() in text.lines[number - 1].lower():
            return number
    raise text.error(f"'{label}' not found", len(text.lines) or None, label)


def _numbers(text: FastText, first: int, count: int, name: str) -> tuple[NDArray, int]:
    """``count`` numbers from line ``first`` on (as many lines as needed, blank lines skipped, stopping at the
    first word that is not a number); (values, last line used)."""
    values: list[float] = []
    last = number = first - 1
    while len(values) < count and number < len(text.lines):
        number += 1
        words = text.lines[number - 1].split()
        if words and not _is_number(words[0]):
            break
        for word in words:
            if len(values) == count or not _is_number(word):
                break
            values.append(to_float(word, text.error, number, name))
            last = number
    if len(values) < count:
        raise text.error(f"expected {count} values, found {len(values)}", max(last, first), name)
    return np.array(values), last


def _values_before(text: FastText, key: str, count: int) -> tuple[NDArray, int]:
    """The first ``count`` numbers in front of ``key`` on its line (e.g. ``3 3  n_wires: ...``)."""
    for number, line in enumerate(text.lines, start=1):
        words = [w for w in line.split() if w != ":"]
        names = [w.rstrip(":") for w in words]
        if key not in names:
            continue
        position = names.index(key)
        if not all(_is_number(w) for w in words[:position]):
            continue
        if position < count:
            raise text.error(f"expected {count} values before the key, found {position}", number, key)
        return np.array([to_float(w, text.error, number, key) for w in words[:count]]), number
    raise text.error("missing key", len(text.lines) or None, key)


def _is_number(word: str) -> bool:
    try:
        float(word.replace("D", "E").replace("d", "e"))
    except ValueError:
        return False
    return True


def _el_loc(text: FastText, nselt: int) -> NDArray:
    label = _label_line(text, "el_loc", after=text.line_of("nselt"))
    values, _ = _numbers(text, label + 1, nselt + 1, "el_loc")
    if values[0] != 0.0 or values[-1] != 1.0 or np.any(np.diff(values) <= 0):
        raise text.error("el_loc must increase strictly from 0 to 1", label + 1, "el_loc")
    return values


def _matrix(text: FastText, label: str, size: int, after: int) -> tuple[NDArray, int]:
    line = _label_line(text, label, after)
    values, last = _numbers(text, line + 1, size * size, label)
    return values.reshape(size, size), last


def _support(text: FastText, nselt: int) -> tuple[str, int, BModesPlatform | None, BModesWires | None]:
    """Layout, tow_support and the support data of a tower deck."""
    tow_support = text.int("tow_support") if text.has("tow_support") else 0
    if tow_support not in (0, 1):
        raise text.error(f"must be 0 or 1, got {tow_support}", text.line_of("tow_support"), "tow_support")
    later = text.has("draft")
    layout = "platform" if later else "v3.00"
    platform = _platform(text) if later and tow_support == 1 else None
    wires = None
    if text.has("n_attachments") and (tow_support == 1 or later):
        attachments = text.int("n_attachments", minimum=0)
        if attachments > 0:
            wires = _wires(text, attachments, nselt)
    return layout, tow_support, platform, wires


def _platform(text: FastText) -> BModesPlatform:
    start = text.line_of("tow_support")
    inertia, last = _matrix(text, "i_matrix_pform", 3, start)
    hydro_m, last = _matrix(text, "hydro_M", 6, last)
    hydro_k, last = _matrix(text, "hydro_K", 6, last)
    mooring_k, last = _matrix(text, "mooring_K", 6, last)
    n_mass = text.int("n_secs_m_distr", minimum=0)
    z_m, _ = _values_before(text, "z_distr_m", max(n_mass, 1))
    m, _ = _values_before(text, "distr_m", max(n_mass, 1))
    n_k = text.int("n_secs_k_distr", minimum=0)
    z_k, _ = _values_before(text, "z_distr_k", max(n_k, 1))
    k, _ = _values_before(text, "distr_k", max(n_k, 1))
    return BModesPlatform(
        draft=text.float("draft"), cm_pform=text.float("cm_pform"), mass_pform=text.float("mass_pform",
                                                                                            non_negative=True),
        i_matrix_pform=inertia, ref_msl=text.float("ref_msl"), hydro_M=hydro_m, hydro_K=hydro_k, mooring_K=mooring_k,
        added_mass_z=z_m[:n_mass], added_mass=m[:n_mass], distributed_stiffness_z=z_k[:n_k],
        distributed_stiffness=k[:n_k])


def _wires(text: FastText, attachments: int, nselt: int) -> BModesWires:
    counts, line = _values_before(text, "n_wires", attachments)
    nodes, node_line = _values_before(text, "node_attach", attachments)
    stiffness, _ = _values_before(text, "wire_stfness", attachments)
    angles, _ = _values_before(text, "th_wire", attachments)
    if np.any(counts < 3):
        raise text.error("at least 3 wires per attachment", line, "n_wires")
    if np.any(nodes < 2) or np.any(nodes > nselt + 1):
        raise text.error(f"attachment nodes must lie in 2..{nselt + 1}", node_line, "node_attach")
    return BModesWires(tuple(int(c) for c in counts), tuple(int(n) for n in nodes),
                       tuple(float(s) for s in stiffness), tuple(math.radians(a) for a in angles))


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
    for name in SECTION_COLUMNS:
        if name not in names:
            raise text.error(f"table header lacks column '{name}'", header, name)
    first = header + 1
    if first <= len(text.lines) and text.lines[first - 1].lstrip().startswith("("):
        first += 1
    rows = text.table(first, count, names)
    lines = tuple(range(first, first + count))
    columns = {name: np.array([row[names.index(name)] for row in rows]) for name in SECTION_COLUMNS}
    _check_sections(text, columns, lines)
    for name in ANGLE_COLUMNS:
        columns[name] = np.array([math.radians(v) for v in columns[name]])
    return BModesSections(title=_line(text, 1), columns=columns, path=text.path, station_lines=lines)


def _check_sections(text: FastText, columns: dict[str, NDArray], lines: tuple[int, ...]) -> None:
    x = columns["sec_loc"]
    if x[0] != 0.0 or x[-1] != 1.0:
        bad = 0 if x[0] != 0.0 else len(x) - 1
        raise text.error(f"sec_loc must run from 0 to 1, got {x[bad]}", lines[bad], "sec_loc")
    steps = np.flatnonzero(np.diff(x) <= 0)
    if steps.size:
        raise text.error("sec_loc must increase strictly", lines[int(steps[0]) + 1], "sec_loc")
    for name in POSITIVE_COLUMNS:
        bad = np.flatnonzero(columns[name] <= 0)
        if bad.size:
            raise text.error(f"must be positive, got {columns[name][bad[0]]}", lines[int(bad[0])], name)
    for name in NON_NEGATIVE_COLUMNS:
        bad = np.flatnonzero(columns[name] < 0)
        if bad.size:
            raise text.error(f"must not be negative, got {columns[name][bad[0]]}", lines[int(bad[0])], name)

