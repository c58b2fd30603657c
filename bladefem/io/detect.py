"""Choose the reader of an input file by its extension and content, and build the model it describes.

Formats: bladefem case files (``.yaml``/``.yml`` without ``components``), windIO turbine files (YAML with
``components``), BModes decks (``.bmi``, or any file with ``beam_type`` and ``sec_props_file``), and ElastoDyn main,
blade and tower files (found by their keys ``NumBl``/``TipRad``, ``NBlInpSt``, ``NTwInpSt``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError
from ..sections import Blade, TipMass
from .tower import Tower

YAML_SUFFIXES = (".yaml", ".yml")
FORMATS = ("case", "windio", "bmodes", "elastodyn-main", "elastodyn-blade", "elastodyn-tower")
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


def detect_format(path: str | Path) -> str:
    """One of :data:`FORMATS`; :class:`InputError` when the file is missing or not recognised."""
    path = Path(path)
    if not path.is_file():
        raise InputError("file not found", file=str(path))
    try:
        with path.open(encoding="utf-8", errors="replace") as stream:
            head = [line for _, line in zip(range(SNIFF_LINES), stream)]
    except OSError as error:
        raise InputError(f"cannot read file ({error.strerror or error})", file=str(path)) from None
    words = {word.rstrip(":") for line in head for word in line.split()[:4]}
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
    if "NBlInpSt" in words:
        return "elastodyn-blade"
    if "NTwInpSt" in words:
        return "elastodyn-tower"
    if {"NumBl", "TipRad"} <= words:
        return "elastodyn-main"
    if any(line.startswith("components:") for line in head):
        return "windio"
    raise InputError("unrecognised input format (expected a bladefem case or windIO .yaml, a BModes .bmi, or an "
                     "ElastoDyn main, blade or tower file)", file=str(path), line=1)


def read_model(path: str | Path, part: str | None = None, geometry: Geometry | None = None,
               **options: object) -> Blade | Tower:
    """The blade (default) or tower (``part='tower'``) described by ``path``, in any supported format. A BModes
    tower on tension wires and a YAML tower case (``kind: tower``) come as the tower model's
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
    if part not in (None, "blade", "tower"):
        raise InputError(f"part must be 'blade' or 'tower', got '{part}'", field="part")
    if kind == "elastodyn-tower" or (part == "tower" and kind == "elastodyn-main"):
        return _elastodyn_tower(Path(path), kind, geometry)
    if kind in ("elastodyn-blade", "elastodyn-main"):
        return _overrides(_elastodyn_blade(Path(path), kind, geometry), geometry)
    if kind == "bmodes":
        from .bmodes import read_bmodes
        from .bmodes_model import (
            blade_from_bmodes,
            tower_from_bmodes,
            tower_model_from_bmodes,
        )
        deck = read_bmodes(path)
        if deck.beam_type == 2:
            return tower_model_from_bmodes(deck) if deck.wires is not None else tower_from_bmodes(deck)
        return _overrides(blade_from_bmodes(deck), geometry)
    if kind == "windio":
        from .windio import read_windio
        from .windio_model import blade_from_windio, tower_from_windio
        turbine = read_windio(path)
        if part == "tower" or turbine.blade is None:
            return tower_from_windio(turbine, geometry.top_mass)
        return _overrides(blade_from_windio(turbine), geometry)
    from .tower_case import is_tower_case, read_tower_case
    if is_tower_case(path):
        return read_tower_case(path)
    from .case import read_case
    return _overrides(read_case(path), geometry)


def _overrides(blade: Blade, geometry: Geometry) -> Blade:
    changes = {name: getattr(geometry, name) for name in ("precone", "pitch") if getattr(geometry, name) is not None}
    return blade.with_(**changes) if changes else blade


def _elastodyn_blade(path: Path, kind: str, g: Geometry) -> Blade:
    from .elastodyn_blade import blade_from_elastodyn, read_elastodyn_blade
    from .elastodyn_main import read_elastodyn_main
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
    return blade_from_elastodyn(read_elastodyn_blade(blade_path), tip_radius=tip_radius, hub_radius=hub_radius,
                                precone=main.precone[0] if main else 0.0, tip_mass=tip_mass)


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
