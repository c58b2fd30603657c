"""A ``bladefem check`` spec: the models and their requirements, read from YAML and validated against the schema.

Paths inside a spec (model inputs, baseline files) are relative to the spec file. Errors name the spec file, the
line and the field.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..formats.yamlnodes import load_yaml
from .schema import AERODYNAMIC, KINDS, SPEC_SCHEMA

DEFAULT_RPM_POINTS = 16
DEFAULT_BLADES = 3
DEFAULT_MODES = 8


@dataclass(frozen=True)
class ModelSpec:
    """One model of a spec.

    name : the model's name in the spec
    input : input file (absolute, or relative to the working directory)
    operating_rpm : operating rotor-speed range (min, max), rpm, or None
    rpm_points : rotor speeds of the Campbell sweep over the operating range
    blades : number of blades (the tower's band is [1P max, blades x P min])
    n_modes : modes solved and tracked
    elements : fixed element count, or None for a converged mesh
    geometry : geometry overrides in SI units (tip_radius, hub_radius, precone, pitch, tip_mass), None when absent
    elastodyn_main : ElastoDyn main file for an ElastoDyn blade file, or None
    aerodyn : AeroDyn primary file of the blade's aerodynamics, or None
    line : line of the model in the spec
    """

    name: str
    input: Path
    operating_rpm: tuple[float, float] | None = None
    rpm_points: int = DEFAULT_RPM_POINTS
    blades: int = DEFAULT_BLADES
    n_modes: int = DEFAULT_MODES
    elements: int | None = None
    geometry: dict[str, float] = field(default_factory=dict)
    elastodyn_main: Path | None = None
    aerodyn: Path | None = None
    line: int | None = None


@dataclass(frozen=True)
class Requirement:
    """One requirement: its kind (``window``, ``resonance``, ``soft_stiff``, ``baseline``, ``elastodyn``), the
    model it applies to, its parameters as written (paths resolved), a display name and its line in the spec."""

    kind: str
    model: str
    parameters: dict[str, Any]
    name: str
    index: int = 0
    source: str = ""
    line: int | None = None

    def error(self, message: str, field: str = "") -> InputError:
        """An :class:`InputError` located at this requirement in the spec file (``field`` below its kind)."""
        where = f"requirements.{self.index}.{self.kind}" + (f".{field}" if field else "")
        return InputError(message, file=self.source, line=self.line, field=where)


@dataclass(frozen=True)
class Spec:
    """A whole spec file."""

    path: Path
    models: dict[str, ModelSpec]
    requirements: list[Requirement]


def _schema_errors(data: Any, path: Path, lines: dict) -> None:
    import jsonschema

    validator = jsonschema.Draft202012Validator(SPEC_SCHEMA)
    error = jsonschema.exceptions.best_match(validator.iter_errors(data))
    if error is None:
        return
    where = tuple(error.absolute_path)
    line = lines.get(where)
    while line is None and where:
        where = where[:-1]
        line = lines.get(where)
    field_name = ".".join(str(part) for part in error.absolute_path) or None
    raise InputError(f"spec schema: {error.message}", file=str(path), line=line, field=field_name)


def _geometry(entry: dict[str, Any]) -> dict[str, Any]:
    geometry = {}
    for key, name, scale in (("tip_radius_m", "tip_radius", 1.0), ("hub_radius_m", "hub_radius", 1.0),
                             ("precone_deg", "precone", math.pi / 180), ("pitch_deg", "pitch", math.pi / 180),
                             ("tip_mass_kg", "tip_mass", 1.0)):
        if key in entry:
            geometry[name] = float(entry[key]) * scale
    for key in ("sections", "axis"):
        if key in entry:
            geometry[key] = entry[key]
    return geometry


def _model(name: str, entry: dict[str, Any], folder: Path, path: Path, lines: dict) -> ModelSpec:
    line = lines.get(("models", name))
    rpm = entry.get("operating_rpm")
    if rpm is not None and not 0 < rpm[0] <= rpm[1]:
        raise InputError(f"need 0 < min <= max, got {rpm}", file=str(path),
                         line=lines.get(("models", name, "operating_rpm")), field=f"models.{name}.operating_rpm")
    main, aerodyn = entry.get("elastodyn_main"), entry.get("aerodyn")
    return ModelSpec(name=name, input=folder / entry["input"],
                     operating_rpm=None if rpm is None else (float(rpm[0]), float(rpm[1])),
                     rpm_points=int(entry.get("rpm_points", DEFAULT_RPM_POINTS)),
                     blades=int(entry.get("blades", DEFAULT_BLADES)),
                     n_modes=int(entry.get("n_modes", DEFAULT_MODES)),
                     elements=entry.get("elements"), geometry=_geometry(entry),
                     elastodyn_main=None if main is None else folder / main,
                     aerodyn=None if aerodyn is None else folder / aerodyn, line=line)


def _requirement(index: int, entry: dict[str, Any], folder: Path, models: dict[str, ModelSpec], path: Path,
                 lines: dict) -> Requirement:
    line = lines.get(("requirements", index))
    kind = next(kind for kind in KINDS if kind in entry)
    if entry["model"] not in models:
        raise InputError(f"unknown model '{entry['model']}' (models: {', '.join(models)})", file=str(path),
                         line=lines.get(("requirements", index, "model")), field=f"requirements.{index}.model")
    parameters = dict(entry[kind])
    for name in ("file", "aero"):
        if name in parameters:
            parameters[name] = folder / parameters[name]
    window = parameters.get("hz")
    if window is not None and window[0] > window[1]:
        raise InputError(f"need low <= high, got {window}", file=str(path),
                         line=lines.get(("requirements", index, kind, "hz")), field=f"requirements.{index}.{kind}.hz")
    model = models[entry["model"]]
    needs_range = kind in ("resonance", "soft_stiff") or parameters.get("rpm") == "operating"
    if needs_range and model.operating_rpm is None:
        raise InputError(f"a '{kind}' requirement needs the model's operating_rpm", file=str(path), line=line,
                         field=f"models.{model.name}.operating_rpm")
    if kind in AERODYNAMIC and model.aerodyn is None:
        raise InputError(f"a '{kind}' requirement needs the model's aerodyn (an AeroDyn primary file)",
                         file=str(path), line=line, field=f"models.{model.name}.aerodyn")
    name = entry.get("name") or f"{entry['model']} {kind.replace('_', '-')}"
    return Requirement(kind=kind, model=entry["model"], parameters=parameters, name=name, index=index,
                       source=str(path), line=line)


def _finite(data: Any, key: tuple, path: Path, lines: dict) -> None:
    """An InputError at the first number that is not finite (the schema's bounds let NaN through)."""
    items = data.items() if isinstance(data, dict) else enumerate(data) if isinstance(data, list) else ()
    for name, value in items:
        if isinstance(value, float) and not math.isfinite(value):
            raise InputError(f"must be a finite number, got {value}", file=str(path), line=lines.get((*key, name)),
                             field=".".join(map(str, (*key, name))))
        _finite(value, (*key, name), path, lines)


def read_spec(path: str | Path) -> Spec:
    """Read and validate a spec file; :class:`InputError` names the file, line and field of the first problem."""
    path = Path(path)
    data, lines = load_yaml(path)
    _schema_errors(data, path, lines)
    _finite(data, (), path, lines)
    folder = path.parent
    models = {name: _model(name, entry, folder, path, lines) for name, entry in data["models"].items()}
    requirements = [_requirement(i, entry, folder, models, path, lines)
                    for i, entry in enumerate(data["requirements"])]
    return Spec(path=path, models=models, requirements=requirements)
