"""Benchmark: bladefem against OpenFAST on the same NREL 5MW deck in steady wind, side by side in one run on this
machine: the deck with ROSCO (cases/nrel5mw/NRELOffshrBsline5MW_Onshore_ROSCO.fst, the default) or with ServoDyn's
torque law (``--torque-law``: cases/nrel5mw/NRELOffshrBsline5MW_Onshore.fst at its 11.4 m/s).

    python bench/bench_rosco.py [--torque-law] [--seconds 100] [--wind 16] [--repeats 1] \
        [--openfast OPENFAST [--library LIBDISCON]] [--also '--method DP54' ...]

bladefem: ``turbine DECK --simulate SECONDS`` (the whole command: deck read, model built, run, table written) in
this process after a warm-up run (the numba kernels compiled and cached); with ROSCO the controller is called every
DLL_DT (0.00625 s), started at ``--pitch-deg 10``, outputs every 0.05 s. OpenFAST: a copy of the deck brought to
v5's layout (tests/data/openfast/rosco/write_decks.py for the ROSCO deck, tests/data/openfast/make_openfast_v5.py
for the torque-law one) with TMax = SECONDS, the torque-law deck otherwise as shipped (11.4 m/s, DT 0.00625 s,
ABM4). ``--also OPTIONS`` times bladefem with those options too, as one more row. With ``--repeats N`` the
tools run alternately N times each and the medians are printed. CPU time of
the process (bladefem) and of the child (OpenFAST), wall time of each; the load average is printed, as the machine
may be shared. Markdown table.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "data" / "openfast" / "rosco"))
sys.path.insert(0, str(ROOT / "tests" / "data" / "openfast"))
CASES = ROOT / "cases" / "nrel5mw"
ROSCO_DECK = CASES / "NRELOffshrBsline5MW_Onshore_ROSCO.fst"
TORQUE_DECK = CASES / "NRELOffshrBsline5MW_Onshore.fst"


def bladefem_argv(torque_law: bool, wind: float, out: Path) -> list[str]:
    if torque_law:
        return ["turbine", str(TORQUE_DECK), "--wind-speed", "11.4", "--quiet", "-o", str(out)]
    return ["turbine", str(ROSCO_DECK), "--wind-speed", str(wind), "--pitch-deg", "10", "--quiet", "-o", str(out)]


def bladefem_seconds(argv: list[str], seconds: float) -> tuple[float, float]:
    from bladefem.cli import main
    cpu, wall = time.process_time(), time.perf_counter()
    code = main([*argv[:2], "--simulate", f"{seconds:g}", *argv[2:]])
    if code:
        raise SystemExit(code)
    return time.process_time() - cpu, time.perf_counter() - wall


def openfast_deck(torque_law: bool, library: str | None, seconds: float, wind: float) -> Path:
    """The .fst of OpenFAST's run, in a scratch folder."""
    folder = Path(tempfile.mkdtemp(prefix="bench-openfast-"))
    if torque_law:
        import make_openfast_v5
        shutil.copytree(CASES, folder / "case")
        make_openfast_v5.to_v5(folder / "case")
        fst = folder / "case" / make_openfast_v5.FST
        make_openfast_v5.set_value(fst, "TMax", f"{seconds:g}")
        return fst
    import write_decks
    write_decks.CASES[wind] = (12.1, 10.0)
    fst = write_decks.write_case(folder / "case", wind, library)
    write_decks.set_value(fst, "TMax", f"{seconds:g}")
    return fst


def openfast_seconds(executable: str, fst: Path) -> tuple[float, float]:
    before, wall = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
    subprocess.run([executable, fst.name], cwd=fst.parent, check=True, stdout=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, time.perf_counter() - wall


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--torque-law", action="store_true")
    parser.add_argument("--seconds", type=float, default=100.0)
    parser.add_argument("--wind", type=float, default=16.0)
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--openfast")
    parser.add_argument("--library")
    parser.add_argument("--also", action="append", default=[], metavar="OPTIONS",
                        help="bladefem options timed as one more row in the same alternation (e.g. '--method DP54', "
                             "the integrator of controlled runs before one RK4 step per interval)")
    args = parser.parse_args()
    argv = bladefem_argv(args.torque_law, args.wind, Path(tempfile.mkdtemp()) / "out.csv")
    bladefem_seconds(argv, 0.5)                                            # compile or load the kernels
    fst = openfast_deck(args.torque_law, args.library, args.seconds, args.wind) if args.openfast else None
    print(f"load average before: {os.getloadavg()[0]:.1f}")
    times: dict[str, list[tuple[float, float]]] = {"bladefem": [], "OpenFAST": []}
    variants = {f"bladefem {options}": [*argv, *options.split()] for options in args.also}
    for name in variants:
        times[name] = []
    for _ in range(args.repeats):
        times["bladefem"].append(bladefem_seconds(argv, args.seconds))
        for name, variant in variants.items():
            times[name].append(bladefem_seconds(variant, args.seconds))
        if fst is not None:
            times["OpenFAST"].append(openfast_seconds(args.openfast, fst))
    print(f"load average after: {os.getloadavg()[0]:.1f}")
    case = "torque law, 11.4 m/s" if args.torque_law else f"ROSCO, {args.wind:g} m/s"
    print(f"| {args.seconds:g} s, {case} (median of {args.repeats}) | CPU [s] | wall [s] | simulated s per CPU s |")
    print("|---|---|---|---|")
    medians = {}
    for name, runs in times.items():
        if runs:
            cpu, wall = statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs)
            medians[name] = (cpu, wall)
            print(f"| {name} | {cpu:.2f} | {wall:.2f} | {args.seconds / cpu:.1f} |")
    if "OpenFAST" in medians:
        cpu_o, wall_o = medians["OpenFAST"]
        for name, (cpu_b, wall_b) in medians.items():
            if name != "OpenFAST":
                print(f"| {name} faster | {cpu_o / cpu_b:.1f}x | {wall_o / wall_b:.1f}x | |")


if __name__ == "__main__":
    main()
