"""windIO turbine ontology (IEA Wind Task 37; versions 1.x and 2.x, as used by the IEA-15MW and IEA-22MW reference
turbines): the blade's and the tower's structural properties and the geometry bladefem needs.

Read (every other entry of the file is ignored):

- ``assembly``: ``number_of_blades``, ``rotor_orientation``;
- ``components.hub``: ``diameter`` (hub radius = diameter / 2), ``cone_angle`` (positive away from the tower for
  upwind and downwind rotors alike; degrees in 2.x, radians in 1.x), ``elastic_properties.mass``;
- ``components.blade`` and ``components.tower``: ``reference_axis`` (x, y, z on normalised arc-length grids),
  ``structure.elastic_properties.stiffness_matrix`` (``grid``, ``K11`` .. ``K66``) and ``inertia_matrix``
  (``grid``, ``mass``, ``cm_x``, ``cm_y``, ``i_edge``, ``i_flap``, ``i_plr``, ``i_cp``); the blade's
  ``outer_shape.twist`` (deg) and, if given, ``outer_shape.chord`` (m, for drawing the planform);
- windIO 1.x blades: ``elastic_properties_mb.six_x_six`` (``reference_axis``, ``twist`` in rad, ``stiff_matrix``
  and ``inertia_matrix``: ``grid`` and, per grid point, the 21 upper-triangle entries of the 6x6 row by row), read
  into the same record (the inertia entries by BeamDyn's mass-matrix form: ``M34 = m cm_y``, ``M35 = -m cm_x``,
  ``M44 = i_edge``, ``M55 = i_flap``, ``M45 = -i_cp``, ``M66 = i_plr``), and ``outer_shape_bem.chord``;
- ``components.drivetrain.elastic_properties.mass`` and ``components.yaw.elastic_properties.mass``.

The blade and the tower are read independently: a part without beam properties (a 1.x tower, or a converted one,
with a layup and no ``elastic_properties``) is None, its reason kept in ``problems`` and raised only when that part
is asked for; a malformed value in a part that has them is an error at once. Every problem is an
:class:`InputError` naming the file, the YAML line and the key path. When the
``windio`` package and ``jsonschema`` are installed, the 2.x ``elastic_properties`` objects are also validated
against windIO's own ``beam`` schema.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError, shown
from ..limits import MAX_MAGNITUDE
from ..sections.checks import MAX_JUMP, MAX_REACH, MAX_TWIST, precone_problem
from .windio_schema import validate_with_windio
from .yamlnodes import Key, load_yaml

STIFFNESS_KEYS = tuple(f"K{i}{j}" for i in range(1, 7) for j in range(i, 7))
INERTIA_KEYS = ("mass", "cm_x", "cm_y", "i_edge", "i_flap", "i_plr", "i_cp")
#: Section properties checked for absurd magnitudes and for jumps between neighbouring grid points
PROPERTIES = tuple(f"K{i}{i}" for i in range(1, 7)) + ("mass", "i_edge", "i_flap", "i_plr", "i_cp")


@dataclass(frozen=True)
class Distribution:
    """A quantity on a normalised arc-length grid (grid from 0 to 1)."""

    grid: NDArray[np.float64]
    values: NDArray[np.float64]

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, Distribution) and np.array_equal(self.grid, other.grid)
                and np.array_equal(self.values, other.values))


@dataclass(frozen=True)
class WindIOBeam:
    """A blade's or tower's structural description as given in windIO (SI; twist in rad).

    reference_axis : 'x', 'y', 'z' -> distributions, m
    stiffness : K11 .. K66 present in the file -> values on ``stiffness_grid`` (N, N m^2)
    inertia : mass (kg/m), cm_x, cm_y (m), i_edge, i_flap, i_plr, i_cp (kg m) present -> values on ``inertia_grid``
    twist : the blade's outer_shape twist (rad), or None for a tower
    chord : the blade's outer_shape chord (m), if given (planform drawing only)
    """

    reference_axis: dict[str, Distribution]
    stiffness_grid: NDArray[np.float64]
    stiffness: dict[str, NDArray[np.float64]]
    inertia_grid: NDArray[np.float64]
    inertia: dict[str, NDArray[np.float64]]
    twist: Distribution | None = None
    chord: Distribution | None = None

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, WindIOBeam):
            return NotImplemented
        def same(a: dict, b: dict) -> bool:
            return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)

        return (self.reference_axis == other.reference_axis and self.twist == other.twist
                and self.chord == other.chord
                and np.array_equal(self.stiffness_grid, other.stiffness_grid) and same(self.stiffness, other.stiffness)
                and np.array_equal(self.inertia_grid, other.inertia_grid) and same(self.inertia, other.inertia))

    @property
    def length(self) -> float:
        """Arc length of the reference axis, m."""
        return arc_length(self.reference_axis)


@dataclass(frozen=True)
class WindIOTurbine:
    """The parts of a windIO turbine file that bladefem uses.

    cone_angle : hub cone angle, rad, positive away from the tower (as in windIO)
    upwind : rotor_orientation is upwind
    """

    name: str
    number_of_blades: int
    upwind: bool
    hub_radius: float
    cone_angle: float
    hub_mass: float
    drivetrain_mass: float
    yaw_mass: float
    blade: WindIOBeam | None
    tower: WindIOBeam | None
    path: str = field(default="", compare=False)
    #: part ('blade', 'tower') -> why it could not be read (raised when that part is asked for)
    problems: dict[str, InputError] = field(default_factory=dict, compare=False, repr=False)
    lines: dict[Key, int] = field(default_factory=dict, compare=False, repr=False)

    @property
    def precone(self) -> float:
        """bladefem's precone (rad, positive downwind): minus the cone angle for an upwind rotor."""
        return -self.cone_angle if self.upwind else self.cone_angle


def arc_length(axis: dict[str, Distribution]) -> float:
    """Length of the piecewise-linear curve through the reference-axis points (on the union of the grids), m."""
    grid = np.unique(np.concatenate([d.grid for d in axis.values()]))
    points = np.stack([np.interp(grid, axis[c].grid, axis[c].values) for c in ("x", "y", "z")])
    return float(np.sum(np.linalg.norm(np.diff(points, axis=1), axis=0)))


def _as_number(value: Any) -> float | None:
    """A finite float from a YAML scalar (numbers resolve by YAML 1.2, so ``1.0e9`` is one); None otherwise."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        return None
    return float(value)


class _Reader:
    """Typed access to the parsed YAML, errors naming the line and the key path."""

    def __init__(self, path: str, data: Any, lines: dict[Key, int]):
        self.path, self.data, self.lines = path, data, lines

    def error(self, message: str, key: Key) -> InputError:
        line = None
        for n in range(len(key), -1, -1):
            if key[:n] in self.lines:
                line = self.lines[key[:n]]
                break
        return InputError(message, file=self.path, line=line, field=".".join(str(k) for k in key) or None)

    def get(self, key: Key, default: Any = ...) -> Any:
        node = self.data
        for i, k in enumerate(key):
            if not isinstance(node, dict) or k not in node:
                if default is not ...:
                    return default
                raise self.error("missing key", key[:i + 1])
            node = node[k]
        return node

    def mapping(self, key: Key) -> dict:
        value = self.get(key)
        if not isinstance(value, dict):
            raise self.error(f"expected a mapping of keys, got {type(value).__name__}", key)
        return value

    def number(self, key: Key, default: Any = ..., minimum: float | None = None) -> float:
        raw = self.get(key, default)
        value = _as_number(raw)
        if value is None:
            raise self.error(f"expected a finite number, got {shown(raw)}", key)
        if abs(value) > MAX_MAGNITUDE:
            raise self.error(f"{value:g} is beyond any real blade or tower (|value| up to {MAX_MAGNITUDE:g})", key)
        if minimum is not None and value < minimum:
            raise self.error(f"must be at least {minimum}, got {value}", key)
        return value

    def array(self, key: Key, length: int | None = None, minimum: float | None = None,
              positive: bool = False) -> NDArray[np.float64]:
        value = self.get(key)
        if not isinstance(value, list) or len(value) < 2:
            raise self.error("expected a list of at least two numbers", key)
        numbers = [_as_number(item) for item in value]
        for i, item in enumerate(numbers):
            if item is None:
                raise self.error(f"expected a finite number, got {shown(value[i])}", key + (i,))
            if positive and item <= 0:
                raise self.error(f"must be positive, got {item}", key + (i,))
            if minimum is not None and item < minimum:
                raise self.error(f"must be at least {minimum}, got {item}", key + (i,))
            if abs(item) > MAX_MAGNITUDE or (key[-1] in PROPERTIES and 0 < abs(item) < 1 / MAX_MAGNITUDE):
                raise self.error(f"{item:g} is beyond any real blade or tower (SI magnitudes from "
                                 f"{1 / MAX_MAGNITUDE:g} to {MAX_MAGNITUDE:g})", key + (i,))
        if key[-1] in PROPERTIES and all(item > 0 for item in numbers):  # type: ignore[operator]
            for i in range(1, len(numbers)):
                ratio = numbers[i] / numbers[i - 1]  # type: ignore[operator]
                if not 1 / MAX_JUMP <= ratio <= MAX_JUMP:
                    raise self.error(f"jumps from {numbers[i - 1]:g} to {numbers[i]:g} between neighbouring grid "
                                     f"points (more than {MAX_JUMP:g} times: a unit slip?)", key + (i,))
        if length is not None and len(value) != length:
            raise self.error(f"expected {length} values (one per grid point), got {len(value)}", key)
        return np.array(numbers, dtype=float)

    def grid(self, key: Key) -> NDArray[np.float64]:
        grid = self.array(key)
        if grid[0] != 0.0 or grid[-1] != 1.0:
            raise self.error("grid must run from 0 to 1", key)
        steps = np.flatnonzero(np.diff(grid) <= 0)
        if steps.size:
            raise self.error("grid must increase strictly", key + (int(steps[0]) + 1,))
        return grid

    def distribution(self, key: Key, scale: float = 1.0) -> Distribution:
        grid = self.grid(key + ("grid",))
        return Distribution(grid, self.array(key + ("values",), len(grid)) * scale)


def read_windio(path: str | Path) -> WindIOTurbine:
    """Read the blade and tower structure of a windIO turbine file."""
    try:
        data, lines = load_yaml(path)
    except InputError as error:
        raise InputError(error.message, file=error.file, line=error.line or 1,
                         field=error.field or "YAML syntax") from None
    r = _Reader(str(path), data, lines)
    if not isinstance(data, dict) or "components" not in data:
        raise InputError("not a windIO turbine file (no 'components')", file=str(path), line=1, field="components")
    components = r.mapping(("components",))
    version1 = isinstance(components.get("blade"), dict) and (
        "elastic_properties_mb" in components["blade"] or "outer_shape_bem" in components["blade"])
    parts: dict[str, WindIOBeam | None] = {"blade": None, "tower": None}
    problems: dict[str, InputError] = {}
    for part in parts:
        if part not in components:
            continue
        given = components[part] if isinstance(components[part], dict) else {}
        structure = given.get("structure")
        if part == "blade" and version1:
            parts[part] = _beam_v1(r, ("components", "blade"))
        elif isinstance(structure, dict) and "elastic_properties" in structure:
            parts[part] = _beam(r, ("components", part), twist=part == "blade")
        else:
            key = ("components", part) + (("structure",) if isinstance(structure, dict) else ())
            problems[part] = r.error(f"the {part} has no elastic_properties (only its geometry or a composite "
                                     "layup, which bladefem does not reduce to beam properties)",
                                     key + ("elastic_properties",))
    if parts["blade"] is None and parts["tower"] is None:
        if problems:
            raise problems.get("blade", problems.get("tower"))  # type: ignore[misc]
        raise r.error("neither a blade nor a tower", ("components",))
    orientation = str(r.get(("assembly", "rotor_orientation"), "upwind")).lower()
    if orientation not in ("upwind", "downwind"):
        raise r.error(f"expected upwind or downwind, got '{orientation}'", ("assembly", "rotor_orientation"))
    blades = r.number(("assembly", "number_of_blades"), 3, minimum=1)
    if blades != int(blades):
        raise r.error(f"expected an integer, got {blades}", ("assembly", "number_of_blades"))
    if not version1:
        validate_with_windio(r, [p for p in parts if parts[p] is not None])
    return WindIOTurbine(
        name=str(data.get("name", Path(path).stem)),
        number_of_blades=int(blades),
        upwind=orientation == "upwind",
        hub_radius=r.number(("components", "hub", "diameter"), 0.0, minimum=0) / 2,
        cone_angle=_cone_angle(r, radians=version1),
        hub_mass=r.number(("components", "hub", "elastic_properties", "mass"), 0.0, minimum=0),
        drivetrain_mass=r.number(("components", "drivetrain", "elastic_properties", "mass"), 0.0, minimum=0),
        yaw_mass=r.number(("components", "yaw", "elastic_properties", "mass"), 0.0, minimum=0),
        blade=parts["blade"], tower=parts["tower"], path=str(path), lines=lines, problems=problems)


def _cone_angle(r: _Reader, radians: bool = False) -> float:
    """The hub's cone angle, rad (given in degrees, in radians by windIO 1.x), within ElastoDyn's precone range."""
    key = ("components", "hub", "cone_angle")
    angle = r.number(key, 0.0) if radians else math.radians(r.number(key, 0.0))
    problem = precone_problem(angle)
    if problem:
        raise r.error(problem.replace("precone", "cone_angle"), key)
    return angle


def _beam(r: _Reader, key: Key, twist: bool) -> WindIOBeam:
    axis = {c: r.distribution(key + ("reference_axis", c)) for c in ("x", "y", "z")}
    elastic = key + ("structure", "elastic_properties")
    stiffness_grid = r.grid(elastic + ("stiffness_matrix", "grid"))
    given = r.mapping(elastic + ("stiffness_matrix",))
    stiffness = {k: r.array(elastic + ("stiffness_matrix", k), len(stiffness_grid)) for k in STIFFNESS_KEYS
                 if k in given}
    for k in ("K44", "K55"):
        if k not in stiffness:
            raise r.error("missing key", elastic + ("stiffness_matrix", k))
        r.array(elastic + ("stiffness_matrix", k), positive=True)
    inertia_grid = r.grid(elastic + ("inertia_matrix", "grid"))
    present = r.mapping(elastic + ("inertia_matrix",))
    inertia = {k: r.array(elastic + ("inertia_matrix", k), len(inertia_grid),
                          minimum=0.0 if k in ("i_edge", "i_flap", "i_plr") else None)
               for k in INERTIA_KEYS if k in present}
    if "mass" not in inertia:
        raise r.error("missing key", elastic + ("inertia_matrix", "mass"))
    r.array(elastic + ("inertia_matrix", "mass"), positive=True)
    beam_twist = r.distribution(key + ("outer_shape", "twist"), math.pi / 180) if twist else None
    if beam_twist is not None and np.any(np.abs(beam_twist.values) > MAX_TWIST):
        i = int(np.flatnonzero(np.abs(beam_twist.values) > MAX_TWIST)[0])
        raise r.error("twist beyond a half turn (degrees expected)", key + ("outer_shape", "twist", "values", i))
    shape = r.get(key + ("outer_shape",), None)
    chord = (r.distribution(key + ("outer_shape", "chord"))
             if twist and isinstance(shape, dict) and "chord" in shape else None)
    beam = WindIOBeam(axis, stiffness_grid, stiffness, inertia_grid, inertia, beam_twist, chord)
    if not beam.length > 0:
        raise r.error("reference axis has zero length", key + ("reference_axis",))
    _check_reach(r, elastic + ("inertia_matrix",), inertia, MAX_REACH * beam.length)
    return beam


def _matrices(r: _Reader, key: Key, length: int) -> list[NDArray[np.float64]]:
    """The 21 upper-triangle entries per grid point of a windIO 1.x six_x_six matrix."""
    values = r.get(key + ("values",))
    if not isinstance(values, list) or len(values) != length:
        raise r.error(f"expected {length} rows of 21 numbers (one per grid point)", key + ("values",))
    rows = []
    for i, entry in enumerate(values):
        if not isinstance(entry, list) or len(entry) != 21:
            raise r.error("expected the 21 upper-triangle entries of the 6x6, row by row", key + ("values", i))
        numbers = [_as_number(v) for v in entry]
        for j, v in enumerate(numbers):
            if v is None:
                raise r.error(f"expected a finite number, got {shown(entry[j])}", key + ("values", i, j))
        rows.append(np.array(numbers, dtype=float))
    return rows


def _beam_v1(r: _Reader, key: Key) -> WindIOBeam:
    """A windIO 1.x blade (elastic_properties_mb.six_x_six) as the 2.x record."""
    six = key + ("elastic_properties_mb", "six_x_six")
    if not isinstance(r.get(six, None), dict):
        raise r.error("a windIO 1.x blade without its six_x_six matrices (elastic_properties_mb.six_x_six)", six)
    axis_key = six + ("reference_axis",) if "reference_axis" in r.mapping(six) else key + (
        "outer_shape_bem", "reference_axis")
    axis = {c: r.distribution(axis_key + (c,)) for c in ("x", "y", "z")}
    stiffness_grid = r.grid(six + ("stiff_matrix", "grid"))
    upper = np.array(_matrices(r, six + ("stiff_matrix",), len(stiffness_grid)))
    stiffness = {name: upper[:, n] for n, name in enumerate(STIFFNESS_KEYS)}
    for name in ("K44", "K55"):
        bad = np.flatnonzero(stiffness[name] <= 0)
        if bad.size:
            raise r.error(f"{name} must be positive, got {stiffness[name][bad[0]]}",
                          six + ("stiff_matrix", "values", int(bad[0])))
    inertia_grid = r.grid(six + ("inertia_matrix", "grid"))
    M = np.array(_matrices(r, six + ("inertia_matrix",), len(inertia_grid)))
    entry = {name: M[:, n] for n, name in enumerate(STIFFNESS_KEYS)}
    mass = entry["K11"]
    bad = np.flatnonzero(mass <= 0)
    if bad.size:
        raise r.error(f"mass (entry 1,1) must be positive, got {mass[bad[0]]}",
                      six + ("inertia_matrix", "values", int(bad[0])))
    inertia = {"mass": mass, "cm_x": -entry["K35"] / mass, "cm_y": entry["K34"] / mass, "i_edge": entry["K44"],
               "i_flap": entry["K55"], "i_plr": entry["K66"], "i_cp": -entry["K45"]}
    twist_key = six + ("twist",) if "twist" in r.mapping(six) else key + ("outer_shape_bem", "twist")
    twist = r.distribution(twist_key)
    if np.any(np.abs(twist.values) > MAX_TWIST):
        i = int(np.flatnonzero(np.abs(twist.values) > MAX_TWIST)[0])
        raise r.error("twist beyond a half turn (windIO 1.x gives radians)", twist_key + ("values", i))
    shape = r.get(key + ("outer_shape_bem",), None)
    chord = (r.distribution(key + ("outer_shape_bem", "chord"))
             if isinstance(shape, dict) and "chord" in shape else None)
    beam = WindIOBeam(axis, stiffness_grid, stiffness, inertia_grid, inertia, twist, chord)
    if not beam.length > 0:
        raise r.error("reference axis has zero length", axis_key)
    _check_reach(r, six + ("inertia_matrix",), inertia, MAX_REACH * beam.length)
    return beam


def _check_reach(r: _Reader, key: Key, inertia: dict[str, NDArray], reach: float) -> None:
    """Centre-of-mass offsets and radii of gyration within :data:`~bladefem.sections.checks.MAX_REACH` beam lengths."""
    for name, values in inertia.items():
        gyration = name.startswith("i_")
        far = values > inertia["mass"] * reach**2 if gyration else np.abs(values) > reach
        if name != "mass" and np.any(far):
            raise r.error(f"{'radius of gyration' if gyration else 'offset'} beyond {MAX_REACH:g} beam lengths "
                          f"({reach / MAX_REACH:g} m)", key + (name, int(np.flatnonzero(far)[0])))
