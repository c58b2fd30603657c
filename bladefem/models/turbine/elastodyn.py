"""Build :class:`TurbineParameters` from an ElastoDyn main file, with blade shapes from bladefem's FE (at a chosen
rotor speed) or from the ElastoDyn polynomials, and tower shapes from the tower file's polynomials."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from ...errors import InputError
from ...io._fast_format import FastText
from ...io._modeshape_blocks import read_block
from ...io.elastodyn_blade import blade_from_elastodyn, read_elastodyn_blade
from ...io.elastodyn_main import read_elastodyn_main
from ...modal.results import ModalResult
from ...sections import Blade, SectionTable, bending_stiffness, total_angle
from .parameters import TurbineParameters
from .shapes import ModalBeam, hermite_evaluator, polynomial_evaluator, sample_beam, twisted_polynomial_nodes

#: NREL 5MW nacelle-yaw spring and damper (ServoDyn YawSpr, YawDamp; not in the ElastoDyn main file)
NREL5MW_YAW_STIFFNESS = 9.02832e9
NREL5MW_YAW_DAMPING = 1.916e7
TOWER_BLOCKS = {"fa1": "TwFAM1Sh", "fa2": "TwFAM2Sh", "ss1": "TwSSM1Sh", "ss2": "TwSSM2Sh"}
ShapeSource = Literal["fe", "polynomial"]


@dataclass(frozen=True)
class ElastoDynTower:
    """An ElastoDyn tower file (fractions of the flexible length, SI; damping in percent of critical)."""

    fraction: NDArray
    mass: NDArray
    fore_aft_stiffness: NDArray
    side_side_stiffness: NDArray
    damping_percent: tuple[float, float, float, float]
    modes: dict[str, NDArray] = field(default_factory=dict)
    path: str = ""


def read_elastodyn_tower(path: str | Path) -> ElastoDynTower:
    """Read an ElastoDyn tower file; AdjTwMa, AdjFASt and AdjSSSt are applied."""
    text = FastText.read(path)
    stations = text.int("NTwInpSt", minimum=2)
    first = text.header_line("HtFract") + 2
    rows = np.array(text.table(first, stations, ("HtFract", "TMassDen", "TwFAStif", "TwSSStif")))
    for column, name in enumerate(("HtFract", "TMassDen", "TwFAStif", "TwSSStif")):
        if column > 0 and np.any(rows[:, column] <= 0):
            bad = int(np.flatnonzero(rows[:, column] <= 0)[0])
            raise text.error(f"must be positive, got {rows[bad, column]}", first + bad, name)
    if abs(rows[0, 0]) > 1e-9 or abs(rows[-1, 0] - 1) > 1e-9 or np.any(np.diff(rows[:, 0]) <= 0):
        raise text.error("HtFract must increase from 0 to 1", first, "HtFract")
    damping = tuple(text.float(key, non_negative=True) for key in
                    ("TwrFADmp(1)", "TwrFADmp(2)", "TwrSSDmp(1)", "TwrSSDmp(2)"))
    return ElastoDynTower(
        fraction=rows[:, 0], mass=rows[:, 1] * text.float("AdjTwMa", positive=True),
        fore_aft_stiffness=rows[:, 2] * text.float("AdjFASt", positive=True),
        side_side_stiffness=rows[:, 3] * text.float("AdjSSSt", positive=True),
        damping_percent=damping,  # type: ignore[arg-type]
        modes={name: read_block(text, prefix) for name, prefix in TOWER_BLOCKS.items()}, path=text.path)


def tower_beam(tower: ElastoDynTower, length: float, subdivisions: int = 2, gauss_points: int = 4) -> ModalBeam:
    """The tower's four polynomial modes (FA1, FA2 along x; SS1, SS2 along y) on the file's stations."""
    stations = tower.fraction * length
    edges = np.unique(np.concatenate([np.linspace(a, b, subdivisions + 1) for a, b in zip(stations, stations[1:])]))
    coefficients = np.array([tower.modes[name] for name in ("fa1", "fa2", "ss1", "ss2")])
    directions = np.array([[1.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 1.0]])

    def stiffness(x: NDArray) -> NDArray:
        D = np.zeros((len(x), 2, 2))
        D[:, 0, 0] = np.interp(x, stations, tower.fore_aft_stiffness)
        D[:, 1, 1] = np.interp(x, stations, tower.side_side_stiffness)
        return D

    return sample_beam(polynomial_evaluator(coefficients, length, directions), edges,
                       lambda x: np.interp(x, stations, tower.mass), stiffness,
                       np.array(tower.damping_percent) / 100.0, ("fore-aft 1", "fore-aft 2", "side-side 1",
                                                                 "side-side 2"), gauss_points)


def tower_sections(tower: ElastoDynTower, length: float) -> SectionTable:
    """The tower file's properties as a section table over the flexible length (flap = fore-aft, edge =
    side-side, as bladefem's tower model reads them)."""
    return SectionTable(span=tower.fraction * length, mass=tower.mass, flap_stiffness=tower.fore_aft_stiffness,
                        edge_stiffness=tower.side_side_stiffness, source=tower.path)


def rotor_nacelle_body(params: TurbineParameters) -> tuple[float, NDArray, NDArray]:
    """The rotor-nacelle assembly (yaw bearing, nacelle, hub, generator, undeflected blades at zero azimuth) as
    one rigid body: mass (kg), centre of mass relative to the tower top and inertia tensor about it (kg m^2),
    earth components."""
    from .kane import TurbineModel
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
    for frame, local in model.rigid_bodies(motion):
        inertia += frame.R @ local @ frame.R.T
    return mass, cm, inertia


def fe_tower_beam(params: TurbineParameters, sections: SectionTable, damping_ratio: NDArray | float = 0.0,
                  gauss_points: int = 4) -> ModalBeam:
    """Tower modes FA1, FA2, SS1, SS2 from bladefem's tower FE with the rotor-nacelle assembly of ``params`` as
    its rigid top body and the same gravity; the FE shapes themselves are the assumed modes."""
    from ...models.tower import tower_modes
    from ...sections.tower import OPENFAST_AXES, TopMass, Tower

    mass, cm, inertia = rotor_nacelle_body(params)
    top = TopMass(mass, OPENFAST_AXES @ cm, OPENFAST_AXES @ inertia @ OPENFAST_AXES.T)
    result = tower_modes(Tower(sections, top_mass=top, gravity=params.gravity), n_modes=8)
    chosen = [result.first(kind, number) for kind in ("fore-aft", "side-side") for number in (1, 2)]
    nodes = chosen[0].shape.x
    # tower frame: w fore-aft (downwind), v side-side to the right; here x downwind, y to the left
    values = np.stack([np.stack([m.shape.flap, -m.shape.edge], axis=-1) for m in chosen])
    slopes = np.stack([np.stack([m.shape.flap_slope, -m.shape.edge_slope], axis=-1) for m in chosen])

    def stiffness(x: NDArray) -> NDArray:
        D = np.zeros((len(x), 2, 2))
        D[:, 0, 0] = sections.at(x, "flap_stiffness")
        D[:, 1, 1] = sections.at(x, "edge_stiffness")
        return D

    return sample_beam(hermite_evaluator(nodes, values, slopes), nodes, lambda x: sections.at(x, "mass"), stiffness,
                       damping_ratio, ("fore-aft 1", "fore-aft 2", "side-side 1", "side-side 2"), gauss_points)


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
                                gauss_points: int = 4) -> ModalBeam:
    """ElastoDyn's polynomial blade modes ('flap1', 'edge1', 'flap2'), twisted by the structural twist + pitch."""
    nodes = blade.sections.span
    c = np.array([coefficients["flap1"], coefficients["edge1"], coefficients["flap2"]])
    values, slopes = twisted_polynomial_nodes(c, blade.length, ("flap", "edge", "flap"), nodes,
                                              lambda x: total_angle(blade.sections, x, blade.pitch))
    mass, stiffness = blade_properties(blade)
    return sample_beam(hermite_evaluator(nodes, values, slopes), nodes, mass, stiffness, damping_ratio,
                       ("flap 1", "edge 1", "flap 2"), gauss_points)


def turbine_from_elastodyn(main_path: str | Path, blade_shapes: ShapeSource = "fe", rpm: float | None = None,
                           pitch: float = 0.0, yaw_stiffness: float = NREL5MW_YAW_STIFFNESS,
                           yaw_damping: float = NREL5MW_YAW_DAMPING, gauss_points: int = 2) -> TurbineParameters:
    """The turbine of an ElastoDyn main file.

    blade_shapes : 'fe' (bladefem's FE modes at ``rpm``, default the file's RotSpeed) or 'polynomial' (the blade
        file's ElastoDyn polynomials, twisted); the tower uses the tower file's polynomials
    pitch : rad; yaw_stiffness, yaw_damping : N m/rad, N m s/rad (ServoDyn inputs; NREL 5MW values by default)
    gauss_points : quadrature points per element for the span nodes of the Kane model
    """
    from ...modal import modes

    if blade_shapes not in ("fe", "polynomial"):
        raise InputError(f"blade shapes must be 'fe' or 'polynomial', got '{blade_shapes}'", field="shapes")
    main = read_elastodyn_main(main_path)
    blade_file = read_elastodyn_blade(main.blade_files[0])
    if len(set(main.precone)) > 1 or len(set(main.tip_mass)) > 1 or len(set(main.blade_files)) > 1:
        raise InputError("all blades must be alike (same file, precone and tip mass)", file=main.path,
                         field="BldFile")
    blade = blade_from_elastodyn(blade_file, tip_radius=main.tip_radius, hub_radius=main.hub_radius,
                                 precone=main.precone[0], pitch=pitch, tip_mass=main.tip_mass[0])
    damping = np.array([blade_file.flap_damping_percent[0], blade_file.edge_damping_percent,
                        blade_file.flap_damping_percent[1]]) / 100.0
    speed = main.rotor_speed_rpm if rpm is None else rpm
    if blade_shapes == "fe":
        beam = blade_beam_from_modes(blade, modes(blade, rpm=speed, n_modes=6), damping, blade.sections.span,
                                     gauss_points)
    else:
        beam = blade_beam_from_polynomials(blade, blade_file.modes, damping, gauss_points)
    tower_length = main.tower_height - main.tower_base_height
    tower = tower_beam(read_elastodyn_tower(main.tower_file), tower_length, gauss_points=gauss_points)
    notes = (f"blade shapes: {'bladefem FE modes at %.4g rpm' % speed if blade_shapes == 'fe' else 'ElastoDyn polynomials (twisted)'}",
             "tower shapes: ElastoDyn polynomials of the tower file",
             f"yaw spring {yaw_stiffness:g} N m/rad and damper {yaw_damping:g} N m s/rad (ServoDyn inputs)")
    return TurbineParameters(
        tower=tower, blade=beam, n_blades=main.num_blades, tower_base_height=main.tower_base_height,
        twr2shft=main.twr2shft, overhang=main.overhang, shaft_tilt=main.shaft_tilt, precone=main.precone[0],
        hub_radius=main.hub_radius, hub_cm=main.hub_cm, hub_mass=main.hub_mass, hub_inertia=main.hub_inertia,
        generator_inertia=main.generator_inertia, gearbox_ratio=main.gearbox_ratio,
        nacelle_mass=main.nacelle_mass, nacelle_yaw_inertia=main.nacelle_yaw_inertia,
        nacelle_cm=np.array(main.nacelle_cm), yaw_bearing_mass=main.yaw_bearing_mass,
        drivetrain_stiffness=main.drivetrain_spring, drivetrain_damping=main.drivetrain_damper,
        yaw_stiffness=yaw_stiffness, yaw_damping=yaw_damping, blade_tip_mass=main.tip_mass[0], pitch=pitch,
        name=Path(main.path).stem, notes=blade.notes + notes)
