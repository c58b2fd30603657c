"""bladefem models from windIO data, and writing the windIO subset back.

Conventions (windIO 2.x schema): blade section axes ``x`` toward the trailing edge, ``y`` toward the suction side,
``z`` along the span; ``K44`` is the flapwise bending stiffness (about ``x``), ``K55`` the edgewise one (about
``y``), ``K66`` torsion, ``K33`` axial, all in the frame turned by the twist. ``i_flap`` (about ``x``) and ``i_edge``
(about ``y``) are taken about the centre of mass. Tower axes: ``x`` downwind, ``y`` lateral, ``z`` up, so fore-aft
bending is ``K55`` and side-side bending ``K44``.

What bladefem's beam does not represent is reported in the model's notes rather than silently dropped: the
off-diagonal stiffness couplings (``K34``, ``K35``, ``K45``, ...), the thickness-wise centre-of-mass offset
``cm_y``, and the curvature of the reference axis (prebend, sweep; the beam is straight with the axis's arc length).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import yaml
from numpy.typing import NDArray

from ..errors import InputError
from ..files import write_atomic
from ..sections import Blade, SectionTable, TipMass
from ..formats._fast_format import degrees_exact
from ..sections.checks import check_section_values
from .tower import Tower
from ..formats.windio import WindIOBeam, WindIOTurbine

#: Couplings smaller than this fraction of sqrt(K_ii K_jj) are not mentioned in the notes.
COUPLING_NOTE = 0.01


def _stations(beam: WindIOBeam) -> NDArray[np.float64]:
    grids = [beam.stiffness_grid, beam.inertia_grid] + ([beam.twist.grid] if beam.twist is not None else [])
    return np.unique(np.concatenate(grids))


def _couplings(beam: WindIOBeam) -> list[str]:
    notes = []
    k = beam.stiffness
    for name, values in k.items():
        i, j = int(name[1]), int(name[2])
        if i == j or f"K{i}{i}" not in k or f"K{j}{j}" not in k:
            continue
        scale = np.sqrt(np.abs(k[f"K{i}{i}"] * k[f"K{j}{j}"]))
        ratio = float(np.max(np.abs(values) / np.maximum(scale, 1e-300)))
        if ratio > COUPLING_NOTE:
            notes.append(f"{name} (up to {ratio:.2g} of sqrt(K{i}{i} K{j}{j}))")
    return notes


def _optional_positive(beam: WindIOBeam, name: str, x: NDArray) -> NDArray | None:
    if name not in beam.stiffness or np.any(beam.stiffness[name] <= 0):
        return None
    return np.interp(x, beam.stiffness_grid, beam.stiffness[name])


def _notes(turbine: WindIOTurbine, beam: WindIOBeam, what: str) -> tuple[str, ...]:
    notes = [f"windIO {what} from {Path(turbine.path).name or 'memory'}: straight beam of the reference axis's arc "
             f"length {beam.length:.6g} m (prebend and sweep are not modelled)"]
    couplings = _couplings(beam)
    if couplings:
        notes.append("stiffness couplings neglected: " + ", ".join(couplings))
    if "cm_y" in beam.inertia and np.any(beam.inertia["cm_y"] != 0):
        notes.append(f"thickness-wise centre-of-mass offset cm_y (up to {np.max(np.abs(beam.inertia['cm_y'])):.3g} m)"
                     " neglected")
    if "K66" not in beam.stiffness:
        notes.append("no K66: torsion rigid")
    return tuple(notes)


def blade_from_windio(turbine: WindIOTurbine, pitch: float = 0.0) -> Blade:
    """A :class:`Blade` from the windIO blade; ``pitch`` in rad."""
    beam = turbine.blade
    if beam is None:
        raise InputError("the file has no blade", file=turbine.path or None,
                         line=turbine.lines.get(("components",)), field="components.blade")
    x = _stations(beam)

    def inertia(name: str) -> NDArray | None:
        return np.interp(x, beam.inertia_grid, beam.inertia[name]) if name in beam.inertia else None

    def stiffness(name: str) -> NDArray:
        return np.interp(x, beam.stiffness_grid, beam.stiffness[name])

    cm_x = inertia("cm_x")
    sections = SectionTable(
        span=x * beam.length,
        mass=inertia("mass"),
        flap_stiffness=stiffness("K44"),
        edge_stiffness=stiffness("K55"),
        torsion_stiffness=_optional_positive(beam, "K66", x),
        axial_stiffness=_optional_positive(beam, "K33", x),
        twist=np.interp(x, beam.twist.grid, beam.twist.values),
        flap_inertia=inertia("i_flap"),
        edge_inertia=inertia("i_edge"),
        cm_offset=None if cm_x is None else -cm_x,
        chord=None if beam.chord is None else np.interp(x, beam.chord.grid, beam.chord.values),
        source=turbine.path,
    )
    check_section_values(sections)
    return Blade(sections=sections, hub_radius=turbine.hub_radius, precone=turbine.precone, pitch=pitch,
                 name=f"{turbine.name} blade", notes=_notes(turbine, beam, "blade"))


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
        raise InputError("the file has no tower", file=turbine.path or None,
                         line=turbine.lines.get(("components",)), field="components.tower")
    x = np.unique(np.concatenate([beam.stiffness_grid, beam.inertia_grid]))
    notes = _notes(turbine, beam, "tower")
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

