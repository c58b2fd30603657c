"""Batch throughput on Dask: converged Campbell sweeps (16 speeds, 0-15 rpm) of Monte-Carlo NREL 5MW blades
(mass and stiffness +-5 %), with 1 and 2 local worker processes, against the same cases solved in-process.

    python bench/bench_batch.py [--cases 2000] [--workers 1 2]

Prints cases per second for each worker count and the per-task overhead of Dask (wall time per case on one worker
minus the in-process time per case). Needs the ``distributed`` extra.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")      # as the workers run: one BLAS thread per process
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def plan_file(folder: Path, count: int) -> Path:
    path = folder / "plan.yaml"
    path.write_text(f"""model: {ROOT / 'cases' / 'nrel5mw_blade.yaml'}
analysis: {{type: campbell, rpm: [0, 15, 16], n_modes: 6}}
samples:
  count: {count}
  seed: 11
  properties:
    mass: {{distribution: uniform, half_width_percent: 5}}
    stiffness: {{distribution: uniform, half_width_percent: 5}}
""")
    return path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=2000)
    parser.add_argument("--serial-cases", type=int, default=100, help="cases timed in-process")
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    args = parser.parse_args()

    from bladefem.batch import read_plan, run_batch, run_case
    with tempfile.TemporaryDirectory() as folder:
        plan = read_plan(plan_file(Path(folder), args.cases))
        run_case(plan.cases[-1])                        # warm: imports, the base model read once
        start = time.perf_counter()
        for case in plan.cases[: args.serial_cases]:
            run_case(case)
        serial = (time.perf_counter() - start) / args.serial_cases
        print(f"in-process: {serial * 1e3:.1f} ms per case ({1 / serial:.2f} cases/s), "
              f"{args.serial_cases} cases")
        for workers in args.workers:
            run = run_batch(plan, Path(folder) / f"out{workers}", workers=workers)
            rate = run.finished / run.seconds
            line = (f"{workers} worker(s): {run.finished} cases in {run.seconds:.1f} s = {rate:.2f} cases/s "
                    f"({run.failed} failed)")
            if workers == 1:
                line += f"; Dask overhead {(run.seconds / run.finished - serial) * 1e3:+.1f} ms per task"
            print(line)


if __name__ == "__main__":
    main()
