"""Plain-text tables for the terminal."""

from __future__ import annotations

import math

from ..modal import CampbellResult, ModalResult
from ..sections import Blade


def header(blade: Blade, notes: tuple[str, ...]) -> list[str]:
    lines = [f"# {blade.name}: flexible length {blade.length:.4g} m, hub radius {blade.hub_radius:.4g} m, "
             f"precone {math.degrees(blade.precone):.4g} deg, pitch {math.degrees(blade.pitch):.4g} deg, "
             f"root {blade.root}"]
    lines += [f"# note: {note}" for note in notes]
    return lines


def modes_table(blade: Blade, result: ModalResult, method: str = "fe") -> str:
    lines = header(blade, result.notes)
    lines.append(f"# method {method}, rotor speed {result.rotor_speed_rpm:g} rpm, {result.n_dofs} DOFs")
    lines.append(f"{'mode':>4}  {'frequency_hz':>12}  {'kind':<8} {'flap':>5} {'edge':>5} {'tors':>5} "
                 f"{'axial':>5}  {'residual':>9}")
    for i, mode in enumerate(result.modes, 1):
        e = mode.energy_fractions
        lines.append(f"{i:>4}  {mode.frequency_hz:>12.5f}  {mode.kind:<8} {e['flap']:>5.2f} {e['edge']:>5.2f} "
                     f"{e['torsion']:>5.2f} {e['axial']:>5.2f}  {mode.residual:>9.1e}")
    return "\n".join(lines)


def campbell_table(blade: Blade, result: CampbellResult) -> str:
    lines = header(blade, result.notes)
    names = [f"{family.kind} {sum(f.kind == family.kind for f in result.families[:i + 1])}"
             for i, family in enumerate(result.families)]
    lines.append(f"# frequencies in Hz; families tracked by MAC (lowest MAC between neighbouring speeds: "
                 f"{min(float(f.mac.min()) for f in result.families):.3f})")
    lines.append(f"{'rpm':>7}" + "".join(f"{name:>11}" for name in names))
    for k, rpm in enumerate(result.rpm):
        lines.append(f"{rpm:>7.2f}" + "".join(f"{family.frequencies_hz[k]:>11.4f}" for family in result.families))
    return "\n".join(lines)
