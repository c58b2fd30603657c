"""Quick start: modes of the NREL 5MW blade at rated speed and its Campbell diagram (also run by the tests).

Run: ``python examples/quickstart.py [OUTPUT_FOLDER]``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from bladefem.builders.case import read_case
from bladefem.modal import campbell, modes
from bladefem.plots.campbell import save_campbell_plot

CASE = Path(__file__).resolve().parent.parent / "cases" / "nrel5mw_blade.yaml"


def main(out: Path) -> None:
    blade = read_case(CASE)
    rated = modes(blade, rpm=12.1, n_modes=6)
    for number, mode in enumerate(rated.modes, 1):
        print(f"mode {number}: {mode.frequency_hz:8.4f} Hz  {mode.kind:<8} residual {mode.residual:.1e}")
    tip = rated.first("flap").shape.at(np.array([blade.length]))
    print(f"first flap mode at the tip: flap {tip['flap'][0]:.3f}, edge {tip['edge'][0]:.3f} (coupled by twist)")
    sweep = campbell(blade, rpm=np.linspace(0.0, 15.0, 16), n_modes=6)
    for family in sweep.families:
        print(f"{family.kind:<8} {family.frequencies_hz[0]:.4f} Hz at rest -> {family.frequencies_hz[-1]:.4f} Hz "
              f"at 15 rpm (lowest MAC between speeds {family.mac.min():.3f})")
    save_campbell_plot(sweep, out / "campbell.png", title=blade.name, operating_rpm=12.1)
    print(f"Campbell diagram: {out / 'campbell.png'}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("out"))
