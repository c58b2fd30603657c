"""Benchmark: the first ``--simulate`` of a fresh install (numba compiles the simulation kernels) and a warm one.

Run from the repository root::

    python bench/bench_first_run.py [--repeat 3] [--seconds 20]

Each repeat starts ``bladefem turbine cases/nrel5mw/NRELOffshrBsline5MW_Onshore.fst --simulate 20 --wind-speed
11.4`` in a subprocess with an empty numba cache (``NUMBA_CACHE_DIR`` a fresh temporary folder: a cold first run,
compilation included), then again with that cache filled (a warm run: the machine code loaded from disk). Wall
time and the child's CPU time (user + system) are printed, with the load average: on a shared machine the wall
time of the cold run follows the load, the CPU time much less. Prints a Markdown table.
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
DECK = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore.fst"


def run(cache: str, seconds: float, output: str) -> tuple[float, float]:
    """(wall, CPU) seconds of one ``--simulate`` in a subprocess with the numba cache in ``cache``."""
    env = {**os.environ, "NUMBA_CACHE_DIR": cache, "PYTHONPATH": str(ROOT)}
    env.pop("BLADEFEM_NO_NUMBA", None)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "bladefem", "turbine", str(DECK), "--simulate", f"{seconds:g}",
                    "--wind-speed", "11.4", "--quiet", "--output", output], cwd=ROOT, env=env, check=True,
                   capture_output=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--seconds", type=float, default=20.0, help="simulated time, s")
    args = parser.parse_args()
    print(f"`--simulate {args.seconds:g} --wind-speed 11.4`, NREL 5MW deck, {os.cpu_count()} CPUs\n")
    print("| run | cold: wall [s] | cold: CPU [s] | warm: wall [s] | warm: CPU [s] | load average |")
    print("|---|---|---|---|---|---|")
    for i in range(args.repeat):
        with tempfile.TemporaryDirectory() as folder:
            cache, output = os.path.join(folder, "numba"), os.path.join(folder, "out.csv")
            load = os.getloadavg()[0]
            cold = run(cache, args.seconds, output)
            warm = run(cache, args.seconds, output)
        print(f"| {i + 1} | {cold[0]:.1f} | {cold[1]:.1f} | {warm[0]:.1f} | {warm[1]:.1f} | {load:.1f} |",
              flush=True)


if __name__ == "__main__":
    main()
