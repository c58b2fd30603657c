"""The turbine of an input deck for ``bladefem turbine``: an OpenFAST ``.fst`` (ElastoDyn, AeroDyn, InflowWind,
ServoDyn) or an ElastoDyn main file alone (structure only).

From a ``.fst``: the structure from ElastoDyn (:func:`turbine_from_elastodyn`), the yaw spring and damper from
ServoDyn's ``YawSpr``, ``YawDamp``, the generator's torque law and efficiency from ServoDyn (``VSContrl`` 1), the
aerodynamics (quasi-steady BEM at the AeroDyn nodes) from AeroDyn and InflowWind; wind speed, shear exponent and
pitch may be overridden. ElastoDyn's DOF switches and initial conditions come with it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError
from ..limits import MAX_WIND_SPEED
from ..models.turbine.aero import TurbineAero
from ..models.turbine.control import Generator
from ..models.turbine.initial import InitialConditions
from ..models.turbine.parameters import TurbineParameters
from .servodyn import ServoDyn
from .turbine_elastodyn import (
    NREL5MW_YAW_DAMPING,
    NREL5MW_YAW_STIFFNESS,
    deck_conditions,
    platform_note,
    turbine_from_elastodyn,
)

#: words of a .fst's first lines that tell it from an ElastoDyn main file
FST_WORDS = {"CompElast", "EDFile"}


@dataclass(frozen=True)
class TurbineDeck:
    """A turbine and its loads as a deck describes them (SI).

    path : the deck; elastodyn : the ElastoDyn main file; params : the structure; aero : aerodynamic loads or None;
    generator : the torque law (None without ServoDyn); switches : ElastoDyn's DOF switches; conditions : its
    initial conditions; openfast : True for a .fst; notes : what the reading of its aerodynamics says
    """

    path: str
    elastodyn: str
    params: TurbineParameters
    aero: TurbineAero | None
    generator: Generator | None
    switches: dict[str, bool]
    conditions: InitialConditions
    openfast: bool
    notes: tuple[str, ...] = ()
    servodyn: ServoDyn | None = None
    time_step: float = 0.0
    hub_height: float = 0.0


def is_openfast_deck(path: str | Path) -> bool:
    """True for an OpenFAST main input file (suffix .fst, or CompElast and EDFile among its first lines)."""
    path = Path(path)
    if path.suffix.lower() == ".fst":
        return True
    try:
        with path.open(encoding="utf-8", errors="replace") as stream:
            words = {word for _, line in zip(range(200), stream) for word in line.split()[:3]}
    except OSError:
        return False
    return FST_WORDS <= words


def read_turbine_deck(path: str | Path, *, aero: bool = True, wind_speed: float | None = None,
                      shear_exponent: float | None = None, pitch: float | None = None,
                      yaw_stiffness: float | None = None, yaw_damping: float | None = None,
                      leave_out: frozenset[str] | set[str] = frozenset(), controller: bool = False,
                      dynamic_wake: bool = False, **structure) -> TurbineDeck:
    """The turbine of a .fst or an ElastoDyn main file.

    aero : include the aerodynamic loads of a .fst (False: structure and generator only)
    wind_speed : m/s at InflowWind's reference height; shear_exponent : power law; pitch : rad (default: BlPitch)
    yaw_stiffness, yaw_damping : N m/rad, N m s/rad (default: ServoDyn's, else the NREL 5MW's)
    leave_out : the ways forward taken (options of :data:`~bladefem.builders.aerodyn_primary.WAYS`: "--foundation
    rigid", "--quasi-steady", "--rpm"); what they leave out is named in the notes
    controller : the caller runs ServoDyn's Bladed-style DLL (else a DLL deck is refused but for --rpm)
    dynamic_wake : the caller simulates in time, with AeroDyn's dynamic wake (DBEMT_Mod 1-3; else refused)
    structure : keyword arguments of :func:`turbine_from_elastodyn` (blade_shapes, rpm, tower_shapes, ...)
    """
    if wind_speed is not None and not 0 <= wind_speed <= MAX_WIND_SPEED:
        raise InputError(f"must lie between 0 and {MAX_WIND_SPEED:g} m/s (MAX_WIND_SPEED), got {wind_speed:g}",
                         field="--wind-speed")
    if pitch is not None and not abs(pitch) <= math.pi:
        raise InputError(f"must lie between -180 and 180 deg, got {math.degrees(pitch):g}", field="--pitch-deg")
    if not Path(path).is_file():
        raise InputError("file not found", file=str(path))
    if not is_openfast_deck(path):
        for name, value in (("--wind-speed", wind_speed), ("--shear-exp", shear_exponent)):
            if value is not None:
                raise InputError("needs aerodynamics: give an OpenFAST .fst deck (this is an ElastoDyn main file)",
                                 file=str(path), field=name)
        params = turbine_from_elastodyn(
            path, pitch=pitch, yaw_stiffness=NREL5MW_YAW_STIFFNESS if yaw_stiffness is None else yaw_stiffness,
            yaw_damping=NREL5MW_YAW_DAMPING if yaw_damping is None else yaw_damping, **structure)
        rigid = "--foundation rigid" in leave_out
        switches, conditions = deck_conditions(path, rigid)
        return TurbineDeck(str(path), str(path), params, None, None, switches, conditions, False,
                           (platform_note(path),) if rigid else ())
    from .openfast_fst import read_openfast_deck
    deck = read_openfast_deck(path, leave_out=set(leave_out) | ({"--no-aero"} if not aero else set()),
                              controller=controller, dynamic_wake=dynamic_wake)
    servo = deck.servodyn
    if yaw_stiffness is None:
        yaw_stiffness = servo.yaw_spring if servo is not None else NREL5MW_YAW_STIFFNESS
    if yaw_damping is None:
        yaw_damping = servo.yaw_damper if servo is not None else NREL5MW_YAW_DAMPING
    main = deck.elastodyn.path
    params = turbine_from_elastodyn(main, pitch=pitch, yaw_stiffness=yaw_stiffness, yaw_damping=yaw_damping,
                                    **structure).with_(gravity=deck.gravity)
    loads = None
    if deck.aerodyn is None:
        for name, value in (("--wind-speed", wind_speed), ("--shear-exp", shear_exponent)):
            if value is not None:
                raise InputError("needs aerodynamics, but the deck has none (CompAero 0)", file=deck.path,
                                 field=name)
    elif aero:
        loads = TurbineAero.from_deck(deck, params, wind_speed=wind_speed, shear_exponent=shear_exponent)
    generator = Generator.from_servodyn(servo) if servo is not None else None
    rigid = "--foundation rigid" in leave_out
    switches, conditions = deck_conditions(main, rigid)
    notes = ((platform_note(main),) if rigid else ()) + deck.left_out
    return TurbineDeck(deck.path, str(main), params, loads, generator, switches, conditions, True, notes, servo,
                       deck.dt, deck.hub_height)
