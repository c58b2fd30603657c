"""Benchmark: start-up of the ``bladefem`` command — ``--help``, an argument error, and a blade ``modes`` run —
as whole processes (Python start and imports included). Run: ``python bench/bench_startup.py``. Prints the
median wall-clock and CPU time (user + system of the child process) of repeated runs.

``python bench/bench_startup.py --exit`` instead times the end of a process: the same commands (a blade ``modes``
run and a warm ``turbine --simulate 20`` of the NREL 5MW deck) through ``python -m bladefem`` (its exit without the
interpreter's teardown, :func:`bladefem.cli.entry`) and through ``SystemExit(main())`` (the teardown), alternated;
a cold run is timed by ``bench/bench_first_run.py``.
"""

from __future__ import annotations

import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RUNS = {
    "bladefem --help": ["--help"],
    "bladefem modes --rpm fast (argument error)": ["modes", "cases/uniform_blade.yaml", "--rpm", "fast"],
    "bladefem modes cases/nrel5mw_blade.yaml": ["modes", "cases/nrel5mw_blade.yaml"],
    "python -c pass (the interpreter alone)": None,
}


#: the commands timed by ``--exit``
ENDS = {"bladefem modes cases/nrel5mw_blade.yaml": ["modes", "cases/nrel5mw_blade.yaml"],
        "bladefem turbine (NREL 5MW) --simulate 20 (warm)": [
            "turbine", "cases/nrel5mw/NRELOffshrBsline5MW_Onshore.fst", "--simulate", "20", "--wind-speed", "11.4",
            "--quiet", "--output", str(Path(tempfile.gettempdir()) / "bench-startup-turbine.csv")]}
#: the command line run with the interpreter's usual teardown at exit
TEARDOWN = "import sys; from bladefem.cli import main; sys.argv[0] = 'bladefem'; raise SystemExit(main())"


def timed(argv: list[str] | None, teardown: bool = False) -> tuple[float, float]:
    """(wall, CPU) seconds of one process (``teardown``: ended by ``SystemExit``, not :func:`bladefem.cli.entry`)."""
    command = ([sys.executable, "-c", "pass"] if argv is None else
               [sys.executable, "-c", TEARDOWN, *argv] if teardown else [sys.executable, "-m", "bladefem", *argv])
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, cwd=ROOT, capture_output=True, check=False,
                          env=dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")))
    wall = time.perf_counter() - start
    if argv in ENDS.values() and done.returncode:
        raise SystemExit(f"{argv} failed: {done.stderr.decode(errors='replace')}")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main(repeats: int = 7) -> None:
    print(f"{'process':<46} {'wall (s)':>9} {'CPU (s)':>8}")
    for name, argv in RUNS.items():
        times = [timed(argv) for _ in range(repeats)]
        wall, cpu = (statistics.median(t[i] for t in times) for i in (0, 1))
        print(f"{name:<46} {wall:>9.3f} {cpu:>8.3f}")


def ends(repeats: int = 7) -> None:
    """The ``--exit`` table: each command ended both ways, alternated."""
    print(f"{'process':<52} {'wall, fast exit':>16} {'wall, teardown':>15} {'CPU, fast exit':>15} {'CPU, teardown':>14}")
    for name, argv in ENDS.items():
        timed(argv)                                    # numba's cache filled: warm runs
        pairs = [(timed(argv), timed(argv, teardown=True)) for _ in range(repeats)]
        fast, slow = ([p[k] for p in pairs] for k in (0, 1))
        median = [statistics.median(t[i] for t in runs) for runs in (fast, slow) for i in (0, 1)]
        print(f"{name:<52} {median[0]:>16.3f} {median[2]:>15.3f} {median[1]:>15.3f} {median[3]:>14.3f}")


if __name__ == "__main__":
    ends() if "--exit" in sys.argv[1:] else main()
