"""Benchmark: CPU time of the NREL 5MW with ROSCO (cases/nrel5mw/NRELOffshrBsline5MW_Onshore_ROSCO.fst) in steady
wind, bladefem and, if its executable is given, OpenFAST on the same deck, one after the other on this machine.

    python bench/bench_rosco.py [--seconds 100] [--wind 16] [--openfast OPENFAST --library LIBDISCON]

bladefem: ``turbine DECK --simulate SECONDS`` in this process after a warm-up run (the numba kernels compiled and
cached), the controller called every DLL_DT (0.00625 s), outputs every 0.05 s; OpenFAST: a copy of the deck
brought to v5's layout by tests/data/openfast/rosco/write_decks.py with TMax = SECONDS. CPU time of the process
(bladefem) and of the child (OpenFAST); the load average is printed, as the machine may be shared. Markdown table.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "data" / "openfast" / "rosco"))


def bladefem_seconds(seconds: float, wind: float, out: Path) -> tuple[float, float]:
    from bladefem.cli import main
    deck = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ROSCO.fst"
    argv = ["turbine", str(deck), "--wind-speed", str(wind), "--pitch-deg", "10", "--quiet", "-o", str(out)]
    main([*argv[:2], "--simulate", "0.5", *argv[2:]])                      # compile or load the kernels
    cpu, wall = time.process_time(), time.perf_counter()
    code = main([*argv[:2], "--simulate", str(seconds), *argv[2:]])
    if code:
        raise SystemExit(code)
    return time.process_time() - cpu, time.perf_counter() - wall


def openfast_seconds(executable: str, library: str, seconds: float, wind: float) -> tuple[float, float]:
    import write_decks
    folder = Path(tempfile.mkdtemp(prefix="bench-rosco-"))
    write_decks.CASES[wind] = (12.1, 10.0)
    fst = write_decks.write_case(folder / "case", wind, library)
    write_decks.set_value(fst, "TMax", f"{seconds:g}")
    before, wall = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
    subprocess.run([executable, fst.name], cwd=fst.parent, check=True, stdout=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, time.perf_counter() - wall


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--seconds", type=float, default=100.0)
    parser.add_argument("--wind", type=float, default=16.0)
    parser.add_argument("--openfast")
    parser.add_argument("--library")
    args = parser.parse_args()
    print(f"load average before: {os.getloadavg()[0]:.1f}")
    rows = [("bladefem", *bladefem_seconds(args.seconds, args.wind, Path(tempfile.mkdtemp()) / "out.csv"))]
    if args.openfast:
        rows.append(("OpenFAST", *openfast_seconds(args.openfast, args.library, args.seconds, args.wind)))
    print(f"load average after: {os.getloadavg()[0]:.1f}")
    print(f"| {args.seconds:g} s at {args.wind:g} m/s | CPU [s] | wall [s] | simulated s per CPU s |")
    print("|---|---|---|---|")
    for name, cpu, wall in rows:
        print(f"| {name} | {cpu:.1f} | {wall:.1f} | {args.seconds / cpu:.2f} |")


if __name__ == "__main__":
    main()
