"""One case of a batch: the base input, the varied inputs, the analysis; its identity (a hash of all of it,
including the input files' bytes) and how its inputs change the model."""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass, replace
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError
from ..files import check_input, read_input

#: section-table columns a plan may scale (``<name>_scale``); 'stiffness' scales every stiffness column at once
SCALES = ("mass", "flap_stiffness", "edge_stiffness", "torsion_stiffness", "axial_stiffness", "flap_inertia",
          "edge_inertia", "stiffness")
STIFFNESSES = ("flap_stiffness", "edge_stiffness", "torsion_stiffness", "axial_stiffness")
#: other varied inputs and their result columns (SI inside, named units at the interface)
COLUMNS = ("tip_mass_kg", "precone_deg", "pitch_deg", "rpm", "wind_speed_m_s", "turbulence_seed")


@dataclass(frozen=True)
class Case:
    """A case: ``index`` in the plan, ``model`` input file, ``inputs`` varied (``<column>_scale`` as a number or
    a list over the stations, ``tip_mass_kg``, ``precone_deg``, ``pitch_deg``, ``rpm``, or ``file``), the analysis,
    the case's ``hash`` and the digest of its ``bundle`` (the input files carried to the worker, see
    :mod:`bladefem.batch.bundle`; None: the worker reads the paths as they are)."""

    index: int
    model: Path
    elastodyn_main: Path | None
    inputs: dict[str, Any]
    analysis: Any
    hash: str
    bundle: str | None = None


@lru_cache(maxsize=64)
def _digest(path: str, stamp: tuple[int, int]) -> str:
    return hashlib.sha256(read_input(path)).hexdigest()


def file_digest(path: Path) -> str:
    """SHA-256 of a file's bytes (cached per modification time); InputError if it is not a readable regular file
    of at most :data:`bladefem.files.MAX_INPUT_BYTES` (checked before reading: a device or pipe is never read)."""
    stat = check_input(path).stat()
    return _digest(str(path), (stat.st_mtime_ns, stat.st_size))


def _plain(value: Any) -> Any:
    if isinstance(value, np.ndarray):
        return [float(v) for v in value]
    return value


def case_hash(content: str, inputs: dict[str, Any], analysis: dict[str, Any]) -> str:
    """Identity of a case: the ``content`` digest of its input files' bytes (every file it reads, see
    :attr:`bladefem.batch.bundle.Bundle.content`), the varied inputs and the analysis."""
    key = {"files": content, "inputs": {k: _plain(v) for k, v in sorted(inputs.items()) if k != "file"},
           "analysis": analysis}
    return hashlib.sha256(json.dumps(key, sort_keys=True).encode()).hexdigest()[:24]


def station_fractions(model: Path, main: Path | None) -> np.ndarray:
    """Station positions of the base model as fractions of its length (for correlated sampling)."""
    from ..check.models import read_structure
    sections = read_structure(model, main).sections
    return sections.span / sections.length


#: the generalised strain of each stiffness column in six-by-six sections (:mod:`bladefem.sections.full_section`)
FULL_STRAINS = {"axial_stiffness": 0, "torsion_stiffness": 3, "flap_stiffness": 4, "edge_stiffness": 5}


def _scaled_full(sections: Any, name: str, factor: Any) -> Any:
    """Six-by-six sections scaled: ``mass`` the whole mass matrix, ``stiffness`` the whole stiffness, a stiffness
    column its strain's diagonal entry (its couplings by the square root: the coupling coefficients kept; flap and
    edge are the bending about the section's chordwise and thickness axes)."""
    full = sections.full
    factor = np.broadcast_to(np.asarray(factor, dtype=float), sections.span.shape)
    if name == "mass":
        return replace(full, mass=full.mass * factor[:, None, None]).table()
    if name == "stiffness":
        return replace(full, stiffness=full.stiffness * factor[:, None, None]).table()
    if name in FULL_STRAINS:
        return full.with_stiffness_scaled(FULL_STRAINS[name], factor).table()
    raise InputError(f"six-by-six sections have no '{name}' column to scale (their rotary inertias are in the mass "
                     "matrix: mass_scale scales it whole)", field=f"{name}_scale")


def _scaled(sections: Any, name: str, factor: Any) -> Any:
    if sections.full is not None:
        return _scaled_full(sections, name, factor)
    names = STIFFNESSES if name == "stiffness" else (name,)
    changes = {}
    for column in names:
        values = getattr(sections, column)
        if values is None:
            if name != "stiffness":
                raise InputError(f"the model has no '{column}' column to scale", field=f"{name}_scale")
            continue
        changes[column] = values * np.asarray(factor, dtype=float)
    return replace(sections, **changes)


def apply_inputs(structure: Any, inputs: dict[str, Any]) -> Any:
    """The blade or tower with the case's inputs applied: section columns scaled (by one factor or one per
    station), tip mass (kg), precone and pitch (degrees). ``rpm`` and ``file`` are not model changes."""
    sections = structure.sections
    for key, value in inputs.items():
        if key.endswith("_scale"):
            sections = _scaled(sections, key[: -len("_scale")], value)
    changes: dict[str, Any] = {"sections": sections}
    blade_only = {"tip_mass_kg", "precone_deg", "pitch_deg"} & set(inputs)
    if blade_only and not hasattr(structure, "precone"):
        raise InputError(f"{', '.join(sorted(blade_only))}: only for blades", field=sorted(blade_only)[0])
    if "precone_deg" in inputs:
        changes["precone"] = math.radians(inputs["precone_deg"])
    if "pitch_deg" in inputs:
        changes["pitch"] = math.radians(inputs["pitch_deg"])
    if "tip_mass_kg" in inputs:
        from ..sections import TipMass
        mass = float(inputs["tip_mass_kg"])
        old = structure.tip_mass
        changes["tip_mass"] = None if mass == 0 else (TipMass(mass=mass) if old is None else replace(old, mass=mass))
    return structure.with_(**changes)
