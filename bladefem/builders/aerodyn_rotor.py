"""The rotor for a blade's aerodynamics from an AeroDyn primary file alone (its first blade file and its airfoils),
with the hub radius and precone of the structural blade: the input of ``bladefem modes --aero``."""

from __future__ import annotations

import os

import numpy as np

from ..aero.rotor import Rotor
from ..errors import InputError
from ..files import input_problem
from ..sections import Blade
from ..formats._labels import Labels
from .aerodyn import SPAN_RTOL, read_aerodyn_blade
from .aerodyn_primary import default_air_density, read_aerodyn_primary
from .airfoil_polars import read_airfoil


def aerodyn_rotor(primary_path: str | os.PathLike, blade: Blade, n_blades: int = 3,
                  offered: frozenset[str] = frozenset(), taken: frozenset[str] = frozenset(),
                  replaced: dict[str, str] | None = None) -> Rotor:
    """A rigid rotor of ``n_blades`` blades with the planform of the primary file's ADBlFile(1), its polars (first
    table of each airfoil file) and BEM switches, and the blade's hub radius and precone (no shaft tilt). Settings
    asking for physics bladefem does not model, a missing blade file, an airfoil number beyond NumAFfiles or an
    AeroDyn blade longer than the structural one are :class:`InputError` naming file, line and field. ``offered``:
    the ways forward (:data:`~bladefem.builders.aerodyn_primary.WAYS`) the calling command has, named in the
    refusal; ``taken``: those given on its command line, which leave such settings out (said in the notes).
    ``replaced``: labels (e.g. ``UA_Mod``) whose physics the caller models its own way -> the note that says how;
    those settings are accepted and the note joins the rotor's notes."""
    primary = read_aerodyn_primary(primary_path)
    replaced = replaced or {}
    unmodelled = primary.unmodelled()
    refused = [item for item in unmodelled if item.way not in taken and item.label not in replaced]
    left_out = tuple(f"left out ({item.way}): {item.label} = {item.message.split(' are not')[0].split(' is not')[0]}"
                     for item in unmodelled if item.way in taken and item.label not in replaced)
    left_out += tuple(f"{item.label} of {primary.path}: {replaced[item.label]}" for item in unmodelled
                      if item.label in replaced)
    if refused:
        first = refused[0]
        message = first.refusal() if first.way in offered else first.message
        raise InputError(message, file=first.file, line=first.line, field=first.label)
    labels = Labels.read(primary.path)
    problem = input_problem(primary.blade_files[0]) if primary.blade_files else "no ADBlFile(1) entry"
    if problem is not None:
        missing = f": {primary.blade_files[0]}" if primary.blade_files else ""
        raise InputError(f"blade file: {problem}{missing}", file=primary.path,
                         line=labels.line("ADBlFile(1)") if labels.has("ADBlFile(1)") else None, field="ADBlFile(1)")
    planform = read_aerodyn_blade(primary.blade_files[0])
    polars = tuple(read_airfoil(file, primary.columns)[0] for file in primary.airfoil_files)
    bad = np.flatnonzero(planform.airfoil > len(polars))
    if bad.size:
        raise InputError(f"airfoil {planform.airfoil[bad[0]]} does not exist (NumAFfiles is {len(polars)})",
                         file=planform.source, line=planform.lines[bad[0]], field="BlAFID")
    if planform.span[-1] > blade.length * (1 + SPAN_RTOL):
        raise InputError(f"the AeroDyn blade reaches {planform.span[-1]:g} m from the root but the structural "
                         f"blade is {blade.length:g} m long", file=planform.source, line=planform.lines[-1],
                         field="BlSpn")
    return Rotor(n_blades=n_blades, hub_radius=blade.hub_radius, span=planform.span, chord=planform.chord,
                 twist=planform.twist, airfoil=planform.airfoil - 1, polars=polars, curve=planform.curve,
                 sweep=planform.sweep, curve_angle=planform.curve_angle, precone=blade.precone,
                 air_density=default_air_density(primary.air_density),
                 options=primary.options(), notes=(f"aerodynamics of {primary.path} ({planform.source})", *left_out))


def require_root_off_axis(rotor: Rotor) -> None:
    """Refuse a rotating BEM whose first AeroDyn node sits on the rotor axis (hub radius 0, BlSpn 0: a blade file
    that does not give the hub radius): the induction and the hub loss divide by the radius."""
    if rotor.hub_radius + rotor.span[0] <= 0.0:
        raise InputError("the first AeroDyn node sits on the rotor axis (hub radius 0, BlSpn 0): the BEM needs a "
                         "positive radius at every node; give the hub radius", field="--hub-radius")
