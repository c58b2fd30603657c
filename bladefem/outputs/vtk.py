"""VTK export of mode shapes (meshio): the blade as a line along its reference axis and, when the chord is known,
as a surface ribbon of its planform; one collection (``.pvd``) indexed by rotor speed plus a JSON sidecar.

Layout written into a directory, for a stem ``S`` (meshio's VTU writer drops field data: the writer adds the
frequencies back into each VTU as float64 field data, and the ``.pvd`` and a JSON sidecar hold the rest):

- ``S_NNN_axis.vtu`` for each rotor speed ``NNN`` (0-based): line cells between the mesh nodes; point data
  ``P_displacement`` (rotor-frame vector, m per unit modal amplitude) and ``P_twist_rad`` for every mode, with the
  prefix ``P`` naming the mode, its kind and frequency, e.g. ``mode01_flap_0.7434Hz`` (one speed), or the family
  and its kind at the first speed, e.g. ``mode01_flap`` (a sweep: one name follows one family through the
  collection); ``span_m``; cell data: section properties at the cell midpoints (SI, unit in the name); field
  data ``rotor_speed_rpm``, ``frequency_hz`` and ``kind_index`` (position in the sidecar's ``kinds``: for a blade
  0 flap, 1 edge, 2 torsion, 3 axial) per mode. An XML comment at the top of every file states the units,
  normalisation (each mode scaled so that its largest displacement component is 1, or its largest twist 1 rad for
  a torsion mode) and frame, and names each mode.
- ``S_NNN_surface.vtu`` when the chord is known: quads between leading and trailing edges, the same arrays
  (displacements of the edge points by the rigid-section kinematics).
- ``S.pvd``: the collection; ParaView's time is the rotor speed in rpm, part 0 the axis and part 1 the surface.
- ``S.json``: frequencies (Hz), kinds and energy shares of every mode at every speed, the frame, units, notes.

For a Campbell sweep, mode ``KK`` at every speed is the mode family ``KK`` tracked by MAC. A tower is written in
its own frame (x up, y side-side, z fore-aft) with its kinds (fore-aft, side-side, ...). Coordinates and frame:
:mod:`bladefem.outputs.vtk_geometry`.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any
from xml.sax.saxutils import quoteattr

import numpy as np
from numpy.typing import NDArray

from ..files import atomic_path
from ..modal import KINDS, CampbellResult, ModalResult
from ..modal.results import Mode
from ..models.tower import TOWER_KINDS
from ..sections import Blade
from .results import campbell_to_dict, dumps, write_atomic
from .vtk_geometry import (
    ModeDisplacement,
    axis_positions,
    has_planform,
    mode_displacement,
    surface_positions,
)

__all__ = ["FORMAT", "FRAME", "NORMALISATION", "VtkExport", "read_vtk", "write_vtk"]

FORMAT = "bladefem-vtk-1"
FRAME = ("rotor frame: origin at the rotor apex; z along the shaft axis, downwind; x radial through the blade "
         "(azimuth zero) in the plane of rotation; y = z cross x, toward the leading edge. A tower keeps its own "
         "frame: x up, z fore-aft, y side-side.")
NORMALISATION = ("displacements in m per unit modal amplitude: each mode scaled so that its largest displacement "
                 "component (flap, edge or axial; for a torsion mode its twist, rad) is 1")
#: section-table column -> cell-data name (SI unit in the name)
SECTION_ARRAYS: dict[str, str] = {
    "mass": "mass_kg_per_m", "flap_stiffness": "flap_stiffness_N_m2", "edge_stiffness": "edge_stiffness_N_m2",
    "torsion_stiffness": "torsion_stiffness_N_m2", "axial_stiffness": "axial_stiffness_N",
    "twist": "structural_twist_rad", "flap_inertia": "flap_inertia_kg_m", "edge_inertia": "edge_inertia_kg_m",
    "cm_offset": "cm_offset_m", "tension_centre_offset": "tension_centre_offset_m", "chord": "chord_m",
    "pitch_axis": "pitch_axis_fraction",
}

Progress = Callable[[Iterable[Any]], Iterable[Any]]


@dataclass(frozen=True)
class SpeedModes:
    """The modes exported at one rotor speed (rpm), in array order, with their array-name prefixes."""

    rotor_speed_rpm: float
    modes: tuple[Mode, ...]
    names: tuple[str, ...]


def array_name(number: int, kind: str, frequency_hz: float | None = None) -> str:
    """Point-data prefix of mode ``number`` (1-based): ``mode01_flap_0.7434Hz``, or without a frequency (the
    families of a sweep) ``mode01_flap``; a kind's hyphen becomes an underscore (``fore_aft``)."""
    name = f"mode{number:02d}_{kind.replace('-', '_')}"
    return name if frequency_hz is None else f"{name}_{frequency_hz:.4g}Hz"


def speeds_of(result: ModalResult | CampbellResult, n_modes: int | None = None) -> list[SpeedModes]:
    """The modes of a single-speed result (the lowest ``n_modes``) or of a sweep (one per family, MAC order)."""
    if isinstance(result, ModalResult):
        modes = tuple(result.modes[:n_modes])
        names = tuple(array_name(k, m.kind, m.frequency_hz) for k, m in enumerate(modes, 1))
        return [SpeedModes(result.rotor_speed_rpm, modes, names)]
    names = tuple(array_name(k, family.kind) for k, family in enumerate(result.families, 1))
    return [SpeedModes(float(rpm), tuple(sweep.modes[family.indices[k]] for family in result.families), names)
            for k, (rpm, sweep) in enumerate(zip(result.rpm, result.results))]


def section_cell_data(blade: Blade, x: NDArray) -> dict[str, NDArray]:
    """Section properties at the midpoints of the cells between span positions ``x`` (columns that are given)."""
    middle = 0.5 * (x[:-1] + x[1:])
    return {name: blade.sections.at(middle, column) for column, name in SECTION_ARRAYS.items()
            if getattr(blade.sections, column) is not None}


def mode_point_data(names: tuple[str, ...], displacements: list[NDArray],
                    twists: list[NDArray]) -> dict[str, NDArray]:
    """``P_displacement`` (n, 3) and ``P_twist_rad`` (n,) point arrays for each prefix ``P`` in ``names``."""
    data = {}
    for name, displacement, twist in zip(names, displacements, twists):
        data[f"{name}_displacement"] = np.ascontiguousarray(displacement, dtype=float)
        data[f"{name}_twist_rad"] = np.ascontiguousarray(twist, dtype=float)
    return data


def axis_mesh(blade: Blade, x: NDArray, modes: list[ModeDisplacement], names: tuple[str, ...]):
    """meshio line mesh of the reference axis with the modes' point data and the section cell data."""
    import meshio

    n = len(x)
    lines = np.stack([np.arange(n - 1), np.arange(1, n)], axis=-1)
    point_data = {"span_m": np.asarray(x, dtype=float)}
    point_data.update(mode_point_data(names, [m.axis for m in modes], [m.twist for m in modes]))
    cells = {name: [value] for name, value in section_cell_data(blade, x).items()}
    return meshio.Mesh(axis_positions(blade, x), [("line", lines)], point_data=point_data, cell_data=cells)


def surface_mesh(blade: Blade, x: NDArray, modes: list[ModeDisplacement], names: tuple[str, ...]):
    """meshio quad mesh of the planform ribbon: points ``[LE_0 .. LE_n-1, TE_0 .. TE_n-1]``."""
    import meshio

    n = len(x)
    i = np.arange(n - 1)
    quads = np.stack([i, i + 1, n + i + 1, n + i], axis=-1)
    points = surface_positions(blade, x).transpose(1, 0, 2).reshape(-1, 3)
    point_data = {"span_m": np.concatenate([x, x]).astype(float)}
    point_data.update(mode_point_data(names, [m.surface.transpose(1, 0, 2).reshape(-1, 3) for m in modes],
                                      [np.concatenate([m.twist, m.twist]) for m in modes]))
    cells = {name: [value] for name, value in section_cell_data(blade, x).items()}
    return meshio.Mesh(points, [("quad", quads)], point_data=point_data, cell_data=cells)


def field_data_xml(arrays: dict[str, NDArray]) -> str:
    """A VTK XML ``<FieldData>`` block of float64 arrays, in ASCII with shortest round-trip reprs (exact)."""
    rows = [f'<DataArray type="Float64" Name={quoteattr(name)} NumberOfTuples="{np.size(values)}" '
            f'format="ascii">{" ".join(repr(float(v)) for v in np.ravel(values))}</DataArray>'
            for name, values in arrays.items()]
    return "<FieldData>\n" + "\n".join(rows) + "\n</FieldData>\n"


def xml_comment(lines: list[str]) -> str:
    """An XML comment block (``--`` inside the text would end it early and is replaced)."""
    return "<!--\n" + "\n".join("  " + line.replace("--", "- -") for line in lines) + "\n-->\n"


def with_field_data(vtu: str, arrays: dict[str, NDArray], comment: str = "") -> str:
    """meshio's VTU text with field data added after the ``<UnstructuredGrid>`` tag (meshio writes none) and a
    comment after the XML declaration."""
    tag = "<UnstructuredGrid>\n"
    if tag not in vtu:
        raise ValueError("unexpected VTU layout: no <UnstructuredGrid> line")
    vtu = vtu.replace(tag, tag + field_data_xml(arrays), 1)
    if comment:
        declaration = vtu.index("?>\n") + 3 if vtu.startswith("<?xml") else 0
        vtu = vtu[:declaration] + comment + vtu[declaration:]
    return vtu


def write_mesh_atomic(path: Path, mesh, field_data: dict[str, NDArray] | None = None, comment: str = "") -> None:
    """meshio VTU (binary, zlib) with optional float64 field data and an XML comment, written to a temporary file
    in the same folder, then renamed."""
    import meshio

    with atomic_path(path) as temporary:
        meshio.write(temporary, mesh, file_format="vtu")
        if field_data or comment:
            temporary.write_text(with_field_data(temporary.read_text(), field_data or {}, comment))


def collection_xml(entries: list[tuple[float, int, str, str]], comment: str = "") -> str:
    """A ParaView ``.pvd`` collection from (rotor speed rpm, part, file, name) entries."""
    rows = [f'    <DataSet timestep="{rpm!r}" part="{part}" name={quoteattr(name)} file={quoteattr(file)}/>'
            for rpm, part, file, name in entries]
    return "\n".join(['<?xml version="1.0"?>', comment.rstrip("\n"), '<VTKFile type="Collection" version="0.1">',
                      "  <Collection>", *rows, "  </Collection>", "</VTKFile>", ""])


def speed_field_data(speed: SpeedModes, kinds: tuple[str, ...] = KINDS) -> dict[str, NDArray]:
    """Field data kept in each VTU: ``rotor_speed_rpm``, ``frequency_hz`` and ``kind_index`` (position in
    ``kinds``; for a blade :data:`bladefem.modal.KINDS`: 0 flap, 1 edge, 2 torsion, 3 axial) of the modes in
    array order."""
    return {"rotor_speed_rpm": np.array([speed.rotor_speed_rpm]),
            "frequency_hz": np.array([mode.frequency_hz for mode in speed.modes]),
            "kind_index": np.array([kinds.index(mode.kind) for mode in speed.modes], dtype=float)}


def speed_comment(structure: str, speed: SpeedModes) -> str:
    """The statement at the top of each VTU: what the arrays hold, the normalisation and frame, each mode."""
    lines = [f"bladefem {structure} mode shapes at rotor speed {speed.rotor_speed_rpm:g} rpm.",
             f"Point data P_displacement (vector) and P_twist_rad per mode: {NORMALISATION}.",
             f"Frame: {FRAME}"]
    lines += [f"{name}: {mode.kind}, {mode.frequency_hz:.6g} Hz" for name, mode in zip(speed.names, speed.modes)]
    return xml_comment(lines)


def mode_record(mode: Mode, name: str) -> dict[str, Any]:
    return {"array": name, "frequency_hz": mode.frequency_hz, "kind": mode.kind,
            "energy_fractions": mode.energy_fractions}


def drawn_beam(structure: Any) -> tuple[Blade, str, tuple[str, ...]]:
    """(the beam drawn, 'blade' or 'tower', the kinds ``kind_index`` counts in) of a blade or a tower."""
    if isinstance(structure, Blade):
        return structure, "blade", KINDS
    return structure.as_beam(), "tower", TOWER_KINDS


@dataclass(frozen=True)
class VtkExport:
    """Paths written by :func:`write_vtk`."""

    collection: Path
    sidecar: Path
    meshes: tuple[Path, ...]


def write_vtk(structure: Any, result: ModalResult | CampbellResult, directory: str | os.PathLike,
              stem: str = "modes", n_modes: int | None = None, progress: Progress | None = None) -> VtkExport:
    """Write the modes of ``result`` (one speed, or a Campbell sweep) of a blade or a tower (a
    :class:`~bladefem.sections.tower.Tower`, drawn in its own frame) as VTU files, a ``.pvd`` collection indexed by
    rotor speed and a JSON sidecar (layout in the module docstring); ``progress`` wraps the loop over speeds."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    blade, kind, kinds = drawn_beam(structure)
    speeds = speeds_of(result, n_modes)
    entries: list[tuple[float, int, str, str]] = []
    records, meshes = [], []
    for k, speed in enumerate((progress or iter)(speeds)):
        x = speed.modes[0].shape.x
        drawn = [mode_displacement(blade, mode.shape, x) for mode in speed.modes]
        fields, comment = speed_field_data(speed, kinds), speed_comment(kind, speed)
        files = {"axis": f"{stem}_{k:03d}_axis.vtu"}
        write_mesh_atomic(directory / files["axis"], axis_mesh(blade, x, drawn, speed.names), fields, comment)
        if has_planform(blade):
            files["surface"] = f"{stem}_{k:03d}_surface.vtu"
            write_mesh_atomic(directory / files["surface"], surface_mesh(blade, x, drawn, speed.names), fields,
                              comment)
        for part, (name, file) in enumerate(files.items()):
            entries.append((speed.rotor_speed_rpm, part, file, name))
            meshes.append(directory / file)
        records.append({"rotor_speed_rpm": speed.rotor_speed_rpm, "files": files,
                        "modes": [mode_record(mode, name) for mode, name in zip(speed.modes, speed.names)]})
    collection, sidecar = directory / f"{stem}.pvd", directory / f"{stem}.json"
    statement = xml_comment([f"bladefem {kind} mode shapes; ParaView time = rotor speed, rpm.", NORMALISATION + ".",
                             f"Frame: {FRAME}", f"Frequencies, kinds and energy shares: {sidecar.name}."])
    write_atomic(collection, collection_xml(entries, statement))
    write_atomic(sidecar, dumps(sidecar_dict(blade, kind, kinds, result, collection.name, records)))
    return VtkExport(collection, sidecar, tuple(meshes))


def sidecar_dict(blade: Blade, kind: str, kinds: tuple[str, ...], result: ModalResult | CampbellResult,
                 collection: str, records: list[dict[str, Any]]) -> dict[str, Any]:
    """The JSON sidecar: what the VTU files cannot keep."""
    data: dict[str, Any] = {
        "format": FORMAT, "structure": kind, kind: blade.name, "source": blade.sections.source,
        "collection": collection, "frame": FRAME, "kinds": list(kinds), "normalisation": NORMALISATION,
        "units": {"points": "m", "displacement": "m per unit modal amplitude (largest component 1)",
                  "twist": "rad", "collection_time": "rotor speed, rpm"},
        "speeds": records, "notes": list(result.notes)}
    if kind == "blade":
        data.update({"hub_radius_m": blade.hub_radius, "precone_deg": math.degrees(blade.precone),
                     "pitch_deg": math.degrees(blade.pitch)})
    if has_planform(blade) and blade.sections.pitch_axis is None:
        data["notes"].append("no pitch-axis position given: the surface is drawn with the axis at 25 % chord")
    if isinstance(result, CampbellResult):
        data["campbell"] = campbell_to_dict(result)
    return data


def read_vtk(sidecar: str | os.PathLike) -> dict[str, Any]:
    """Read an export back with meshio: the sidecar dict, with each speed's ``meshes`` ({"axis": meshio.Mesh, ...})."""
    import meshio

    sidecar = Path(sidecar)
    data = json.loads(sidecar.read_text())
    for record in data["speeds"]:
        record["meshes"] = {name: meshio.read(sidecar.parent / file) for name, file in record["files"].items()}
    return data
