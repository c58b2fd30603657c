"""Run the cases of a plan as Dask tasks (``dask.distributed``): on a local cluster of worker processes, or on an
existing cluster through its scheduler address; results go to a Parquet dataset in chunks as tasks finish.

A worker that dies takes its running task with it; the scheduler gives the task to another worker, and the client
writes each case exactly once (the first result of its hash). ``resume`` skips the cases that finished and runs the
failed ones again (their error rows are removed first).

Each case carries its input files (:mod:`bladefem.batch.bundle`): one task per distinct set of files holds their
bytes (recomputed by the scheduler if the worker that held it dies), and the cases depend on it, so a worker in
another folder or on another machine runs on the very bytes the client read.
"""

from __future__ import annotations

import logging
import tempfile
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import InputError
from .bundle import INPUTS_FOLDER, Bundle, check_results_folder
from .cases import Case
from .plan import Plan
from .store import ResultStore
from .worker import input_columns, run_case

#: results are written when this many cases have finished, or after FLUSH_SECONDS
CHUNK_CASES = 64
FLUSH_SECONDS = 5.0
#: glibc's trim threshold in the local workers, bytes. Dask sets 64 KiB to hand freed memory back to the system at
#: once; a modal solve allocates and frees arrays of a few hundred KiB all the time, and at 64 KiB each one costs
#: fresh page faults: the same case took 58 ms of CPU on a worker against 39 ms in-process, 41 ms with this value.
WORKER_TRIM_THRESHOLD = 2**27


@dataclass(frozen=True)
class BatchRun:
    """What a batch run did: cases in the plan, skipped (finished in an earlier run), run, failed (with the first
    failure's message); wall time, s; ``retried``: failed cases of an earlier run that this one ran again;
    ``repeated``: cases identical to an earlier one of the plan (same files, inputs and analysis), not run again."""

    total: int
    skipped: int
    finished: int
    failed: int
    seconds: float
    first_error: str | None = None
    retried: int = 0
    repeated: int = 0


def check_output(plan: Plan, results: str | Path, resume: bool) -> ResultStore:
    """The results store, refused (InputError, before anything runs or is printed) when ``results`` is a file, is
    or holds an input of the plan, or already holds results and ``resume`` is not given."""
    check_results_folder(results, plan.inputs())
    store = ResultStore(results)
    if store.parts() and not resume:
        raise InputError("already holds batch results: add --resume to finish that batch, or choose another "
                         "folder", file=str(store.path), field="-o")
    return store


def _bundle_data(bundle: Bundle) -> Bundle:
    return bundle


@contextmanager
def dask_client(scheduler: str | None = None, workers: int | None = None) -> Iterator[Any]:
    """A client of the cluster at ``scheduler`` (e.g. tcp://host:8786), or of a new local cluster of ``workers``
    single-threaded worker processes (default: one per core) whose copies of the inputs go to a temporary folder
    removed with the cluster."""
    from dask.distributed import Client, LocalCluster
    if scheduler:
        try:
            client = Client(scheduler, timeout="20s")
        except OSError as error:
            raise InputError(f"cannot reach the Dask scheduler ({error})", field="--scheduler") from None
        with client:
            yield client
        return
    import dask
    environment = {"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": WORKER_TRIM_THRESHOLD}
    with tempfile.TemporaryDirectory(prefix="bladefem-batch-") as inputs:   # the workers' copies, removed after
        with dask.config.set(environment):
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0",
                                   silence_logs=logging.ERROR, env={"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1",
                                                                    INPUTS_FOLDER: inputs})
        with cluster, Client(cluster) as client:
            yield client


def dashboard_address(client: Any) -> str | None:
    """The Dask dashboard's address, or None when the scheduler has none: started without it, or without bokeh
    (then its address serves only a page asking to install bokeh)."""
    try:
        if "dashboard" not in client.scheduler_info().get("services", {}):
            return None
        if not client.run_on_scheduler(_has_bokeh):
            return None
        return client.dashboard_link
    except Exception:                                   # pragma: no cover - informational only
        return None


def _has_bokeh() -> bool:
    import importlib.util
    return importlib.util.find_spec("bokeh") is not None


def _failure_rows(case: Case, error: BaseException) -> list[dict[str, Any]]:
    return [{"case_index": case.index, "case_hash": case.hash, **input_columns(case), "status": "error",
             "error": f"{type(error).__name__}: {error}"}]


def run_batch(plan: Plan, results: str | Path, *, scheduler: str | None = None, workers: int | None = None,
              resume: bool = False, progress: Callable[[int, int, int], None] | None = None,
              on_result: Callable[[Any, Case], None] | None = None, chunk: int = CHUNK_CASES) -> BatchRun:
    """Run every case of ``plan`` not yet in ``results`` (with ``resume``) on Dask and write their rows.

    ``progress(done, failed, remaining)`` is called after each case; ``on_result(client, case)`` too (a hook for
    tests and tools). A case that raises records its error and the batch goes on; finished results are written
    even when the run is interrupted.
    """
    from dask.distributed import as_completed
    store = check_output(plan, results, resume)
    retried = store.drop_failed() if resume else 0
    done = store.done_hashes() if resume else set()
    unique = list({case.hash: case for case in reversed(plan.cases)}.values())[::-1]   # a repeated case runs once
    todo = [case for case in unique if case.hash not in done]
    start = time.perf_counter()
    written: set[str] = set()
    buffer: list[dict[str, Any]] = []
    failed = 0
    first_error = None
    last_flush = time.monotonic()

    def flush() -> None:
        nonlocal last_flush
        store.append(buffer)
        buffer.clear()
        last_flush = time.monotonic()

    with dask_client(scheduler, workers) as client:
        by_key = {}
        futures = []
        needed = {case.bundle for case in todo}
        inputs = {digest: client.submit(_bundle_data, bundle, key=f"bladefem-inputs-{digest}", pure=False)
                  for digest, bundle in plan.bundles.items() if digest in needed}
        for case in todo:
            future = client.submit(run_case, case, inputs.get(case.bundle), key=f"bladefem-case-{case.hash}",
                                   pure=False)
            by_key[future.key] = case
            futures.append(future)
        try:
            for future in as_completed(futures):
                case = by_key[future.key]
                try:
                    rows = future.result()
                except Exception as error:                 # e.g. KilledWorker after repeated worker deaths
                    rows = _failure_rows(case, error)
                if case.hash in written:
                    continue
                written.add(case.hash)
                errors = [row["error"] for row in rows if row["status"] == "error"]
                failed += bool(errors)
                if errors and first_error is None:
                    first_error = f"case {case.index}: {errors[0]}"
                buffer += rows
                if len(written) % chunk == 0 or time.monotonic() - last_flush > FLUSH_SECONDS:
                    flush()
                if progress is not None:
                    progress(len(written), failed, len(todo) - len(written))
                if on_result is not None:
                    on_result(client, case)
        finally:
            flush()
            for future in [*futures, *inputs.values()]:
                future.cancel()
    return BatchRun(len(plan.cases), len(unique) - len(todo), len(written), failed,
                    time.perf_counter() - start, first_error, retried, len(plan.cases) - len(unique))
