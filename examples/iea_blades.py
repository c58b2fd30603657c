"""The IEA-15MW and IEA-22MW blades' first six modes from every format bladefem reads, through the three section
models (the whole six-by-six in the FE with the transverse shear, a Timoshenko beam; the same with the shear
condensed, an Euler-Bernoulli beam; and the diagonal reduction), parked and at rated rotor speed; and what the
shear and the reduction's dropped terms each contribute; and the full sections against OpenFAST/BeamDyn on the
straightened blades. ``python examples/iea_blades.py`` prints the tables of docs/iea-blades.md.

Rated rotor speeds are the turbines' controller settings (ROSCO ``PC_RefSpd``, gearbox ratio 1): IEA-15MW 0.79168
rad/s = 7.560 rpm, IEA-22MW 0.72086 rad/s = 6.884 rpm (IEA-22-280-RWT at 022e8f8, OpenFAST/IEA-22-280-RWT-Monopile/
IEA-22-280-RWT_DISCON.IN). Hub radii from the ElastoDyn main files: 3.97 m and 4.2 m. Clamped root, no precone, no
gravity, the files' curved reference axis (prebend), at rated speed on the axis deflected by the centrifugal load
(:func:`bladefem.modal.operating_point.deflected_blade`), mesh refined until converged. The prebend's effect
(prebent over straightened, with the decks' precone, against OpenFAST with BeamDyn) is the third table.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from bladefem.builders.detect import read_model
from bladefem.builders.section_axes import full_sections_from_beamdyn
from bladefem.formats.beamdyn import read_beamdyn_blade, read_beamdyn_primary
from bladefem.modal import modes
from bladefem.modal.operating_point import deflected_blade
from bladefem.sections import Blade, FullSections, full_sections_from_table
from bladefem.sections.full_section import CLASSICAL, SHEAR, about_reference, condensed

DATA = Path(__file__).resolve().parent.parent / "tests" / "data"
#: the first six modes, by kind and order
SIX = (("flap", 1), ("edge", 1), ("flap", 2), ("edge", 2), ("flap", 3), ("torsion", 1))
RATED_RPM = {"IEA-15MW": 0.79168 * 60 / (2 * math.pi), "IEA-22MW": 0.72086 * 60 / (2 * math.pi)}
HUB_RADIUS = {"IEA-15MW": 3.97, "IEA-22MW": 4.2}
SECTION_MODELS = ("full", "condensed", "reduced")
INPUTS = {
    "IEA-15MW": {
        "BeamDyn": (DATA / "iea15" / "beamdyn" / "IEA-15-240-RWT_BeamDyn.dat", {}),
        "HAWC2 FPM st + htc": (DATA / "iea15" / "hawc2" / "IEA_15MW_RWT_Blade_st_FPM.st",
                               {"htc": DATA / "iea15" / "hawc2" / "IEA_15MW_RWT_WTG_bodies_noFPM.htc"}),
        "HAWC2 isotropic st + htc": (DATA / "iea15" / "hawc2" / "IEA_15MW_RWT_Blade_st_noFPM.st",
                                     {"htc": DATA / "iea15" / "hawc2" / "IEA_15MW_RWT_WTG_bodies_noFPM.htc"}),
        "windIO 2.x": (DATA / "iea15" / "windio" / "IEA-15-240-RWT_windio2_blade.yaml", {}),
        "windIO 1.x": (DATA / "iea15" / "windio" / "IEA-15-240-RWT_windio1.yaml", {}),
    },
    "IEA-22MW": {
        "BeamDyn": (DATA / "iea22" / "beamdyn" / "IEA-22-280-RWT_BeamDyn.dat", {}),
        "HAWC2 st + htc": (DATA / "iea22" / "hawc2" / "iea_22mw_rwt_steps_blade1.htc", {}),
        "windIO 2.x": (DATA / "iea22" / "windio" / "IEA-22-280-RWT_windio2_blade.yaml", {}),
    },
}


@dataclass(frozen=True)
class Row:
    turbine: str
    source: str
    sections: str
    rpm: float
    hz: tuple[float, ...]


def blade(turbine: str, source: str, sections: str) -> Blade:
    path, options = INPUTS[turbine][source]
    return read_model(path, hub_radius=HUB_RADIUS[turbine], sections=sections, **options)


def first_six(model: Blade, rpm: float) -> tuple[float, ...]:
    """Frequencies (Hz) of flap 1-3, edge 1-2, torsion 1 (by the modes' kinds); at speed on the deflected axis."""
    result = modes(deflected_blade(model, rpm)[0] if rpm > 0 else model, rpm, 12)
    found: dict[str, list[float]] = {}
    for kind, hz in zip(result.kinds, result.frequencies_hz):
        found.setdefault(kind, []).append(float(hz))
    return tuple(found[kind][order - 1] for kind, order in SIX)


def rows() -> list[Row]:
    out = []
    for turbine, sources in INPUTS.items():
        for source in sources:
            for sections in SECTION_MODELS:
                model = blade(turbine, source, sections)
                for rpm in (0.0, RATED_RPM[turbine]):
                    out.append(Row(turbine, source, sections, rpm, first_six(model, rpm)))
    return out


def with_sections(model: Blade, full: FullSections) -> Blade:
    return model.with_(sections=full.table())


def decoupled_torsion(full: FullSections) -> FullSections:
    """The same sections with the twist rate uncoupled from extension and bending in the classical (shear-
    condensed) stiffness: what the reduction drops of the stiffness besides the thickness-wise tension centre."""
    C = np.moveaxis(condensed(np.moveaxis(full.stiffness, 0, -1)), -1, 0)
    C[:, 1, [0, 2, 3]] = C[:, [0, 2, 3], 1] = 0.0
    K = np.zeros_like(full.stiffness)
    K[:, np.ix_(CLASSICAL, CLASSICAL)[0], np.ix_(CLASSICAL, CLASSICAL)[1]] = C
    s = np.ix_(SHEAR, SHEAR)
    K[:, s[0], s[1]] = full.stiffness[:, s[0], s[1]]
    return replace(full, stiffness=K)


def in_frame_of(full: FullSections, matrices: NDArray, twist: NDArray) -> NDArray:
    """Section matrices given in a frame turned by ``twist`` (rad), in the section frame of ``full``."""
    return np.array([about_reference(m, (0.0, 0.0), d) for m, d in zip(matrices, twist - full.twist)])


def contributions(turbine: str = "IEA-15MW", source: str = "BeamDyn", rpm: float = 0.0) -> dict[str, tuple]:
    """First six frequencies of: the full sections with the shear condensed (Euler-Bernoulli, like the reduction);
    the same with the shear kept (Timoshenko); the full stiffness with the reduction's mass; the reduction's
    stiffness with the full mass; the full mass turned with the principal axes (as the diagonal beam, whose one
    angle turns both, places it); the full sections with the twist rate uncoupled; the reduction written back as
    six-by-six matrices; the reduction. The reduction's matrices are turned into the full sections' frame (the
    reduction's twist holds the principal angle)."""
    full_blade = blade(turbine, source, "condensed")
    reduced_blade = blade(turbine, source, "reduced")
    full = full_blade.sections.full
    as_matrices = full_sections_from_table(reduced_blade.sections)
    variants = {
        "condensed six-by-six": full_blade,
        "full six-by-six, shear kept (Timoshenko)": blade(turbine, source, "full"),
        "full stiffness, reduced mass": with_sections(full_blade, replace(
            full, mass=in_frame_of(full, as_matrices.mass, as_matrices.twist))),
        "reduced stiffness, full mass": with_sections(full_blade, replace(
            full, stiffness=in_frame_of(full, as_matrices.stiffness, as_matrices.twist))),
        "full, mass turned with the principal axes": with_sections(full_blade, replace(
            full, mass=in_frame_of(full, full.mass, reduced_blade.sections.twist))),
        "full, twist uncoupled": with_sections(full_blade, decoupled_torsion(full)),
        "reduced, as six-by-six matrices": with_sections(full_blade, as_matrices),
        "reduced (diagonal beam)": reduced_blade,
    }
    return {name: first_six(model, rpm) for name, model in variants.items()}


#: OpenFAST v5.0.0 with BeamDyn (tests/data/openfast/beamdyn): turbine -> key, BeamDyn primary file, the deck's
#: HubRad (m), PreCone (deg), rated rpm and the finest order_elem run
REFERENCE = DATA / "openfast" / "beamdyn" / "linearizations.json"
DECKS = {"IEA-15MW": ("iea15", DATA / "iea15" / "beamdyn" / "IEA-15-240-RWT_BeamDyn.dat", 3.97, -4.0, 7.56, 14),
         "IEA-22MW": ("iea22", DATA / "iea22" / "beamdyn" / "IEA-22-280-RWT_BeamDyn.dat", 4.2, -4.0, 7.06, 14),
         "NREL 5MW": ("nrel5mw", DATA / "nrel5mw_beamdyn" / "bd_primary_nrel_5mw.inp", 1.5, -2.5, 12.1, 18)}


def straightened(turbine: str, shear: bool = True) -> Blade:
    """The BeamDyn blade as the OpenFAST reference ran it straightened (key points' x and y zero), with the deck's
    hub radius and precone."""
    _, path, hub, precone, _, _ = DECKS[turbine]
    primary = read_beamdyn_primary(path)
    blade_file = read_beamdyn_blade(primary.blade_path())
    z, twist = primary.key_points[:, 2], primary.key_points[:, 3]
    span = blade_file.eta * z[-1]
    full = full_sections_from_beamdyn(span, blade_file.stiffness, blade_file.mass,
                                      np.radians(np.interp(span, z, twist)))
    return Blade(full.with_shear(shear).table(), hub_radius=hub, precone=np.radians(precone))


def prebent(turbine: str) -> Blade:
    """The BeamDyn blade on its key points' curved axis, with the deck's hub radius and precone."""
    _, path, hub, precone, _, _ = DECKS[turbine]
    return read_model(path, hub_radius=hub, precone=np.radians(precone))


def beamdyn_rows(axis: str = "straight") -> list[tuple[str, float, list[str], NDArray, NDArray]]:
    """(turbine, rpm, bladefem's kinds, bladefem's and BeamDyn's lowest six frequencies in Hz, ascending) of the
    straightened blades, or of the ``"prebent"`` ones (the IEA blades; at speed on the deflected axis, as BeamDyn)."""
    runs = json.loads(REFERENCE.read_text())["runs"]
    out = []
    for turbine, (key, _, _, _, rated, order) in DECKS.items():
        if axis == "prebent" and turbine not in INPUTS:
            continue
        blade_ = straightened(turbine) if axis == "straight" else prebent(turbine)
        for rpm in (0.0, rated):
            run = next(r for r in runs if (r["turbine"], r["rpm"], r["reference_axis"], r["order_elem"])
                       == (key, rpm, axis, order))
            at = deflected_blade(blade_, rpm)[0] if axis == "prebent" and rpm > 0 else blade_
            result = modes(at, rpm, 6)
            out.append((turbine, rpm, result.kinds, result.frequencies_hz, np.array(run["frequencies_hz"][:6])))
    return out


def beamdyn_table(rows_: list[tuple[str, float, list[str], NDArray, NDArray]], label: str = "straightened") -> str:
    lines = [f"| {label} blade | rpm | mode 1 | mode 2 | mode 3 | mode 4 | mode 5 | mode 6 |",
             "|---|---|---|---|---|---|---|---|"]
    for turbine, rpm, kinds, ours, theirs in rows_:
        lines.append(f"| {turbine} | {rpm:.2f} | " + " | ".join(
            f"{kind} {b:.4f} / {t:.4f} ({100 * (b / t - 1):+.2f} %)" for kind, b, t in zip(kinds, ours, theirs))
            + " |")
    return "\n".join(lines)


def table(rows_: list[Row]) -> str:
    """One section model's rows as docs/iea-blades.md holds them."""
    lines = ["| blade, file | rpm | flap 1 | edge 1 | flap 2 | edge 2 | flap 3 | torsion 1 |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows_:
        lines.append(f"| {r.turbine} {r.source} | {r.rpm:.2f} | "
                     + " | ".join(f"{v:.4f}" for v in r.hz) + " |")
    return "\n".join(lines)


def contribution_table(values: dict[str, tuple]) -> str:
    base = np.array(values["condensed six-by-six"])
    lines = ["| model | flap 1 | edge 1 | flap 2 | edge 2 | flap 3 | torsion 1 |", "|---|---|---|---|---|---|---|"]
    for name, hz in values.items():
        cells = [f"{v:.4f}" if name == "condensed six-by-six" else f"{100 * (v / b - 1):+.3f} %"
                 for v, b in zip(hz, base)]
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


#: the decks' precone (deg) and the rated speeds of the BeamDyn linearizations (rpm)
DECK_PRECONE = {"IEA-15MW": -4.0, "IEA-22MW": -4.0}
DECK_RATED = {"IEA-15MW": 7.56, "IEA-22MW": 7.06}


def prebend_effects() -> dict[tuple[str, float], tuple[float, ...]]:
    """The lowest six frequencies' change (%, ascending as BeamDyn's) of the BeamDyn blade prebent over
    straightened, with the decks' hub radius and precone, parked and at the decks' rated speed (on the deflected
    axis)."""
    out = {}
    for turbine in INPUTS:
        path, options = INPUTS[turbine]["BeamDyn"]
        blades = [read_model(path, hub_radius=HUB_RADIUS[turbine], precone=math.radians(DECK_PRECONE[turbine]),
                             axis=axis, **options) for axis in ("curved", "straight")]
        for rpm in (0.0, DECK_RATED[turbine]):
            at = [deflected_blade(b, rpm)[0] if rpm > 0 else b for b in blades]
            curved, straight = (modes(b, rpm, 6).frequencies_hz for b in at)
            out[(turbine, rpm)] = tuple(100 * (curved / straight - 1))
    return out


def prebend_table(values: dict[tuple[str, float], tuple[float, ...]]) -> str:
    lines = ["| blade | rpm | 1 | 2 | 3 | 4 | 5 | 6 |", "|---|---|---|---|---|---|---|---|"]
    for (turbine, rpm), change in values.items():
        lines.append(f"| {turbine} bladefem | {rpm:.2f} | " + " | ".join(f"{v:+.2f} %" for v in change) + " |")
    return "\n".join(lines)


if __name__ == "__main__":
    computed = rows()
    for model in SECTION_MODELS:
        print(table([r for r in computed if r.sections == model]))
        print()
    for turbine in INPUTS:
        print(contribution_table(contributions(turbine)))
        print()
    print(beamdyn_table(beamdyn_rows()))
    print()
    print(beamdyn_table(beamdyn_rows("prebent"), "prebent"))
    print()
    print(prebend_table(prebend_effects()))
