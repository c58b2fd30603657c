"""Error of the controlled run's integrators: the NREL 5MW deck with ROSCO
(cases/nrel5mw/NRELOffshrBsline5MW_Onshore_ROSCO.fst) at 16 m/s from 10 deg of pitch, each integrator against
Dormand-Prince 5(4) at rtol 1e-9 (the reference), the largest difference over the run and the difference of the
means over its last 5 s, of the tip deflection, generator power, pitch, rotor speed, blade-root and tower-base
moments; CPU time and right-hand sides per simulated second. Markdown table.

    python bench/bench_rosco_error.py [--seconds 30]
"""

from __future__ import annotations

import argparse
import contextlib
import io
import re
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas

ROOT = Path(__file__).resolve().parents[1]
DECK = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ROSCO.fst"
CHANNELS = ("OoPDefl1_m", "GenPwr_kW", "BldPitch1_deg", "RotSpeed_rpm", "RootMOoP1_kNm", "TwrBsMyt_kNm")
RUNS = {"DP54 rtol 1e-9 (reference)": ["--method", "DP54", "--rtol", "1e-9"],
        "DP54 rtol 1e-6 (before)": ["--method", "DP54"],
        "RK4, one step per interval, induction held over its stages (auto, before)": ["--method", "RK4", "--step",
                                                                                      "0.00625"],
        "ABM4, one step per interval, induction held at the predicted end (auto, now)": []}


def run(seconds: float, options: list[str]) -> tuple[dict[str, np.ndarray], float, int]:
    """The run's columns, its CPU time (s) and right-hand sides."""
    from bladefem.cli import main
    out = Path(tempfile.mkdtemp()) / "out.csv"
    argv = ["turbine", str(DECK), "--simulate", f"{seconds:g}", "--wind-speed", "16", "--pitch-deg", "10", "-o",
            str(out), "--quiet", *options]
    messages = io.StringIO()
    cpu = time.process_time()
    with contextlib.redirect_stderr(messages):
        code = main(argv)
    cpu = time.process_time() - cpu
    if code:
        raise SystemExit(code)
    table = pandas.read_csv(out, comment="#")
    columns = {name: table[name].to_numpy() for name in table.columns}
    count = int(re.search(r"(\d+) right-hand sides", messages.getvalue()).group(1))
    return columns, cpu, count


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--seconds", type=float, default=30.0)
    args = parser.parse_args()
    results = {name: run(args.seconds, options) for name, options in RUNS.items()}
    reference = next(iter(results.values()))[0]
    last = reference["Time_s"] >= args.seconds - 5 - 1e-9
    print(f"| {args.seconds:g} s at 16 m/s | RHS per s | CPU [s] | "
          + " | ".join(f"{c}: max, mean of last 5 s" for c in CHANNELS) + " |")
    print("|---" * (3 + len(CHANNELS)) + "|")
    for name, (columns, cpu, count) in results.items():
        cells = [f"{np.max(np.abs(columns[c] - reference[c])):.2g}, "
                 f"{abs(np.mean(columns[c][last]) - np.mean(reference[c][last])):.2g}" for c in CHANNELS]
        print(f"| {name} | {count / args.seconds:.0f} | {cpu:.2f} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    sys.exit(main())
