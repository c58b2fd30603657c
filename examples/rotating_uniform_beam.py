"""The rotating uniform cantilever against the published table (Wright et al. 1982; Hodges and Rutkowski 1981).

Prints omega * sqrt(m L^4 / EI) of the first three flap modes for lambda = Omega sqrt(m L^4 / EI) = 0..12 next to
the table (Wright, Smith, Thresher and Wang 1982, J. Appl. Mech. 49:197; Hodges and Rutkowski 1981, AIAA J.
19(11):1459), and the in-plane modes from omega_lag^2 = omega_flap^2 - Omega^2.
Run: ``python examples/rotating_uniform_beam.py``.
"""

from __future__ import annotations

import numpy as np

from bladefem.assembly import assemble_blade
from bladefem.modal import solve_modes
from bladefem.sections import Blade, uniform_sections

TABLE_W1 = [3.51602, 3.68165, 4.13732, 4.79728, 5.58500, 6.44954, 7.36037, 8.29964, 9.25684, 10.22569, 11.20233,
            12.18434, 13.17015]


def main() -> None:
    blade = Blade(uniform_sections(1.0, 1.0, 1.0))     # m = EI = L = 1, equal flap and edge stiffness
    matrices = assemble_blade(blade, elements=80)       # assembled once; each speed is one eigen-solve
    print(" lambda   flap 1 (FE)  table      edge 1 (FE)  sqrt(flap^2 - lambda^2)")
    for lam, reference in enumerate(TABLE_W1):
        result = solve_modes(matrices, rpm=lam * 30 / np.pi, n_modes=4)
        flap = 2 * np.pi * result.first("flap").frequency_hz
        edge = 2 * np.pi * result.first("edge").frequency_hz
        print(f"{lam:6d}   {flap:10.5f}  {reference:9.5f}   {edge:10.5f}   {np.sqrt(flap**2 - lam**2):10.5f}")


if __name__ == "__main__":
    main()
