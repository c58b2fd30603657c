"""The labels of OpenFAST's input files from v3.0 to v5.0: one canonical name per field, every spelling a version
writes.

OpenFAST compares labels without regard to case, and reads the per-blade and per-mode entries of ElastoDyn
(``BldFile``, ``BldFlDmp``, ``FlStTunr``, ...) by position, without checking their label at all. The files that
OpenFAST's own tools write (and the IEA-15MW and IEA-22MW decks, written by WEIS/AeroElasticSE) therefore spell the
same field ``BldFile(1)`` or ``BldFile1``. bladefem reads by label: :func:`spellings` gives every name a field may
carry, canonical name first, and :class:`~bladefem.formats._fast_format.FastText` looks each of them up (case-insensitive).

Renames that change the meaning of the value as well (AeroDyn's ``WakeMod`` -> ``Wake_Mod`` + ``DBEMT_Mod``,
``AFAeroMod`` -> ``UA_Mod``, ``SkewMod`` -> ``Skew_Mod``) are not aliases: :data:`RENAMED` lists them for the docs,
and :mod:`bladefem.builders.aerodyn_primary` maps their values as AeroDyn does.
"""

from __future__ import annotations

import re

#: Fields with one entry per blade or per mode, written ``Name(i)`` (OpenFAST's templates, r-test) or ``Namei``
#: (WEIS/AeroElasticSE, the IEA-15MW and IEA-22MW decks); OpenFAST reads them by position.
INDEXED = (
    # ElastoDyn main file
    "BlPitch", "PreCone", "TipMass", "BldFile", "PBrIner", "BlPIner",
    # ElastoDyn blade file
    "BldFlDmp", "BldEdDmp", "FlStTunr",
    # ElastoDyn tower file
    "TwrFADmp", "TwrSSDmp", "FAStTunr", "SSStTunr",
    # AeroDyn primary file; the .fst (BeamDyn files of each blade)
    "ADBlFile", "BDBldFile",
    # ServoDyn
    "PitNeut", "PitSpr", "PitDamp", "TPitManS", "PitManRat", "BlPitchF", "TBDepISp", "BlAlpha", "BlUMod",
)

#: Pure renames (same value, other label): canonical label -> (older or newer spelling, where it is written).
ALIASES: dict[str, tuple[tuple[str, str], ...]] = {
    "PLExp": (("PLexp", "InflowWind (case only)"),),
    "VFlowAng": (("VflowAng", "InflowWind (case only)"),),
    "SkewRedistrFactor": (("SkewModFactor", "AeroDyn up to v3.5"),),
}

#: Renames that map values (documented; :mod:`bladefem.builders.aerodyn_primary` does the mapping):
#: (label up to OpenFAST v3.5, labels from v4.0, how the value maps).
RENAMED = (
    ("WakeMod", "Wake_Mod, DBEMT_Mod", "0 -> 0; 1 -> 1 with DBEMT_Mod 0; 2 -> 1 with DBEMT_Mod > 0; 3 -> 3"),
    ("WakeMod 10, 11, 12 (v3.5 only)", "Wake_Mod, BEM_Mod 2", "as WakeMod 0, 1, 2 with the polar projection"),
    ("AFAeroMod, UAMod", "UA_Mod", "AFAeroMod 1 -> 0 (steady); AFAeroMod 2 -> UA_Mod = UAMod"),
    ("SkewMod", "Skew_Mod", "0 -> -1; 1 -> 0; 2 -> 1"),
    ("FrozenWake", "DBEMT_Mod", "True -> -1"),
)

INDEX = re.compile(r"^(?P<name>[A-Za-z_]+?)\((?P<index>\d+)\)$")


def spellings(label: str) -> tuple[str, ...]:
    """Every label under which a field may be written, the canonical one first (matching is case-insensitive)."""
    names = [label]
    match = INDEX.match(label)
    if match and match["name"] in INDEXED:
        names += [f"{match['name']}{match['index']}", f"{match['name']}_{match['index']}"]
    names += [alias for alias, _ in ALIASES.get(label, ())]
    return tuple(names)
