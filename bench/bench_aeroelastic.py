"""Benchmark: the aeroelastic Campbell diagram of the whole NREL 5MW (16-DOF turbine model, quasi-steady BEM with a
frozen wake, MBC and azimuth averaging) over 12 wind speeds, 3 to 25 m/s, rotor speed and pitch from the Table 7-1
schedule. Run: ``python bench/bench_aeroelastic.py``.

Two figures: the whole command (``bladefem turbine DECK.fst --campbell --wind-speed 3:25:12 --schedule ...``,
Python start, imports and the cached numba kernels included) and the sweep in-process (operating points,
linearizations, the structure built once per pitch). Median wall time and smallest CPU time of repeats, BLAS on one
thread.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import resource  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
DECK = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"
SCHEDULE = ROOT / "cases" / "nrel5mw" / "table_7_1_schedule.csv"
ARGS = ["turbine", str(DECK), "--campbell", "--wind-speed", "3:25:12", "--schedule", str(SCHEDULE), "--quiet"]
REPEATS = 3


def whole_command() -> tuple[float, float]:
    """(wall, CPU) seconds of one ``bladefem`` process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "bladefem", *ARGS], check=True, capture_output=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def in_process() -> tuple[float, float]:
    """(wall, CPU) seconds of the sweep in this process, from reading the deck to the named modes."""
    from bladefem.cli import main

    start, cpu = time.perf_counter(), time.process_time()
    with open(os.devnull, "w") as sink:
        stdout, sys.stdout = sys.stdout, sink
        try:
            main(ARGS)
        finally:
            sys.stdout = stdout
    return time.perf_counter() - start, time.process_time() - cpu


def report(label: str, runs: list[tuple[float, float]]) -> None:
    walls, cpus = zip(*runs)
    print(f"{label:<58} {statistics.median(walls):6.2f} s wall {min(cpus):6.2f} s CPU")


def main() -> None:
    whole_command()                                   # compiles or loads the numba cache, warms the file cache
    print(f"NREL 5MW aeroelastic Campbell, 12 wind speeds 3-25 m/s (load average {os.getloadavg()[0]:.1f})")
    report("whole command (start, imports, sweep, table)", [whole_command() for _ in range(REPEATS)])
    in_process()
    report("sweep in-process", [in_process() for _ in range(REPEATS)])


if __name__ == "__main__":
    main()
