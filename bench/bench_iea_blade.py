"""Benchmark: the IEA-15MW blade's converged 16-speed Campbell diagram in-process, with full six-by-six sections
(the default for its BeamDyn files: a Timoshenko beam on its curved reference axis), with the shear condensed, with
the diagonal reduction and straightened, side by side with the NREL 5MW blade's in one run. The target: the
IEA-15MW's full-section Campbell within 3x the 5MW's time per call.

Run: ``python bench/bench_iea_blade.py [--repeats N]``. Speeds 0 to 7.56 rpm (the IEA-15MW's rated rotor speed)
and 0 to 15 rpm for the 5MW, 16 each, 6 families, mesh choice included. Median wall-clock time of interleaved
repeats and the smallest CPU time; BLAS on one thread (set before numpy loads), as in bench_blade.py. Each row also
gives the automatic mesh (nested refinements of the graded starting mesh, the coarsest whose frequencies are
estimated within half the 1e-6 tolerance: the "converged" mesh) and its estimated error.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_blade import timed  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
CASE = ROOT / "cases" / "nrel5mw_blade.yaml"
IEA15 = ROOT / "tests" / "data" / "iea15" / "beamdyn" / "IEA-15-240-RWT_BeamDyn.dat"
N_MODES = 6


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=15)
    args = parser.parse_args()

    from bladefem.builders.case import read_case
    from bladefem.builders.detect import read_model
    from bladefem.modal import campbell, converged_mesh

    nrel = read_case(CASE)
    full = read_model(IEA15, hub_radius=3.97)
    condensed = read_model(IEA15, hub_radius=3.97, sections="condensed")
    reduced = read_model(IEA15, hub_radius=3.97, sections="reduced")
    straight = read_model(IEA15, hub_radius=3.97, axis="straight")
    speeds = {"NREL 5MW": np.linspace(0.0, 15.0, 16), "IEA-15MW": np.linspace(0.0, 7.56, 16)}
    blades = {"NREL 5MW (column sections)": ("NREL 5MW", nrel),
              "IEA-15MW BeamDyn, full six-by-six sections (Timoshenko)": ("IEA-15MW", full),
              "IEA-15MW BeamDyn, shear condensed (--sections condensed)": ("IEA-15MW", condensed),
              "IEA-15MW BeamDyn, reduced (--sections reduced)": ("IEA-15MW", reduced),
              "IEA-15MW BeamDyn, full, straightened (--straight-axis)": ("IEA-15MW", straight)}
    functions = {name: (lambda b=blade, r=speeds[turbine]: campbell(b, r, N_MODES))
                 for name, (turbine, blade) in blades.items()}
    for function in functions.values():
        function()                                                   # warm-up: imports, caches
    rows = timed(functions, args.repeats)
    base, base_cpu = rows["NREL 5MW (column sections)"]
    print("| blade | automatic mesh: DOFs, elements (level), estimated error | Campbell, 16 speeds, 6 families | "
          "against the NREL 5MW (wall, CPU) |")
    print("|---|---|---|---|")
    for name, (wall, cpu) in rows.items():
        turbine, blade = blades[name]
        choice = converged_mesh(blade, N_MODES, rpm=float(speeds[turbine][-1]))
        mesh = (f"{choice.matrices.M.shape[0]}, {len(choice.matrices.dofs.nodes) - 1} ({choice.level}), "
                f"{choice.error:.1e}")
        print(f"| {name} | {mesh} | {1e3 * wall:.0f} ms wall, {1e3 * cpu:.0f} ms CPU | {wall / base:.2f}x, "
              f"{cpu / base_cpu:.2f}x |")


if __name__ == "__main__":
    main()
