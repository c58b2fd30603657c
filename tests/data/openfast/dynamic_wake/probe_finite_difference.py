"""Why OpenFAST's finite-difference dynamic wake (DBEMT_Mod 1) departs from its own equations on the wind step: a
probe, not run by the tests (needs OpenFAST).

The wind step of ``make_dynamic_wake.py`` on a rigid turbine (every ElastoDyn DOF off, the rotor at 12.1 rpm), no
skew model (``Skew_Mod`` 0, so that the node's induction is the filter's output alone), DBEMT_Mod 1 (tau1 4 s),
35 s, outputs every time step with blade 1's node 16 ``AxInd``, ``AxInd_qs`` and ``Vx``. Then the finite-difference
update of ``DBEMT.f90`` (``DBEMT_UpdateStates``, its eqs. 1.17-1.25) is applied here to the node's quasi-steady
induced velocity ``-AxInd_qs Vx`` and compared with OpenFAST's filtered one ``-AxInd Vx``:

- with the input of each step taken consistently (``u(1)`` at t, ``u(2)`` at t + dt) it stays within 0.11 m/s of
  the quasi-steady value, as the equations (and bladefem, and OpenFAST's DBEMT_Mod 3) have it; OpenFAST's moves
  0.45 m/s away from it (-3.49 against -4.02 m/s at t = 27 s, the quasi-steady -3.95 m/s);
- with ``u(2)`` = ``-AxInd_qs(t + dt) Vx(t)`` (the new induction with the axial velocity of the step's start) it
  follows OpenFAST's within 0.08 m/s (-3.53 m/s at 27 s).

So OpenFAST's DBEMT_Mod 1 and 2 behave as if the derivative term ``k tau1 dv_qs/dt`` saw the induction's change
without the wind's. The likely cause, read in v5.0.0's ``modules/aerodyn/src/AeroDyn.f90`` (``AD_UpdateStates``):
the loop that sets the BEM inputs ``m%BEMT_u(1)`` (t) and ``m%BEMT_u(2)`` (t + dt) computes each level's wind into
``m%Inflow(1)`` but passes ``SetInputs`` the ``InflowInterp`` copied before the loop, so both levels carry the same
wind (on a rigid turbine the same ``Vx``).

    python tests/data/openfast/dynamic_wake/probe_finite_difference.py OPENFAST_EXECUTABLE RUN_FOLDER
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))
from make_aeroturbine import read_out  # noqa: E402
from make_dynamic_wake import AD, ED, FST, write_case  # noqa: E402
from make_openfast_v5 import set_value  # noqa: E402

NODE, TAU1, K, DT = "016", 4.0, 0.6, 0.00625
RIGID = ("FlapDOF1", "FlapDOF2", "EdgeDOF", "TwFADOF1", "TwFADOF2", "TwSSDOF1", "TwSSDOF2", "DrTrDOF", "YawDOF")


def run(executable: str, folder: Path) -> dict:
    write_case(folder, "1")
    for label in RIGID:
        set_value(folder / ED, label, "False")
    for path, label, value in ((folder / AD, "Skew_Mod", "0"), (folder / FST, "DT_Out", f"{DT}"),
                               (folder / FST, "TMax", "35"), (folder / AD, "BldNd_BladesOut", "1")):
        set_value(path, label, value)
    lines = (folder / AD).read_text().splitlines()
    start = next(k for k, line in enumerate(lines) if line.split()[:1] == ["OutList_Nodal"])
    end = next(k for k in range(start + 1, len(lines)) if lines[k].startswith("END"))
    lines[start + 1:end] = ['"AxInd"', '"Vx"', '"AxInd_qs"']
    (folder / AD).write_text("\n".join(lines) + "\n")
    subprocess.run([executable, FST], cwd=folder, check=True, stdout=subprocess.DEVNULL)
    return read_out(folder / FST.replace(".fst", ".out"))[0]


def finite_difference(u1: np.ndarray, u2: np.ndarray, ratio: float) -> np.ndarray:
    """DBEMT_UpdateStates' update over each step from the inputs at its start (u1) and end (u2)."""
    tau2 = (0.39 - 0.26 * ratio**2) * TAU1
    v1 = v = u1[0]
    out = [v]
    for i in range(len(u1) - 1):
        b = (u2[i] - u1[i]) / DT
        a = u1[i] + b * K * TAU1
        c0 = v1 - a + b * TAU1
        c2 = v - c0 / (1 - tau2 / TAU1) - a + b * (TAU1 + tau2)
        v = (c2 * np.exp(-DT / tau2) + a + b * (DT - TAU1 - tau2) + c0 / (1 - tau2 / TAU1) * np.exp(-DT / TAU1))
        v1 = c0 * np.exp(-DT / TAU1) + a + b * (DT - TAU1)
        out.append(v)
    return np.array(out)


def main(executable: str, folder: Path) -> None:
    data = run(executable, folder)
    t, vx, a_qs = data["Time"], data[f"AB1N{NODE}Vx"], data[f"AB1N{NODE}AxInd_qs"]
    quasi, openfast = -a_qs * vx, -data[f"AB1N{NODE}AxInd"] * vx
    consistent = finite_difference(quasi, np.append(quasi[1:], quasi[-1]), 0.75)
    stale = finite_difference(quasi, np.append(-a_qs[1:] * vx[:-1], quasi[-1]), 0.75)
    print("t [s] | quasi-steady | OpenFAST | consistent inputs | u(2) with Vx(t)")
    for when in (24.9, 25.5, 26.0, 27.0, 28.0, 30.0, 34.9):
        i = int(np.argmin(np.abs(t - when)))
        print(f"{when:5.1f} | {quasi[i]:.4f} | {openfast[i]:.4f} | {consistent[i]:.4f} | {stale[i]:.4f}")


if __name__ == "__main__":
    main(sys.argv[1], Path(sys.argv[2]))
