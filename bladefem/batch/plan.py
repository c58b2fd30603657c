"""A batch plan: the base model, what varies (a grid, random samples or a list of files) and the analysis per case,
read from YAML, validated against a JSON Schema (errors name the line), and expanded into cases.

    model: nrel5mw_blade.yaml                 # any input bladefem reads, relative to the plan
    analysis: {type: modes, rpm: 12.1, n_modes: 6}
    samples:                                  # or grid: {flap_stiffness_scale: [0.9, 1, 1.1], rpm: [6.9, 12.1]}
      count: 64                               # or files: [a.yaml, b.bmi]
      seed: 2026
      properties:
        mass: {distribution: uniform, half_width_percent: 5}
        flap_stiffness: {distribution: normal, std_percent: 5, correlation_length: 0.3}
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any


from ..errors import InputError
from ..files import check_input
from ..formats.yamlnodes import load_yaml
from .bundle import Bundle, bundle_of
from .cases import COLUMNS, SCALES, Case, case_hash, file_digest
from .flutter import PROPERTIES as FLUTTER_PROPERTIES
from .flutter import check_grid, flutter_fields
from .samples import sample_cases
from .standstill import PROPERTIES as STANDSTILL_PROPERTIES
from .standstill import standstill_fields

ANALYSES = ("modes", "campbell", "check", "turbine_simulate", "turbine_linearize", "standstill", "flutter")
#: analyses of the whole turbine (an OpenFAST deck), not of a blade or tower
TURBINE_ANALYSES = ("turbine_simulate", "turbine_linearize")
DISTRIBUTIONS = ("normal", "uniform", "lognormal")
MAX_CASES = 1_000_000

_NUMBER = {"type": "number"}
#: what a grid may vary, and within which physical bounds (a scale factor within 1e-3..1e3 of the base section
#: property, rotor speed up to the CLI's limit, pitch, cone and tip mass as a turbine can have them)
GRID_BOUNDS: dict[str, tuple[float, float]] = {
    **{f"{c}_scale": (1e-3, 1e3) for c in SCALES}, "tip_mass_kg": (0.0, 1e7), "precone_deg": (-45.0, 45.0),
    "pitch_deg": (-180.0, 180.0), "rpm": (0.0, 1e5), "wind_speed_m_s": (0.0, 100.0),
    "turbulence_seed": (0, 2**32 - 1)}
#: what makes a turbine_simulate case's turbulent box (bladefem.aero.turbulence) and its integrator's relative
#: tolerance, with their JSON Schema
TURBULENCE_KEYS: dict[str, Any] = {
    "turbulence_class": {"enum": ["A", "B", "C"]},
    "turbulence_intensity_percent": {"type": "number", "exclusiveMinimum": 0, "maximum": 50},
    "turbulence_grid": {"type": "integer", "minimum": 3, "maximum": 65},
    "turbulence_dt": {"type": "number", "minimum": 0.01, "maximum": 2},
    "rtol": {"type": "number", "minimum": 1e-13, "maximum": 1e-2}}
PLAN_SCHEMA: dict[str, Any] = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "title": "bladefem batch plan",
    "type": "object",
    "additionalProperties": False,
    "required": ["analysis"],
    "properties": {
        "model": {"type": "string"},
        "elastodyn_main": {"type": "string"},
        "analysis": {
            "type": "object", "additionalProperties": False, "required": ["type"],
            "properties": {
                "type": {"enum": list(ANALYSES)},
                "rpm": {"anyOf": [{"type": "number", "minimum": 0},
                                  {"type": "array", "items": _NUMBER, "minItems": 3, "maxItems": 3}]},
                "n_modes": {"type": "integer", "minimum": 1, "maximum": 30},
                "elements": {"type": "integer", "minimum": 1, "maximum": 5000},
                "spec": {"type": "string"}, "spec_model": {"type": "string"},
                "wind_speed_m_s": {"anyOf": [{"type": "number", "minimum": 0, "maximum": 100},
                                             {"type": "array", "minItems": 3, "maxItems": 3,
                                              "items": {"type": "number", "minimum": 0, "maximum": 1000}}]},
                "pitch_deg": {"type": "number", "minimum": -180, "maximum": 180},
                "seconds": {"type": "number", "exclusiveMinimum": 0, "maximum": 3600},
                "dt": {"type": "number", "exclusiveMinimum": 0, "maximum": 10},
                "statistics_from_s": {"type": "number", "minimum": 0},
                "induction": {"enum": ["frozen", "quasi-steady"]},
                "foundation": {"enum": ["rigid"]},
                "quasi_steady": {"type": "boolean"},
                "elastodyn_blades": {"type": "boolean"},
                **STANDSTILL_PROPERTIES,
                **FLUTTER_PROPERTIES,
                **TURBULENCE_KEYS,
            },
        },
        "grid": {"type": "object", "minProperties": 1, "additionalProperties": False,
                 "properties": {name: {"type": "array", "minItems": 1,
                                       "items": {"type": "number", "minimum": low, "maximum": high}}
                                for name, (low, high) in GRID_BOUNDS.items()}},
        "samples": {
            "type": "object", "additionalProperties": False, "required": ["count", "seed", "properties"],
            "properties": {
                "count": {"type": "integer", "minimum": 1, "maximum": MAX_CASES},
                "seed": {"type": "integer", "minimum": 0, "maximum": 2**63 - 1},
                "properties": {
                    "type": "object", "minProperties": 1, "propertyNames": {"enum": list(SCALES)},
                    "additionalProperties": {
                        "type": "object", "additionalProperties": False, "required": ["distribution"],
                        "properties": {
                            "distribution": {"enum": list(DISTRIBUTIONS)},
                            "std_percent": {"type": "number", "exclusiveMinimum": 0, "maximum": 50},
                            "half_width_percent": {"type": "number", "exclusiveMinimum": 0, "maximum": 90},
                            "sigma": {"type": "number", "exclusiveMinimum": 0, "maximum": 2},
                            "correlation_length": {"type": "number", "exclusiveMinimum": 0,
                                                   "description": "along the span, as a fraction of its length"},
                        },
                    },
                },
            },
        },
        "files": {"type": "array", "items": {"type": "string"}, "minItems": 1},
    },
    "oneOf": [{"required": ["grid"]}, {"required": ["samples"]}, {"required": ["files"]}],
}


@dataclass(frozen=True)
class Analysis:
    """What each case computes: 'modes' at ``rpm`` (rpm), a 'campbell' sweep over ``sweep`` (start, stop, count
    rpm), the requirements of ``spec`` (a check spec) on its model ``spec_model``, or 'turbine_simulate': the
    turbine of an OpenFAST deck simulated for ``seconds`` (s, output every ``dt`` s) at ``wind_speed`` (m/s),
    ``turbine_rpm`` (rpm, generator locked) and ``pitch_deg`` (deg), each None for the deck's, with statistics
    from ``statistics_from`` (s) to the end, or 'turbine_linearize' there with the BEM ``induction`` frozen or
    quasi-steady; or 'standstill': the parked blade's damping against yaw (:mod:`bladefem.batch.standstill`) with
    the AeroDyn file ``aerodyn``, yaw ``yaw_sweep`` (start, stop, count deg), ``azimuths`` (deg), ``tilt_deg``,
    ``structural`` damping (flap, edge, torsion %) and ``damping_only``; or 'flutter': the blade's flutter onset
    (:mod:`bladefem.batch.flutter`) along the rotor-speed ``sweep`` at ``wind_speed`` or the ``wind_sweep`` at
    ``rpm``, with ``aerodyn`` and ``blades``."""

    type: str
    rpm: float = 0.0
    sweep: tuple[float, float, int] | None = None
    n_modes: int = 6
    elements: int | None = None
    spec: Path | None = None
    spec_model: str | None = None
    wind_speed: float | None = None
    turbine_rpm: float | None = None
    pitch_deg: float | None = None
    seconds: float | None = None
    dt: float = 0.05
    statistics_from: float = 0.0
    induction: str = "frozen"
    #: the turbulent box of each case (class or intensity in percent, grid points, time step), None: the deck's wind
    turbulence: tuple[str | None, float | None, int, float] | None = None
    #: relative tolerance of a turbine_simulate case's integrator (absolute: a hundredth of it)
    rtol: float = 1e-6
    #: the command line's ways forward the deck needs (``--foundation rigid``, ``--quasi-steady``,
    #: ``--elastodyn-blades``): what bladefem does not model is left out, and said so, instead of refused
    leave_out: tuple[str, ...] = ()
    aerodyn: Path | None = None
    yaw_sweep: tuple[float, float, int] | None = None
    azimuths: tuple[float, ...] = (0.0,)
    tilt_deg: float = 0.0
    structural: tuple[float, ...] = ()
    damping_only: bool = False
    #: a flutter analysis's wind-speed sweep (start, stop, count m/s; its rotor-speed sweep is ``sweep``) and blades
    wind_sweep: tuple[float, float, int] | None = None
    blades: int = 3

    def key(self) -> dict[str, Any]:
        key = {"type": self.type, "rpm": self.rpm, "sweep": self.sweep, "n_modes": self.n_modes,
               "elements": self.elements, "spec": None if self.spec is None else file_digest(self.spec),
               "spec_model": self.spec_model}
        if self.type in TURBINE_ANALYSES:
            key.update(wind_speed=self.wind_speed, turbine_rpm=self.turbine_rpm, pitch_deg=self.pitch_deg,
                       seconds=self.seconds, dt=self.dt, statistics_from=self.statistics_from,
                       induction=self.induction, leave_out=list(self.leave_out))
            if self.turbulence is not None:
                key.update(turbulence=list(self.turbulence))
            if self.rtol != 1e-6:
                key.update(rtol=self.rtol)
        if self.type == "standstill":
            key.update(aerodyn=None if self.aerodyn is None else file_digest(self.aerodyn),
                       wind_speed=self.wind_speed, pitch_deg=self.pitch_deg, yaw_sweep=self.yaw_sweep,
                       azimuths=list(self.azimuths), tilt_deg=self.tilt_deg, structural=list(self.structural),
                       damping_only=self.damping_only, leave_out=list(self.leave_out))
        if self.type == "flutter":
            key.update(aerodyn=None if self.aerodyn is None else file_digest(self.aerodyn),
                       wind_speed=self.wind_speed, wind_sweep=self.wind_sweep, pitch_deg=self.pitch_deg,
                       blades=self.blades)
        return key


@dataclass(frozen=True)
class Plan:
    """A plan read from ``path``: the analysis and its expanded cases (in a fixed order)."""

    path: Path
    analysis: Analysis
    cases: list[Case] = field(repr=False)
    varied: tuple[str, ...] = ()
    bundles: dict[str, Bundle] = field(default_factory=dict, repr=False)

    def inputs(self) -> list[Path]:
        """Every file the batch reads: the plan and each case's input files."""
        return [self.path, *(path for bundle in self.bundles.values() for path in bundle.paths)]


def _validate(data: Any, path: Path, lines: dict) -> None:
    import jsonschema
    error = jsonschema.exceptions.best_match(jsonschema.Draft202012Validator(PLAN_SCHEMA).iter_errors(data))
    if error is not None:
        where = tuple(error.absolute_path)
        raise InputError(f"plan schema: {error.message}", file=str(path),
                         line=_line(lines, where), field=".".join(map(str, where)) or None)


def _line(lines: dict, where: tuple) -> int | None:
    """The line of the plan entry at ``where`` (key path), else of the nearest entry holding it, else line 1."""
    while where:
        if where in lines:
            return lines[where]
        where = where[:-1]
    return lines.get((), 1)


def _turbine_analysis(entry: dict[str, Any], path: Path, lines: dict) -> Analysis:
    def refuse(message: str, field_: str) -> InputError:
        return InputError(message, file=str(path), line=_line(lines, ("analysis", field_)), field=f"analysis.{field_}")

    simulate = entry["type"] == "turbine_simulate"
    own = ("seconds", "dt", "statistics_from_s", *TURBULENCE_KEYS) if simulate else ("induction",)
    for key in ("n_modes", "elements", "spec", "spec_model", "seconds", "dt", "statistics_from_s", "induction",
                *TURBULENCE_KEYS):
        if key in entry and key not in own:
            raise refuse(f"not an input of a {entry['type']} analysis", key)
    rpm = entry.get("rpm")
    if isinstance(rpm, list):
        raise refuse("a turbine analysis takes one rotor speed (rpm)", "rpm")
    ways = tuple(way for way, taken in (("--foundation rigid", entry.get("foundation") == "rigid"),
                                        ("--quasi-steady", entry.get("quasi_steady", False)),
                                        ("--elastodyn-blades", entry.get("elastodyn_blades", False))) if taken)
    if not simulate:
        return Analysis(entry["type"], wind_speed=entry.get("wind_speed_m_s"), turbine_rpm=rpm,
                        pitch_deg=entry.get("pitch_deg"), induction=entry.get("induction", "frozen"),
                        leave_out=ways)
    if "seconds" not in entry:
        raise refuse("a turbine_simulate analysis needs seconds (the simulated time, s)", "type")
    seconds, dt = float(entry["seconds"]), float(entry.get("dt", 0.05))
    start = float(entry.get("statistics_from_s", seconds / 2))
    if dt > seconds or start >= seconds:
        raise refuse(f"need dt <= seconds and statistics_from_s < seconds ({seconds:g} s)",
                     "dt" if dt > seconds else "statistics_from_s")
    turbulence = None
    if "turbulence_class" in entry and "turbulence_intensity_percent" in entry:
        raise refuse("give a turbulence class or an intensity, not both", "turbulence_intensity_percent")
    if "turbulence_class" in entry or "turbulence_intensity_percent" in entry:
        turbulence = (entry.get("turbulence_class"), entry.get("turbulence_intensity_percent"),
                      int(entry.get("turbulence_grid", 9)), float(entry.get("turbulence_dt", 0.25)))
    else:
        for key in ("turbulence_grid", "turbulence_dt"):
            if key in entry:
                raise refuse("needs turbulence_class or turbulence_intensity_percent", key)
    return Analysis(entry["type"], wind_speed=entry.get("wind_speed_m_s"), turbine_rpm=rpm,
                    pitch_deg=entry.get("pitch_deg"), seconds=seconds, dt=dt, statistics_from=start, leave_out=ways,
                    turbulence=turbulence, rtol=float(entry.get("rtol", 1e-6)))


def _analysis(entry: dict[str, Any], folder: Path, path: Path, lines: dict) -> Analysis:
    kind = entry["type"]

    def refuse(message: str, key: str) -> InputError:
        return InputError(message, file=str(path), line=_line(lines, ("analysis", key)), field=f"analysis.{key}")
    if isinstance(entry.get("wind_speed_m_s"), list) and kind != "flutter":
        raise refuse(f"a {kind} analysis takes one wind speed", "wind_speed_m_s")
    if kind in TURBINE_ANALYSES:
        return _turbine_analysis(entry, path, lines)
    if kind in ("standstill", "flutter"):
        fields = standstill_fields if kind == "standstill" else flutter_fields
        return Analysis(kind, **fields(entry, refuse, lambda name, where: _input_file(name, folder, path, lines,
                                                                                        where)))
    for key in ("wind_speed_m_s", "seconds", "dt", "statistics_from_s", "pitch_deg", "induction", *TURBULENCE_KEYS):
        if key in entry:
            raise InputError(f"an input of the turbine analyses, not of {kind}", file=str(path),
                             line=_line(lines, ("analysis", key)), field=f"analysis.{key}")
    rpm = entry.get("rpm", 0.0)
    sweep = None
    if kind == "campbell":
        if not isinstance(rpm, list):
            raise InputError("a campbell analysis needs rpm: [START, STOP, COUNT]", file=str(path),
                             line=_line(lines, ("analysis",)), field="analysis.rpm")
        start, stop, count = rpm
        if not (0 <= start <= stop and float(count).is_integer() and 1 <= count <= 1000):
            raise InputError(f"need 0 <= START <= STOP and 1 <= COUNT <= 1000, got {rpm}", file=str(path),
                             line=_line(lines, ("analysis", "rpm")), field="analysis.rpm")
        sweep, rpm = (float(start), float(stop), int(count)), 0.0
    elif isinstance(rpm, list):
        raise InputError(f"a {kind} analysis takes one rotor speed", file=str(path),
                         line=_line(lines, ("analysis", "rpm")), field="analysis.rpm")
    spec = entry.get("spec")
    if kind == "check" and (spec is None or "spec_model" not in entry):
        raise InputError("a check analysis needs spec (a check spec file) and spec_model (its model)",
                         file=str(path), line=_line(lines, ("analysis",)), field="analysis")
    if spec is not None:
        spec = _input_file(spec, folder, path, lines, ("analysis", "spec"))
    return Analysis(kind, float(rpm), sweep, int(entry.get("n_modes", 6)), entry.get("elements"), spec,
                    entry.get("spec_model"))


def _input_file(name: str, folder: Path, plan: Path, lines: dict, where: tuple) -> Path:
    """The file a plan field names (relative to the plan), made absolute (a worker runs in another folder) and
    checked before anything reads it: a readable regular file of a sane size (a device such as /dev/zero or a FIFO
    is never opened)."""
    path = (folder / name).absolute()
    try:
        check_input(path)
    except InputError as error:
        raise InputError(f"{path}: {error.message}", file=str(plan), line=_line(lines, where),
                         field=".".join(map(str, where))) from None
    return path


def _bundle(analysis: Analysis, model: Path, main: Path | None) -> Bundle:
    """The files a case of ``model`` reads, found by reading them once here (see :mod:`bladefem.batch.bundle`)."""
    named = [model] + [p for p in (main, analysis.spec, analysis.aerodyn) if p is not None]
    if analysis.type in TURBINE_ANALYSES:
        from ..builders.turbine_deck import read_turbine_deck
        ways = set(analysis.leave_out) | {"--rpm"}         # each case refuses a controller it has no rpm for
        dynamic = analysis.type == "turbine_simulate"     # a time simulation models the dynamic wake
        return bundle_of(lambda: read_turbine_deck(model, leave_out=ways, dynamic_wake=dynamic), named)
    from ..check.models import read_structure

    def read() -> None:
        if analysis.spec is not None:
            from ..check import read_spec
            read_spec(analysis.spec)
        structure = read_structure(model, main)
        if analysis.aerodyn is not None:
            from . import flutter, standstill
            (flutter if analysis.type == "flutter" else standstill).rotor_of(analysis, structure)
    return bundle_of(read, named)


def read_plan(path: str | Path) -> Plan:
    """Read, validate and expand a plan; :class:`InputError` names the file, line and field of a problem."""
    from .cases import station_fractions
    path = Path(path)
    data, lines = load_yaml(path)
    _validate(data, path, lines)
    folder = path.parent
    analysis = _analysis(data["analysis"], folder, path, lines)
    main = data.get("elastodyn_main")
    main = None if main is None else _input_file(main, folder, path, lines, ("elastodyn_main",))
    if "files" in data:
        variants = [{"file": str(_input_file(name, folder, path, lines, ("files", i)))}
                    for i, name in enumerate(data["files"])]
        base = None
    else:
        if "model" not in data:
            raise InputError("a grid or samples plan needs 'model' (the base input)", file=str(path), line=1,
                             field="model")
        base = _input_file(data["model"], folder, path, lines, ("model",))
        if analysis.type in TURBINE_ANALYSES and "samples" in data:
            raise InputError("samples scatter blade section properties: a turbine analysis varies wind_speed_m_s, "
                             "rpm and pitch_deg in a grid, or decks in files", file=str(path),
                             line=_line(lines, ("samples",)), field="samples")
        windy = (*TURBINE_ANALYSES, "standstill", "flutter")
        if analysis.type not in windy and "wind_speed_m_s" in data.get("grid", {}):
            raise InputError(f"a turbine input: a {analysis.type} analysis has no wind", file=str(path),
                             line=_line(lines, ("grid", "wind_speed_m_s")), field="grid.wind_speed_m_s")
        if "turbulence_seed" in data.get("grid", {}) and analysis.turbulence is None:
            raise InputError("turbulence boxes need analysis.turbulence_class or turbulence_intensity_percent",
                             file=str(path), line=_line(lines, ("grid", "turbulence_seed")),
                             field="grid.turbulence_seed")
        if analysis.type == "flutter":
            check_grid(analysis, data.get("grid", {}), lambda key: InputError(
                f"{key} is the flutter analysis's sweep: a grid varies the other speed", file=str(path),
                line=_line(lines, ("grid", key)), field=f"grid.{key}"))
        if "grid" in data:
            names = list(data["grid"])
            variants = [dict(zip(names, values)) for values in itertools.product(*data["grid"].values())]
        else:
            variants = sample_cases(data["samples"], path, station_fractions(base, main))
    if len(variants) > MAX_CASES:
        raise InputError(f"{len(variants)} cases: at most {MAX_CASES}", file=str(path), field="grid")
    varied = tuple(variants[0])
    cases = []
    bundles: dict[Path, Bundle] = {}
    for index, inputs in enumerate(variants):
        model = Path(inputs["file"]) if "file" in inputs else base
        if model not in bundles:
            bundles[model] = _bundle(analysis, model, main)
        bundle = bundles[model]
        cases.append(Case(index=index, model=model, elastodyn_main=main, inputs=inputs, analysis=analysis,
                          hash=case_hash(bundle.content, inputs, analysis.key()), bundle=bundle.digest))
    return Plan(path=path, analysis=analysis, cases=cases, varied=tuple(v for v in varied if v in COLUMNS or
                                                                        v == "file" or v.endswith("_scale")),
                bundles={bundle.digest: bundle for bundle in bundles.values()})


__all__ = ["ANALYSES", "TURBINE_ANALYSES", "Analysis", "PLAN_SCHEMA", "Plan", "read_plan"]
