"""Batch runs on Dask: a plan of cases (a parameter grid, Monte-Carlo samples, or a list of files) and an analysis
per case, run as ``dask.distributed`` tasks on a local cluster or an existing one, results in a Parquet dataset.

Needs the ``distributed`` extra: ``pip install "bladefem[distributed]"`` (dask, distributed, pyarrow).

    from bladefem.batch import read_plan, run_batch
    plan = read_plan("cases/nrel5mw_uq.yaml")
    run_batch(plan, "out/uq", workers=2)
"""

from __future__ import annotations

from .cases import Case
from .plan import Analysis, Plan, read_plan
from .runner import BatchRun, run_batch
from .store import ResultStore
from .summary import BatchSummary, format_summary, plot_summary, summarize
from .worker import run_case

__all__ = ["Analysis", "BatchRun", "BatchSummary", "Case", "Plan", "ResultStore", "format_summary", "plot_summary",
           "read_plan", "run_batch", "run_case", "summarize"]
