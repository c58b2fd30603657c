"""Benchmark: start-up of the ``bladefem`` command — ``--help``, an argument error, and a blade ``modes`` run —
as whole processes (Python start and imports included). Run: ``python bench/bench_startup.py``. Prints the
median wall-clock and CPU time (user + system of the child process) of repeated runs.
"""

from __future__ import annotations

import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RUNS = {
    "bladefem --help": ["--help"],
    "bladefem modes --rpm fast (argument error)": ["modes", "cases/uniform_blade.yaml", "--rpm", "fast"],
    "bladefem modes cases/nrel5mw_blade.yaml": ["modes", "cases/nrel5mw_blade.yaml"],
    "python -c pass (the interpreter alone)": None,
}


def timed(argv: list[str] | None) -> tuple[float, float]:
    """(wall, CPU) seconds of one process."""
    command = [sys.executable, "-c", "pass"] if argv is None else [sys.executable, "-m", "bladefem", *argv]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(command, cwd=ROOT, capture_output=True, check=False,
                   env=dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")))
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main(repeats: int = 7) -> None:
    print(f"{'process':<46} {'wall (s)':>9} {'CPU (s)':>8}")
    for name, argv in RUNS.items():
        times = [timed(argv) for _ in range(repeats)]
        wall, cpu = (statistics.median(t[i] for t in times) for i in (0, 1))
        print(f"{name:<46} {wall:>9.3f} {cpu:>8.3f}")


if __name__ == "__main__":
    main()
