"""ElastoDyn tower input file: distributed properties, adjustment factors, mode-shape coefficients.

Layout (OpenFAST ElastoDyn v1.00): ``NTwInpSt``, damping ``TwrFADmp(1..2)``, ``TwrSSDmp(1..2)`` (percent of
critical), tuners ``FAStTunr(1..2)``, ``SSStTunr(1..2)``, factors ``AdjTwMa``, ``AdjFASt``, ``AdjSSSt``, a table
``HtFract TMassDen TwFAStif TwSSStif`` (older files have more columns; columns are found by their header names),
and the blocks ``TwFAM1Sh``, ``TwFAM2Sh``, ``TwSSM1Sh``, ``TwSSM2Sh``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..files import write_atomic
from ..sections import SectionTable, TipMass
from ..formats._fast_format import FastText, format_number
from ..formats._modeshape_blocks import block_lines, block_values, read_block
from ..sections.checks import check_section_values
from .elastodyn_blade import _check_stations, blade_from_elastodyn, read_elastodyn_blade
from ..formats.elastodyn_main import read_elastodyn_main
from .tower import Tower

#: Mode name -> ElastoDyn block prefix.
TOWER_BLOCKS = {"fa1": "TwFAM1Sh", "fa2": "TwFAM2Sh", "ss1": "TwSSM1Sh", "ss2": "TwSSM2Sh"}
REQUIRED_COLUMNS = ("HtFract", "TMassDen", "TwFAStif", "TwSSStif")


@dataclass(frozen=True)
class ElastoDynTowerFile:
    """The contents of an ElastoDyn tower file (values as in the file).

    fraction : HtFract, height fraction from the base (0) to the top (1)
    mass : TMassDen before AdjTwMa, kg/m
    fa_stiffness, ss_stiffness : TwFAStif, TwSSStif before AdjFASt/AdjSSSt, N m^2
    adj_mass, adj_fa_stiffness, adj_ss_stiffness : AdjTwMa, AdjFASt, AdjSSSt
    fa_tuners, ss_tuners : FAStTunr(1..2), SSStTunr(1..2)
    fa_damping_percent, ss_damping_percent : TwrFADmp(1..2), TwrSSDmp(1..2), percent of critical
    modes : 'fa1', 'fa2', 'ss1', 'ss2' -> coefficients of x^2 .. x^6
    """

    fraction: NDArray[np.float64]
    mass: NDArray[np.float64]
    fa_stiffness: NDArray[np.float64]
    ss_stiffness: NDArray[np.float64]
    adj_mass: float = 1.0
    adj_fa_stiffness: float = 1.0
    adj_ss_stiffness: float = 1.0
    fa_tuners: tuple[float, float] = (1.0, 1.0)
    ss_tuners: tuple[float, float] = (1.0, 1.0)
    fa_damping_percent: tuple[float, float] = (0.0, 0.0)
    ss_damping_percent: tuple[float, float] = (0.0, 0.0)
    modes: dict[str, NDArray[np.float64]] = field(default_factory=dict)
    title: str = ""
    path: str = field(default="", compare=False)
    station_lines: tuple[int, ...] = field(default=(), compare=False)
    key_lines: dict[str, int] = field(default_factory=dict, compare=False)

    @property
    def stations(self) -> int:
        return len(self.fraction)


def read_elastodyn_tower(path: str | Path) -> ElastoDynTowerFile:
    """Read an ElastoDyn tower file; every malformed value is an :class:`InputError` naming file, line, field."""
    text = FastText.read(path)
    stations = text.int("NTwInpSt", minimum=2)
    header = text.header_line("HtFract", after=text.line_of("NTwInpSt"))
    columns = tuple(text.lines[header - 1].split())
    for name in REQUIRED_COLUMNS:
        if name not in columns:
            raise text.error(f"table header lacks column '{name}' (found {' '.join(columns)})", header, name)
    first_row = header + 1
    if first_row <= len(text.lines) and text.lines[first_row - 1].lstrip().startswith("("):
        first_row += 1
    rows = text.table(first_row, stations, columns, exact=True)
    table = {name: np.array([row[i] for row in rows]) for i, name in enumerate(columns)}
    station_lines = tuple(range(first_row, first_row + stations))
    _check_stations(text, table, station_lines, "HtFract", ("TMassDen", "TwFAStif", "TwSSStif"))

    def pair(key: str, **check: bool) -> tuple[float, float]:
        return text.float(f"{key}(1)", **check), text.float(f"{key}(2)", **check)

    if text.has("NTwCMass") and text.int("NTwCMass", minimum=0) > 0:
        raise text.error(f"tower concentrated masses (NTwCMass {text.int('NTwCMass')}, the optional section of "
                         "OpenFAST 4.2 and later) are not modelled: set NTwCMass 0", text.line_of("NTwCMass"),
                         "NTwCMass")

    keys = ["NTwInpSt", "AdjTwMa", "AdjFASt", "AdjSSSt"] + [
        f"{key}({i})" for key in ("TwrFADmp", "TwrSSDmp", "FAStTunr", "SSStTunr") for i in (1, 2)] + [
        f"{prefix}({p})" for prefix in TOWER_BLOCKS.values() for p in range(2, 7)]
    return ElastoDynTowerFile(
        fraction=table["HtFract"],
        mass=table["TMassDen"],
        fa_stiffness=table["TwFAStif"],
        ss_stiffness=table["TwSSStif"],
        adj_mass=text.float("AdjTwMa", positive=True),
        adj_fa_stiffness=text.float("AdjFASt", positive=True),
        adj_ss_stiffness=text.float("AdjSSSt", positive=True),
        fa_tuners=pair("FAStTunr", positive=True),
        ss_tuners=pair("SSStTunr", positive=True),
        fa_damping_percent=pair("TwrFADmp", non_negative=True),
        ss_damping_percent=pair("TwrSSDmp", non_negative=True),
        modes={name: read_block(text, prefix) for name, prefix in TOWER_BLOCKS.items()},
        title=text.lines[1].strip() if len(text.lines) > 1 else "",
        path=text.path,
        station_lines=station_lines,
        key_lines={key: text.line_of(key) for key in keys},
    )


def tower_from_elastodyn(tower_file: ElastoDynTowerFile, *, height: float, base_height: float = 0.0,
                         top_mass: TipMass | float | None = None) -> Tower:
    """A :class:`Tower` from an ElastoDyn tower file.

    height : flexible tower length TowerHt - TowerBsHt, m
    base_height : TowerBsHt, m
    top_mass : the tower-top body (kg as a point mass, or a :class:`TipMass`), e.g. from
        :func:`tower_from_elastodyn_main`
    """
    f = tower_file
    if not height > 0:
        raise InputError(f"tower flexible length must be positive, got {height}", file=f.path or None,
                         field="TowerHt")
    sections = SectionTable(
        span=f.fraction * height,
        mass=f.mass * f.adj_mass,
        flap_stiffness=f.fa_stiffness * f.adj_fa_stiffness,
        edge_stiffness=f.ss_stiffness * f.adj_ss_stiffness,
        source=f.path,
        lines=f.station_lines or None,
    )
    check_section_values(sections)
    if isinstance(top_mass, (int, float)):
        top_mass = TipMass(float(top_mass)) if top_mass > 0 else None
    notes = (f"ElastoDyn tower file {Path(f.path).name if f.path else ''}: AdjTwMa = {f.adj_mass:g}, "
             f"AdjFASt = {f.adj_fa_stiffness:g}, AdjSSSt = {f.adj_ss_stiffness:g} applied",
             "tower torsion and extension rigid (ElastoDyn tower files carry no GJ or EA)")
    return Tower(sections=sections, base_height=base_height, top_mass=top_mass,
                 name=Path(f.path).stem if f.path else "elastodyn tower", notes=notes)


# -- writing ----------------------------------------------------------------------------------------------------

def elastodyn_tower_text(tower_file: ElastoDynTowerFile) -> str:
    """A complete ElastoDyn tower file (v1.00 layout)."""
    f = tower_file

    def key(value: float, name: str, description: str) -> str:
        return f"{format_number(value):>24}   {name} - {description}\n"

    out = ["------- ELASTODYN V1.00.* TOWER INPUT FILE -------------------------------------\n",
           f"{f.title or 'Written by bladefem'}\n",
           "---------------------- TOWER PARAMETERS ----------------------------------------\n",
           f"{f.stations:>24}   NTwInpSt    - Number of input stations to specify tower geometry\n"]
    for i in (0, 1):
        out.append(key(f.fa_damping_percent[i], f"TwrFADmp({i + 1})", f"Tower fore-aft mode {i + 1} damping (%)"))
    for i in (0, 1):
        out.append(key(f.ss_damping_percent[i], f"TwrSSDmp({i + 1})", f"Tower side-to-side mode {i + 1} damping (%)"))
    out.append("---------------------- TOWER ADJUSTMUNT FACTORS --------------------------------\n")
    for i in (0, 1):
        out.append(key(f.fa_tuners[i], f"FAStTunr({i + 1})", f"Tower fore-aft modal stiffness tuner, mode {i + 1} (-)"))
    for i in (0, 1):
        out.append(key(f.ss_tuners[i], f"SSStTunr({i + 1})", f"Tower side-to-side stiffness tuner, mode {i + 1} (-)"))
    out += [key(f.adj_mass, "AdjTwMa", "Factor to adjust tower mass density (-)"),
            key(f.adj_fa_stiffness, "AdjFASt", "Factor to adjust tower fore-aft stiffness (-)"),
            key(f.adj_ss_stiffness, "AdjSSSt", "Factor to adjust tower side-to-side stiffness (-)"),
            "---------------------- DISTRIBUTED TOWER PROPERTIES ----------------------------\n",
            "".join(f"{name:>24}" for name in ("HtFract", "TMassDen", "TwFAStif", "TwSSStif")) + "\n",
            "".join(f"{unit:>24}" for unit in ("(-)", "(kg/m)", "(Nm^2)", "(Nm^2)")) + "\n"]
    for j in range(f.stations):
        row = (f.fraction[j], f.mass[j], f.fa_stiffness[j], f.ss_stiffness[j])
        out.append("".join(f"{format_number(v):>24}" for v in row) + "\n")
    labels = {"fa1": "Mode 1", "fa2": "Mode 2", "ss1": "Mode 1", "ss2": "Mode 2"}
    for name, prefix in TOWER_BLOCKS.items():
        if name == "fa1":
            out.append("---------------------- TOWER FORE-AFT MODE SHAPES ------------------------------\n")
        if name == "ss1":
            out.append("---------------------- TOWER SIDE-TO-SIDE MODE SHAPES --------------------------\n")
        out += block_lines(prefix, f.modes[name], labels[name])
    return "".join(out)


def write_elastodyn_tower(tower_file: ElastoDynTowerFile, path: str | Path) -> None:
    """Write a complete ElastoDyn tower file atomically."""
    write_atomic(path, elastodyn_tower_text(tower_file))


def tower_with_mode_shapes(path: str | Path, modes: dict[str, NDArray]) -> tuple[str, str]:
    """(old text, new text) of an existing tower file with the coefficient lines of the given modes
    ('fa1', 'fa2', 'ss1', 'ss2') replaced; every other byte is kept."""
    text = FastText.read(path)
    values: dict[str, str] = {}
    for name, coefficients in modes.items():
        values.update(block_values(TOWER_BLOCKS[name], coefficients))
    return "".join(text.lines), text.replaced(values)


def tower_from_elastodyn_main(main_path: str | Path) -> Tower:
    """A :class:`Tower` from an ElastoDyn main file: TwrFile, TowerHt - TowerBsHt, and the rotor-nacelle mass
    (NumBl blades from BldFile(i) with AdjBlMs and TipMass(i), plus HubMass, NacMass and YawBrMass) as a point mass
    at the tower top, which is how ElastoDyn's tower mode-shape integrals see it (its TwrTpMass)."""
    main = read_elastodyn_main(main_path)
    blades = 0.0
    for i in range(main.num_blades):
        blade = blade_from_elastodyn(read_elastodyn_blade(main.blade_files[i]), tip_radius=main.tip_radius,
                                     hub_radius=main.hub_radius)
        blades += blade.sections.mass_moments()[0] + main.tip_mass[i]
    top = blades + main.rotor_nacelle_mass
    tower = tower_from_elastodyn(read_elastodyn_tower(main.tower_file),
                                 height=main.tower_height - main.tower_base_height,
                                 base_height=main.tower_base_height, top_mass=top)
    return Tower(sections=tower.sections, base_height=tower.base_height, top_mass=tower.top_mass, name=tower.name,
                 notes=tower.notes + (f"tower-top mass {top:.6g} kg (blades {blades:.6g} kg, hub, nacelle and yaw "
                                      "bearing from the main file) as a point mass; its rotary inertia and offset "
                                      "are left out, as in ElastoDyn's tower mode-shape integrals",))
