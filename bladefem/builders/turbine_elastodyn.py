"""Build :class:`TurbineParameters` from an ElastoDyn main file, with blade shapes from bladefem's FE (at a chosen
rotor speed) or from the ElastoDyn polynomials, and tower shapes from the tower file's polynomials."""

from __future__ import annotations

from contextlib import contextmanager

from dataclasses import replace
from pathlib import Path
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..modal.results import ModalResult
from ..models.turbine.parameters import TurbineParameters
from ..models.turbine.shapes import (
    ModalBeam,
    hermite_evaluator,
    polynomial_evaluator,
    sample_beam,
    twisted_polynomial_nodes,
)
from ..sections import Blade, SectionTable, bending_stiffness, total_angle
from .elastodyn_blade import blade_from_elastodyn, read_elastodyn_blade
from ..formats.elastodyn_main import read_elastodyn_main
from .elastodyn_tower import (
    ElastoDynTowerFile,
    read_elastodyn_tower,
    tower_from_elastodyn,
)

#: NREL 5MW nacelle-yaw spring and damper (ServoDyn YawSpr, YawDamp; not in the ElastoDyn main file)
NREL5MW_YAW_STIFFNESS = 9.02832e9
NREL5MW_YAW_DAMPING = 1.916e7
#: node count standing for exact span integrals when polynomials are fitted for bladefem's own integration
FINE_NODES = 400
#: the damping conventions, as the notes state them
DAMPING_NOTES = {"elastodyn": "ElastoDyn's convention (each mode's frequency of the beam alone, without the tip or "
                              "tower-top mass)",
                 "rna": "modal masses with the blade tip mass and the rotor-nacelle assembly on the tower"}
#: 'fe': bladefem's FE shapes themselves; 'fe-polynomial': ElastoDyn polynomials fitted to them
#: (bladefem.modal.elastodyn_fit); 'polynomial': the polynomials of the input files
ShapeSource = Literal["fe", "fe-polynomial", "polynomial"]
SHAPE_SOURCES = ("fe", "fe-polynomial", "polynomial")


def tower_damping(tower: ElastoDynTowerFile) -> NDArray:
    """Damping ratios of the modes FA1, FA2, SS1, SS2 (fraction of critical)."""
    return np.array(tower.fa_damping_percent + tower.ss_damping_percent) / 100.0


def tower_sections(tower: ElastoDynTowerFile, length: float) -> SectionTable:
    """The tower file's properties over the flexible length (flap = fore-aft, edge = side-side)."""
    return tower_from_elastodyn(tower, height=length).sections


def tower_edges(sections: SectionTable, subdivisions: int = 2, elements: int | None = None) -> NDArray:
    """The stations with each interval subdivided, or ``elements`` equal elements."""
    if elements is not None:
        return np.linspace(0.0, sections.length, elements + 1)
    stations = sections.span
    return np.unique(np.concatenate([np.linspace(a, b, subdivisions + 1) for a, b in zip(stations, stations[1:])]))


def tower_beam(sections: SectionTable, coefficients: dict[str, NDArray], damping_ratio: NDArray | float = 0.0,
               edges: NDArray | None = None, gauss_points: int = 4) -> ModalBeam:
    """Four polynomial tower modes ('fa1', 'fa2' along x; 'ss1', 'ss2' along y) on ``edges`` (default: the
    stations, each interval halved)."""
    c = np.array([coefficients[name] for name in ("fa1", "fa2", "ss1", "ss2")])
    directions = np.array([[1.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 1.0]])
    return sample_beam(polynomial_evaluator(c, sections.length, directions),
                       tower_edges(sections) if edges is None else edges, lambda x: sections.at(x, "mass"),
                       tower_stiffness(sections), damping_ratio,
                       ("fore-aft 1", "fore-aft 2", "side-side 1", "side-side 2"), gauss_points)


def tower_stiffness(sections: SectionTable):
    """Bending stiffness diag(fore-aft, side-side) as a function of height, (len(x), 2, 2) N m^2."""
    def stiffness(x: NDArray) -> NDArray:
        D = np.zeros((len(x), 2, 2))
        D[:, 0, 0] = sections.at(x, "flap_stiffness")
        D[:, 1, 1] = sections.at(x, "edge_stiffness")
        return D
    return stiffness


def rotor_nacelle_body(params: TurbineParameters) -> tuple[float, NDArray, NDArray]:
    """The rotor-nacelle assembly (yaw bearing, nacelle, hub, generator, undeflected blades at zero azimuth) as
    one rigid body: mass (kg), centre of mass relative to the tower top and inertia tensor about it (kg m^2),
    earth components."""
    from ..models.turbine.kane import TurbineModel
    model = TurbineModel(params)
    zero = np.zeros(model.n)
    motion = model.motion(zero, zero)
    top = motion.tower_top.r
    positions = np.concatenate([top[None], motion.rigid.r, motion.blades.r.reshape(-1, 3)])
    masses = model.masses[len(params.tower.x):]
    mass = float(masses.sum())
    cm = masses @ (positions - top) / mass
    relative = positions - top - cm
    inertia = np.einsum("p,pi,pj->ij", masses, relative, relative)
    inertia = np.trace(inertia) * np.eye(3) - inertia
    for _, axis, moment in model.rigid_bodies(motion):
        inertia += moment * np.outer(axis, axis)
    return mass, cm, inertia


def fe_tower(params: TurbineParameters, sections: SectionTable):
    """bladefem's tower model of these sections with the rotor-nacelle assembly of ``params`` as its rigid top
    body (tower frame: x up, y side-side to the right, z downwind) and the same gravity."""
    from ..sections.tower import OPENFAST_AXES, TopMass, Tower

    mass, cm, inertia = rotor_nacelle_body(params)
    top = TopMass(mass, OPENFAST_AXES @ cm, OPENFAST_AXES @ inertia @ OPENFAST_AXES.T)
    return Tower(sections, top_mass=top, gravity=params.gravity)


def fe_tower_beam(params: TurbineParameters, sections: SectionTable, damping_ratio: NDArray | float = 0.0,
                  gauss_points: int = 4, edges: NDArray | None = None) -> ModalBeam:
    """Tower modes FA1, FA2, SS1, SS2 from bladefem's tower FE (:func:`fe_tower`); the FE shapes themselves are
    the assumed modes."""
    from ..models.tower import tower_modes

    result = tower_modes(fe_tower(params, sections), n_modes=8)
    chosen = [result.first(kind, number) for kind in ("fore-aft", "side-side") for number in (1, 2)]
    nodes = chosen[0].shape.x
    # tower frame: w fore-aft (downwind), v side-side to the right; here x downwind, y to the left
    values = np.stack([np.stack([m.shape.flap, -m.shape.edge], axis=-1) for m in chosen])
    slopes = np.stack([np.stack([m.shape.flap_slope, -m.shape.edge_slope], axis=-1) for m in chosen])

    return sample_beam(hermite_evaluator(nodes, values, slopes), nodes if edges is None else edges,
                       lambda x: sections.at(x, "mass"), tower_stiffness(sections), damping_ratio,
                       ("fore-aft 1", "fore-aft 2", "side-side 1", "side-side 2"), gauss_points)


def blade_properties(blade: Blade):
    """Mass per length and the 2x2 bending stiffness for (v'', w'') of a blade, as functions of x."""
    return (lambda x: blade.sections.at(x, "mass"),
            lambda x: np.moveaxis(bending_stiffness(blade.sections, x, blade.pitch), -1, 0))


def blade_beam_from_modes(blade: Blade, result: ModalResult, damping_ratio: NDArray | float = 0.0,
                          edges: NDArray | None = None, gauss_points: int = 4) -> ModalBeam:
    """Blade modes flap 1, edge 1, flap 2 of a bladefem modal result (FE or Galerkin) as assumed modes.

    The shapes are the modes' own Hermite fields through their nodes; ``edges`` (default: the modes' nodes) sets
    the quadrature mesh.
    """
    chosen = [result.first("flap", 1), result.first("edge", 1), result.first("flap", 2)]
    nodes = chosen[0].shape.x
    values = np.stack([np.stack([m.shape.edge, m.shape.flap], axis=-1) for m in chosen])
    slopes = np.stack([np.stack([m.shape.edge_slope, m.shape.flap_slope], axis=-1) for m in chosen])
    mass, stiffness = blade_properties(blade)
    return sample_beam(hermite_evaluator(nodes, values, slopes), nodes if edges is None else edges, mass,
                       stiffness, damping_ratio, ("flap 1", "edge 1", "flap 2"), gauss_points)


def blade_beam_from_polynomials(blade: Blade, coefficients: dict[str, NDArray], damping_ratio: NDArray | float = 0.0,
                                gauss_points: int = 4, edges: NDArray | None = None) -> ModalBeam:
    """ElastoDyn's polynomial blade modes ('flap1', 'edge1', 'flap2'), twisted by the structural twist + pitch
    (integrated between the section stations); ``edges`` sets the quadrature mesh (default: the stations)."""
    nodes = blade.sections.span
    c = np.array([coefficients["flap1"], coefficients["edge1"], coefficients["flap2"]])
    values, slopes = twisted_polynomial_nodes(c, blade.length, ("flap", "edge", "flap"), nodes,
                                              lambda x: total_angle(blade.sections, x, blade.pitch))
    mass, stiffness = blade_properties(blade)
    return sample_beam(hermite_evaluator(nodes, values, slopes), nodes if edges is None else edges, mass,
                       stiffness, damping_ratio, ("flap 1", "edge 1", "flap 2"), gauss_points)


def blade_damping(blade_file) -> NDArray:
    """Damping ratios of the blade modes flap 1, edge 1, flap 2 (fraction of critical)."""
    return np.array([blade_file.flap_damping_percent[0], blade_file.edge_damping_percent,
                     blade_file.flap_damping_percent[1]]) / 100.0


def deck_pitch(main, pitch: float | None) -> float:
    """The blade pitch (rad): ``pitch`` if given, else the deck's BlPitch, which must be the same for all
    blades."""
    if pitch is not None:
        return pitch
    if len(set(main.blade_pitch)) > 1:
        raise InputError("the blades have different initial pitch angles; bladefem's blades are alike",
                         file=main.path, line=main.key_lines.get("BlPitch(2)"), field="BlPitch(2)")
    return main.blade_pitch[0] if main.blade_pitch else 0.0


def turbine_from_elastodyn(main_path: str | Path, blade_shapes: ShapeSource = "fe", rpm: float | None = None,
                           pitch: float | None = None, yaw_stiffness: float = NREL5MW_YAW_STIFFNESS,
                           yaw_damping: float = NREL5MW_YAW_DAMPING, gauss_points: int = 2,
                           blade_elements: int | None = None, tower_elements: int | None = None,
                           tower_shapes: ShapeSource = "polynomial", elastodyn_compatible: bool = False,
                           damping: str = "elastodyn") -> TurbineParameters:
    """The turbine of an ElastoDyn main file.

    blade_shapes : 'fe' (bladefem's FE modes at ``rpm``, default the file's RotSpeed), 'fe-polynomial' (ElastoDyn
        polynomials fitted to those modes) or 'polynomial' (the blade file's); polynomials are twisted as
        ElastoDyn does
    pitch : rad (default: the deck's BlPitch); yaw_stiffness, yaw_damping : N m/rad, N m s/rad (ServoDyn inputs;
        NREL 5MW values by default)
    gauss_points : quadrature points per element for the span nodes of the Kane model
    blade_elements, tower_elements : equal elements for those span nodes (default: the files' stations)
    tower_shapes : 'polynomial' (the tower file's), 'fe' (bladefem's tower FE with this rotor-nacelle assembly
        as a rigid top body, and gravity) or 'fe-polynomial' (ElastoDyn polynomials fitted to those)
    elastodyn_compatible : ElastoDyn's own discretization (:mod:`bladefem.models.turbine.elastodyn_beams`: the
        polynomials at the midpoints of BldNodes / TwrNodes elements, its shape integration and stiffness tuners)
        and damping convention; needs polynomial shapes ('polynomial' or 'fe-polynomial')
    damping : 'elastodyn' (ElastoDyn's CBF/CBE/CTFA/CTSS: each mode's frequency of the beam alone) or 'rna'
        (modal masses with the tip mass and, for the tower, the rotor-nacelle assembly)
    """
    from ..modal import modes
    from ..modal.elastodyn_fit import blade_coefficients
    from ..models.tower_fit import tower_coefficients
    from ..models.turbine.elastodyn_beams import (
        elastodyn_blade_beam,
        elastodyn_tower_beam,
        tuned,
    )

    for name, value in (("blade shapes", blade_shapes), ("tower shapes", tower_shapes)):
        if value not in SHAPE_SOURCES:
            raise InputError(f"{name} must be one of {', '.join(SHAPE_SOURCES)}, got '{value}'",
                             field=name.replace(" ", "_"))
        if elastodyn_compatible and value == "fe":
            raise InputError(f"ElastoDyn-compatible models use polynomial {name} ('polynomial' or "
                             "'fe-polynomial'), not 'fe'", field=name.replace(" ", "_"))
    if elastodyn_compatible and damping != "elastodyn":
        raise InputError("ElastoDyn-compatible models use ElastoDyn's damping convention", field="damping")
    main = read_elastodyn_main(main_path)
    blade_file = read_elastodyn_blade(main.blade_files[0])
    if len(set(main.precone)) > 1 or len(set(main.tip_mass)) > 1 or len(set(main.blade_files)) > 1:
        raise InputError("all blades must be alike (same file, precone and tip mass)", file=main.path,
                         field="BldFile")
    pitch = deck_pitch(main, pitch)
    blade = blade_from_elastodyn(blade_file, tip_radius=main.tip_radius, hub_radius=main.hub_radius,
                                 precone=main.precone[0], pitch=pitch, tip_mass=main.tip_mass[0])
    speed = main.rotor_speed_rpm if rpm is None else rpm
    edges = None if blade_elements is None else np.linspace(0.0, blade.length, blade_elements + 1)
    # fitted polynomials keep the FE frequency with the consumer's integrals: ElastoDyn's nodes, or (bladefem's
    # exact span integration) a fine node rule
    fit_nodes = (main.blade_nodes, main.tower_nodes) if elastodyn_compatible else (FINE_NODES, FINE_NODES)
    coefficients = blade_file.modes if blade_shapes != "fe-polynomial" else \
        blade_coefficients(blade, speed, nodes=fit_nodes[0]).coefficients
    if elastodyn_compatible:
        beam = elastodyn_blade_beam(blade.sections, coefficients, main.blade_nodes, pitch, blade_file.flap_tuners,
                                    blade_damping(blade_file))
    elif blade_shapes == "fe":
        beam = blade_beam_from_modes(blade, modes(blade, rpm=speed, n_modes=6), blade_damping(blade_file),
                                     blade.sections.span if edges is None else edges, gauss_points)
    else:
        beam = blade_beam_from_polynomials(blade, coefficients, blade_damping(blade_file), gauss_points, edges)
        flap = np.ix_([0, 2], [0, 2])
        stiffness = beam.generalized_stiffness().copy()
        stiffness[flap] = tuned(stiffness[flap], np.asarray(blade_file.flap_tuners))
        beam = replace(beam, elastic_stiffness=stiffness)
    tower_file = read_elastodyn_tower(main.tower_file)
    sections = tower_sections(tower_file, main.tower_height - main.tower_base_height)
    tower_edges_ = tower_edges(sections, elements=tower_elements)
    tuners = np.concatenate([tower_file.fa_tuners, tower_file.ss_tuners])
    if elastodyn_compatible:
        tower = elastodyn_tower_beam(sections, tower_file.modes, main.tower_nodes, tower_file.fa_tuners,
                                     tower_file.ss_tuners, tower_damping(tower_file))
    else:
        tower = tower_beam(sections, tower_file.modes, tower_damping(tower_file), tower_edges_, gauss_points)
        tower = replace(tower, elastic_stiffness=tuned(tower.generalized_stiffness(), tuners))
    blade_note = {"fe": f"bladefem FE modes at {speed:.4g} rpm",
                  "fe-polynomial": f"ElastoDyn polynomials fitted to bladefem FE modes at {speed:.4g} rpm, twisted",
                  "polynomial": "ElastoDyn polynomials of the blade file, twisted"}[blade_shapes]
    tower_note = {"fe": "bladefem tower FE with the rigid rotor-nacelle on top",
                  "fe-polynomial": "ElastoDyn polynomials fitted to bladefem's tower FE modes (rigid rotor-nacelle "
                                   "on top)",
                  "polynomial": "ElastoDyn polynomials of the tower file"}[tower_shapes]
    notes = (f"blade shapes: {blade_note}", f"tower shapes: {tower_note}",
             f"yaw spring {yaw_stiffness:g} N m/rad and damper {yaw_damping:g} N m s/rad (ServoDyn inputs)",
             f"structural damping: {DAMPING_NOTES[damping]}")
    if elastodyn_compatible:
        notes += (f"ElastoDyn-compatible: span integrals at the midpoints of BldNodes = {main.blade_nodes} and "
                  f"TwrNodes = {main.tower_nodes} elements, ElastoDyn's shape integration and tuners",)
    with _located(main):
        params = TurbineParameters(
            tower=tower, blade=beam, n_blades=main.num_blades, tower_base_height=main.tower_base_height,
            twr2shft=main.twr2shft, overhang=main.overhang, shaft_tilt=main.shaft_tilt, precone=main.precone[0],
            hub_radius=main.hub_radius, hub_cm=main.hub_cm, hub_mass=main.hub_mass, hub_inertia=main.hub_inertia,
            generator_inertia=main.generator_inertia, gearbox_ratio=main.gearbox_ratio,
            nacelle_mass=main.nacelle_mass, nacelle_yaw_inertia=main.nacelle_yaw_inertia,
            nacelle_cm=np.array(main.nacelle_cm), yaw_bearing_mass=main.yaw_bearing_mass,
            drivetrain_stiffness=main.drivetrain_spring, drivetrain_damping=main.drivetrain_damper,
            yaw_stiffness=yaw_stiffness, yaw_damping=yaw_damping, blade_tip_mass=main.tip_mass[0], pitch=pitch,
            damping=damping, name=Path(main.path).stem, notes=blade.notes + notes)
    if tower_shapes == "fe":
        params = params.with_(tower=fe_tower_beam(params, sections, tower.damping_ratio, gauss_points, tower_edges_))
    elif tower_shapes == "fe-polynomial":
        fitted = tower_coefficients(fe_tower(params, sections), nodes=fit_nodes[1]).coefficients
        tower = elastodyn_tower_beam(sections, fitted, main.tower_nodes, tower_file.fa_tuners, tower_file.ss_tuners,
                                     tower.damping_ratio) if elastodyn_compatible else \
            tower_beam(sections, fitted, tower.damping_ratio, tower_edges_, gauss_points)
        params = params.with_(tower=tower)
    return params


@contextmanager
def _located(main):
    """An InputError of the model about an ElastoDyn entry (e.g. NacYIner) located at that entry of ``main``."""
    try:
        yield
    except InputError as error:
        if error.file is None and error.field in main.key_lines:
            raise InputError(error.message, file=main.path, line=main.key_lines[error.field],
                             field=error.field) from None
        raise


#: ElastoDyn's platform DOF switches, left out (switched off) by ``--foundation rigid``
PLATFORM_DOFS = ("PtfmSgDOF", "PtfmSwDOF", "PtfmHvDOF", "PtfmRDOF", "PtfmPDOF", "PtfmYDOF")


def deck_conditions(main_path: str | Path, rigid_foundation: bool = False):
    """ElastoDyn's DOF switches (name -> flag) and initial conditions of a main file. A platform DOF switched on
    is refused (file, line, switch, and the way forward ``--foundation rigid``), or with ``rigid_foundation``
    switched off."""
    from ..models.turbine.initial import InitialConditions
    main = read_elastodyn_main(main_path)
    dofs = dict(main.dofs)
    for key in PLATFORM_DOFS:
        if dofs.get(key) and not rigid_foundation:
            raise InputError(f"{key} is on, but bladefem's turbine model has no platform motion: set it to False; "
                             "or --foundation rigid runs the turbine with the tower clamped at its base (platform, "
                             "hydrodynamics and substructure left out)", file=main.path, line=main.key_lines.get(key),
                             field=key)
        if rigid_foundation:
            dofs[key] = False
    if main.text is not None and main.text.has("YawFrctMod") and main.text.int("YawFrctMod") != 0 and dofs.get(
            "YawDOF", True):
        line = main.text.line_of("YawFrctMod")
        raise InputError("yaw-bearing friction (YawFrctMod, OpenFAST 4) is not modelled: set YawFrctMod 0, or lock "
                         "the yaw (YawDOF False)", file=main.path, line=line, field="YawFrctMod")
    return dofs, InitialConditions(
        oop_deflection=main.oop_deflection, ip_deflection=main.ip_deflection,
        azimuth=main.azimuth - main.azimuth_blade1_up, nacelle_yaw=main.nacelle_yaw, rotor_speed=main.rotor_speed,
        tower_top_fa=main.tower_top_fa, tower_top_ss=main.tower_top_ss)


def platform_note(main_path: str | Path) -> str:
    """What ``--foundation rigid`` leaves out of an ElastoDyn main file (said in the output's header)."""
    main = read_elastodyn_main(main_path)
    on = [key for key in PLATFORM_DOFS if main.dofs.get(key)]
    text = main.text
    mass = text.float("PtfmMass") if text is not None and text.has("PtfmMass") else 0.0
    return (f"foundation rigid: the tower is clamped at its base, TowerBsHt {main.tower_base_height:g} m; left out of "
            f"{Path(main.path).name}: the platform DOFs {', '.join(on) or '(none on)'} and the platform mass "
            f"PtfmMass {mass:g} kg")
