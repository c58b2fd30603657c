"""Fresh ElastoDyn mode-shape coefficients for the NREL 5MW blade (12.1 rpm) and tower, compared with the ones
shipped in the NREL files: fit quality against the FE mode shapes, and the frequencies ElastoDyn derives from each
set of polynomials next to the FE frequencies.

Run:  python examples/elastodyn_coefficients.py
(reads cases/nrel5mw/; the same numbers are quoted in docs/formats.md)
"""

from __future__ import annotations

from pathlib import Path

from bladefem.builders.elastodyn_blade import blade_from_elastodyn_main, read_elastodyn_blade
from bladefem.formats.elastodyn_main import read_elastodyn_main
from bladefem.builders.elastodyn_tower import read_elastodyn_tower, tower_from_elastodyn_main
from bladefem.builders.tower_elastodyn import elastodyn_tower
from bladefem.modal.elastodyn_fit import blade_coefficients
from bladefem.models.tower_fit import tower_coefficients

CASE = Path(__file__).resolve().parent.parent / "cases" / "nrel5mw"
MAIN = CASE / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"


def table(title, result) -> str:
    lines = [f"\n{title}",
             f"{'mode':<6} {'FE Hz':>8} | {'fresh: ED Hz':>12} {'diff %':>7} {'RMS':>8} {'tip slope':>9} | "
             f"{'shipped: ED Hz':>14} {'diff %':>7} {'RMS':>8} {'tip slope':>9}"]
    for name, fresh in result.fits.items():
        old = result.shipped[name]
        row = [f"{name:<6} {fresh.fe_frequency_hz:>8.4f} |"]
        for fit, width in ((fresh, 12), (old, 14)):
            diff = 100 * (fit.elastodyn_frequency_hz / fit.fe_frequency_hz - 1)
            row.append(f"{fit.elastodyn_frequency_hz:>{width}.4f} {diff:>7.2f} {fit.fit.rms_error:>8.1e} "
                       f"{fit.fit.tip_slope_error:>9.2f} |")
        lines.append(" ".join(row).rstrip(" |"))
    lines += [f"warning: {w}" for w in result.warnings]
    return "\n".join(lines)


def main() -> None:
    ed = read_elastodyn_main(MAIN)
    blade = blade_from_elastodyn_main(MAIN)
    shipped_blade = read_elastodyn_blade(ed.blade_files[0]).modes
    blade_result = blade_coefficients(blade, ed.rotor_speed_rpm, nodes=ed.blade_nodes, shipped=shipped_blade)
    print(table(f"NREL 5MW blade at {ed.rotor_speed_rpm:g} rpm, ElastoDyn integrals over BldNodes = "
                f"{ed.blade_nodes}", blade_result))
    tower = tower_from_elastodyn_main(MAIN)
    shipped_tower = read_elastodyn_tower(ed.tower_file).modes
    tower_result = tower_coefficients(tower, nodes=ed.tower_nodes, shipped=shipped_tower)
    print(table(f"NREL 5MW tower with gravity and the rotor-nacelle mass ({tower.top_mass.mass:.0f} kg) as a point "
                f"mass (ElastoDyn's TwrTpMass), TwrNodes = {ed.tower_nodes}", tower_result))
    rigid = tower_coefficients(elastodyn_tower(MAIN), nodes=ed.tower_nodes, shipped=shipped_tower)
    print(table("the same tower with the rotor-nacelle assembly as a rigid body (offset centre of mass, rotary "
                "inertia): ElastoDyn's integrals still see a point mass", rigid))


if __name__ == "__main__":
    main()
