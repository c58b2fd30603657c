"""Campbell diagram and inspection report of the NREL 5MW blade (Jonkman et al. 2009) at its rated 12.1 rpm.

Run from the repository root::

    python examples/campbell_report.py [OUTPUT_DIR]      # default: out/nrel5mw_report

It writes ``report.md`` and ``report.html`` with the model summary, the frequency table at 12.1 rpm, the first six
modes drawn in 3-D (if pyvista is installed), the Campbell diagram from 0 to 15 rpm with the 1P, 3P, 6P and 9P
lines and the ElastoDyn mode-shape coefficients; and the VTK collection of the sweep for ParaView in ``vtk/``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from bladefem.builders.case import read_case
from bladefem.outputs.vtk import write_vtk
from bladefem.modal import blade_matrices
from bladefem.report import sweep, write_report

CASE = Path(__file__).resolve().parents[1] / "cases" / "nrel5mw_blade.yaml"
RATED_RPM = 12.1                       # NREL 5MW rated rotor speed (Jonkman et al. 2009, Table 1-1)
SWEEP_RPM = np.linspace(0.0, 15.0, 16)


def main(output: str | Path = "out/nrel5mw_report", n_modes: int = 6) -> Path:
    blade = read_case(CASE)
    report = write_report(blade, output, RATED_RPM, SWEEP_RPM, n_modes)
    campbell = sweep(blade_matrices(blade, None, n_modes), SWEEP_RPM, n_modes, blade.notes)
    write_vtk(blade, campbell, Path(output) / "vtk", stem="nrel5mw_campbell")
    return report.markdown


if __name__ == "__main__":
    print(main(*sys.argv[1:2]))
