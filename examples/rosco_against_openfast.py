"""The NREL 5MW with ROSCO 2.10.6 in steady wind, bladefem against OpenFAST v5.0.0 with the same controller library
(tests/data/openfast/rosco/): runs bladefem's four cases (150 s each, as the tests do) unless their tables are given,
prints the table of means over 100-150 s and draws the first 60 s overlaid.

    python examples/rosco_against_openfast.py OUT_DIR [--tables DIR]   # DIR holding bf_8.csv, bf_11.4.csv, ...

Needs ROSCO's library (pip install --no-deps rosco==2.10.6) and matplotlib; writes OUT_DIR/rosco-transient.png.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data" / "openfast" / "rosco"
DECK = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ROSCO.fst"
CHANNELS = (("BldPitch1", "deg", 0), ("RotSpeed", "rpm", 1), ("GenPwr", "kW", 1), ("RotThrust", "kN", 1),
            ("OoPDefl1", "m", 1))


def table(path: Path) -> dict[str, np.ndarray]:
    lines = path.read_text().splitlines()
    names = [name.rsplit("_", 1)[0] for name in lines[0].split(",")]
    data = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    return {name: data[:, i] for i, name in enumerate(names)}


def main(out: Path, tables: Path | None) -> None:
    from bladefem.cli import main as bladefem

    steady = json.loads((DATA / "steady.json").read_text())
    transient = json.loads((DATA / "transient.json").read_text())["cases"]
    out.mkdir(parents=True, exist_ok=True)
    runs = {}
    for wind, initial in steady["provenance"]["initial"].items():
        path = (tables or out) / f"bf_{wind}.csv"
        if not path.is_file():
            code = bladefem(["turbine", str(DECK), "--simulate", "150", "--wind-speed", wind, "--initial",
                             f"RotSpeed={initial['RotSpeed_rpm']}", "--pitch-deg", str(initial["BlPitch_deg"]),
                             "--quiet", "-o", str(path)])
            if code:
                raise SystemExit(code)
        runs[wind] = table(path)
    print("| wind [m/s] | channel | bladefem | OpenFAST | difference |")
    print("|---|---|---|---|---|")
    for wind, data in runs.items():
        window = data["Time"] >= steady["window_s"][0] - 1e-9
        for name, unit, relative in CHANNELS:
            ours, theirs = float(np.mean(data[name][window])), steady["cases"][wind][name]["mean"]
            difference = f"{100 * (ours / theirs - 1):+.2f} %" if relative else f"{ours - theirs:+.3f} {unit}"
            print(f"| {wind} | {name} [{unit}] | {ours:.4g} | {theirs:.4g} | {difference} |")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(len(CHANNELS), len(runs), figsize=(13, 10), sharex=True, layout="constrained")
    for column, (wind, data) in enumerate(runs.items()):
        reference = transient[wind]
        for row, (name, unit, _) in enumerate(CHANNELS):
            axis = axes[row, column]
            axis.plot(reference["Time"], reference[name], color="k", lw=2.2, alpha=0.45, label="OpenFAST v5.0.0")
            keep = data["Time"] <= reference["Time"][-1] + 1e-9
            axis.plot(data["Time"][keep], data[name][keep], color="C0", lw=1, label="bladefem")
            axis.grid(alpha=0.3)
            if column == 0:
                axis.set_ylabel(f"{name} [{unit}]", fontsize=8)
            if row == 0:
                axis.set_title(f"{wind} m/s", fontsize=10)
            if row == len(CHANNELS) - 1:
                axis.set_xlabel("time [s]")
    axes[0, 0].legend(fontsize=7)
    figure.suptitle("NREL 5MW with ROSCO 2.10.6, steady wind, start at the schedule's speed and pitch", fontsize=11)
    figure.savefig(out / "rosco-transient.png", dpi=90)
    print(f"figure: {out / 'rosco-transient.png'}")


if __name__ == "__main__":
    arguments = sys.argv[1:]
    given = Path(arguments[arguments.index("--tables") + 1]) if "--tables" in arguments else None
    main(Path(arguments[0]), given)
