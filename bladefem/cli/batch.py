"""``bladefem batch`` and ``bladefem batch-summary``: many cases on Dask, results in Parquet, and their statistics.

Needs the ``distributed`` extra (``pip install "bladefem[distributed]"``).
"""

from __future__ import annotations

import argparse


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    batch = subparsers.add_parser(
        "batch", help="run a plan of cases (grid, Monte Carlo, files) on Dask; results in Parquet",
        description="Run the cases of a plan (YAML: a base model and a grid, random samples or a list of files, and "
                    "the analysis per case) as Dask tasks, on a local cluster or on an existing one, writing one "
                    "Parquet row per case and mode as tasks finish.")
    batch.add_argument("plan", metavar="PLAN.yaml", help="the plan")
    batch.add_argument("-o", "--output", required=True, metavar="RESULTS", help="results folder (Parquet dataset)")
    batch.add_argument("--scheduler", metavar="ADDRESS",
                       help="address of a running Dask scheduler (e.g. tcp://host:8786); default a local cluster")
    batch.add_argument("--workers", type=int, metavar="N", help="worker processes of the local cluster "
                                                               "(default one per core)")
    batch.add_argument("--resume", action="store_true",
                       help="keep the cases that finished in RESULTS and run the rest, failed ones again")
    batch.add_argument("--quiet", action="store_true", help="no progress bar")
    batch.set_defaults(run=run_batch_command)

    summary = subparsers.add_parser(
        "batch-summary", help="statistics and sensitivities of batch results",
        description="Per-mode statistics (mean, std, 5 and 95 % quantiles) of a batch's results, the correlation of "
                    "each varied input with each frequency, and optionally histograms and a tornado chart.")
    summary.add_argument("results", metavar="RESULTS", help="results folder of 'bladefem batch'")
    summary.add_argument("--plot", metavar="DIR", help="write histograms.png and tornado.png into DIR")
    summary.set_defaults(run=run_summary_command)


def _needs_distributed() -> None:
    from ..errors import InputError
    try:
        import dask.distributed  # noqa: F401
        import pyarrow  # noqa: F401
    except ImportError:
        raise InputError('needs the distributed extra: pip install "bladefem[distributed]"',
                         field="batch") from None


def run_batch_command(args: argparse.Namespace) -> int:
    from ..errors import InputError
    if args.workers is not None and not 1 <= args.workers <= 256:
        raise InputError(f"need 1 to 256 worker processes, got {args.workers}", field="--workers")
    _needs_distributed()
    from ..batch import read_plan, run_batch
    from ..batch.runner import check_output, dashboard_address
    plan = read_plan(args.plan)
    check_output(plan, args.output, args.resume)          # before any output: the bar is not drawn for an error
    bar = None if args.quiet else _ProgressBar(len({case.hash for case in plan.cases}))
    first = {"shown": False}

    def on_result(client, case) -> None:
        if not first["shown"] and not args.quiet:
            address = dashboard_address(client)
            if address:
                bar.note(f"Dask dashboard: {address}")
            first["shown"] = True

    try:
        run = run_batch(plan, args.output, scheduler=args.scheduler, workers=args.workers, resume=args.resume,
                        progress=None if bar is None else bar.update, on_result=on_result)
    finally:
        if bar is not None:
            bar.close()
    retried = f", {run.retried} failed before and run again" if run.retried else ""
    repeated = f", {run.repeated} repeating an earlier case (run once)" if run.repeated else ""
    print(f"# {run.total} cases{repeated}: {run.skipped} already in {args.output}, {run.finished} run "
          f"({run.failed} failed{retried}) in {run.seconds:.1f} s; results in {args.output}")
    if run.failed:
        import sys
        print(f"bladefem: error: {run.failed} of {run.finished} cases failed (first: {run.first_error}); their "
              f"messages are in {args.output} (status 'error'); fix the cause and run again with --resume",
              file=sys.stderr)
        return 1
    return 0


def run_summary_command(args: argparse.Namespace) -> int:
    from pathlib import Path

    from ..errors import InputError
    _needs_distributed()
    from ..batch import ResultStore, format_summary, plot_summary, summarize
    store = ResultStore(args.results)
    if not store.parts():
        raise InputError("no batch results here", file=str(Path(args.results)))
    summary = summarize(store.table())
    print(format_summary(summary))
    if args.plot:
        for path in plot_summary(summary, args.plot, title=Path(args.results).name or str(args.results)):
            print(f"# wrote {path}")
    return 0


class _ProgressBar:
    """Cases done / failed / remaining on stderr (rich)."""

    def __init__(self, total: int) -> None:
        from rich.console import Console
        from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn
        self.progress = Progress(TextColumn("cases"), BarColumn(), TextColumn("{task.fields[counts]}"),
                                 TimeElapsedColumn(), console=Console(stderr=True), transient=False)
        self.total = total
        self.task = self.progress.add_task("batch", total=total, counts="")
        self.progress.start()

    def note(self, text: str) -> None:
        self.progress.console.print(text)

    def update(self, done: int, failed: int, remaining: int) -> None:
        self.progress.update(self.task, completed=self.total - remaining,
                             counts=f"done {done}  failed {failed}  remaining {remaining}")

    def close(self) -> None:
        self.progress.stop()
