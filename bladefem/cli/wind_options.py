"""The wind options of ``bladefem turbine DECK --simulate``: a turbulent box made for the case (``--turbulence``,
``--turbulence-intensity``, ``--turbulence-key``, its grid and time step, ``--turbulence-box`` to keep it as a
TurbSim ``.bts`` for OpenFAST), and the check that a full-field wind holds the rotor for the whole run."""

from __future__ import annotations

import argparse
import math
from dataclasses import replace

from ..errors import InputError

#: options that make a turbulent box (dest names)
TURBULENCE = ("turbulence", "turbulence_intensity", "turbulence_seed", "turbulence_grid", "turbulence_dt",
              "turbulence_box")


def add_wind_options(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("turbulent wind (--simulate; replaces the deck's steady wind)")
    group.add_argument("--turbulence", choices=("A", "B", "C"), default=None, metavar="CLASS",
                       help="IEC 61400-1 normal turbulence of class A, B or C (Kaimal spectrum, IEC coherence, made "
                            "by pyconturb) about --wind-speed (or HWindSpeed) with the shear of PLExp/--shear-exp")
    group.add_argument("--turbulence-intensity", type=float, default=None, metavar="PERCENT",
                       help="the longitudinal turbulence intensity instead of an IEC class, percent")
    group.add_argument("--turbulence-key", "--turbulence-seed", dest="turbulence_seed", type=int, default=None,
                       metavar="N", help="random key (seed) of the box (default 1): one key, one box")
    group.add_argument("--turbulence-grid", type=int, default=None, metavar="N",
                       help="points per side of the square grid over the rotor (default 9)")
    group.add_argument("--turbulence-dt", type=float, default=None, metavar="SECONDS",
                       help="time step of the box, s (default 0.25)")
    group.add_argument("--turbulence-box", default=None, metavar="FILE.bts",
                       help="also write the box as a TurbSim .bts file (to run OpenFAST in the same wind)")


def wants_turbulence(args: argparse.Namespace) -> bool:
    return args.turbulence is not None or args.turbulence_intensity is not None


def check_wind_options(args: argparse.Namespace) -> None:
    """Refuse turbulence options without --simulate, both a class and an intensity, the details without either,
    and values out of range."""
    given = [name for name in TURBULENCE if getattr(args, name, None) is not None]
    if given and not args.simulate:
        raise InputError("applies to --simulate only", field="--" + given[0].replace("_", "-"))
    if args.turbulence is not None and args.turbulence_intensity is not None:
        raise InputError("give an IEC class (--turbulence) or an intensity, not both", field="--turbulence-intensity")
    if given and not wants_turbulence(args):
        raise InputError("needs --turbulence CLASS or --turbulence-intensity", field="--" + given[0].replace("_", "-"))
    if given and args.no_aero:
        raise InputError("has no effect with --no-aero", field="--" + given[0].replace("_", "-"))
    checks = (("turbulence_intensity", lambda v: math.isfinite(v) and 0 < v <= 50, "a percentage in (0, 50]"),
              ("turbulence_grid", lambda v: 3 <= v <= 65, "between 3 and 65 points"),
              ("turbulence_dt", lambda v: math.isfinite(v) and 0.01 <= v <= 2.0, "between 0.01 and 2 s"),
              ("turbulence_seed", lambda v: 0 <= v < 2**32, "between 0 and 2^32 - 1"))
    names = {"turbulence_seed": "turbulence-key"}
    for name, good, what in checks:
        value = getattr(args, name)
        if value is not None and not good(value):
            raise InputError(f"must be {what}, got {value}", field="--" + names.get(name, name.replace("_", "-")))


def apply_wind(args: argparse.Namespace, model):
    """The model in the wind the options ask for: a turbulent box made here (and written to --turbulence-box), or
    the deck's; a full field that does not hold the rotor for the run is refused."""
    if model.aero is None:
        return model
    radius = float(model.aero.rotor.hub_radius + model.aero.rotor.span[-1])
    hub_height = float(model.aero.rotor.hub_height)
    inflow = model.aero.inflow
    if wants_turbulence(args):
        if inflow.kind != "steady":
            raise InputError(f"the deck's InflowWind gives {inflow.kind} wind already: a turbulent box replaces "
                             "steady wind (WindType 1) only", field="--turbulence")
        inflow = replace(inflow, grid=turbulent_box(args, inflow, hub_height, radius))
        model = type(model)(model.params, aero=replace(model.aero, inflow=inflow), generator=model.generator)
    elif inflow.kind != "steady" and (args.wind_speed is not None or args.shear_exp is not None):
        raise InputError(f"the deck's {inflow.kind} wind file sets the wind", field="--wind-speed"
                         if args.wind_speed is not None else "--shear-exp")
    inflow.check_covers(hub_height, radius, args.simulate)
    return model


def turbulent_box(args: argparse.Namespace, inflow, hub_height: float, radius: float):
    """The periodic box of the options about the hub (written as a .bts if asked)."""
    from ..aero.turbulence import TurbulenceSpec, rotor_width, turbulent_grid

    spec = TurbulenceSpec(speed=inflow.speed * (hub_height / inflow.reference_height) ** inflow.shear_exponent,
                          hub_height=hub_height, shear_exponent=inflow.shear_exponent, duration=args.simulate,
                          width=rotor_width(radius), turbulence_class=args.turbulence,
                          intensity=None if args.turbulence_intensity is None else args.turbulence_intensity / 100,
                          key=1 if args.turbulence_seed is None else args.turbulence_seed,
                          dt=0.25 if args.turbulence_dt is None else args.turbulence_dt,
                          points=9 if args.turbulence_grid is None else args.turbulence_grid)
    if spec.speed <= 0:
        raise InputError("a turbulent box needs a positive mean wind speed", field="--wind-speed")
    grid = turbulent_grid(spec)
    if args.turbulence_box:
        from ..formats.turbsim import TurbSimBox, write_turbsim
        write_turbsim(args.turbulence_box, TurbSimBox(
            velocity=grid.velocity, tower=grid.velocity[:, :0, 0, :], dt=grid.dt, dy=grid.dy, dz=grid.dz, z0=grid.z0,
            mean_speed=grid.mean_speed, hub_height=hub_height, periodic=True,
            description=f"bladefem: IEC normal turbulence (pyconturb), key {spec.key}"))
    return grid
