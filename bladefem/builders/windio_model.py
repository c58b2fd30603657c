"""bladefem models from windIO data, and writing the windIO subset back.

Blade axes. windIO's reference axis is documented (turbine_schema.yaml, ``reference_axis``) with ``x`` toward the
suction side and ``y`` toward the trailing edge, BeamDyn's blade axes (OpenFAST docs/source/user/beamdyn/
input_files.rst). The same schema's ``K44``/``K55`` descriptions say the opposite (``x`` toward the trailing edge,
``K44`` flapwise); the data settle it for BeamDyn's axes: in the IEA-15MW and IEA-22MW files ``K44`` equals the
ElastoDyn blade file's edgewise stiffness (IEA-15MW at 50 % span 1.559e10 against EdgStff 1.570e10) and ``K55`` its
flapwise one (4.893e9 against FlpStff 5.280e9), and every entry (``K``, ``mass``, ``cm_y``, ``i_edge``) equals the
BeamDyn blade file's 6x6 at the same station (tests/test_beam_formats.py). So: ``K44`` bending about ``x`` is
edgewise, ``K55`` about ``y`` flapwise; ``cm_y`` is chordwise (toward the trailing edge, reaching 0.88 m on the
IEA-15MW), ``cm_x`` thickness-wise; ``i_edge``, ``i_flap``, ``i_cp``, ``i_plr`` are BeamDyn's ``M44``, ``M55``,
``-M45``, ``M66``, about the reference axis (equal to the BeamDyn file's entries). The 6x6 stiffness and mass are
built from them and go to the FE whole (or, with ``sections="reduced"``, as bladefem's diagonal beam) through
:mod:`bladefem.builders.section6x6`, which names what the reduction drops.

Tower axes (turbine_schema.yaml, the tower's ``reference_axis``): ``x`` downwind, ``y`` lateral, ``z`` up, so
fore-aft bending (about ``y``) is ``K55`` and side-side bending ``K44`` (the IEA towers are round, ``K44 = K55``: the
data cannot tell, the schema does).
The blade's reference axis (prebend ``x``, sweep ``y``) is its curved axis, straightened on request
(:meth:`~bladefem.builders.section6x6.SixBySixBlade.on_axis`); the tower is a straight beam of its axis's arc length.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import yaml
from numpy.typing import NDArray

from ..errors import InputError
from ..files import write_atomic
from ..builders.section6x6 import SixBySixBlade
from ..sections import Blade, SectionTable, TipMass
from ..formats._fast_format import degrees_exact
from ..sections.checks import check_section_values
from .tower import Tower
from ..formats.windio import WindIOBeam, WindIOTurbine


def _stations(beam: WindIOBeam) -> NDArray[np.float64]:
    grids = [beam.stiffness_grid, beam.inertia_grid] + ([beam.twist.grid] if beam.twist is not None else [])
    return np.unique(np.concatenate(grids))


def _optional_positive(beam: WindIOBeam, name: str, x: NDArray) -> NDArray | None:
    if name not in beam.stiffness or np.any(beam.stiffness[name] <= 0):
        return None
    return np.interp(x, beam.stiffness_grid, beam.stiffness[name])


def six_by_six(beam: WindIOBeam, x: NDArray) -> tuple[NDArray, NDArray]:
    """(n, 6, 6) stiffness and mass at grid points ``x`` in BeamDyn's axes (missing entries zero)."""
    n = len(x)
    K = np.zeros((n, 6, 6))
    for name, values in beam.stiffness.items():
        i, j = int(name[1]) - 1, int(name[2]) - 1
        K[:, i, j] = K[:, j, i] = np.interp(x, beam.stiffness_grid, values)

    def inertia(name: str) -> NDArray:
        return np.interp(x, beam.inertia_grid, beam.inertia[name]) if name in beam.inertia else np.zeros(n)

    m, cm_x, cm_y = inertia("mass"), inertia("cm_x"), inertia("cm_y")
    M = np.zeros((n, 6, 6))
    M[:, 0, 0] = M[:, 1, 1] = M[:, 2, 2] = m
    M[:, 0, 5] = M[:, 5, 0] = -m * cm_y
    M[:, 1, 5] = M[:, 5, 1] = m * cm_x
    M[:, 2, 3] = M[:, 3, 2] = m * cm_y
    M[:, 2, 4] = M[:, 4, 2] = -m * cm_x
    M[:, 3, 3], M[:, 4, 4] = inertia("i_edge"), inertia("i_flap")
    M[:, 3, 4] = M[:, 4, 3] = -inertia("i_cp")
    M[:, 5, 5] = inertia("i_plr")
    return K, M


def windio_sections(turbine: WindIOTurbine) -> SixBySixBlade:
    """The windIO blade as six-by-six sections in BeamDyn's axes on the union of its grids."""
    beam = turbine.blade
    if beam is None:
        if "blade" in turbine.problems:
            raise turbine.problems["blade"]
        raise InputError("the file has no blade", file=turbine.path or None,
                         line=turbine.lines.get(("components",)), field="components.blade")
    x = _stations(beam)
    K, M = six_by_six(beam, x)
    twist = np.interp(x, beam.twist.grid, beam.twist.values)
    axis = np.stack([np.interp(x, beam.reference_axis[c].grid, beam.reference_axis[c].values) for c in "xyz"], axis=1)
    key = ("components", "blade", "structure", "elastic_properties", "stiffness_matrix")
    if key not in turbine.lines:
        key = ("components", "blade", "elastic_properties_mb", "six_x_six", "stiff_matrix")
    line = turbine.lines.get(key)
    grid = np.unique(np.concatenate([beam.reference_axis[c].grid for c in "xyz"]))
    points = np.column_stack([grid * beam.length] + [np.interp(grid, beam.reference_axis[c].grid,
                                                               beam.reference_axis[c].values) for c in "xyz"])
    return SixBySixBlade(x * beam.length, K, M, twist, axis, source=turbine.path,
                         lines=(line,) * len(x) if line else None, field=".".join(key), axis_points=points)


def blade_from_windio(turbine: WindIOTurbine, pitch: float = 0.0, sections: str = "full",
                      axis: str = "curved") -> Blade:
    """A :class:`Blade` from the windIO blade; ``pitch`` in rad; ``sections`` ``"full"`` (the whole 6x6 in the FE),
    ``"condensed"`` (the shear condensed) or ``"reduced"`` (:meth:`SixBySixBlade.table`); ``axis`` ``"curved"``
    (the reference axis's prebend and sweep) or ``"straight"`` (:meth:`SixBySixBlade.on_axis`)."""
    six, reference, axis_note = windio_sections(turbine).on_axis(axis)
    beam = turbine.blade
    chord = None if beam.chord is None else np.interp(six.span / six.span[-1], beam.chord.grid, beam.chord.values)
    table, reduction = six.table(sections, chord=chord)
    check_section_values(table)
    notes = [f"windIO blade from {Path(turbine.path).name or 'memory'}: {axis_note}"] + reduction
    return Blade(sections=table, hub_radius=turbine.hub_radius, precone=turbine.precone, pitch=pitch,
                 name=f"{turbine.name} blade", notes=tuple(notes), axis=reference)


def rotor_nacelle_mass(turbine: WindIOTurbine) -> float:
    """Blades (exact integral of the linear mass distribution), hub, drivetrain and yaw system, kg."""
    blades = 0.0
    if turbine.blade is not None:
        blades = turbine.number_of_blades * blade_from_windio(turbine).sections.mass_moments()[0]
    return blades + turbine.hub_mass + turbine.drivetrain_mass + turbine.yaw_mass


def tower_from_windio(turbine: WindIOTurbine, top_mass: TipMass | float | None = None) -> Tower:
    """A :class:`Tower` from the windIO tower; by default the rotor-nacelle mass as a point mass at the top."""
    beam = turbine.tower
    if beam is None:
        if "tower" in turbine.problems:
            problem = turbine.problems["tower"]
            raise InputError(f"the tower cannot be built: {problem.message}", file=problem.file, line=problem.line,
                             field=problem.field)
        raise InputError("the file has no tower", file=turbine.path or None,
                         line=turbine.lines.get(("components",)), field="components.tower")
    x = np.unique(np.concatenate([beam.stiffness_grid, beam.inertia_grid]))
    notes = (f"windIO tower from {Path(turbine.path).name or 'memory'}: straight beam of the reference axis's arc "
             f"length {beam.length:.6g} m, diagonal stiffness (fore-aft K55, side-side K44, torsion K66)",)
    if top_mass is None:
        top_mass = rotor_nacelle_mass(turbine)
        notes += (f"tower-top mass {top_mass:.6g} kg (blades, hub, drivetrain, yaw) as a point mass",)
    if isinstance(top_mass, (int, float)):
        top_mass = TipMass(float(top_mass)) if top_mass > 0 else None
    sections = SectionTable(
        span=x * beam.length,
        mass=np.interp(x, beam.inertia_grid, beam.inertia["mass"]),
        flap_stiffness=np.interp(x, beam.stiffness_grid, beam.stiffness["K55"]),
        edge_stiffness=np.interp(x, beam.stiffness_grid, beam.stiffness["K44"]),
        torsion_stiffness=_optional_positive(beam, "K66", x),
        source=turbine.path,
    )
    base = float(beam.reference_axis["z"].values[0])
    check_section_values(sections)
    return Tower(sections=sections, base_height=base, top_mass=top_mass, name=f"{turbine.name} tower", notes=notes)


# -- writing ------------------------------------------------------------------------------------------------------

def _distribution(d) -> dict:
    return {"grid": [float(v) for v in d.grid], "values": [float(v) for v in d.values]}


def _beam_dict(beam: WindIOBeam) -> dict:
    out = {"reference_axis": {c: _distribution(d) for c, d in beam.reference_axis.items()},
           "structure": {"elastic_properties": {
               "stiffness_matrix": {"grid": [float(v) for v in beam.stiffness_grid],
                                    **{k: [float(v) for v in values] for k, values in beam.stiffness.items()}},
               "inertia_matrix": {"grid": [float(v) for v in beam.inertia_grid],
                                  **{k: [float(v) for v in values] for k, values in beam.inertia.items()}},
               "structural_damping": {"mu": [0.0] * 6}}}}
    if beam.twist is not None:
        out["outer_shape"] = {"twist": {"grid": [float(v) for v in beam.twist.grid],
                                        "values": [degrees_exact(v) for v in beam.twist.values]}}
    if beam.chord is not None:
        out.setdefault("outer_shape", {})["chord"] = _distribution(beam.chord)
    return out


def windio_text(turbine: WindIOTurbine) -> str:
    """The windIO subset bladefem reads, as YAML (floats written so that they read back exactly)."""
    components: dict = {"hub": {"diameter": 2 * turbine.hub_radius, "cone_angle": degrees_exact(turbine.cone_angle),
                                "elastic_properties": {"mass": turbine.hub_mass}},
                        "drivetrain": {"elastic_properties": {"mass": turbine.drivetrain_mass}},
                        "yaw": {"elastic_properties": {"mass": turbine.yaw_mass}}}
    if turbine.blade is not None:
        components["blade"] = _beam_dict(turbine.blade)
    if turbine.tower is not None:
        components["tower"] = _beam_dict(turbine.tower)
    document = {"windIO_version": 2.0, "name": turbine.name,
                "assembly": {"number_of_blades": turbine.number_of_blades,
                             "rotor_orientation": "upwind" if turbine.upwind else "downwind"},
                "components": components}
    return "# windIO turbine subset written by bladefem (blade and tower structure)\n" + yaml.safe_dump(
        document, sort_keys=False, default_flow_style=None, width=100)


def write_windio(turbine: WindIOTurbine, path: str | Path) -> None:
    """Write :func:`windio_text` atomically."""
    write_atomic(path, windio_text(turbine))

