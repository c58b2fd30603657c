"""OpenFAST main input file (.fst) and the deck it names: ElastoDyn, AeroDyn (primary, blade and airfoil files),
InflowWind and ServoDyn, gathered in one :class:`OpenFASTDeck`.

Read from the .fst: ``TMax``, ``DT``, ``Gravity``, the module switches (``CompElast`` 1 ElastoDyn; ``CompInflow`` 0
still air or 1 InflowWind; ``CompAero`` 0 or 2 AeroDyn; ``CompServo`` 0 or 1; every other module off), the
environment (``AirDens``, ``KinVisc``, ``SpdSound`` when the .fst has them, OpenFAST 3.2 and later) and the module
file names, resolved against the .fst's folder. A switch or setting asking for something bladefem does not model
is an :class:`Unmodelled` entry (file, line, label, what to change); by default the first one is raised as an
:class:`InputError`, with ``unmodelled="keep"`` they are returned in :attr:`OpenFASTDeck.unmodelled`.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ..aero.polars import Polar
from ..aero.rotor import Inflow, Rotor
from ..errors import InputError
from ..formats._labels import Labels
from ..files import input_problem
from .aerodyn import AeroDynBlade, read_aerodyn_blade
from .aerodyn_primary import AeroDynPrimary, Unmodelled, default_air_density, read_aerodyn_primary
from .airfoil_polars import read_airfoil
from ..formats.elastodyn_main import ElastoDynMain, read_elastodyn_main
from ..models.turbine.parameters import STANDARD_GRAVITY
from .inflowwind import read_inflowwind
from .servodyn import ServoDyn, read_servodyn

#: Module switches that must be off: label -> (what it would add, the option that runs without it or "").
OFF_SWITCHES = {"CompSeaSt": ("sea state", "--foundation rigid"), "CompHydro": ("hydrodynamics", "--foundation rigid"),
                "CompSub": ("substructure", "--foundation rigid"), "CompMooring": ("mooring", "--foundation rigid"),
                "CompSoil": ("soil", "--foundation rigid"), "CompIce": ("ice loads", ""), "CompLidar": ("lidar", ""),
                "MHK": ("a marine turbine", "")}


@dataclass(frozen=True)
class OpenFASTDeck:
    """Everything bladefem reads from an OpenFAST deck (SI, rad).

    path : the .fst; t_max : TMax, s; dt : DT, s; gravity : Gravity, m/s^2 (standard gravity where the .fst has none)
    elastodyn : the ElastoDyn main file; pitch : BlPitch(i), rad; yaw : NacYaw, rad
    aerodyn : the AeroDyn primary file (None with CompAero 0); blades : its blade files (one per blade);
    polars : the first table of each airfoil file (AFTabMod 1), in AFNames order
    inflow : steady wind (zero wind with CompInflow 0); servodyn : None with CompServo 0
    air_density, kinematic_viscosity, speed_of_sound : resolved (AeroDyn's value, else the .fst's, else OpenFAST's
    standard air 1.225 kg/m^3, 1.464e-5 m^2/s, 335 m/s)
    unmodelled : settings asking for unmodelled physics (only with ``unmodelled="keep"``)
    left_out : what the ways forward of ``leave_out`` left out, one line each (said in the output's header)
    """

    path: str
    t_max: float
    dt: float
    elastodyn: ElastoDynMain
    pitch: tuple[float, ...]
    yaw: float
    aerodyn: AeroDynPrimary | None
    blades: tuple[AeroDynBlade, ...]
    polars: tuple[Polar, ...]
    inflow: Inflow
    servodyn: ServoDyn | None
    air_density: float
    kinematic_viscosity: float
    speed_of_sound: float
    unmodelled: tuple[Unmodelled, ...] = ()
    left_out: tuple[str, ...] = ()
    gravity: float = STANDARD_GRAVITY

    @property
    def hub_height(self) -> float:
        """Rotor centre above the ground (ElastoDyn: TowerHt + Twr2Shft + OverHang sin ShftTilt), m."""
        ed = self.elastodyn
        return ed.tower_height + ed.twr2shft + ed.overhang * math.sin(ed.shaft_tilt)

    def rotor(self) -> Rotor:
        """The rigid rotor of this deck for :func:`bladefem.aero.rotor_performance`."""
        if self.aerodyn is None:
            raise InputError("the deck has no aerodynamics (CompAero 0)", file=self.path, field="CompAero")
        ed, blade = self.elastodyn, self.blades[0]
        if any(abs(cone - ed.precone[0]) > 1e-12 for cone in ed.precone):
            raise InputError("bladefem's rotor needs equal PreCone for every blade", file=ed.path,
                             line=ed.key_lines.get("PreCone(2)"), field="PreCone(2)")
        if blade.span[-1] > (ed.tip_radius - ed.hub_radius) * 1.001:
            raise InputError(f"the AeroDyn blade reaches {blade.span[-1]:g} m from the root but ElastoDyn's blade "
                             f"is {ed.tip_radius - ed.hub_radius:g} m long (TipRad - HubRad)", file=blade.source,
                             line=blade.lines[-1], field="BlSpn")
        return Rotor(n_blades=ed.num_blades, hub_radius=ed.hub_radius, span=blade.span, chord=blade.chord,
                     twist=blade.twist, airfoil=blade.airfoil - 1, polars=self.polars, curve=blade.curve,
                     sweep=blade.sweep, curve_angle=blade.curve_angle, precone=ed.precone[0], shaft_tilt=ed.shaft_tilt,
                     hub_height=self.hub_height,
                     air_density=self.air_density, kinematic_viscosity=self.kinematic_viscosity,
                     options=self.aerodyn.options(), notes=(f"rotor of {self.path}",),
                     dynamic_wake=self.aerodyn.dynamic_wake())


def read_openfast_deck(path: str | os.PathLike, unmodelled: str = "error",
                       leave_out: frozenset[str] | set[str] = frozenset(), controller: bool = False,
                       dynamic_wake: bool = False) -> OpenFASTDeck:
    """Read a .fst and its modules. ``unmodelled``: "error" raises the first unmodelled setting as an
    :class:`InputError` naming the option of :data:`~bladefem.builders.aerodyn_primary.WAYS` that runs without it;
    "keep" returns them in the deck. ``leave_out``: the ways forward taken (options of ``WAYS``): what they cover
    is left out and listed in :attr:`OpenFASTDeck.left_out`; "--no-aero" (the caller leaves the aerodynamic loads
    out) drops AeroDyn's unmodelled settings. ``controller``: the caller runs a Bladed-style DLL of ServoDyn (a
    simulation without --rpm). ``dynamic_wake``: the caller models AeroDyn's dynamic wake (a time simulation), which
    the rotor then carries; otherwise DBEMT_Mod 1-3 is refused (or left out with --quasi-steady)."""
    if unmodelled not in ("error", "keep"):
        raise ValueError(f"unmodelled must be 'error' or 'keep', got {unmodelled!r}")
    fst = Labels.read(path)
    refused: list[Unmodelled] = []

    def refuse(label: str, message: str, way: str = "") -> None:
        refused.append(Unmodelled(fst.path, fst.line(label), fst.which(label) or label, message, way))

    elast = fst.int("CompElast")
    if elast == 2:
        refuse("CompElast", "BeamDyn blades (CompElast 2) are not modelled in the turbine: set 1 (ElastoDyn)",
               "--elastodyn-blades")
    elif elast != 1:
        refuse("CompElast", f"CompElast {elast} is not modelled: set 1 (ElastoDyn)")
    inflow_switch = fst.int("CompInflow", choices=(0, 1, 2))
    if inflow_switch == 2:
        refuse("CompInflow", "external inflow (CompInflow 2) is not modelled: set 1 (InflowWind) or 0")
    aero_switch = fst.int("CompAero", choices=(0, 1, 2, 3))
    if aero_switch in (1, 3):
        what = "AeroDyn 14 / AeroDisk" if aero_switch == 1 else "external loads"
        refuse("CompAero", f"CompAero {aero_switch} ({what}) is not modelled: set 2 (AeroDyn) or 0")
    servo_switch = fst.int("CompServo", choices=(0, 1))
    for label, (what, way) in OFF_SWITCHES.items():
        if fst.has(label) and fst.int(label) != 0:
            refuse(label, f"{what} ({label} {fst.int(label)}) is not modelled: set {label} 0", way)
    if fst.has("NRotors") and fst.int("NRotors") != 1:
        refuse("NRotors", "more than one rotor is not modelled: set NRotors 1")
    if fst.has("MirrorRotor") and fst.bool("MirrorRotor"):
        refuse("MirrorRotor", "a mirrored (counter-clockwise) rotor is not modelled: set MirrorRotor False")
    t_max = fst.float("TMax", positive=True)
    elastodyn = read_elastodyn_main(fst.existing_file("EDFile"))
    ed_labels = Labels(elastodyn.text)
    pitch = tuple(math.radians(ed_labels.float(f"BlPitch({i})")) for i in range(1, elastodyn.num_blades + 1))
    aerodyn, blades, polars = None, (), ()
    if aero_switch == 2:
        aerodyn = read_aerodyn_primary(fst.existing_file("AeroFile"))
        if "--no-aero" not in leave_out:         # with the aerodynamic loads left out, what they lack does not matter
            refused += aerodyn.unmodelled(dynamic_wake=dynamic_wake and "--quasi-steady" not in leave_out)
        if not dynamic_wake or "--quasi-steady" in leave_out:      # refused above, or left out
            aerodyn = replace(aerodyn, dbemt_mod=min(aerodyn.dbemt_mod, 0))
        blades = _blades(aerodyn, elastodyn.num_blades)
        polars = tuple(read_airfoil(file, aerodyn.columns)[0] for file in aerodyn.airfoil_files)
        _check_airfoil_ids(aerodyn, blades)
    servo = read_servodyn(fst.existing_file("ServoFile")) if servo_switch == 1 else None
    if servo is not None:
        refused += servo.unmodelled(t_max, controller)
    left_out = _left_out(refused, leave_out)
    refused = [entry for entry in refused if entry.way not in leave_out or not entry.way]
    if refused and unmodelled == "error":
        first = refused[0]
        raise InputError(first.refusal(), file=first.file, line=first.line, field=first.label)
    deck = OpenFASTDeck(
        path=fst.path, t_max=t_max, dt=fst.float("DT", positive=True), elastodyn=elastodyn, pitch=pitch,
        yaw=math.radians(ed_labels.float("NacYaw")) if ed_labels.has("NacYaw") else 0.0, aerodyn=aerodyn,
        blades=blades, polars=polars, inflow=Inflow(0.0, 1.0), servodyn=servo,
        air_density=default_air_density(_environment(aerodyn, fst, "air_density", "AirDens")),
        kinematic_viscosity=_environment(aerodyn, fst, "kinematic_viscosity", "KinVisc") or 1.464e-5,
        speed_of_sound=_environment(aerodyn, fst, "speed_of_sound", "SpdSound") or 335.0,
        unmodelled=tuple(refused), left_out=left_out,
        gravity=fst.float("Gravity", non_negative=True) if fst.has("Gravity") else STANDARD_GRAVITY)
    inflow = read_inflowwind(fst.existing_file("InflowFile")) if inflow_switch == 1 else Inflow(0.0,
                                                                                                  deck.hub_height)
    return OpenFASTDeck(**{**deck.__dict__, "inflow": inflow})


def _left_out(found: list[Unmodelled], leave_out: frozenset[str] | set[str]) -> tuple[str, ...]:
    """One line per way forward taken, naming everything it leaves out with its file and label."""
    lines = []
    for way, what in (("--foundation rigid", "foundation rigid: the tower is clamped at its base; left out"),
                      ("--quasi-steady", "quasi-steady aerodynamics: not modelled and left out"),
                      ("--rpm", "fixed operation at --rpm and the pitch of --pitch-deg (or BlPitch): left out"),
                      ("--elastodyn-blades", "blades from ElastoDyn's blade files (BldFile): left out")):
        entries = [entry for entry in found if entry.way == way]
        if way in leave_out and entries:
            lines.append(f"{what}: " + "; ".join(f"{re.split(' (?:is|are) not ', entry.message)[0]} ({Path(entry.file).name}, "
                                                 f"line {entry.line}, {entry.label})" for entry in entries))
    return tuple(lines)


def _environment(aerodyn: AeroDynPrimary | None, fst: Labels, name: str, label: str) -> float | None:
    value = getattr(aerodyn, name) if aerodyn is not None else None
    if value is None and fst.has(label) and not fst.is_default(label):
        value = fst.float(label, positive=True)
    return value


def _blades(aerodyn: AeroDynPrimary, count: int) -> tuple[AeroDynBlade, ...]:
    """One AeroDyn blade file per ElastoDyn blade, all with the same planform."""
    if len(aerodyn.blade_files) < count:
        labels = Labels.read(aerodyn.path)
        last = f"ADBlFile({len(aerodyn.blade_files)})"
        raise InputError(f"ElastoDyn has {count} blades but only {len(aerodyn.blade_files)} ADBlFile entries",
                         file=aerodyn.path, line=labels.line(last) if labels.has(last) else len(labels.text.lines),
                         field=f"ADBlFile({len(aerodyn.blade_files) + 1})")
    blades = []
    for i, file in enumerate(aerodyn.blade_files[:count]):
        label = f"ADBlFile({i + 1})"
        problem = input_problem(file)
        if problem is not None:
            raise InputError(f"{problem}: {file}", file=aerodyn.path,
                             line=Labels.read(aerodyn.path).line(label), field=label)
        blades.append(read_aerodyn_blade(file))
    first = blades[0]
    for i, blade in enumerate(blades[1:], start=2):
        same = (blade.span.shape == first.span.shape and np.array_equal(blade.span, first.span)
                and np.array_equal(blade.chord, first.chord) and np.array_equal(blade.twist, first.twist)
                and np.array_equal(blade.airfoil, first.airfoil))
        if not same:
            raise InputError("blades with different AeroDyn planforms are not modelled: give every blade the same "
                             "file", file=aerodyn.path, line=Labels.read(aerodyn.path).line(f"ADBlFile({i})"),
                             field=f"ADBlFile({i})")
    return tuple(blades)


def _check_airfoil_ids(aerodyn: AeroDynPrimary, blades: tuple[AeroDynBlade, ...]) -> None:
    for blade in blades:
        bad = np.flatnonzero(blade.airfoil > len(aerodyn.airfoil_files))
        if bad.size:
            raise InputError(f"airfoil {blade.airfoil[bad[0]]} does not exist (NumAFfiles is "
                             f"{len(aerodyn.airfoil_files)})", file=blade.source, line=blade.lines[bad[0]],
                             field="BlAFID")
