"""ElastoDyn blade input file: distributed properties, adjustment factors, mode-shape coefficients.

Layout (OpenFAST ElastoDyn v1.00): ``NBlInpSt``, damping ``BldFlDmp(1..2)``, ``BldEdDmp(1)`` (percent of
critical), tuners ``FlStTunr(1..2)``, factors ``AdjBlMs``, ``AdjFlSt``, ``AdjEdSt``, a table with the columns
``BlFract [PitchAxis] StrcTwst BMassDen FlpStff EdgStff`` (PitchAxis is absent in later ElastoDyn versions; the
columns are found by their header names), and the blocks ``BldFl1Sh``, ``BldFl2Sh``, ``BldEdgSh``.

ElastoDyn blade files carry no torsional or axial stiffness and no section inertias or offsets: a blade built
from one is rigid in torsion and extension (those DOFs are removed from the FE model) and its mass is lumped on the
pitch axis. ``PitchAxis`` (chordwise position of the pitch axis, fraction of chord from the leading edge) has no
structural role in ElastoDyn and is kept for reference only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..files import write_atomic
from ..sections import Blade, SectionTable, TipMass
from ..formats._fast_format import FastText, degrees_exact, format_number
from ..formats._modeshape_blocks import block_lines, block_values, read_block
from ..sections.checks import check_section_values
from ..formats.elastodyn_main import read_elastodyn_main

#: Mode name -> ElastoDyn block prefix.
BLADE_BLOCKS = {"flap1": "BldFl1Sh", "flap2": "BldFl2Sh", "edge1": "BldEdgSh"}
REQUIRED_COLUMNS = ("BlFract", "StrcTwst", "BMassDen", "FlpStff", "EdgStff")
POSITIVE_COLUMNS = ("BMassDen", "FlpStff", "EdgStff")


@dataclass(frozen=True)
class ElastoDynBladeFile:
    """The contents of an ElastoDyn blade file (values as in the file, angles in rad).

    fraction : BlFract, span fraction from the root (0) to the tip (1)
    pitch_axis : PitchAxis, chordwise fraction from the leading edge, or None when the column is absent
    twist : StrcTwst, structural twist, rad
    mass : BMassDen, mass per length before AdjBlMs, kg/m
    flap_stiffness, edge_stiffness : FlpStff, EdgStff before AdjFlSt/AdjEdSt, N m^2
    adj_mass, adj_flap_stiffness, adj_edge_stiffness : AdjBlMs, AdjFlSt, AdjEdSt
    flap_tuners : FlStTunr(1), FlStTunr(2)
    flap_damping_percent : BldFlDmp(1), BldFlDmp(2), percent of critical
    edge_damping_percent : BldEdDmp(1), percent of critical
    modes : 'flap1', 'flap2', 'edge1' -> coefficients of x^2 .. x^6
    title : the file's second line
    station_lines : 1-based line number of each table row
    key_lines : 1-based line number of each key read
    """

    fraction: NDArray[np.float64]
    pitch_axis: NDArray[np.float64] | None
    twist: NDArray[np.float64]
    mass: NDArray[np.float64]
    flap_stiffness: NDArray[np.float64]
    edge_stiffness: NDArray[np.float64]
    adj_mass: float = 1.0
    adj_flap_stiffness: float = 1.0
    adj_edge_stiffness: float = 1.0
    flap_tuners: tuple[float, float] = (1.0, 1.0)
    flap_damping_percent: tuple[float, float] = (0.0, 0.0)
    edge_damping_percent: float = 0.0
    modes: dict[str, NDArray[np.float64]] = field(default_factory=dict)
    title: str = ""
    path: str = field(default="", compare=False)
    station_lines: tuple[int, ...] = field(default=(), compare=False)
    key_lines: dict[str, int] = field(default_factory=dict, compare=False)

    @property
    def stations(self) -> int:
        return len(self.fraction)


def read_elastodyn_blade(path: str | Path) -> ElastoDynBladeFile:
    """Read an ElastoDyn blade file; every malformed value is an :class:`InputError` naming file, line, field."""
    text = FastText.read(path)
    stations = text.int("NBlInpSt", minimum=2)
    columns, first_row = _table_layout(text)
    rows = text.table(first_row, stations, columns, exact=True)
    table = {name: np.array([row[i] for row in rows]) for i, name in enumerate(columns)}
    station_lines = tuple(range(first_row, first_row + stations))
    _check_stations(text, table, station_lines)
    keys = ("NBlInpSt", "BldFlDmp(1)", "BldFlDmp(2)", "BldEdDmp(1)", "FlStTunr(1)", "FlStTunr(2)", "AdjBlMs",
            "AdjFlSt", "AdjEdSt")
    return ElastoDynBladeFile(
        fraction=table["BlFract"],
        pitch_axis=table.get("PitchAxis"),
        twist=np.array([math.radians(t) for t in table["StrcTwst"]]),
        mass=table["BMassDen"],
        flap_stiffness=table["FlpStff"],
        edge_stiffness=table["EdgStff"],
        adj_mass=text.float("AdjBlMs", positive=True),
        adj_flap_stiffness=text.float("AdjFlSt", positive=True),
        adj_edge_stiffness=text.float("AdjEdSt", positive=True),
        flap_tuners=(text.float("FlStTunr(1)", positive=True), text.float("FlStTunr(2)", positive=True)),
        flap_damping_percent=(text.float("BldFlDmp(1)", non_negative=True),
                              text.float("BldFlDmp(2)", non_negative=True)),
        edge_damping_percent=text.float("BldEdDmp(1)", non_negative=True),
        modes={name: read_block(text, prefix) for name, prefix in BLADE_BLOCKS.items()},
        title=text.lines[1].strip() if len(text.lines) > 1 else "",
        path=text.path,
        station_lines=station_lines,
        key_lines={key: text.line_of(key) for key in keys + tuple(
            f"{prefix}({p})" for prefix in BLADE_BLOCKS.values() for p in range(2, 7))},
    )


def _table_layout(text: FastText) -> tuple[tuple[str, ...], int]:
    """Column names of the distributed-properties table (as in its header) and the line of its first row."""
    header = text.header_line("BlFract", after=text.line_of("NBlInpSt"))
    columns = tuple(text.lines[header - 1].split())
    for name in REQUIRED_COLUMNS:
        if name not in columns:
            raise text.error(f"table header lacks column '{name}' (found {' '.join(columns)})", header, name)
    first_row = header + 1
    if first_row <= len(text.lines) and text.lines[first_row - 1].lstrip().startswith("("):
        first_row += 1
    return columns, first_row


def _check_stations(text: FastText, table: dict[str, NDArray], lines: tuple[int, ...],
                    fraction: str = "BlFract", positive: tuple[str, ...] = POSITIVE_COLUMNS) -> None:
    """Span fractions from 0 to 1, strictly increasing; masses and stiffnesses positive."""
    x = table[fraction]
    if x[0] != 0.0:
        raise text.error(f"first station must be at 0, got {x[0]}", lines[0], fraction)
    if x[-1] != 1.0:
        raise text.error(f"last station must be at 1, got {x[-1]}", lines[-1], fraction)
    steps = np.flatnonzero(np.diff(x) <= 0)
    if steps.size:
        i = int(steps[0]) + 1
        raise text.error(f"stations must increase strictly ({x[i - 1]} then {x[i]})", lines[i], fraction)
    for name in positive:
        bad = np.flatnonzero(table[name] <= 0)
        if bad.size:
            raise text.error(f"must be positive, got {table[name][bad[0]]}", lines[int(bad[0])], name)


# -- building a Blade --------------------------------------------------------------------------------------------

def blade_from_elastodyn(blade_file: ElastoDynBladeFile, *, tip_radius: float, hub_radius: float,
                         precone: float = 0.0, pitch: float = 0.0, tip_mass: float = 0.0) -> Blade:
    """A :class:`Blade` from an ElastoDyn blade file and the rotor geometry of the main file.

    tip_radius, hub_radius : TipRad and HubRad, m (the flexible length is their difference)
    precone, pitch : rad
    tip_mass : TipMass (tip-brake mass), kg, a point mass on the pitch axis at the tip
    """
    length = tip_radius - hub_radius
    if not (math.isfinite(length) and length > 0):
        raise InputError(f"TipRad ({tip_radius}) must exceed HubRad ({hub_radius})", file=blade_file.path or None,
                         field="TipRad")
    f = blade_file
    sections = SectionTable(
        span=f.fraction * length,
        mass=f.mass * f.adj_mass,
        flap_stiffness=f.flap_stiffness * f.adj_flap_stiffness,
        edge_stiffness=f.edge_stiffness * f.adj_edge_stiffness,
        twist=f.twist,
        pitch_axis=f.pitch_axis,
        source=f.path,
        lines=f.station_lines or None,
    )
    check_section_values(sections)
    notes = (
        f"ElastoDyn blade file {Path(f.path).name if f.path else ''}: AdjBlMs = {f.adj_mass:g} applied to the mass, "
        f"AdjFlSt = {f.adj_flap_stiffness:g} and AdjEdSt = {f.adj_edge_stiffness:g} to the flap and edge stiffness",
        "torsion and axial motion are rigid (ElastoDyn blade files carry no GJ or EA); section inertias and offsets "
        "are zero (not in the file)",
    )
    if any(t != 1.0 for t in f.flap_tuners):
        notes += (f"FlStTunr = {f.flap_tuners} (ElastoDyn's modal stiffness tuners) are not applied to the FE model",)
    return Blade(sections=sections, hub_radius=hub_radius, precone=precone, pitch=pitch,
                 tip_mass=TipMass(tip_mass) if tip_mass > 0 else None,
                 name=Path(f.path).stem if f.path else "elastodyn blade", notes=notes)


def blade_from_elastodyn_main(main_path: str | Path, pitch: float = 0.0) -> Blade:
    """A :class:`Blade` from an ElastoDyn main file: BldFile(1), TipRad, HubRad, PreCone(1), TipMass(1).
    ``pitch`` in rad."""
    main = read_elastodyn_main(main_path)
    blade = blade_from_elastodyn(read_elastodyn_blade(main.blade_files[0]), tip_radius=main.tip_radius,
                                 hub_radius=main.hub_radius, precone=main.precone[0], pitch=pitch,
                                 tip_mass=main.tip_mass[0])
    return blade.with_(notes=blade.notes + (f"geometry from ElastoDyn main file {Path(main_path).name}",))


# -- writing ----------------------------------------------------------------------------------------------------

def elastodyn_blade_text(blade_file: ElastoDynBladeFile) -> str:
    """A complete ElastoDyn blade file (v1.00 layout; the PitchAxis column only when the data has one)."""
    f = blade_file

    def key(value: float, name: str, description: str) -> str:
        return f"{format_number(value):>24}   {name} - {description}\n"

    out = ["------- ELASTODYN V1.00.* INDIVIDUAL BLADE INPUT FILE --------------------------\n",
           f"{f.title or 'Written by bladefem'}\n",
           "---------------------- BLADE PARAMETERS ----------------------------------------\n",
           f"{f.stations:>24}   NBlInpSt    - Number of blade input stations (-)\n",
           key(f.flap_damping_percent[0], "BldFlDmp(1)", "Blade flap mode #1 structural damping, % of critical"),
           key(f.flap_damping_percent[1], "BldFlDmp(2)", "Blade flap mode #2 structural damping, % of critical"),
           key(f.edge_damping_percent, "BldEdDmp(1)", "Blade edge mode #1 structural damping, % of critical"),
           "---------------------- BLADE ADJUSTMENT FACTORS --------------------------------\n",
           key(f.flap_tuners[0], "FlStTunr(1)", "Blade flapwise modal stiffness tuner, 1st mode (-)"),
           key(f.flap_tuners[1], "FlStTunr(2)", "Blade flapwise modal stiffness tuner, 2nd mode (-)"),
           key(f.adj_mass, "AdjBlMs", "Factor to adjust blade mass density (-)"),
           key(f.adj_flap_stiffness, "AdjFlSt", "Factor to adjust blade flap stiffness (-)"),
           key(f.adj_edge_stiffness, "AdjEdSt", "Factor to adjust blade edge stiffness (-)"),
           "---------------------- DISTRIBUTED BLADE PROPERTIES ----------------------------\n"]
    names = ["BlFract", "PitchAxis", "StrcTwst", "BMassDen", "FlpStff", "EdgStff"]
    units = ["(-)", "(-)", "(deg)", "(kg/m)", "(Nm^2)", "(Nm^2)"]
    columns = [f.fraction, f.pitch_axis, [degrees_exact(t) for t in f.twist], f.mass, f.flap_stiffness,
               f.edge_stiffness]
    keep = [i for i, column in enumerate(columns) if column is not None]
    out.append("".join(f"{names[i]:>24}" for i in keep) + "\n")
    out.append("".join(f"{units[i]:>24}" for i in keep) + "\n")
    for j in range(f.stations):
        out.append("".join(f"{format_number(columns[i][j]):>24}" for i in keep) + "\n")
    out.append("---------------------- BLADE MODE SHAPES ---------------------------------------\n")
    labels = {"flap1": "Flap mode 1", "flap2": "Flap mode 2", "edge1": "Edge mode 1"}
    for name, prefix in BLADE_BLOCKS.items():
        out += block_lines(prefix, f.modes[name], labels[name])
    return "".join(out)


def write_elastodyn_blade(blade_file: ElastoDynBladeFile, path: str | Path) -> None:
    """Write a complete ElastoDyn blade file atomically."""
    write_atomic(path, elastodyn_blade_text(blade_file))


def blade_with_mode_shapes(path: str | Path, modes: dict[str, NDArray]) -> tuple[str, str]:
    """(old text, new text) of an existing blade file with the coefficient lines of the given modes
    ('flap1', 'flap2', 'edge1') replaced; every other byte is kept."""
    text = FastText.read(path)
    values: dict[str, str] = {}
    for name, coefficients in modes.items():
        values.update(block_values(BLADE_BLOCKS[name], coefficients))
    return "".join(text.lines), text.replaced(values)
