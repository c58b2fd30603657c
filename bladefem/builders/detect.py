"""Choose the reader of an input file by its extension and content, and build the model it describes.

Formats: bladefem case files (``.yaml``/``.yml`` without ``components``), windIO turbine files (YAML with
``components``, versions 1.x and 2.x), BModes decks (``.bmi``, or any file with ``beam_type`` and ``sec_props_file``),
ElastoDyn main, blade and tower files (found by their keys ``NumBl``/``TipRad``, ``NBlInpSt``, ``NTwInpSt``), BeamDyn
primary and blade files (``kp_total`` with ``BldFile``; ``station_total``), HAWC2 structural files (``.st``, or
``#1`` then ``$1 rows``) and HAWC2 ``.htc`` files (the blade body's st file and c2_def).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..files import read_input
from ..formats._fast_format import KEY_LINE
from ..sections import Blade, TipMass
from ..sections.checks import body_problem, check_section_values, length_problem, precone_problem
from .tower import Tower

YAML_SUFFIXES = (".yaml", ".yml")
FORMATS = ("case", "windio", "bmodes", "elastodyn-main", "elastodyn-blade", "elastodyn-tower", "beamdyn-primary",
           "beamdyn-blade", "hawc2-st", "hawc2-htc")
#: Formats that describe a blade by six-by-six sections
BEAM_FORMATS = ("beamdyn-primary", "beamdyn-blade", "hawc2-st", "hawc2-htc")
#: Lines read to recognise a text format.
SNIFF_LINES = 400


@dataclass(frozen=True)
class Geometry:
    """Options for files that do not carry the rotor geometry themselves (an ElastoDyn blade or tower file), and
    overrides. Lengths in m, angles in rad, masses in kg; None means "from the file" (or the main file)."""

    tip_radius: float | None = None
    hub_radius: float | None = None
    precone: float | None = None
    pitch: float | None = None
    tip_mass: float | None = None
    elastodyn_main: str | Path | None = None
    tower_height: float | None = None
    top_mass: float | None = None
    htc: str | Path | None = None
    #: six-by-six blades (BeamDyn, HAWC2, windIO): "full" (default, the whole 6x6 in the FE), "condensed" or "reduced"
    #: (bladefem's diagonal beam, :meth:`bladefem.builders.section6x6.SixBySixBlade.table`)
    sections: str | None = None
    #: six-by-six blades: "curved" (default, the reference axis's prebend and sweep) or "straight" (straightened
    #: onto the pitch axis, :meth:`bladefem.builders.section6x6.SixBySixBlade.on_axis`)
    axis: str | None = None


def detect_format(path: str | Path) -> str:
    """One of :data:`FORMATS`; :class:`InputError` when the file is missing or not recognised."""
    path = Path(path)
    data = read_input(path)
    if b"\x00" in data[:65536]:
        raise InputError("not a text file (contains NUL bytes)", file=str(path),
                         line=data[:data.index(b"\x00")].count(b"\n") + 1)
    head = data.decode("utf-8", errors="replace").splitlines()[:SNIFF_LINES]
    words = {word.rstrip(":") for line in head for word in line.split()[:4]}
    words |= {match["key"] for line in head if (match := KEY_LINE.match(line))}     # after a quoted value with blanks
    if path.suffix.lower() in YAML_SUFFIXES:
        if any(line.startswith("requirements:") for line in head):
            raise InputError("a bladefem check spec (requirements on models), not a model: run 'bladefem check "
                             f"{path}'", file=str(path), line=1)
        if any(line.startswith("analysis:") for line in head):
            raise InputError("a bladefem batch plan, not a model: run 'bladefem batch "
                             f"{path} -o RESULTS'", file=str(path), line=1)
        return "windio" if any(line.startswith("components:") for line in head) else "case"
    if path.suffix.lower() == ".bmi" or {"beam_type", "sec_props_file"} <= words:
        return "bmodes"
    if path.suffix.lower() == ".htc":
        return "hawc2-htc"
    if "station_total" in words:
        return "beamdyn-blade"
    if {"kp_total", "BldFile"} <= words:
        return "beamdyn-primary"
    first = [line.split()[0] for line in head if line.split()]
    if path.suffix.lower() == ".st" or (any(t[:1] == "#" and t[1:].isdigit() for t in first)
                                        and any(t[:1] == "$" and t[1:].isdigit() for t in first)):
        return "hawc2-st"
    if "NBlInpSt" in words:
        return "elastodyn-blade"
    if "NTwInpSt" in words:
        return "elastodyn-tower"
    if {"NumBl", "TipRad"} <= words:
        return "elastodyn-main"
    if any(line.startswith("components:") for line in head):
        return "windio"
    if path.suffix.lower() == ".fst" or {"CompElast", "EDFile"} <= words:
        from ..formats._labels import Labels
        labels = Labels.read(path)
        if labels.has("EDFile"):
            raise InputError(f"an OpenFAST deck: give its ElastoDyn main file (EDFile: {labels.file('EDFile')}) for "
                             "the blade and tower, or run 'bladefem turbine' on the deck for the whole turbine",
                             file=str(path), line=labels.line("EDFile"), field="EDFile")
    raise InputError(f"unrecognised input format: not .yaml/.yml/.bmi, and none of its first {len(head)} lines "
                     "names the keys of an ElastoDyn main (NumBl, TipRad), blade (NBlInpSt) or tower (NTwInpSt) "
                     "file, a BModes deck (beam_type, sec_props_file), a BeamDyn primary (kp_total, BldFile) or blade "
                     "(station_total) file or a HAWC2 st (#1, $1 rows) or .htc file", file=str(path), line=1)


def read_model(path: str | Path, part: str | None = None, geometry: Geometry | None = None,
               **options: object) -> Blade | Tower:
    """The blade (default) or tower (``part='tower'``) described by ``path``, in any supported format. A BModes
    tower deck and a YAML tower case (``kind: tower``) come as the tower model's
    :class:`bladefem.sections.tower.Tower` (with supports).

    Geometry for files that lack it, and overrides, as a :class:`Geometry` or as keyword options with the same
    names (``tip_radius=63.0, elastodyn_main="main.dat"``; SI units, angles in rad)."""
    if options:
        unknown = set(options) - set(Geometry.__dataclass_fields__)
        if unknown:
            raise TypeError(f"unknown geometry options: {', '.join(sorted(unknown))}")
        geometry = Geometry(**{**(geometry.__dict__ if geometry else {}), **options})  # type: ignore[arg-type]
    geometry = geometry or Geometry()
    kind = detect_format(path)
    if kind not in BEAM_FORMATS + ("windio",):
        _refuse(geometry, ("sections", "axis"), "this input (its sections are columns, not six-by-six matrices on "
                "a reference axis; --sections and --straight-axis choose how BeamDyn, HAWC2 and windIO blades reach "
                "the FE)", path)
    if part not in (None, "blade", "tower"):
        raise InputError(f"part must be 'blade' or 'tower', got '{part}'", field="part")
    if kind == "elastodyn-tower" or (part == "tower" and kind == "elastodyn-main"):
        _refuse(geometry, BLADE_OPTIONS + (("tower_height", "top_mass") if kind == "elastodyn-main" else ()),
                "a tower given by an ElastoDyn main file" if kind == "elastodyn-main" else "a tower", path)
        return _elastodyn_tower(Path(path), kind, geometry)
    if kind in ("elastodyn-blade", "elastodyn-main"):
        _refuse(geometry, TOWER_OPTIONS, "a blade", path)
        return _overrides(_elastodyn_blade(Path(path), kind, geometry), geometry, path)
    if kind != "hawc2-st" and geometry.htc is not None:
        raise InputError("--htc applies to a HAWC2 st file only", file=str(path), field="--htc")
    if kind in BEAM_FORMATS:
        _refuse(geometry, TOWER_OPTIONS + ("elastodyn_main", "tip_radius"),
                "a six-by-six blade (its reference axis fixes the length; --hub-radius moves the root)", path)
        if part == "tower":
            raise InputError("this input describes a blade, not a tower", file=str(path), field="--part")
        from .beam_inputs import beamdyn_blade, hawc2_blade
        hub = geometry.hub_radius or 0.0
        model = geometry.sections or "full"
        axis = geometry.axis or "curved"
        blade = (beamdyn_blade(kind, Path(path), hub, 0.0, model, axis) if kind.startswith("beamdyn")
                 else hawc2_blade(kind, Path(path), geometry.htc, hub, 0.0, model, axis))
        check_section_values(blade.sections)
        return _overrides(blade, geometry, path)
    if kind == "bmodes":
        from ..formats.bmodes import read_bmodes
        from .bmodes_model import blade_from_bmodes
        from .bmodes_tower import tower_from_bmodes
        deck = read_bmodes(path)
        if deck.beam_type == 2:
            _refuse(geometry, BLADE_OPTIONS + TOWER_OPTIONS + ("elastodyn_main",), "a BModes tower deck", path)
            tower = tower_from_bmodes(deck)
            check_section_values(tower.sections)
            return tower
        _refuse(geometry, TOWER_OPTIONS + ("elastodyn_main",), "a blade", path)
        if geometry.precone is None and precone_problem(deck.precone):
            raise InputError(str(precone_problem(deck.precone)), file=str(path), line=deck.key_lines.get("precone"),
                             field="precone")
        radius = deck.radius if geometry.tip_radius is None else geometry.tip_radius
        hub = deck.hub_rad if geometry.hub_radius is None else geometry.hub_radius
        _check_length(hub, radius, path, geometry)
        blade = blade_from_bmodes(replace(deck, radius=radius, hub_rad=hub))
        check_section_values(blade.sections)
        body = blade.tip_mass
        problem = body_problem(body.mass, body.offset, body.inertia, blade.length) if body is not None else None
        if problem and geometry.tip_mass is None:
            raise InputError(f"tip mass: {problem}", file=str(path), line=deck.key_lines.get("tip_mass"),
                             field="tip_mass")
        return _overrides(blade, geometry, path)
    if kind == "windio":
        from ..formats.windio import read_windio
        from .windio_model import blade_from_windio, tower_from_windio
        turbine = read_windio(path)
        if part == "tower" or turbine.blade is None:
            _refuse(geometry, BLADE_OPTIONS + ("tower_height", "elastodyn_main", "sections", "axis"), "a windIO tower",
                    path)
            return tower_from_windio(turbine, geometry.top_mass)
        _refuse(geometry, TOWER_OPTIONS + ("elastodyn_main",), "a blade", path)
        _refuse(geometry, ("tip_radius",), "a windIO blade (its reference axis fixes the length; --hub-radius "
                "moves the root)", path)
        if geometry.hub_radius is not None:
            _check_length(geometry.hub_radius, geometry.hub_radius + turbine.blade.length, path, geometry)
            turbine = replace(turbine, hub_radius=geometry.hub_radius)
        return _overrides(blade_from_windio(turbine, sections=geometry.sections or "full",
                                            axis=geometry.axis or "curved"), geometry, path)
    from .tower_case import is_tower_case, read_tower_case
    if is_tower_case(path):
        _refuse(geometry, BLADE_OPTIONS + ("tower_height", "elastodyn_main"), "a bladefem tower case", path)
        if geometry.top_mass is not None:
            _refuse(geometry, ("top_mass",), "a bladefem tower case (its top_mass key gives it)", path)
        return read_tower_case(path)
    from .case import read_case
    _refuse(geometry, TOWER_OPTIONS + ("elastodyn_main",), "a bladefem blade case", path)
    return _overrides(read_case(path, geometry.tip_radius, geometry.hub_radius), geometry, path)


#: Geometry fields that only blades take, and only towers
BLADE_OPTIONS = ("tip_radius", "hub_radius", "precone", "pitch", "tip_mass")
TOWER_OPTIONS = ("tower_height", "top_mass")
#: Geometry field -> command-line option
OPTION_NAMES = {"tip_radius": "--tip-radius", "hub_radius": "--hub-radius", "precone": "--precone-deg",
                "pitch": "--pitch-deg", "tip_mass": "--tip-mass", "elastodyn_main": "--elastodyn-main",
                "tower_height": "--tower-height", "top_mass": "--top-mass", "htc": "--htc",
                "sections": "--sections", "axis": "--straight-axis"}


def _refuse(geometry: Geometry, names: tuple[str, ...], what: str, path: str | Path) -> None:
    """An InputError for the first of ``names`` that is set: it does not apply to this input."""
    for name in names:
        if getattr(geometry, name) is not None:
            raise InputError(f"{OPTION_NAMES[name]} ({name}) does not apply to {what}", file=str(path),
                             field=OPTION_NAMES[name])


def _check_length(hub_radius: float, tip_radius: float, path: str | Path, geometry: Geometry) -> None:
    problem = length_problem(hub_radius, tip_radius)
    if problem:
        option = "--tip-radius" if geometry.tip_radius is not None else "--hub-radius"
        raise InputError(problem, file=str(path), field=option if (geometry.tip_radius, geometry.hub_radius) != (
            None, None) else "radius")


def _overrides(blade: Blade, geometry: Geometry, path: str | Path) -> Blade:
    """Precone, pitch and tip mass from ``geometry`` (the tip mass replaces the mass of the file's tip body, its
    offsets and inertias kept); the precone checked whatever its source."""
    changes: dict[str, object] = {name: getattr(geometry, name) for name in ("precone", "pitch")
                                  if getattr(geometry, name) is not None}
    for name in ("pitch", "tip_mass"):
        value = getattr(geometry, name)
        if value is not None and not (math.isfinite(value) and (name == "pitch" or value >= 0)):
            raise InputError(f"must be a {'finite' if name == 'pitch' else 'non-negative'} number, got {value}",
                             file=str(path), field=OPTION_NAMES[name])
    if geometry.tip_mass is not None:
        body = blade.tip_mass
        keep = body is not None and (np.any(body.offset) or np.any(body.inertia))
        changes["tip_mass"] = (replace(body, mass=geometry.tip_mass) if keep
                               else TipMass(geometry.tip_mass) if geometry.tip_mass > 0 else None)
    problem = precone_problem(changes.get("precone", blade.precone))  # type: ignore[arg-type]
    if problem:
        raise InputError(problem, file=str(path), field="--precone-deg" if "precone" in changes else "precone")
    blade = blade.with_(**changes) if changes else blade
    body = blade.tip_mass
    problem = body_problem(body.mass, body.offset, body.inertia, blade.length) if body is not None else None
    if problem:
        raise InputError(f"tip mass: {problem}", file=str(path),
                         field="--tip-mass" if geometry.tip_mass else "tip_mass")
    return blade


def _elastodyn_blade(path: Path, kind: str, g: Geometry) -> Blade:
    from .elastodyn_blade import blade_from_elastodyn, read_elastodyn_blade
    from ..formats.elastodyn_main import read_elastodyn_main
    main = read_elastodyn_main(path if kind == "elastodyn-main" else g.elastodyn_main) if (
        kind == "elastodyn-main" or g.elastodyn_main) else None
    blade_path = main.blade_files[0] if kind == "elastodyn-main" else path
    tip_radius = g.tip_radius if g.tip_radius is not None else (main.tip_radius if main else None)
    if tip_radius is None:
        raise InputError("an ElastoDyn blade file needs the tip radius (--tip-radius) or an ElastoDyn main file "
                         "(--elastodyn-main)", file=str(path), field="TipRad")
    hub_radius = g.hub_radius if g.hub_radius is not None else (main.hub_radius if main else 0.0)
    tip_mass = g.tip_mass if g.tip_mass is not None else (main.tip_mass[0] if main else 0.0)
    if not (math.isfinite(tip_mass) and tip_mass >= 0):
        raise InputError(f"must be a non-negative number, got {tip_mass}", field="tip_mass")
    precone = main.precone[0] if main else 0.0
    if main is not None and precone_problem(precone):
        raise InputError(str(precone_problem(precone)), file=main.path, line=main.key_lines.get("PreCone(1)"),
                         field="PreCone(1)")
    problem = length_problem(hub_radius, tip_radius)
    if problem:
        given = g.tip_radius is not None or g.hub_radius is not None
        raise InputError(problem, file=str(path) if given or main is None else main.path,
                         line=None if given or main is None else main.key_lines.get("TipRad"),
                         field=("--tip-radius" if g.tip_radius is not None else "--hub-radius") if given else "TipRad")
    return blade_from_elastodyn(read_elastodyn_blade(blade_path), tip_radius=tip_radius, hub_radius=hub_radius,
                                precone=precone, tip_mass=tip_mass)


def _elastodyn_tower(path: Path, kind: str, g: Geometry) -> Tower:
    from .elastodyn_tower import (
        read_elastodyn_tower,
        tower_from_elastodyn,
        tower_from_elastodyn_main,
    )
    if kind == "elastodyn-main":
        return tower_from_elastodyn_main(path)
    if g.elastodyn_main:
        tower = tower_from_elastodyn_main(g.elastodyn_main)
        return tower_from_elastodyn(read_elastodyn_tower(path), height=tower.height, base_height=tower.base_height,
                                    top_mass=tower.top_mass if g.top_mass is None else g.top_mass)
    if g.tower_height is None:
        raise InputError("an ElastoDyn tower file needs the tower height (--tower-height) or an ElastoDyn main file "
                         "(--elastodyn-main)", file=str(path), field="TowerHt")
    top: TipMass | float | None = g.top_mass
    return tower_from_elastodyn(read_elastodyn_tower(path), height=g.tower_height, top_mass=top)
