"""AeroDyn primary input file (AeroDyn 15 of OpenFAST 2.x-3.x and the renamed layout of OpenFAST 4 and 5).

Labels are found wherever they are and whatever their case. The legacy names map to the new ones as AeroDyn itself
maps them: WakeMod 1 -> Wake_Mod 1 (DBEMT_Mod 0), WakeMod 2 -> Wake_Mod 1 with dynamic wake, AFAeroMod 1 ->
UA_Mod 0, AFAeroMod 2 -> UA_Mod = UAMod, SkewMod 0/1/2 -> Skew_Mod -1/0/1, SkewModFactor -> SkewRedistrFactor,
FrozenWake True -> DBEMT_Mod -1; missing new entries take AeroDyn's defaults (Wake_Mod 1, BEM_Mod 1, Skew_Mod 1,
SkewMomCorr False, SkewRedistr_Mod 1, SectAvg False).

Physics bladefem does not model (unsteady airfoil aerodynamics, free vortex wake, tower influence and drag, nacelle
and tail-fin drag, buoyancy, cavitation, aero-acoustics, sector averaging, Reynolds interpolation of the polars,
the skew momentum correction; the dynamic wake outside time simulations) is listed by
:meth:`AeroDynPrimary.unmodelled` with the line and label of the switch that asks for it, so that a caller can
refuse the deck with a one-line error. The dynamic wake (DBEMT_Mod 1, 2, 3 with ``tau1_const``) is modelled in the
turbine's time simulation (:mod:`bladefem.aero.dynamic_wake`, :meth:`AeroDynPrimary.dynamic_wake`).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

from ..aero.dynamic_wake import DynamicWake
from ..aero.options import PITT_PETERS_FACTOR, BEMOptions
from ..formats._labels import Labels
from ..files import input_problem
from ..limits import MAX_BEM_ITERATIONS
from .airfoil_polars import PolarColumns

#: (label, value bladefem models, what the other values would add)
FLAGS = (("TwrPotent", 0, "tower potential-flow influence"), ("TwrShadow", 0, "tower shadow"),
         ("TwrAero", False, "tower drag"), ("CavitCheck", False, "cavitation check"),
         ("Buoyancy", False, "buoyancy"), ("NacelleDrag", False, "nacelle drag"),
         ("CompAA", False, "aero-acoustics"), ("TFinAero", False, "tail-fin aerodynamics"),
         ("SectAvg", False, "sector averaging"), ("AFTabMod", 1, "polar interpolation in Re or UserProp"),
         ("SkewMomCorr", False, "the skew momentum correction"))


#: The ways forward offered when a deck asks for what bladefem does not model: command-line option -> what it does.
WAYS = {"--foundation rigid": "runs the turbine with the tower clamped at its base (platform, hydrodynamics and "
                              "substructure left out)",
        "--quasi-steady": "runs quasi-steady BEM, leaving out the aerodynamic features bladefem does not model",
        "--rpm": "runs at a fixed rotor speed (--rpm R, with --pitch-deg P) without the controller",
        "--elastodyn-blades": "runs the blades of ElastoDyn's blade files (BldFile), which the deck carries, instead "
                              "of BeamDyn's"}


@dataclass(frozen=True)
class Unmodelled:
    """A switch asking for physics bladefem does not model: file, line, label, a one-line explanation, and the
    command-line option of :data:`WAYS` that runs the deck without it ("" when there is none: change the file)."""

    file: str
    line: int
    label: str
    message: str
    way: str = ""

    def refusal(self) -> str:
        """The message with the way forward, when there is one."""
        if not self.way:
            return self.message
        return f"{self.message}; or {self.way} {WAYS[self.way]}"


@dataclass(frozen=True)
class AeroDynPrimary:
    """The entries of an AeroDyn primary file (SI). ``None`` for an environment value means "default" (the
    glue code's value).

    wake_mod : 0 none, 1 BEM, 3 free vortex wake; dbemt_mod : dynamic wake (0 none, -1 frozen, 1-3 models)
    tau1_const : DBEMT's constant time constant tau1, s (DBEMT_Mod 1 and 3; nan when absent)
    ua_mod : unsteady airfoil model (0 quasi-steady); bem_mod : 1 legacy, 2 polar-grid projection
    skew_mod : -1 orthogonal only, 0 none, 1 skew model; skew_redistribution : SkewRedistr_Mod (0, 1)
    skew_factor : SkewRedistrFactor; tip_loss ... ti_drag, tolerance, max_iterations : the BEM switches
    use_cm : UseBlCm; columns : InCol_*; airfoil_files : AFNames (resolved, existing); blade_files : ADBlFile(i)
    flags : the values of the switches in :data:`FLAGS` that the file sets; lines : label -> line
    """

    path: str
    wake_mod: int
    dbemt_mod: int
    tau1_const: float
    ua_mod: int
    bem_mod: int
    skew_mod: int
    skew_redistribution: int
    skew_factor: float
    tip_loss: bool
    hub_loss: bool
    tangential_induction: bool
    axial_drag: bool
    tangential_drag: bool
    tolerance: float
    max_iterations: int
    air_density: float | None
    kinematic_viscosity: float | None
    speed_of_sound: float | None
    use_cm: bool
    columns: PolarColumns
    airfoil_files: tuple[Path, ...]
    blade_files: tuple[Path, ...]
    flags: dict[str, object]
    lines: dict[str, tuple[str, int]]

    def options(self) -> BEMOptions:
        """The BEM switches of this file."""
        return BEMOptions(
            induction=self.wake_mod != 0, tip_loss=self.tip_loss, hub_loss=self.hub_loss,
            tangential_induction=self.tangential_induction, axial_drag=self.axial_drag,
            tangential_drag=self.tangential_drag, pitching_moment=self.use_cm,
            skew_redistribution=self.skew_mod == 1 and self.skew_redistribution == 1,
            skew_factor=self.skew_factor, formulation=2 if self.bem_mod == 2 else 1, tolerance=self.tolerance,
            max_iterations=self.max_iterations)

    def dynamic_wake(self) -> DynamicWake | None:
        """The dynamic wake of DBEMT_Mod 1, 2, 3 (with the BEM, Wake_Mod 1), else None."""
        if self.wake_mod != 1 or self.dbemt_mod <= 0:
            return None
        return DynamicWake(self.dbemt_mod, self.tau1_const if self.dbemt_mod != 2 else math.nan)

    def unmodelled(self, dynamic_wake: bool = False) -> list[Unmodelled]:
        """Every switch of this file that asks for physics bladefem does not model; ``dynamic_wake``: the caller
        models DBEMT_Mod 1-3 (a time simulation), else they are listed too."""
        found = []

        def refuse(name: str, message: str, way: str = "--quasi-steady") -> None:
            label, line = self.lines[name]
            found.append(Unmodelled(self.path, line, label, message, way))

        if self.wake_mod not in (0, 1):
            refuse("wake_mod", f"Wake_Mod {self.wake_mod} (free vortex wake) is not modelled: set 1 (BEM) or 0", "")
        if self.wake_mod == 1 and self.dbemt_mod == -1:
            refuse("dbemt_mod", "a frozen wake in time (DBEMT_Mod -1, for linearization) is not modelled: set "
                                "DBEMT_Mod 0 (quasi-steady) or 1-3 (dynamic wake)")
        elif self.wake_mod == 1 and self.dbemt_mod > 0 and not dynamic_wake:
            refuse("dbemt_mod", f"dynamic wake (DBEMT_Mod {self.dbemt_mod}) is not modelled here: this analysis "
                                "is quasi-steady (set DBEMT_Mod 0, or the legacy WakeMod 1)")
        if self.ua_mod != 0:
            refuse("ua_mod", f"unsteady airfoil aerodynamics (UA_Mod {self.ua_mod}) are not modelled: set UA_Mod 0 "
                             "(legacy AFAeroMod 1)")
        if self.skew_mod == -1:
            refuse("skew_mod", "Skew_Mod -1 (orthogonal inflow only, for linearization) is not modelled: set 1", "")
        for label, modelled, physics in FLAGS:
            value = self.flags.get(label, modelled)
            if value != modelled:
                refuse(label, f"{physics} is not modelled: set {label} to {modelled}")
        return found


def read_aerodyn_primary(path: str | os.PathLike) -> AeroDynPrimary:
    """Read an AeroDyn primary file; malformed entries are :class:`InputError` naming file, line and label."""
    labels = Labels.read(path)
    lines: dict[str, tuple[str, int]] = {}

    def where(name: str, *keys: str) -> None:
        key = labels.which(*keys)
        lines[name] = (key or keys[0], labels.line(key) if key else max(len(labels.text.lines), 1))

    wake_mod, dbemt_mod = _wake(labels)
    where("wake_mod", "Wake_Mod", "WakeMod")
    where("dbemt_mod", "DBEMT_Mod", "WakeMod", "FrozenWake")
    tau1_const = _tau1_const(labels, wake_mod, dbemt_mod)
    ua_mod = _unsteady(labels)
    where("ua_mod", "UA_Mod", "AFAeroMod", "UAMod")
    skew_mod = _skew(labels)
    where("skew_mod", "Skew_Mod", "SkewMod")
    flags: dict[str, object] = {}
    for label, modelled, _ in FLAGS:
        if labels.has(label):
            flags[label] = labels.bool(label) if isinstance(modelled, bool) else labels.int(label)
            where(label, label)
    columns = PolarColumns(*(_column(labels, name, default)
                             for name, default in (("Alfa", 1), ("Cl", 2), ("Cd", 3), ("Cm", 4))))
    taken = [c for c in (columns.alpha, columns.cl, columns.cd, columns.cm) if c]
    if len(set(taken)) < len(taken):
        raise labels.error(f"InCol_Alfa, InCol_Cl, InCol_Cd, InCol_Cm must name different columns, got {taken}",
                           labels.line("InCol_Cl") if labels.has("InCol_Cl") else None, "InCol_Cl")
    use_cm = labels.bool("UseBlCm")
    if use_cm and columns.cm == 0:
        raise labels.error("UseBlCm is True but InCol_Cm is 0 (no moment column)", labels.line("UseBlCm"),
                           "UseBlCm")
    return AeroDynPrimary(
        path=labels.path, wake_mod=wake_mod, dbemt_mod=dbemt_mod, tau1_const=tau1_const, ua_mod=ua_mod,
        bem_mod=_bem_mod(labels), skew_mod=skew_mod,
        skew_redistribution=(labels.int("SkewRedistr_Mod", default=1, choices=(0, 1))
                             if labels.has("SkewRedistr_Mod") else 1),
        skew_factor=labels.float("SkewRedistrFactor", "SkewModFactor", default=PITT_PETERS_FACTOR)
        if labels.has("SkewRedistrFactor", "SkewModFactor") else PITT_PETERS_FACTOR,
        tip_loss=labels.bool("TipLoss"), hub_loss=labels.bool("HubLoss"),
        tangential_induction=labels.bool("TanInd"), axial_drag=labels.bool("AIDrag"),
        tangential_drag=labels.bool("TIDrag"),
        tolerance=labels.float("IndToler", default=5e-10, positive=True),
        max_iterations=_iterations(labels),
        air_density=_environment(labels, "AirDens"), kinematic_viscosity=_environment(labels, "KinVisc"),
        speed_of_sound=_environment(labels, "SpdSound"), use_cm=use_cm, columns=columns,
        airfoil_files=_airfoil_files(labels), blade_files=_blade_files(labels), flags=flags, lines=lines)


def _wake(labels: Labels) -> tuple[int, int]:
    """(Wake_Mod, DBEMT_Mod) with the legacy WakeMod and FrozenWake mapped as AeroDyn does (WakeMod 10, 11, 12 of
    OpenFAST v3.5 as 0, 1, 2: :func:`_bem_mod`)."""
    if labels.has("Wake_Mod") and labels.has("WakeMod"):
        raise labels.error("give either Wake_Mod or the legacy WakeMod, not both", labels.line("WakeMod"),
                           "WakeMod")
    dbemt = labels.int("DBEMT_Mod", choices=(-1, 0, 1, 2, 3)) if labels.has("DBEMT_Mod") else 0
    if labels.has("WakeMod"):
        legacy = labels.int("WakeMod", choices=(0, 1, 2, 3, 10, 11, 12)) % 10   # 1x: see polar_projection()
        wake, dbemt = (1, dbemt) if legacy == 2 else (legacy, 0 if legacy == 1 else dbemt)
        if legacy == 2 and dbemt <= 0:
            raise labels.error("the legacy WakeMod 2 needs DBEMT_Mod > 0", labels.line("WakeMod"), "WakeMod")
    else:
        wake = labels.int("Wake_Mod", choices=(0, 1, 3)) if labels.has("Wake_Mod") else 1
    if labels.has("FrozenWake") and labels.bool("FrozenWake"):
        dbemt = -1
    return wake, dbemt


def _tau1_const(labels: Labels, wake_mod: int, dbemt_mod: int) -> float:
    """tau1_const, s: required (positive) with the BEM's DBEMT_Mod 1 and 3, else not read (nan)."""
    if wake_mod != 1 or dbemt_mod not in (1, 3):
        return math.nan
    if not labels.has("tau1_const"):
        raise labels.error(f"DBEMT_Mod {dbemt_mod} needs tau1_const (the time constant, s)",
                           labels.line("DBEMT_Mod", "WakeMod"), "tau1_const")
    return labels.float("tau1_const", positive=True)


def _bem_mod(labels: Labels) -> int:
    """BEM_Mod; OpenFAST v3.5's WakeMod 10, 11, 12 are WakeMod 0, 1, 2 with the polar projection (its
    "AeroProjMod 2", BEM_Mod 2 from v4.0; AeroDyn.f90 of v3.5.0 to v3.5.5)."""
    if labels.has("BEM_Mod"):
        return labels.int("BEM_Mod", choices=(1, 2))
    if labels.has("WakeMod") and labels.int("WakeMod") >= 10:
        return 2
    return 1


def _unsteady(labels: Labels) -> int:
    """UA_Mod, from the legacy AFAeroMod/UAMod pair when it is not given."""
    if labels.has("UA_Mod"):
        if labels.has("UAMod"):
            raise labels.error("give either UA_Mod or the legacy UAMod, not both", labels.line("UAMod"), "UAMod")
        return labels.int("UA_Mod", choices=(0, 1, 2, 3, 4, 5, 6, 7))
    legacy = labels.int("AFAeroMod", choices=(1, 2))
    return 0 if legacy == 1 else labels.int("UAMod", choices=(1, 2, 3, 4, 5, 6, 7))


def _skew(labels: Labels) -> int:
    """Skew_Mod (-1, 0, 1), from the legacy SkewMod (0, 1, 2) when it is not given."""
    if labels.has("Skew_Mod"):
        if labels.has("SkewMod"):
            raise labels.error("give either Skew_Mod or the legacy SkewMod, not both", labels.line("SkewMod"),
                               "SkewMod")
        return labels.int("Skew_Mod", choices=(-1, 0, 1))
    if labels.has("SkewMod"):
        return {0: -1, 1: 0, 2: 1}[labels.int("SkewMod", choices=(0, 1, 2))]
    return 1


def _environment(labels: Labels, label: str) -> float | None:
    if not labels.has(label) or labels.is_default(label):
        return None
    return labels.float(label, positive=True)


def _airfoil_files(labels: Labels) -> tuple[Path, ...]:
    """AFNames: the file on the AFNames line and the next NumAFfiles - 1 names, one per line, each existing."""
    count = labels.int("NumAFfiles")
    if count < 1:
        raise labels.error(f"must be at least 1, got {count}", labels.line("NumAFfiles"), "NumAFfiles")
    first = labels.line("AFNames")
    folder = Path(labels.path).parent
    files, number = [], first
    while len(files) < count:
        if number > len(labels.text.lines):
            raise labels.error(f"expected {count} airfoil file names, found {len(files)}", len(labels.text.lines),
                               "AFNames")
        words = labels.text.lines[number - 1].split()
        if words and not words[0].startswith("!"):
            name = words[0].strip("\"'")
            path = Path(os.path.normpath(folder / name))
            problem = input_problem(path)
            if problem is not None:
                raise labels.error(f"airfoil file {len(files) + 1}: {problem}: {path}", number, "AFNames")
            files.append(path)
        number += 1
    return tuple(files)


def _iterations(labels: Labels) -> int:
    """MaxIter: 1 to :data:`~bladefem.limits.MAX_BEM_ITERATIONS`."""
    count = labels.int("MaxIter")
    if not 1 <= count <= MAX_BEM_ITERATIONS:
        raise labels.error(f"must lie between 1 and {MAX_BEM_ITERATIONS}, got {count}", labels.line("MaxIter"),
                           "MaxIter")
    return count


#: Most columns of an airfoil table (AeroDyn's hold 4 to 5; a few more with unsteady-aerodynamics data)
MAX_POLAR_COLUMNS = 100


def _column(labels: Labels, name: str, default: int) -> int:
    """A 1-based column of the airfoil tables, InCol_<name>; only Cm may be 0 (no moment column)."""
    if not labels.has(f"InCol_{name}"):
        return default
    column = labels.int(f"InCol_{name}")
    lowest = 0 if name == "Cm" else 1
    if not lowest <= column <= MAX_POLAR_COLUMNS:
        raise labels.error(f"a column number (counted from 1{', 0: none' if lowest == 0 else ''}) must lie between "
                           f"{lowest} and {MAX_POLAR_COLUMNS}, got {column}", labels.line(f"InCol_{name}"),
                           labels.which(f"InCol_{name}"))
    return column


def _blade_files(labels: Labels) -> tuple[Path, ...]:
    files = []
    for i in range(1, 4):
        if labels.has(f"ADBlFile({i})"):
            files.append(labels.file(f"ADBlFile({i})"))
    if not files:
        raise labels.error("missing label", len(labels.text.lines), "ADBlFile(1)")
    return tuple(files)


def default_air_density(value: float | None) -> float:
    """AirDens, or OpenFAST's standard air (1.225 kg/m^3) for "default"."""
    return 1.225 if value is None or not math.isfinite(value) else value
