"""Plain-text tables for the terminal."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from ..plots.labels import mode_labels

if TYPE_CHECKING:
    from ..modal import CampbellResult, ModalResult
    from ..models.tower_campbell import TowerCampbell
    from ..sections import Blade
    from ..sections.tower import Tower


def header(blade: Blade, notes: tuple[str, ...]) -> list[str]:
    lines = [f"# {blade.name}: flexible length {blade.length:.4g} m, hub radius {blade.hub_radius:.4g} m, "
             f"precone {math.degrees(blade.precone):.4g} deg, pitch {math.degrees(blade.pitch):.4g} deg, "
             f"root {blade.root}"]
    lines += [f"# note: {note}" for note in notes]
    return lines


def modes_table(blade: Blade, result: ModalResult, method: str = "fe") -> str:
    lines = header(blade, result.notes)
    damped = bool(result.modes) and result.modes[0].damping_ratio is not None
    lines.append(f"# method {method}, rotor speed {result.rotor_speed_rpm:g} rpm, {result.n_dofs} DOFs"
                 + (", quadratic eigenproblem: frequency |lambda|/2pi, damping ratio -Re(lambda)/|lambda|"
                    if damped else ""))
    lines.append(f"{'mode':>4}  {'frequency_hz':>12}  " + (f"{'damping':>9}  " if damped else "")
                 + f"{'kind':<8} {'flap':>5} {'edge':>5} {'tors':>5} {'axial':>5}  {'residual':>9}")
    for i, mode in enumerate(result.modes, 1):
        e = mode.energy_fractions
        damping = f"{mode.damping_ratio:>9.6f}  " if damped else ""
        lines.append(f"{i:>4}  {mode.frequency_hz:>12.5f}  {damping}{mode.kind:<8} {e['flap']:>5.2f} "
                     f"{e['edge']:>5.2f} {e['torsion']:>5.2f} {e['axial']:>5.2f}  {mode.residual:>9.1e}")
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
    if result.families and result.families[0].damping_ratios is not None:
        lines.append("# damping ratios (fraction of critical), Coriolis coupling (quadratic eigenproblem)")
        lines.append(f"{'rpm':>7}" + "".join(f"{name:>11}" for name in names))
        for k, rpm in enumerate(result.rpm):
            lines.append(f"{rpm:>7.2f}" + "".join(f"{family.damping_ratios[k]:>11.6f}"  # type: ignore[index]
                                                  for family in result.families))
    return "\n".join(lines)


def tower_campbell_table(tower: Tower, chart: TowerCampbell) -> str:
    """The tower's modes against the rotor's excitation bands, and the design classification."""
    from .tower import tower_header

    lines = [tower_header(tower)]
    lines += [f"# note: {note}" for note in chart.modes.notes]
    low, high = chart.operating_rpm
    lines.append(f"# rotor operating range {low:g}-{high:g} rpm, {chart.blades} blades; bands widened by "
                 f"{chart.margin:.0%} count as hits")
    for band in chart.bands:
        lines.append(f"# {band.harmonic}P band: {band.low_hz:.5g}-{band.high_hz:.5g} Hz")
    lines.append(f"{'mode':>4}  {'frequency_hz':>12}  {'kind':<10} {'label':<14} {'in band':<8}")
    for i, (mode, label) in enumerate(zip(chart.modes.modes, mode_labels(chart.modes.modes)), 1):
        hit = ",".join(chart.bands_hit(mode)) or "-"
        lines.append(f"{i:>4}  {mode.frequency_hz:>12.5f}  {mode.kind:<10} {label:<14} {hit:<8}")
    lines.append(f"# design: {chart.statement()}")
    return "\n".join(lines)
