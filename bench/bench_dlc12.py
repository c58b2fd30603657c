"""The shipped DLC 1.2 plan (cases/nrel5mw_dlc12.yaml: 6 wind speeds x 2 turbulence boxes, 630 s each) on a local
Dask cluster of 2 workers: the wall time of the batch (box generation and simulation), then the loads
(``bladefem batch-loads``) and their figures.

    python bench/bench_dlc12.py [--workers 2] [--seconds 630] [--out bench/out/dlc12]

Prints the wall time, the time per case, the lifetime DELs of the blade root and the shaft, and writes del.png and
extremes.png under --out. ``--seconds`` shortens every case (statistics over its last 600 s or its second half).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")      # as the workers run: one BLAS thread per process
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse  # noqa: E402
import shutil  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--seconds", type=float, default=None, help="simulated seconds per case (default the plan's)")
    parser.add_argument("--out", default=str(ROOT / "bench" / "out" / "dlc12"))
    args = parser.parse_args()

    from bladefem.batch import read_plan, run_batch
    from bladefem.batch.loads import IEC_MEAN_SPEED, lifetime_loads
    from bladefem.batch.store import ResultStore
    from bladefem.plots.loads import plot_loads

    source = ROOT / "cases" / "nrel5mw_dlc12.yaml"
    out = Path(args.out)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    plan_path = out / "plan.yaml"
    text = source.read_text().replace("model: nrel5mw/", f"model: {ROOT / 'cases' / 'nrel5mw'}/")
    if args.seconds:
        start = max(args.seconds - 600, args.seconds / 2)
        text = text.replace("seconds: 630", f"seconds: {args.seconds:g}").replace(
            "statistics_from_s: 30", f"statistics_from_s: {start:g}")
    plan_path.write_text(text)
    plan = read_plan(plan_path)
    began = time.perf_counter()
    run = run_batch(plan, out / "results", workers=args.workers)
    wall = time.perf_counter() - began
    print(f"{run.finished} cases ({run.failed} failed) of {plan.analysis.seconds:g} s on {args.workers} workers: "
          f"{wall:.1f} s wall, {wall / max(run.finished, 1):.1f} s per case")
    rows = [r for r in ResultStore(out / "results").table().to_pylist() if r.get("channel")]
    channels = lifetime_loads(rows, IEC_MEAN_SPEED["I"])
    for c in channels:
        if c.channel in ("RootMOoP1", "RootMIP1", "RotThrust", "RotTorq", "TTDspFA"):
            print(f"  {c.channel}: lifetime DEL {c.lifetime_del:.4g} {c.unit} (m = {c.wohler:g}), "
                  f"extremes {c.minimum:.4g} .. {c.maximum:.4g}")
    for path in plot_loads(channels, out, IEC_MEAN_SPEED["I"], title="NREL 5MW DLC 1.2 (class IB)"):
        print(f"# wrote {path}")


if __name__ == "__main__":
    main()
