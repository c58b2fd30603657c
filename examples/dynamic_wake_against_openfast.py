"""The NREL 5MW's wind step (8 -> 11 m/s at 12.1 rpm, pitch 0) with and without AeroDyn's dynamic wake, bladefem
against OpenFAST v5.0.0 (tests/data/openfast/dynamic_wake/): runs bladefem through its command line on copies of the
shipped deck with DBEMT_Mod 0, 1 and 2 (60 s each), prints the table of overshoots and settling times of the rotor
thrust, torque and tip deflection (the figures of tests/test_dynamic_wake_openfast.py) and draws the thrust, torque
and tip deflection after the step, bladefem over OpenFAST.

    python examples/dynamic_wake_against_openfast.py OUT_DIR

Needs matplotlib; writes OUT_DIR/dynamic-wake-step.png and the runs' tables OUT_DIR/bf_dbemtN.csv.
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "tests" / "data" / "openfast" / "dynamic_wake"))
from make_dynamic_wake import WIND, uniform_wind  # noqa: E402
from test_dynamic_wake_openfast import (  # noqa: E402
    AERODYN, CASE, CHANNELS, FST, INFLOW, openfast_series, set_value, settled, settling_time, step_figures)

#: bladefem's DBEMT_Mod -> OpenFAST's drawn beside it
PAIRS = (("0", "0"), ("1", "3"), ("2", "2"))
UNITS = {"RtAeroFxh": ("kN", 1e-3), "RtAeroMxh": ("kN m", 1e-3), "OoPDefl1": ("m", 1.0)}


def run(out: Path, dbemt: str) -> dict[str, np.ndarray]:
    from bladefem.cli import main as bladefem
    table = out / f"bf_dbemt{dbemt}.csv"
    if not table.is_file():
        deck = out / f"deck{dbemt}"
        if deck.exists():
            shutil.rmtree(deck)
        shutil.copytree(CASE, deck)
        set_value(deck / AERODYN, "DBEMT_Mod", dbemt)
        set_value(deck / INFLOW, "WindType", "2")
        set_value(deck / INFLOW, "FileName_Uni", f'"{WIND}"')
        (deck / WIND).write_text(uniform_wind())
        code = bladefem(["turbine", str(deck / FST), "--simulate", "60", "--rpm", "12.1", "--pitch-deg", "0",
                         "--dt", "0.1", "--quiet", "-o", str(table)])
        if code:
            raise SystemExit(code)
    lines = table.read_text().splitlines()
    names = [name.rsplit("_", 1)[0] for name in lines[0].split(",")]
    data = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    return {name: data[:, i] for i, name in enumerate(names)}


def main(out: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    ours = {dbemt: run(out, dbemt) for dbemt, _ in PAIRS}
    theirs = {dbemt: openfast_series(dbemt) for dbemt in ("0", "1", "2", "3")}
    print("| bladefem | OpenFAST | channel | overshoot bladefem | overshoot OpenFAST | settling bladefem [s] "
          "| settling OpenFAST [s] |")
    print("|---|---|---|---|---|---|---|")
    for mine, reference in (*PAIRS, ("1", "1")):
        for name in CHANNELS:
            a = ours[mine]
            b = theirs[reference]
            s_a, s_b = settled(ours["0"], name), settled(theirs["0"], name)
            print(f"| DBEMT_Mod {mine} | DBEMT_Mod {reference} | {name} | {step_figures(a['Time'], a[name], s_a)[0]:.3f} "
                  f"| {step_figures(b['Time'], b[name], s_b)[0]:.3f} | {settling_time(a['Time'], a[name], s_a):.1f} "
                  f"| {settling_time(b['Time'], b[name], s_b):.1f} |")
    figure, axes = plt.subplots(len(CHANNELS), len(PAIRS), figsize=(13, 8), sharex=True, sharey="row")
    for column, (mine, reference) in enumerate(PAIRS):
        for row, name in enumerate(CHANNELS):
            unit, scale = UNITS[name]
            axis = axes[row, column]
            window = theirs[reference]["Time"] >= 20.0
            axis.plot(theirs[reference]["Time"][window], scale * theirs[reference][name][window], "k-", lw=1.6,
                      label=f"OpenFAST DBEMT_Mod {reference}")
            if mine == "2":
                axis.plot(theirs["1"]["Time"][window], scale * theirs["1"][name][window], color="0.6", lw=1.0,
                          label="OpenFAST DBEMT_Mod 1 (tau1 4 s)")
            window = ours[mine]["Time"] >= 20.0
            axis.plot(ours[mine]["Time"][window], scale * ours[mine][name][window], "C3--", lw=1.3,
                      label=f"bladefem DBEMT_Mod {mine}")
            axis.grid(alpha=0.3)
            if column == 0:
                axis.set_ylabel(f"{name} [{unit}]")
            if row == 0:
                axis.set_title(("quasi-steady", "tau1 = 4 s", "tau1 from the rotor (DBEMT_Mod 2)")[column])
                axis.legend(fontsize=7, loc="lower right")
    for axis in axes[-1]:
        axis.set_xlabel("time [s] (wind 8 -> 11 m/s over 25-25.5 s)")
    figure.tight_layout()
    figure.savefig(out / "dynamic-wake-step.png", dpi=110)


if __name__ == "__main__":
    main(Path(sys.argv[1]))
