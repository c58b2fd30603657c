"""The NREL 5MW with ROSCO 2.10.6 in a wind step (10 -> 14 m/s at 40 s, InflowWind uniform wind file), bladefem
against OpenFAST v5.0.0 with the same controller library (tests/data/openfast/rosco/step.json): runs bladefem's case
(100 s, as the test does) unless its table is given, prints the peak and settled values and draws the time
histories overlaid.

    python examples/rosco_wind_step.py OUT_DIR [--table CSV]

Needs ROSCO's library (pip install --no-deps rosco==2.10.6) and matplotlib; writes OUT_DIR/rosco-step.png.
"""

from __future__ import annotations

import json
import shutil
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data" / "openfast" / "rosco"
CASE = ROOT / "cases" / "nrel5mw"
FST = "NRELOffshrBsline5MW_Onshore_ROSCO.fst"
INFLOW = "NRELOffshrBsline5MW_InflowWind_Steady11p4mps.dat"
CHANNELS = (("BldPitch1", "deg"), ("RotSpeed", "rpm"), ("GenPwr", "kW"), ("RotThrust", "kN"), ("OoPDefl1", "m"))
#: the step's window (s): peaks after the step, settled means over the last 10 s
STEP, SETTLED = 40.0, (90.0, 100.0)


def step_deck(folder: Path) -> Path:
    """The shipped ROSCO deck in ``folder`` with InflowWind WindType 2 and the stored step file."""
    import re
    shutil.copytree(CASE, folder)
    shutil.copyfile(DATA / "wind_step.wnd", folder / "wind_step.wnd")
    path = folder / INFLOW
    text = path.read_text()
    for label, value in (("WindType", "2"), ("FileName_Uni", '"wind_step.wnd"')):
        text, count = re.subn(rf"^(\s*)\S+(\s+{label}\s)", rf"\g<1>{value}\g<2>", text, count=1, flags=re.M)
        assert count == 1, label
    path.write_text(text)
    return folder / FST


def run(out_csv: Path) -> int:
    """bladefem's run of the step case (the OpenFAST run's start), written to ``out_csv``."""
    from bladefem.cli import main as bladefem
    reference = json.loads((DATA / "step.json").read_text())["provenance"]["initial"]
    with tempfile.TemporaryDirectory() as scratch:
        fst = step_deck(Path(scratch) / "deck")
        return bladefem(["turbine", str(fst), "--simulate", "100", "--initial",
                         f"RotSpeed={reference['RotSpeed_rpm']}", "--pitch-deg", str(reference["BlPitch_deg"]),
                         "--quiet", "-o", str(out_csv)])


def table(path: Path) -> dict[str, np.ndarray]:
    lines = path.read_text().splitlines()
    names = [name.rsplit("_", 1)[0] for name in lines[0].split(",")]
    data = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    return {name: data[:, i] for i, name in enumerate(names)}


def figures(time: np.ndarray, series: dict[str, np.ndarray]) -> dict[str, float]:
    """Peak after the step (largest value from the step on; for the pitch, its largest value), settled mean."""
    after = time >= STEP - 1e-9
    settled = (time >= SETTLED[0] - 1e-9) & (time <= SETTLED[1] + 1e-9)
    return {"peak": float(np.max(series[after])), "settled": float(np.mean(series[settled])),
            "before": float(np.mean(series[(time >= STEP - 10 - 1e-9) & (time < STEP - 1e-9)]))}


def main(out: Path, given: Path | None) -> None:
    reference = json.loads((DATA / "step.json").read_text())["history"]
    out.mkdir(parents=True, exist_ok=True)
    path = given or out / "bf_step.csv"
    if given is None and run(path):
        raise SystemExit(1)
    ours = table(path)
    time = np.array(reference["Time"])
    print("| channel | | bladefem | OpenFAST | difference |")
    print("|---|---|---|---|---|")
    for name, unit in CHANNELS:
        mine = figures(ours["Time"], ours[name])
        theirs = figures(time, np.array(reference[name]))
        for what in ("before", "peak", "settled"):
            difference = (f"{mine[what] - theirs[what]:+.3f} {unit}" if name == "BldPitch1"
                          else f"{100 * (mine[what] / theirs[what] - 1):+.2f} %")
            print(f"| {name} [{unit}] | {what} | {mine[what]:.4g} | {theirs[what]:.4g} | {difference} |")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(len(CHANNELS), 1, figsize=(8, 10), sharex=True, layout="constrained")
    for axis, (name, unit) in zip(axes, CHANNELS):
        axis.plot(time, reference[name], color="k", lw=1.6, label="OpenFAST v5.0.0")
        axis.plot(ours["Time"], ours[name], color="tab:red", lw=1.0, ls="--", label="bladefem")
        axis.axvline(STEP, color="0.6", lw=0.8)
        axis.set_ylabel(f"{name} [{unit}]")
        axis.grid(alpha=0.3)
    axes[0].legend(loc="lower right", fontsize=8)
    axes[0].set_title("NREL 5MW, ROSCO 2.10.6, wind step 10 -> 14 m/s at 40 s")
    axes[-1].set_xlabel("time [s]")
    axes[-1].set_xlim(20, 100)
    figure.savefig(out / "rosco-step.png", dpi=110)


if __name__ == "__main__":
    args = sys.argv[1:]
    main(Path(args[0]), Path(args[args.index("--table") + 1]) if "--table" in args else None)
