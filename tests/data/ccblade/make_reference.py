"""Regenerate nrel5mw_ccblade.json: CCBlade (WISDEM) on the NREL 5MW rotor, the reference of tests/test_aero_ccblade.py.

CCBlade is not a test dependency of bladefem (WISDEM pulls in a large stack); run this in a separate environment:

    python -m venv /tmp/ccb && /tmp/ccb/bin/pip install --only-binary=:all: wisdem
    /tmp/ccb/bin/python tests/data/ccblade/make_reference.py cases/nrel5mw

It reads the AeroDyn blade file and the airfoil tables with its own small parser (independent of bladefem's
readers) and gives CCBlade a linear-interpolation airfoil (AeroDyn's InterpOrd 1) instead of CCAirfoil's smoothing
spline, so that the two codes see the same polars. Settings: 3 blades, Rhub 1.5 m (HubRad), Rtip 62.9999 m (the
last AeroDyn node, BlSpn 61.4999 m: AeroDyn's tip distance zTip), the 17 interior AeroDyn nodes (CCBlade appends
zero loads at Rhub and Rtip), no precone, tilt, yaw or shear, rho 1.225 kg/m^3, tip and hub loss, wake rotation,
no drag in the induction equations (usecd False = AeroDyn AIDrag/TIDrag False).
"""

import json
import math
import sys
from importlib.metadata import version
from pathlib import Path

import numpy as np
from wisdem.ccblade.ccblade import CCBlade

#: Jonkman et al. 2009 (NREL/TP-500-38060) Table 7-1: wind speed (m/s), rotor speed (rpm), pitch (deg).
SCHEDULE = ((5.0, 7.506, 0.0), (8.0, 9.156, 0.0), (11.4, 12.1, 0.0), (16.0, 12.1, 12.06), (25.0, 12.1, 23.47))


class LinearAirfoil:
    """cl, cd (and cm) linearly interpolated in the angle of attack (rad), as AeroDyn's InterpOrd 1."""

    def __init__(self, path: Path) -> None:
        lines = [line.split() for line in path.read_text().splitlines()]
        count_line = next(i for i, words in enumerate(lines) if len(words) > 1 and words[1] == "NumAlf")
        count = int(lines[count_line][0])
        rows = [words for words in lines[count_line + 1:] if words and not words[0].startswith("!")][:count]
        table = np.array([[float(x) for x in words[:4]] for words in rows])
        self.alpha, self.cl, self.cd, self.cm = np.radians(table[:, 0]), table[:, 1], table[:, 2], table[:, 3]

    def evaluate(self, alpha, Re, return_cm=False):
        a = (alpha + math.pi) % (2 * math.pi) - math.pi
        cl, cd = np.interp(a, self.alpha, self.cl), np.interp(a, self.alpha, self.cd)
        return (cl, cd, np.interp(a, self.alpha, self.cm)) if return_cm else (cl, cd)


def main(deck: Path) -> None:
    primary = (deck / "NRELOffshrBsline5MW_Onshore_AeroDyn.dat").read_text().splitlines()
    first = next(i for i, line in enumerate(primary) if "AFNames" in line.split())
    names = [line.split()[0].strip('"') for line in primary[first:first + 8]]
    airfoils = [LinearAirfoil(deck / name) for name in names]
    blade = (deck / "NRELOffshrBsline5MW_AeroDyn_blade.dat").read_text().splitlines()
    header = next(i for i, line in enumerate(blade) if line.split()[:1] == ["BlSpn"])
    rows = np.array([[float(x) for x in line.split()[:7]] for line in blade[header + 2:header + 2 + 19]])
    inner = slice(1, -1)
    r = 1.5 + rows[inner, 0]
    tip = 1.5 + rows[-1, 0]
    rotor = CCBlade(r, rows[inner, 5], rows[inner, 4], [airfoils[int(i) - 1] for i in rows[inner, 6]], 1.5, tip,
                    B=3, rho=1.225, precone=0.0, tilt=0.0, yaw=0.0, shearExp=0.0, hubHt=90.0, tiploss=True,
                    hubloss=True, wakerotation=True, usecd=False)
    cases = []
    for speed, rpm, pitch in SCHEDULE:
        loads, _ = rotor.distributedAeroLoads(speed, rpm, pitch, 0.0)
        total, _ = rotor.evaluate([speed], [rpm], [pitch])
        cases.append({"wind_speed": speed, "rpm": rpm, "pitch_deg": pitch, "thrust": float(total["T"][0]),
                      "torque": float(total["Q"][0]), "power": float(total["P"][0]),
                      "Np": loads["Np"].tolist(), "Tp": loads["Tp"].tolist(), "a": loads["a"].tolist(),
                      "ap": loads["ap"].tolist(), "alpha_deg": loads["alpha"].tolist()})
    out = {"provenance": f"CCBlade from wisdem {version('wisdem')}, made by tests/data/ccblade/make_reference.py "
                         "from cases/nrel5mw (see the script's docstring for the settings)",
           "hub_radius": 1.5, "tip_radius": tip, "r": r.tolist(), "cases": cases}
    (Path(__file__).parent / "nrel5mw_ccblade.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "cases/nrel5mw"))
