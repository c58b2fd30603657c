"""ElastoDyn main input file: rotor and tower geometry, masses and inertias, drivetrain, DOF switches, and the
blade and tower files it references.

Only the entries bladefem uses are read (by key, so the order of the file does not matter); the rest of the file is
kept as text so that :func:`write_elastodyn_main` changes those entries and nothing else. Angles are stored in rad
and the rotor speed in rad/s. File names are resolved relative to the main file's folder.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field, fields
from pathlib import Path

from ..files import write_atomic
from ..limits import MAX_GEARBOX_RATIO, MAX_TURBINE_LENGTH
from ._fast_format import (
    FastText,
    degrees_exact,
    format_number,
    rpm_exact,
    rpm_to_rad_per_s,
)

#: DOF switches read when present.
DOF_KEYS = ("PitchDOF", "FlapDOF1", "FlapDOF2", "EdgeDOF", "TeetDOF", "DrTrDOF", "GenDOF", "YawDOF", "TwFADOF1",
            "TwFADOF2", "TwSSDOF1", "TwSSDOF2", "PtfmSgDOF", "PtfmSwDOF", "PtfmHvDOF", "PtfmRDOF", "PtfmPDOF",
            "PtfmYDOF")

#: Scalar entries: attribute -> (key, kind). Kinds: 'float' (SI as in the file), 'positive', 'mass' (>= 0),
#: 'deg' (file degrees, stored rad), 'rpm' (file rpm, stored rad/s).
SCALARS = {
    "tip_radius": ("TipRad", "positive"),
    "hub_radius": ("HubRad", "mass"),
    "tower_height": ("TowerHt", "positive"),
    "tower_base_height": ("TowerBsHt", "float"),
    "overhang": ("OverHang", "float"),
    "shaft_tilt": ("ShftTilt", "deg"),
    "twr2shft": ("Twr2Shft", "float"),
    "hub_cm": ("HubCM", "float"),
    "hub_mass": ("HubMass", "mass"),
    "hub_inertia": ("HubIner", "mass"),
    "generator_inertia": ("GenIner", "mass"),
    "nacelle_mass": ("NacMass", "mass"),
    "nacelle_yaw_inertia": ("NacYIner", "mass"),
    "yaw_bearing_mass": ("YawBrMass", "mass"),
    "gearbox_ratio": ("GBRatio", "positive"),
    "drivetrain_spring": ("DTTorSpr", "mass"),
    "drivetrain_damper": ("DTTorDmp", "mass"),
    "rotor_speed": ("RotSpeed", "rpm"),
}
#: Initial conditions and the azimuth convention, read when present (0 otherwise): attribute -> (key, kind).
INITIAL = {
    "oop_deflection": ("OoPDefl", "float"),
    "ip_deflection": ("IPDefl", "float"),
    "azimuth": ("Azimuth", "deg"),
    "nacelle_yaw": ("NacYaw", "deg"),
    "tower_top_fa": ("TTDspFA", "float"),
    "tower_top_ss": ("TTDspSS", "float"),
    "azimuth_blade1_up": ("AzimB1Up", "deg"),
}
#: ElastoDyn's own analysis nodes: attribute -> key.
NODE_COUNTS = {"blade_nodes": "BldNodes", "tower_nodes": "TwrNodes"}
NACELLE_CM_KEYS = ("NacCMxn", "NacCMyn", "NacCMzn")


@dataclass(frozen=True)
class ElastoDynMain:
    """The entries of an ElastoDyn main file that bladefem uses (SI, angles in rad, rotor speed in rad/s).

    num_blades : NumBl
    tip_radius, hub_radius : TipRad, HubRad, m (from the rotor apex along the preconed pitch axis)
    precone : PreCone(1..NumBl), rad
    tip_mass : TipMass(1..NumBl), tip-brake masses, kg
    tower_height, tower_base_height : TowerHt, TowerBsHt, m
    overhang : OverHang, m (yaw axis to rotor apex, negative upwind); shaft_tilt : ShftTilt, rad
    twr2shft : Twr2Shft, vertical distance from the tower top to the shaft, m
    hub_cm : HubCM, m; hub_mass : HubMass, kg; hub_inertia : HubIner about the shaft, kg m^2
    generator_inertia : GenIner about the high-speed shaft, kg m^2; gearbox_ratio : GBRatio
    nacelle_mass : NacMass, kg; nacelle_yaw_inertia : NacYIner, kg m^2; nacelle_cm : NacCMxn/yn/zn, m
    yaw_bearing_mass : YawBrMass, kg
    drivetrain_spring : DTTorSpr, N m/rad; drivetrain_damper : DTTorDmp, N m s/rad
    rotor_speed : RotSpeed, rad/s
    blade_nodes, tower_nodes : BldNodes, TwrNodes, ElastoDyn's numbers of analysis nodes (equal elements)
    dofs : DOF switch name -> flag
    oop_deflection, ip_deflection : OoPDefl, IPDefl, initial blade-tip deflections out of the plane (downwind) and in
        it (toward the trailing edge), m
    blade_pitch : BlPitch(1..NumBl), rad
    azimuth : Azimuth, initial azimuth of blade 1, rad (ElastoDyn's I/O convention, see azimuth_blade1_up)
    nacelle_yaw : NacYaw, rad
    tower_top_fa, tower_top_ss : TTDspFA, TTDspSS, initial tower-top displacements (downwind; to the left looking
        downwind), m
    azimuth_blade1_up : AzimB1Up, the I/O azimuth value when blade 1 points up, rad
    blade_files : BldFile(1..NumBl), resolved against the main file's folder
    tower_file : TwrFile, resolved likewise
    """

    num_blades: int
    tip_radius: float
    hub_radius: float
    precone: tuple[float, ...]
    tip_mass: tuple[float, ...]
    tower_height: float
    tower_base_height: float
    overhang: float
    shaft_tilt: float
    twr2shft: float
    hub_cm: float
    hub_mass: float
    hub_inertia: float
    generator_inertia: float
    nacelle_mass: float
    nacelle_yaw_inertia: float
    nacelle_cm: tuple[float, float, float]
    yaw_bearing_mass: float
    gearbox_ratio: float
    drivetrain_spring: float
    drivetrain_damper: float
    rotor_speed: float
    blade_nodes: int
    tower_nodes: int
    dofs: dict[str, bool]
    blade_files: tuple[Path, ...]
    tower_file: Path
    blade_pitch: tuple[float, ...] = ()
    oop_deflection: float = 0.0
    ip_deflection: float = 0.0
    azimuth: float = 0.0
    nacelle_yaw: float = 0.0
    tower_top_fa: float = 0.0
    tower_top_ss: float = 0.0
    azimuth_blade1_up: float = 0.0
    path: str = field(default="", compare=False)
    key_lines: dict[str, int] = field(default_factory=dict, compare=False)
    text: FastText | None = field(default=None, compare=False, repr=False)

    @property
    def rotor_speed_rpm(self) -> float:
        return self.rotor_speed * 30.0 / math.pi

    @property
    def rotor_nacelle_mass(self) -> float:
        """Hub, nacelle and yaw-bearing mass (kg), without the blades."""
        return self.hub_mass + self.nacelle_mass + self.yaw_bearing_mass


def read_elastodyn_main(path: str | Path) -> ElastoDynMain:
    """Read an ElastoDyn main file; every malformed entry is an :class:`InputError` naming file, line, field."""
    text = FastText.read(path)
    num_blades = text.int("NumBl", minimum=1)
    if num_blades > 3:
        raise text.error(f"ElastoDyn supports 1 to 3 blades, got {num_blades}", text.line_of("NumBl"), "NumBl")
    blades = range(1, num_blades + 1)
    folder = Path(text.path).parent
    values = {name: _scalar(text, key, kind) for name, (key, kind) in SCALARS.items()}
    tip_radius, hub_radius = values["tip_radius"], values["hub_radius"]
    if tip_radius <= hub_radius:
        raise text.error(f"must exceed HubRad ({hub_radius}), got {tip_radius}", text.line_of("TipRad"), "TipRad")
    values.update({name: text.int(key, minimum=1) for name, key in NODE_COUNTS.items()})
    values.update({name: _scalar(text, key, kind) for name, (key, kind) in INITIAL.items() if text.has(key)})
    pitch_keys = [f"BlPitch({i})" for i in blades]
    if all(text.has(key) for key in pitch_keys):
        values["blade_pitch"] = tuple(math.radians(text.float(key)) for key in pitch_keys)
    key_names = ["NumBl", *NODE_COUNTS.values(), *(key for key, _ in SCALARS.values()), *NACELLE_CM_KEYS, "TwrFile"]
    key_names += [f"{key}({i})" for key in ("PreCone", "TipMass", "BldFile") for i in blades]
    key_names += [key for key in DOF_KEYS if text.has(key)]
    key_names += [key for key, _ in INITIAL.values() if text.has(key)] + [
        f"BlPitch({i})" for i in blades if text.has(f"BlPitch({i})")]
    return ElastoDynMain(
        num_blades=num_blades,
        precone=tuple(math.radians(text.float(f"PreCone({i})")) for i in blades),
        tip_mass=tuple(text.float(f"TipMass({i})", non_negative=True) for i in blades),
        nacelle_cm=tuple(text.float(key) for key in NACELLE_CM_KEYS),  # type: ignore[arg-type]
        dofs={key: text.bool(key) for key in DOF_KEYS if text.has(key)},
        blade_files=tuple(_file(text, folder, f"BldFile({i})") for i in blades),
        tower_file=_file(text, folder, "TwrFile"),
        path=text.path,
        key_lines={key: text.line_of(key) for key in key_names},
        text=text,
        **values,
    )


#: Bounds of the layout's lengths and the gearbox ratio (see :mod:`bladefem.limits`)
BOUNDED = {**dict.fromkeys(("TipRad", "HubRad", "TowerHt", "TowerBsHt", "OverHang", "Twr2Shft", "HubCM"),
                           MAX_TURBINE_LENGTH), "GBRatio": MAX_GEARBOX_RATIO}


def _scalar(text: FastText, key: str, kind: str) -> float:
    if key in BOUNDED and abs(text.float(key)) > BOUNDED[key]:
        raise text.error(f"must be at most {BOUNDED[key]:g} in magnitude (see bladefem.limits), got "
                         f"{text.string(key)}", text.line_of(key), key)
    if kind == "deg":
        return math.radians(text.float(key))
    if kind == "rpm":
        return rpm_to_rad_per_s(text.float(key))
    return text.float(key, positive=kind == "positive", non_negative=kind == "mass")


def _file(text: FastText, folder: Path, key: str) -> Path:
    name = text.string(key).strip()
    if not name:
        raise text.error("empty file name", text.line_of(key), key)
    return Path(os.path.normpath(folder / name))


def elastodyn_main_text(main: ElastoDynMain, path: str | Path | None = None) -> str:
    """The text of ``main``'s own file with every entry bladefem reads set from ``main``; all other bytes are kept.
    File names are written relative to the folder of ``path`` (the file to be written)."""
    if main.text is None:
        raise ValueError("an ElastoDynMain written back needs the text it was read from (read_elastodyn_main)")
    folder = Path(path).parent if path is not None else Path(main.path).parent
    values: dict[str, str] = {}
    for f in fields(main):
        if f.name in SCALARS:
            key, kind = SCALARS[f.name]
            value = getattr(main, f.name)
            value = degrees_exact(value) if kind == "deg" else rpm_exact(value) if kind == "rpm" else value
            values[key] = format_number(value)
    for name, (key, kind) in INITIAL.items():
        if key in main.key_lines:
            value = getattr(main, name)
            values[key] = format_number(degrees_exact(value) if kind == "deg" else value)
    for i, pitch in enumerate(main.blade_pitch):
        if f"BlPitch({i + 1})" in main.key_lines:
            values[f"BlPitch({i + 1})"] = format_number(degrees_exact(pitch))
    values["NumBl"] = str(main.num_blades)
    values.update({key: str(getattr(main, name)) for name, key in NODE_COUNTS.items()})
    for i in range(main.num_blades):
        values[f"PreCone({i + 1})"] = format_number(degrees_exact(main.precone[i]))
        values[f"TipMass({i + 1})"] = format_number(main.tip_mass[i])
        values[f"BldFile({i + 1})"] = _quoted(main.blade_files[i], folder)
    values.update({key: format_number(value) for key, value in zip(NACELLE_CM_KEYS, main.nacelle_cm)})
    values.update({key: str(flag) for key, flag in main.dofs.items()})
    values["TwrFile"] = _quoted(main.tower_file, folder)
    return main.text.replaced(values)


def _quoted(file: Path, folder: Path) -> str:
    return '"' + Path(os.path.relpath(file, folder)).as_posix() + '"'


def write_elastodyn_main(main: ElastoDynMain, path: str | Path) -> None:
    """Write ``main`` (see :func:`elastodyn_main_text`) atomically."""
    write_atomic(path, elastodyn_main_text(main, path))
